/// @file model_data_test.cpp
/// Model data (model.h): file round trips, validation messages naming the field, auto_correct,
/// baked transforms against their analytic results, coordinate spaces (exact over every pair of
/// the 48 conventions), signed-distance grids against the exact box distance, and OFF files.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <random>

#include "mesh_test_helpers.h"
#include "superdex/physics/error.h"
#include "superdex/physics/mesh_io.h"
#include "superdex/physics/mesh_validation.h"
#include "superdex/physics/model.h"
#include "superdex/physics/params/actor_params.h"

namespace superdex::physics::test {
namespace {

using ::testing::HasSubstr;
using ::testing::ThrowsMessage;

// The cube [-0.5, 0.5]^3 as one cell of six positively oriented tetrahedra.
ModelData tet_cube() {
  MeshData m;
  m.nodes_per_element = 4;
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i) m.coordinates.insert(m.coordinates.end(), {real(i) - real(0.5), real(j) - real(0.5), real(k) - real(0.5)});
  m.connectivity = {0, 1, 3, 7, 0, 1, 7, 5, 0, 2, 7, 3, 0, 2, 6, 7, 0, 4, 5, 7, 0, 4, 7, 6};
  ModelData d;
  d.mesh = m;
  return d;
}

double volume(const MeshData& m, int e) {
  auto p = [&](int k) {
    const int n = m.connectivity[4 * e + k];
    return Eigen::Vector3d(m.coordinates[3 * n], m.coordinates[3 * n + 1], m.coordinates[3 * n + 2]);
  };
  return (p(1) - p(0)).dot((p(2) - p(0)).cross(p(3) - p(0))) / 6;
}

TEST(ModelData, TheTestCubeIsValidAndPositivelyOriented) {
  const ModelData d = tet_cube();
  model::validate(d);
  double total = 0;
  for (int e = 0; e < 6; ++e) {
    EXPECT_GT(volume(*d.mesh, e), 0) << e;
    total += volume(*d.mesh, e);
  }
  EXPECT_NEAR(total, 1.0, 1e-12);
}

TEST(ModelData, JsonAndH5RoundTripsAreExact) {
  ModelData d = tet_cube();
  d.mesh->coordinates[0] = real(0.1);
  d.constrained_nodes = std::vector<int>{5, 2};
  d.sdf = GridSdfData{Int3(2, 2, 2), {1, 2, 3, 4, 5, 6, 7, real(1) / 3}, Aabb{Real3::Zero(), Real3::Ones()},
                      Aabb{Real3::Constant(real(0.25)), Real3::Constant(real(0.75))}, Real3::Constant(2), std::nullopt, Real3(0, 0, 1)};
  PerElementSoftMaterialData material;
  material.youngs_modulus.assign(6, real(2e5));
  material.poisson_ratio.assign(6, real(0.3));
  d.material = material;
  EXPECT_EQ(model::load_from_bytes_unchecked(model::save_to_json_string(d)), d);
  TempDir dir;
  model::save_to_file(d, dir.file("sub/m.mochi.h5"), FileFormat::H5);
  EXPECT_EQ(model::load_from_file_unchecked(dir.file("sub/m.mochi.h5")), d);
  d.constrained_nodes = std::vector<int>{2, 5};  // auto_correct sorts them
  EXPECT_EQ(model::load_from_file(dir.file("sub/m.mochi.h5")), d);
}

TEST(ModelData, ValidateNamesTheField) {
  ModelData d = tet_cube();
  d.mesh->connectivity[12] = 40;
  EXPECT_THAT([&] { model::validate(d); }, ThrowsMessage<Error>(HasSubstr("mesh.connectivity[12]: node 40 out of range (8 nodes)")));
  d = tet_cube();
  d.box = Box{};
  EXPECT_THAT(error_of([&] { model::validate(d); }), HasSubstr("model: must contain exactly one type of shape"));
  d = tet_cube();
  d.sdf = GridSdfData{};
  EXPECT_THAT(error_of([&] { model::validate(d); }), HasSubstr("sdf.dims: every dimension must be at least 2"));
}

TEST(ModelData, AutoCorrectNormalisesAndDropsEmptyParts) {
  ModelData d = tet_cube();
  d.mesh->skinning = SkinningData{1, std::vector<int>(8, 0), {2, 2, 2, 2, 2, 2, 2, 2}};
  d.constrained_nodes = std::vector<int>{};
  d.plane = Plane{Real3(0, 0, 3), 1};
  model::auto_correct(d);
  EXPECT_EQ(d.mesh->skinning->weights, std::vector<real>(8, 1));
  EXPECT_FALSE(d.constrained_nodes.has_value());
  EXPECT_EQ(d.plane->normal, Real3(0, 0, 1));
  EXPECT_EQ(d.plane->distance, 1);
}

TEST(ModelData, BakeTransformIsTheAnalyticMap) {
  const ModelData src = tet_cube();
  ModelData d = src;
  const Quaternion q(Eigen::AngleAxis<real>(real(0.7), Real3(1, 2, 3).normalized()));
  const Real3 s(2, 3, 4), t(1, -1, 0.5);
  model::bake_transform(d, s, q, t);
  for (int n = 0; n < 8; ++n) {
    const Real3 p(src.mesh->coordinates[3 * n], src.mesh->coordinates[3 * n + 1], src.mesh->coordinates[3 * n + 2]);
    const Real3 want = q * s.cwiseProduct(p) + t;
    for (int a = 0; a < 3; ++a) EXPECT_NEAR(d.mesh->coordinates[3 * n + a], want[a], 1e-12);
  }
  ModelData mirrored = src;
  model::bake_transform(mirrored, Real3(1, -1, 1));
  for (int e = 0; e < 6; ++e) EXPECT_NEAR(volume(*mirrored.mesh, e), volume(*src.mesh, e), 1e-12) << "re-wound after mirroring";
  EXPECT_THAT(error_of([&] { model::bake_transform(mirrored, Real3(0, 1, 1)); }), HasSubstr("scale must be finite and non-zero"));
}

TEST(ModelData, CoordinateSpacesConvertExactlyBetweenEveryPair) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-10, 10);
  MeshData mesh;
  mesh.nodes_per_element = 3;
  for (int i = 0; i < 30; ++i) mesh.coordinates.push_back(static_cast<real>(u(rng)));
  mesh.connectivity = {0, 1, 2, 3, 4, 5};
  for (CoordinateSpaceAxes a : kAllCoordinateSpaceAxes)
    for (CoordinateSpaceAxes b : kAllCoordinateSpaceAxes) {
      const CoordinateSpace from{a, 1.0}, to{b, 1.0};
      MeshData m = mesh;
      model::bake_coordinate_space_transform(m, from, to);
      const bool flips = coordinate_space_rotation(from, to).determinant() < 0;
      EXPECT_EQ(m.connectivity[0] == 1, flips) << coordinate_space_axes_name(a) << " -> " << coordinate_space_axes_name(b);
      model::bake_coordinate_space_transform(m, to, from);
      ASSERT_EQ(m, mesh) << coordinate_space_axes_name(a) << " -> " << coordinate_space_axes_name(b);
    }
  // FLU -> FRU (Unreal) negates y and scales by 100
  EXPECT_EQ(coordinate_space_rotation(CoordinateSpace::engine_default(), CoordinateSpace::unreal()), Eigen::Vector3d(1, -1, 1).asDiagonal().toDenseMatrix());
  EXPECT_EQ(CoordinateSpace::engine_default().right(), Eigen::Vector3d(0, -1, 0));
  EXPECT_STREQ(coordinate_space_axes_name(CoordinateSpaceAxes::RUB), "RUB");
  EXPECT_THAT(error_of([] { CoordinateSpace{static_cast<CoordinateSpaceAxes>(0), 1.0}.validate(); }), HasSubstr("CoordinateSpace.axes"));
}

TEST(ModelData, BakeSdfIsTheExactBoxDistance) {
  ModelData d = tet_cube();
  GridSdfParams params;
  params.boundary_padding_dist = real(0.25);
  model::bake_sdf(d, params);
  const GridSdfData& s = *d.sdf;
  const Eigen::Vector3d lo = s.bounds.min.cast<double>(), hi = s.bounds.max.cast<double>();
  const Eigen::Vector3d cell = (hi - lo).cwiseQuotient((s.dims - Int3::Ones()).cast<double>());
  for (int k = 0; k < s.dims[2]; ++k)
    for (int j = 0; j < s.dims[1]; ++j)
      for (int i = 0; i < s.dims[0]; ++i) {
        const Eigen::Vector3d p = lo + Eigen::Vector3d(i, j, k).cwiseProduct(cell);
        ASSERT_NEAR(s.values[i + s.dims[0] * (j + s.dims[1] * k)], box_distance(p, Eigen::Vector3d::Constant(0.5)), 1e-9);
      }
  model::validate(d);
}

TEST(ModelData, OffFilesAndBytes) {
  const std::string off = "OFF\n8 6 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n"
                          "4 0 3 2 1\n4 4 5 6 7\n4 0 1 5 4\n4 2 3 7 6\n4 1 2 6 5\n4 0 4 7 3\n";
  const TriangleMesh from_bytes = read_off_bytes(off, "cube");
  EXPECT_EQ(from_bytes.vertices.size(), 8u);
  EXPECT_EQ(from_bytes.triangles.size(), 12u);
  EXPECT_TRUE(is_closed(from_bytes));
  EXPECT_GT(signed_volume(from_bytes), 0);
  TempDir dir;
  const TriangleMesh from_file = read_mesh_file(write_file(dir.file("cube.OFF"), off));
  EXPECT_EQ(from_file.triangles, from_bytes.triangles);
  EXPECT_EQ(model::load_from_bytes(off, MeshFileType::OFF), model::load_from_file(dir.file("cube.OFF")));
  EXPECT_THAT(error_of([] { read_off_bytes("OFF\n3 1 0\n0 0 0\n1 0 0\n", "short"); }), HasSubstr("short"));
}

}  // namespace
}  // namespace superdex::physics::test

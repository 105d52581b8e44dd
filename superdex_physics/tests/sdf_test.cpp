/// @file sdf_test.cpp
/// Signed-distance grids of a cube and an icosphere against the analytic box and sphere
/// distances, the mesh geometry queries built on them, the on-disk cache, and the exact mass
/// properties of mesh shapes.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <numbers>

#include "collision/collision_geometry.h"
#include "mesh_test_helpers.h"
#include "superdex/physics/error.h"
#include "superdex/physics/mesh_shape.h"
#include "superdex/physics/mesh_validation.h"
#include "superdex/physics/sdf.h"

namespace superdex::physics::test {
namespace {

using ::testing::HasSubstr;
using ::testing::ThrowsMessage;

double cell_size(const SdfGrid& g) { return (g.grid_max.x() - g.grid_min.x()) / (g.size[0] - 1); }

Eigen::Vector3d node(const SdfGrid& g, int i, int j, int k) {
  return g.grid_min.cast<double>() + Eigen::Vector3d(i, j, k).cwiseProduct((g.grid_max - g.grid_min).cast<double>().cwiseQuotient(
                                                                      Eigen::Vector3d(g.size[0] - 1, g.size[1] - 1, g.size[2] - 1)));
}

// Points spread over the grid box (fixed seed).
std::vector<Vec3> random_points(const SdfGrid& g, int n) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Vec3> out;
  for (int i = 0; i < n; ++i)
    out.push_back((g.grid_min.cast<double>() + Eigen::Vector3d(u(rng), u(rng), u(rng)).cwiseProduct((g.grid_max - g.grid_min).cast<double>())).cast<real>());
  return out;
}

// Keeps the cache in a temporary directory for one test.
class CacheDir {
 public:
  CacheDir() { setenv("SUPERDEX_CACHE_DIR", dir_.path().c_str(), 1); }
  ~CacheDir() { unsetenv("SUPERDEX_CACHE_DIR"); }
  const TempDir& dir() const { return dir_; }

 private:
  TempDir dir_;
};

TEST(Sdf, LayoutPadsAndUsesCubicCells) {
  TriangleMesh box = cube_mesh();
  for (Vec3& v : box.vertices) v = v.cwiseProduct(Vec3(2, 1, 1));  // 2 x 1 x 1
  const SdfGrid g = compute_sdf(box, {16, 3}, "box");
  EXPECT_EQ(g.size, (std::array<int, 3>{16 + 6 + 1, 8 + 6 + 1, 8 + 6 + 1}));
  const double h = cell_size(g);
  EXPECT_NEAR(h, 2.0 / 16, 1e-12);
  EXPECT_NEAR(g.grid_min.x(), -1 - 3 * h, 1e-12);
  EXPECT_NEAR(g.grid_max.z(), 0.5 + 3 * h, 1e-12);
}

TEST(Sdf, CubeMatchesTheBoxDistance) {
  const TriangleMesh cube = cube_mesh(0.5);
  const SdfGrid g = compute_sdf(cube, {32, 3}, "cube");
  const Eigen::Vector3d half(0.5, 0.5, 0.5);
  double worst_node = 0;
  for (int k = 0; k < g.size[2]; ++k)
    for (int j = 0; j < g.size[1]; ++j)
      for (int i = 0; i < g.size[0]; ++i) {
        const double want = box_distance(node(g, i, j, k), half);
        worst_node = std::max(worst_node, std::abs(g.values[i + g.size[0] * (j + g.size[1] * k)] - want));
      }
  EXPECT_LT(worst_node, 1e-9);

  // between nodes, trilinear interpolation is off by at most 3/8 of a cell at the creases
  MeshShape shape{std::make_shared<TriangleMesh>(cube), std::make_shared<SdfGrid>(g), true, "cube"};
  const double h = cell_size(g);
  for (const Vec3& p : random_points(g, 2000)) {
    Vec3 grad;
    const double d = mesh_signed_distance(shape, p, &grad);
    EXPECT_NEAR(d, box_distance(p.cast<double>(), half), 0.375 * h + 1e-9) << p.transpose();
    EXPECT_NEAR(grad.norm(), 1.0, 1e-9);
  }
  // the gradient points out of the face a point is near
  Vec3 grad;
  EXPECT_NEAR(mesh_signed_distance(shape, Vec3(0.3, 0.05, 0.02), &grad), -0.2, 1e-9);
  EXPECT_GT(grad.x(), 0.99);
}

TEST(Sdf, IcosphereMatchesTheSphereDistance) {
  const TriangleMesh sphere = icosphere(3, 1.0);  // 1280 triangles
  const SdfGrid g = compute_sdf(sphere, {32, 3}, "sphere");  // its time: BM_ComputeSdf in benchmarks/cpp

  MeshShape shape{std::make_shared<TriangleMesh>(sphere), std::make_shared<SdfGrid>(g), true, "sphere"};
  const double h = cell_size(g);
  // the faceted sphere lies within ~0.005 of the round one at this subdivision
  for (const Vec3& p : random_points(g, 2000)) {
    Vec3 grad;
    const double d = mesh_signed_distance(shape, p, &grad);
    const double r = p.cast<double>().norm();
    EXPECT_NEAR(d, r - 1.0, 0.25 * h + 0.006) << p.transpose();
    if (r > 0.3) {
      EXPECT_GT(grad.cast<double>().dot(p.cast<double>() / r), 0.95) << p.transpose();
    }
  }
  EXPECT_LT(mesh_signed_distance(shape, Vec3::Zero(), nullptr), -0.99);
}

TEST(Sdf, OutsideTheGridAddsTheDistanceToTheBox) {
  // the cube's field is exact at the grid's faces: far along an axis the value stays exact
  const TriangleMesh cube = cube_mesh(0.5);
  MeshShape box{std::make_shared<TriangleMesh>(cube), std::make_shared<SdfGrid>(compute_sdf(cube, {16, 2}, "cube")), true, "cube"};
  Vec3 grad;
  EXPECT_NEAR(mesh_signed_distance(box, Vec3(5, 0.1, -0.2), &grad), 4.5, 1e-9);
  EXPECT_NEAR(grad.x(), 1.0, 1e-9);
  const TriangleMesh sphere = icosphere(2, 1.0);
  MeshShape ball{std::make_shared<TriangleMesh>(sphere), std::make_shared<SdfGrid>(compute_sdf(sphere, {24, 2}, "sphere")), true, "sphere"};
  const Vec3 corner(4, 4, 4);
  EXPECT_NEAR(mesh_signed_distance(ball, corner, &grad), corner.norm() - 1, 0.05);
  EXPECT_GT(grad.dot(corner.normalized()), 0.99);
}

TEST(Sdf, InsideOutMeshGivesTheSameField) {
  TriangleMesh cube = cube_mesh();
  const SdfGrid a = compute_sdf(cube, {8, 2}, "cube");
  for (auto& t : cube.triangles) std::swap(t[1], t[2]);
  const SdfGrid b = compute_sdf(cube, {8, 2}, "cube");
  ASSERT_EQ(a.values.size(), b.values.size());
  for (size_t i = 0; i < a.values.size(); ++i) EXPECT_NEAR(a.values[i], b.values[i], 1e-12);
}

TEST(Sdf, OpenMeshIsAnError) {
  TriangleMesh open = cube_mesh();
  open.triangles.pop_back();
  EXPECT_THAT([&] { compute_sdf(open, {}, "open.obj"); },
              ThrowsMessage<Error>(HasSubstr("open.obj: computing a signed-distance field needs a closed mesh: 3 boundary edges")));
  const MeshShape shape = make_mesh_shape(open, "open.obj");
  EXPECT_EQ(shape.sdf, nullptr);
  EXPECT_THAT([&] { mesh_signed_distance(shape, Vec3::Zero(), nullptr); },
              ThrowsMessage<Error>(HasSubstr("open.obj: the mesh is open and has no signed-distance field")));
  EXPECT_THAT([&] { compute_sdf(cube_mesh(), {1, 3}, "cube"); }, ThrowsMessage<Error>(HasSubstr("cube: SDF resolution must be between 2 and 1024")));
}

TEST(SdfCache, StoresReusesAndRepairs) {
  CacheDir cache;
  const TriangleMesh sphere = icosphere(2, 0.5);
  const SdfOptions options{16, 2};
  const auto first = cached_sdf(sphere, options, "sphere");
  const std::filesystem::path file = cache.dir().path() / sdf_cache_key(sphere, options);
  ASSERT_TRUE(std::filesystem::exists(file));
  const auto again = cached_sdf(sphere, options, "sphere");
  EXPECT_EQ(again->values, first->values);
  EXPECT_EQ(again->size, first->size);

  // another resolution is another entry
  EXPECT_NE(sdf_cache_key(sphere, {17, 2}), sdf_cache_key(sphere, options));
  TriangleMesh moved = sphere;
  moved.vertices[0].x() += real(1e-9);
  EXPECT_NE(sdf_cache_key(moved, options), sdf_cache_key(sphere, options));

  // a corrupt entry is ignored, recomputed and rewritten
  write_file(file.string(), "not an hdf5 file");
  const auto repaired = cached_sdf(sphere, options, "sphere");
  EXPECT_EQ(repaired->values, first->values);
  EXPECT_GT(std::filesystem::file_size(file), 1000u);
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(cache.dir().path())) files += entry.is_regular_file();
  EXPECT_EQ(files, 1) << "no temporary files left behind";
}

TEST(SdfCache, UnwritableDirectoryOnlyDisablesCaching) {
  TempDir dir;
  const std::string blocker = write_file(dir.file("a_file"), "x");
  setenv("SUPERDEX_CACHE_DIR", (blocker + "/sub").c_str(), 1);
  const auto grid = cached_sdf(cube_mesh(), {8, 2}, "cube");
  unsetenv("SUPERDEX_CACHE_DIR");
  EXPECT_EQ(grid->size[0], 8 + 4 + 1);
}

TEST(MeshGeometry, ConvexMeshesAreSampledAlongTheirEdges) {
  CacheDir cache;
  const MeshShape shape = make_mesh_shape(cube_mesh(0.5), "cube");
  ASSERT_TRUE(shape.convex);
  const std::vector<Vec3> samples = mesh_surface_samples(shape);
  for (int v = 0; v < 8; ++v) EXPECT_EQ(samples[v], shape.mesh->vertices[v]);
  // vertices and points along the triangle edges (the cube's edges and face diagonals): on a face
  // diagonal at most, never strictly inside a face away from both diagonals
  for (const Vec3& s : samples) {
    const Eigen::Vector3d a = s.cast<double>().cwiseAbs();
    int on_faces = 0;
    for (int k = 0; k < 3; ++k) on_faces += std::abs(a[k] - 0.5) < 1e-9;
    ASSERT_GE(on_faces, 1) << s.transpose();
    if (on_faces == 1) {
      Eigen::Vector2d in_face;
      for (int k = 0, j = 0; k < 3; ++k)
        if (std::abs(a[k] - 0.5) >= 1e-9) in_face[j++] = a[k];
      EXPECT_NEAR(in_face[0], in_face[1], 1e-9) << "off the face diagonals: " << s.transpose();
    }
  }
}

TEST(MeshGeometry, SurfaceSamplesCoverTheSurface) {
  CacheDir cache;
  // sampled as a general (non-convex) mesh: faces too
  MeshShape shape = make_mesh_shape(cube_mesh(0.5), "cube");
  shape.convex = false;
  const std::vector<Vec3> samples = mesh_surface_samples(shape);
  EXPECT_EQ(samples, mesh_surface_samples(shape)) << "deterministic";
  for (int v = 0; v < 8; ++v) EXPECT_EQ(samples[v], shape.mesh->vertices[v]);
  for (const Vec3& s : samples) EXPECT_NEAR(box_distance(s.cast<double>(), Eigen::Vector3d::Constant(0.5)), 0.0, 1e-9);
  // every point of the surface has a sample within a few percent of the size
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-0.5, 0.5);
  for (int n = 0; n < 300; ++n) {
    Eigen::Vector3d p(u(rng), u(rng), u(rng));
    p[n % 3] = n % 2 ? 0.5 : -0.5;
    double nearest = 1e9;
    for (const Vec3& s : samples) nearest = std::min(nearest, (s.cast<double>() - p).norm());
    EXPECT_LT(nearest, 0.04) << p.transpose();
  }
  const Bounds box = mesh_local_aabb(shape);
  EXPECT_TRUE(box.min.isApprox(Vec3::Constant(-0.5)));
  EXPECT_TRUE(box.max.isApprox(Vec3::Constant(0.5)));
}

TEST(MeshMass, CubeMatchesTheBoxFormulas) {
  CacheDir cache;
  // a 1 x 2 x 3 box, rotated and moved: mass, COM and rotated inertia are exact
  TriangleMesh box = cube_mesh(0.5);
  const Quat q(Eigen::AngleAxis<real>(real(0.7), Vec3(1, 2, 3).normalized()));
  const Vec3 t(1, -2, 0.5);
  for (Vec3& v : box.vertices) v = q * v.cwiseProduct(Vec3(1, 2, 3)) + t;
  const ShapeGeometry shape = make_mesh_shape(box, "box");
  EXPECT_NEAR(shape_volume(shape), 6.0, 1e-9);
  const MassProperties mp = shape_mass_properties(shape, 1000);
  EXPECT_NEAR(mp.mass, 6000, 1e-6);
  EXPECT_TRUE(mp.center_of_mass.isApprox(t, 1e-9));
  const Mat3 local = Vec3(mp.mass * (4 + 9) / 12, mp.mass * (1 + 9) / 12, mp.mass * (1 + 4) / 12).asDiagonal();
  const Mat3 want = q.toRotationMatrix() * local * q.toRotationMatrix().transpose();
  EXPECT_LT((mp.inertia_about_com - want).norm(), 1e-6 * want.norm());
}

TEST(MeshMass, IcosphereApproachesTheBall) {
  CacheDir cache;
  const MassProperties mp = shape_mass_properties(make_mesh_shape(icosphere(4, 1.0), "ball"), 1);
  const double volume = 4 * std::numbers::pi / 3;
  EXPECT_NEAR(mp.mass, volume, 0.01 * volume);
  EXPECT_LT(mp.center_of_mass.norm(), 1e-9);
  for (int a = 0; a < 3; ++a) EXPECT_NEAR(mp.inertia_about_com(a, a), 0.4 * volume, 0.02 * 0.4 * volume);
}

TEST(MeshMass, OpenMeshAndBadShapesAreErrors) {
  TriangleMesh open = cube_mesh();
  open.triangles.pop_back();
  const ShapeGeometry shape = make_mesh_shape(open, "open.stl");
  EXPECT_THAT([&] { shape_mass_properties(shape, 1000); },
              ThrowsMessage<Error>(HasSubstr("open.stl: computing mass properties needs a closed mesh: 3 boundary edges")));
  MeshShape bad = std::get<MeshShape>(shape);
  auto mesh = std::make_shared<TriangleMesh>(*bad.mesh);
  mesh->vertices[2].z() = std::numeric_limits<real>::quiet_NaN();
  bad.mesh = mesh;
  EXPECT_THAT([&] { validate_shape(bad, "create_shape"); },
              ThrowsMessage<Error>(HasSubstr("create_shape (open.stl): vertex 2 has a non-finite coordinate")));
}

TEST(MeshShapes, InsideOutMeshIsTurnedRightSideOutAndMarkedConvex) {
  CacheDir cache;
  TriangleMesh cube = cube_mesh();
  for (auto& t : cube.triangles) std::swap(t[1], t[2]);
  const MeshShape shape = make_mesh_shape(cube, "cube");
  EXPECT_GT(signed_volume(*shape.mesh), 0);
  EXPECT_TRUE(shape.convex);
  ASSERT_NE(shape.sdf, nullptr);
  EXPECT_LT(mesh_signed_distance(shape, Vec3::Zero(), nullptr), -0.49);
}

}  // namespace
}  // namespace superdex::physics::test

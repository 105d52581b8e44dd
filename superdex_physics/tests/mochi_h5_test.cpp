/// @file mochi_h5_test.cpp
/// The `.mochi.h5` format: a write/read round trip of every group, the C-order grid layout in
/// the file, shapes made from files (primitives, meshes with stored or computed grids, baking),
/// and malformed files rejected with messages naming the file, the group or attribute and the
/// defect.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdlib>

#include "collision/collision_geometry.h"
#include "io/h5_file.h"
#include "mesh_test_helpers.h"
#include "superdex/physics/error.h"
#include "superdex/physics/mesh_shape.h"
#include "superdex/physics/mochi_h5.h"

namespace superdex::physics::test {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;
using ::testing::ThrowsMessage;

MochiMesh mochi_mesh(const TriangleMesh& m) {
  MochiMesh out;
  out.coordinates = m.vertices;
  for (const auto& t : m.triangles) out.connectivity.insert(out.connectivity.end(), t.begin(), t.end());
  return out;
}

// A 3 x 4 x 5 grid whose value encodes its node: i + 10 j + 100 k.
SdfGrid coded_grid() {
  SdfGrid g;
  g.size = {3, 4, 5};
  g.grid_min = Vec3(-1, -2, -3);
  g.grid_max = Vec3(1, 2, 3);
  for (int k = 0; k < 5; ++k)
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < 3; ++i) g.values.push_back(real(i + 10 * j + 100 * k));
  return g;
}

class MochiH5Test : public ::testing::Test {
 protected:
  void SetUp() override { setenv("SUPERDEX_CACHE_DIR", cache_.path().c_str(), 1); }
  void TearDown() override { unsetenv("SUPERDEX_CACHE_DIR"); }
  TempDir dir_, cache_;
};

TEST_F(MochiH5Test, RoundTripOfEveryGroup) {
  MochiH5 data;
  data.mesh = mochi_mesh(cube_mesh());
  data.mesh->constrained_nodes = {0, 3, 7};
  data.visual_mesh = mochi_mesh(icosphere(1));
  data.sdf = MochiSdf{coded_grid(), Vec3(2, 2, 2), Quat(Eigen::AngleAxis<real>(real(0.3), Vec3::UnitZ())), Vec3(0.1, 0.2, 0.3)};
  data.material = MochiMaterial{"NeoHookean", std::vector<real>(12, real(1e6)), std::vector<real>(12, real(0.3))};
  data.box = BoxShape{Vec3(0.1, 0.2, 0.3)};
  data.sphere = SphereShape{Vec3(0, 0, 1), real(0.25)};
  data.plane = PlaneShape{Vec3(0, 0.6, 0.8), real(1.5)};
  const std::string path = dir_.file("all.mochi.h5");
  write_mochi_h5(path, data);
  const MochiH5 back = read_mochi_h5(path);

  ASSERT_TRUE(back.mesh && back.visual_mesh && back.sdf && back.material && back.box && back.sphere && back.plane);
  EXPECT_EQ(back.mesh->coordinates, data.mesh->coordinates);
  EXPECT_EQ(back.mesh->connectivity, data.mesh->connectivity);
  EXPECT_EQ(back.mesh->nodes_per_element, 3);
  EXPECT_EQ(back.mesh->constrained_nodes, data.mesh->constrained_nodes);
  EXPECT_EQ(back.visual_mesh->coordinates, data.visual_mesh->coordinates);
  EXPECT_EQ(back.visual_mesh->connectivity, data.visual_mesh->connectivity);
  EXPECT_EQ(back.sdf->grid.size, data.sdf->grid.size);
  EXPECT_EQ(back.sdf->grid.values, data.sdf->grid.values);
  EXPECT_EQ(back.sdf->grid.grid_min, data.sdf->grid.grid_min);
  EXPECT_EQ(back.sdf->grid.grid_max, data.sdf->grid.grid_max);
  EXPECT_EQ(*back.sdf->scale, *data.sdf->scale);
  EXPECT_TRUE(back.sdf->rotation->isApprox(*data.sdf->rotation));
  EXPECT_EQ(*back.sdf->translation, *data.sdf->translation);
  EXPECT_EQ(back.material->type, "NeoHookean");
  EXPECT_EQ(back.material->youngs_modulus, data.material->youngs_modulus);
  EXPECT_EQ(back.material->poisson_ratio, data.material->poisson_ratio);
  EXPECT_EQ(back.box->half_extents, data.box->half_extents);
  EXPECT_EQ(back.sphere->center, data.sphere->center);
  EXPECT_EQ(back.sphere->radius, data.sphere->radius);
  EXPECT_TRUE(back.plane->normal.isApprox(data.plane->normal));
  EXPECT_NEAR(back.plane->distance, data.plane->distance, 1e-12);
}

TEST_F(MochiH5Test, GridIsStoredCOrderInTheFile) {
  MochiH5 data;
  data.sdf = MochiSdf{coded_grid(), {}, {}, {}};
  const std::string path = dir_.file("grid.mochi.h5");
  write_mochi_h5(path, data);
  auto guard = h5::lock();
  const h5::Numbers grid = h5::Reader(path).dataset("sdf/grid", false);
  ASSERT_EQ(grid.dims, (std::vector<hsize_t>{3, 4, 5}));
  // file index (i * ny + j) * nz + k holds node (i, j, k)
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 4; ++j)
      for (int k = 0; k < 5; ++k) EXPECT_EQ(grid.values[(i * 4 + j) * 5 + k], i + 10 * j + 100 * k);
}

TEST_F(MochiH5Test, PrimitiveFilesGivePrimitives) {
  MochiH5 box, sphere, plane;
  box.box = BoxShape{Vec3(0.1, 0.2, 0.3)};
  sphere.sphere = SphereShape{Vec3::Zero(), real(0.5)};
  plane.plane = PlaneShape{Vec3::UnitZ(), real(-1)};
  write_mochi_h5(dir_.file("box.mochi.h5"), box);
  write_mochi_h5(dir_.file("sphere.mochi.h5"), sphere);
  write_mochi_h5(dir_.file("plane.mochi.h5"), plane);
  const ShapeGeometry b = load_shape_file(dir_.file("box.mochi.h5"), {Vec3(2, 2, 2)});
  EXPECT_TRUE(std::get<BoxShape>(b).half_extents.isApprox(Vec3(0.2, 0.4, 0.6)));
  ShapeBake moved;
  moved.translation = Vec3(0, 0, 1);
  const ShapeGeometry s = shape_from_mochi_h5(dir_.file("sphere.mochi.h5"), moved);
  EXPECT_EQ(std::get<SphereShape>(s).radius, real(0.5));
  EXPECT_EQ(std::get<SphereShape>(s).center, Vec3(0, 0, 1));
  const ShapeGeometry p = shape_from_mochi_h5(dir_.file("plane.mochi.h5"), moved);
  EXPECT_NEAR(std::get<PlaneShape>(p).distance, 0.0, 1e-12);
  // a moved box becomes a closed mesh with a distance field
  const ShapeGeometry mb = shape_from_mochi_h5(dir_.file("box.mochi.h5"), moved);
  const MeshShape& mesh = std::get<MeshShape>(mb);
  ASSERT_NE(mesh.sdf, nullptr);
  // within half a cell (0.6 / 32 m) of the distance to the nearest face
  EXPECT_NEAR(mesh_signed_distance(mesh, Vec3(0, 0, 1), nullptr), -0.1, 0.01);
  EXPECT_NEAR(shape_volume(mb), 8 * 0.1 * 0.2 * 0.3, 1e-9);
}

TEST_F(MochiH5Test, MeshFilesUseTheStoredGridOrComputeOne) {
  MochiH5 with_grid;
  with_grid.mesh = mochi_mesh(cube_mesh());
  with_grid.sdf = MochiSdf{coded_grid(), {}, {}, {}};
  write_mochi_h5(dir_.file("stored.mochi.h5"), with_grid);
  const MeshShape stored = std::get<MeshShape>(shape_from_mochi_h5(dir_.file("stored.mochi.h5")));
  EXPECT_EQ(stored.sdf->values, coded_grid().values);
  EXPECT_TRUE(stored.convex);
  EXPECT_EQ(stored.source, dir_.file("stored.mochi.h5"));

  // a uniform scale and a translation move the stored grid with the mesh
  ShapeBake bake;
  bake.scale = Vec3::Constant(2);
  bake.translation = Vec3(1, 0, 0);
  const MeshShape baked = std::get<MeshShape>(shape_from_mochi_h5(dir_.file("stored.mochi.h5"), bake));
  EXPECT_TRUE(baked.sdf->grid_min.isApprox(Vec3(-1, -4, -6)));
  EXPECT_EQ(baked.sdf->values[1], 2 * coded_grid().values[1]);

  MochiH5 plain;
  plain.mesh = mochi_mesh(icosphere(2));
  write_mochi_h5(dir_.file("plain.mochi.h5"), plain);
  const MeshShape computed = std::get<MeshShape>(shape_from_mochi_h5(dir_.file("plain.mochi.h5")));
  ASSERT_NE(computed.sdf, nullptr);
  EXPECT_NEAR(mesh_signed_distance(computed, Vec3::Zero(), nullptr), -0.99, 0.02);
}

TEST_F(MochiH5Test, TetrahedraAreNotRigidShapes) {
  MochiH5 tet;
  tet.mesh = MochiMesh{{Vec3::Zero(), Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ()}, 4, {0, 1, 2, 3}, {}};
  write_mochi_h5(dir_.file("tet.mochi.h5"), tet);
  EXPECT_EQ(read_mochi_h5(dir_.file("tet.mochi.h5")).mesh->nodes_per_element, 4);
  EXPECT_THAT([&] { shape_from_mochi_h5(dir_.file("tet.mochi.h5")); },
              ThrowsMessage<Error>(AllOf(HasSubstr("tet.mochi.h5"), HasSubstr("tet meshes become soft bodies, not rigid shapes"))));
}

// Writes an sdf/ group with the given attribute values (empty = omitted) and grid dims.
std::string sdf_file(const TempDir& dir, const std::string& name, const std::vector<double>& grid_min, const std::vector<double>& grid_max,
                     const std::vector<hsize_t>& dims = {2, 2, 2}, double fill = 1.0) {
  const std::string path = dir.file(name);
  auto guard = h5::lock();
  h5::Writer w(path);
  w.group("sdf");
  size_t n = 1;
  for (hsize_t d : dims) n *= d;
  w.dataset("sdf/grid", dims, std::vector<double>(n, fill));
  if (!grid_min.empty()) w.attribute("sdf", "grid_min", grid_min);
  if (!grid_max.empty()) w.attribute("sdf", "grid_max", grid_max);
  w.close();
  return path;
}

TEST_F(MochiH5Test, MalformedSdfGroups) {
  const std::vector<double> lo{0, 0, 0}, hi{1, 1, 1};
  auto read = [](const std::string& p) { return [p] { read_mochi_h5(p); }; };
  EXPECT_THAT(error_of(read(sdf_file(dir_, "a.mochi.h5", {}, hi))), AllOf(HasSubstr("a.mochi.h5: sdf/grid_min: missing attribute")));
  EXPECT_THAT(error_of(read(sdf_file(dir_, "b.mochi.h5", {0, 0}, hi))), HasSubstr("b.mochi.h5: sdf/grid_min: wrong shape: expected 3 values, got 2"));
  EXPECT_THAT(error_of(read(sdf_file(dir_, "c.mochi.h5", lo, {1, 0, 1}))),
              HasSubstr("c.mochi.h5: sdf: grid_min must be < grid_max on every axis, got grid_min [0, 0, 0] and grid_max [1, 0, 1]"));
  EXPECT_THAT(error_of(read(sdf_file(dir_, "d.mochi.h5", lo, hi, {4, 4}))), HasSubstr("d.mochi.h5: sdf/grid: wrong rank: expected a 3-D dataset"));
  EXPECT_THAT(error_of(read(sdf_file(dir_, "e.mochi.h5", lo, hi, {2, 1, 2}))), HasSubstr("sdf/grid: wrong shape: every dimension must be at least 2"));
  EXPECT_THAT(error_of(read(sdf_file(dir_, "f.mochi.h5", lo, hi, {2, 2, 2}, std::nan("")))), HasSubstr("f.mochi.h5: sdf/grid: NaN at [0, 0, 0]"));
  EXPECT_THAT(error_of(read(sdf_file(dir_, "g.mochi.h5", lo, {1, std::nan(""), 1}))), HasSubstr("sdf/grid_max: NaN at index 1"));
  {
    auto guard = h5::lock();
    h5::Writer w(dir_.file("h.mochi.h5"));
    w.group("sdf");
    w.dataset("sdf/grid", {2, 2, 2}, std::vector<double>(8, 0.0));
    w.string_attribute("sdf", "grid_min", "zero");
    w.attribute("sdf", "grid_max", hi);
    w.close();
  }
  EXPECT_THAT(error_of(read(dir_.file("h.mochi.h5"))), HasSubstr("h.mochi.h5: sdf/grid_min: wrong type: expected numbers, got a string"));
  // an sdf alone is no shape
  EXPECT_THAT(error_of([&] { shape_from_mochi_h5(sdf_file(dir_, "i.mochi.h5", lo, hi)); }), HasSubstr("sdf/ without mesh/"));
}

TEST_F(MochiH5Test, MalformedMeshGroups) {
  auto write = [&](const std::string& name, const std::vector<hsize_t>& cdims, const std::vector<double>& coords,
                   const std::vector<hsize_t>& edims, const std::vector<int>& conn, bool float_connectivity = false) {
    const std::string path = dir_.file(name);
    auto guard = h5::lock();
    h5::Writer w(path);
    w.group("mesh");
    w.dataset("mesh/coordinates", cdims, coords);
    if (float_connectivity) w.dataset("mesh/connectivity", edims, std::vector<double>(conn.begin(), conn.end()));
    else if (!conn.empty() || !edims.empty()) w.dataset("mesh/connectivity", edims, conn);
    w.close();
    return path;
  };
  const std::vector<double> tri{0, 0, 0, 1, 0, 0, 0, 1, 0};
  auto read = [](const std::string& p) { return [p] { read_mochi_h5(p); }; };
  EXPECT_THAT(error_of(read(write("a.mochi.h5", {3, 3}, tri, {}, {}))), HasSubstr("a.mochi.h5: mesh/connectivity: missing dataset"));
  EXPECT_THAT(error_of(read(write("b.mochi.h5", {3, 3}, tri, {1, 3}, {0, 1, 2}, true))),
              HasSubstr("b.mochi.h5: mesh/connectivity: wrong type: expected integers, got floating-point numbers"));
  EXPECT_THAT(error_of(read(write("c.mochi.h5", {9}, tri, {1, 3}, {0, 1, 2}))), HasSubstr("mesh/coordinates: wrong rank: expected a 2-D dataset N x 3"));
  EXPECT_THAT(error_of(read(write("d.mochi.h5", {3, 3}, tri, {1, 3}, {0, 1, 3}))),
              HasSubstr("d.mochi.h5: mesh/connectivity: index 3 at row 0 out of range: the mesh has 3 nodes"));
  EXPECT_THAT(error_of(read(write("e.mochi.h5", {3, 3}, {0, 0, 0, 1, std::nan(""), 0, 0, 1, 0}, {1, 3}, {0, 1, 2}))),
              HasSubstr("e.mochi.h5: mesh/coordinates: NaN at row 1, column 1"));
  EXPECT_THAT(error_of(read(write("f.mochi.h5", {0, 3}, {}, {1, 3}, {0, 1, 2}))), HasSubstr("f.mochi.h5: mesh/coordinates: empty mesh"));
  EXPECT_THAT(error_of(read(write("g.mochi.h5", {3, 3}, tri, {1, 5}, {0, 1, 2, 0, 1}))),
              HasSubstr("mesh/connectivity: wrong shape: expected M x 2 (a rod's polyline), M x 3 (triangles) or M x 4 (tetrahedra), got [1, 5]"));
  // a degenerate triangle is caught when the file becomes a shape
  EXPECT_THAT(error_of([&] { shape_from_mochi_h5(write("h.mochi.h5", {3, 3}, {0, 0, 0, 1, 0, 0, 2, 0, 0}, {1, 3}, {0, 1, 2})); }),
              HasSubstr("h.mochi.h5: mesh/: 1 degenerate (zero-area) triangle; the first is triangle 0"));
}

TEST_F(MochiH5Test, UnreadableFilesAndOtherGroups) {
  EXPECT_THAT(error_of([&] { read_mochi_h5(dir_.file("missing.mochi.h5")); }), HasSubstr("missing.mochi.h5: file not found"));
  write_file(dir_.file("text.mochi.h5"), "hello");
  EXPECT_THAT(error_of([&] { read_mochi_h5(dir_.file("text.mochi.h5")); }), HasSubstr("text.mochi.h5: not an HDF5 file"));
  {
    auto guard = h5::lock();
    h5::Writer w(dir_.file("mat.mochi.h5"));
    w.group("material");
    w.attribute("material", "type", {1.0});
    w.group("box");
    w.attribute("box", "half_extents", {1, -1, 1});
    w.close();
  }
  EXPECT_THAT(error_of([&] { read_mochi_h5(dir_.file("mat.mochi.h5")); }), HasSubstr("material/type: wrong type: expected a string, got floating-point numbers"));
  MochiH5 two;
  two.box = BoxShape{Vec3::Ones()};
  two.sphere = SphereShape{Vec3::Zero(), 1};
  write_mochi_h5(dir_.file("two.mochi.h5"), two);
  EXPECT_THAT(error_of([&] { shape_from_mochi_h5(dir_.file("two.mochi.h5")); }), HasSubstr("several primitive groups"));
  MochiH5 empty;
  write_mochi_h5(dir_.file("empty.mochi.h5"), empty);
  EXPECT_THAT(error_of([&] { shape_from_mochi_h5(dir_.file("empty.mochi.h5")); }), HasSubstr("empty.mochi.h5: no shape"));
  EXPECT_THAT(error_of([&] { load_shape_file(dir_.file("shape.fbx")); }), HasSubstr("unknown shape file extension '.fbx'"));
}

}  // namespace
}  // namespace superdex::physics::test

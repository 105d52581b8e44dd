/// @file convex_hull_test.cpp
/// Convex hulls against shapes whose hull is known: a cube from its corners among interior,
/// duplicate and face points; an icosphere (every vertex extreme); an open box; and the inputs
/// that span no volume.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <random>

#include "mesh_test_helpers.h"
#include "superdex/physics/convex_hull.h"
#include "superdex/physics/mesh_validation.h"

namespace superdex::physics::test {
namespace {

using ::testing::HasSubstr;

// Largest signed distance of any point above any of the hull's triangle planes (m): <= 0 when
// the hull contains them all.
double max_outside(const TriangleMesh& hull, const std::vector<Vec3>& points) {
  double worst = -1e300;
  for (const auto& t : hull.triangles) {
    const Eigen::Vector3d a = hull.vertices[t[0]].cast<double>(), b = hull.vertices[t[1]].cast<double>(),
                          c = hull.vertices[t[2]].cast<double>();
    const Eigen::Vector3d n = (b - a).cross(c - a).normalized();
    for (const Vec3& p : points) worst = std::max(worst, n.dot(p.cast<double>() - a));
  }
  return worst;
}

TEST(ConvexHull, CubeFromCornersAmongInteriorDuplicateAndFacePoints) {
  std::vector<Vec3> points = cube_mesh(0.5).vertices;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-0.5, 0.5);
  for (int i = 0; i < 200; ++i) points.push_back(Vec3(real(u(rng) * 0.99), real(u(rng) * 0.99), real(u(rng) * 0.99)));
  for (int i = 0; i < 8; ++i) points.push_back(points[static_cast<size_t>(i)]);  // duplicates
  points.push_back(Vec3(0, 0, real(0.5)));                                       // on a face
  const TriangleMesh hull = convex_hull(points, "cube points");
  EXPECT_TRUE(is_closed(hull));
  EXPECT_TRUE(is_convex(hull));
  EXPECT_NEAR(signed_volume(hull), 1.0, 1e-6);  // positive: counter-clockwise seen from outside
  EXPECT_LE(max_outside(hull, points), 1e-6);
  // the 8 corners, plus at most one centroid per square face (its two triangles may be merged)
  EXPECT_GE(hull.vertices.size(), 8u);
  EXPECT_LE(hull.vertices.size(), 14u);
  for (const Vec3& v : hull.vertices) EXPECT_NEAR(v.cwiseAbs().maxCoeff(), 0.5, 1e-6) << v.transpose();
  EXPECT_TRUE(degenerate_triangles(hull).empty());
}

TEST(ConvexHull, IcosphereKeepsEveryVertexAndItsVolume) {
  const TriangleMesh sphere = icosphere(3, 0.2);
  const TriangleMesh hull = convex_hull(sphere.vertices, "icosphere");
  EXPECT_TRUE(is_closed(hull));
  EXPECT_EQ(hull.vertices.size(), sphere.vertices.size());
  EXPECT_EQ(hull.triangles.size(), sphere.triangles.size());
  EXPECT_NEAR(signed_volume(hull), signed_volume(sphere), 1e-12);
}

TEST(ConvexHull, OpenBoxBecomesTheClosedBox) {
  TriangleMesh open = cube_mesh(0.25, Vec3(1, 2, 3));
  open.triangles.resize(10);  // the last face's two triangles dropped: an open box
  ASSERT_FALSE(is_closed(open));
  const TriangleMesh hull = convex_hull(open.vertices, "open box");
  EXPECT_TRUE(is_closed(hull));
  EXPECT_NEAR(signed_volume(hull), 0.125, 1e-9);
}

TEST(ConvexHull, PointsSpanningNoVolumeAreRejected) {
  const std::vector<Vec3> flat = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(1, 1, 0), Vec3(real(0.5), real(0.2), 0)};
  EXPECT_THAT(error_of([&] { convex_hull(flat, "plate.stl"); }), HasSubstr("plate.stl: no convex hull: the points span no volume"));
  EXPECT_THAT(error_of([&] { convex_hull({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)}, "tri"); }), HasSubstr("tri: a convex hull needs at least 4 points"));
  std::vector<Vec3> bad = cube_mesh().vertices;
  bad[3].x() = std::numeric_limits<real>::quiet_NaN();
  EXPECT_THAT(error_of([&] { convex_hull(bad, "nan"); }), HasSubstr("nan: a convex hull needs finite points"));
}

}  // namespace
}  // namespace superdex::physics::test

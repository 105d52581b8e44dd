/// @file contact_reduction_test.cpp
/// A shape pair's contacts cut down to a manifold: a flat patch keeps its corners and its
/// deepest point, points facing other ways are kept apart, small sets are untouched.

#include <gtest/gtest.h>

#include <algorithm>

#include "collision/collision_detection.h"

namespace superdex::physics::test {
namespace {

bool has_point(const std::vector<ShapeContact>& c, const Vec3& p) {
  return std::any_of(c.begin(), c.end(), [&](const ShapeContact& x) { return (x.p_W - p).norm() < 1e-6; });
}

TEST(ContactReduction, FlatPatchKeepsCornersAndDeepestInOrder) {
  // a 21 x 21 grid on z = 0 (0.01 m apart), all 1 mm deep but one interior point at 3 mm
  std::vector<ShapeContact> points;
  for (int i = 0; i <= 20; ++i)
    for (int j = 0; j <= 20; ++j) points.push_back({Vec3(real(0.01 * i), real(0.01 * j), 0), Vec3::UnitZ(), real(-0.001)});
  const Vec3 deep(real(0.07), real(0.13), 0);
  for (auto& p : points)
    if ((p.p_W - deep).norm() < 1e-9) p.phi = real(-0.003);
  const std::vector<ShapeContact> all = points;
  reduce_contacts(points, 12);
  ASSERT_EQ(points.size(), 12u);
  for (const Vec3& corner : {Vec3(0, 0, 0), Vec3(real(0.2), 0, 0), Vec3(0, real(0.2), 0), Vec3(real(0.2), real(0.2), 0)})
    EXPECT_TRUE(has_point(points, corner)) << corner.transpose();
  EXPECT_TRUE(has_point(points, deep));
  // kept in the order they came
  size_t last = 0;
  for (const ShapeContact& p : points) {
    const size_t at = static_cast<size_t>(std::find_if(all.begin(), all.end(), [&](const ShapeContact& a) { return (a.p_W - p.p_W).norm() < 1e-9; }) - all.begin());
    EXPECT_GE(at, last);
    last = at;
  }
}

TEST(ContactReduction, PointsFacingOtherWaysAreKept) {
  // a dense floor patch and, at its centre, a few points on a wall facing +x
  std::vector<ShapeContact> points;
  for (int i = 0; i <= 10; ++i)
    for (int j = 0; j <= 10; ++j) points.push_back({Vec3(real(0.01 * i), real(0.01 * j), 0), Vec3::UnitZ(), real(-0.001)});
  for (int k = 0; k < 3; ++k) points.push_back({Vec3(real(0.05), real(0.05), real(0.001 * k)), Vec3::UnitX(), real(-0.001)});
  reduce_contacts(points, 8);
  EXPECT_TRUE(std::any_of(points.begin(), points.end(), [](const ShapeContact& c) { return c.n_W.x() > real(0.5); }));
}

TEST(ContactReduction, SmallSetsAreUntouched) {
  std::vector<ShapeContact> points = {{Vec3(0, 0, 0), Vec3::UnitZ(), real(-0.001)}, {Vec3(1, 0, 0), Vec3::UnitZ(), real(-0.002)}};
  reduce_contacts(points, 12);
  ASSERT_EQ(points.size(), 2u);
  EXPECT_EQ(points[1].phi, real(-0.002));
}

}  // namespace
}  // namespace superdex::physics::test

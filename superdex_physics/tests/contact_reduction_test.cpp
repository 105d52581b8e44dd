/// @file contact_reduction_test.cpp
/// A shape pair's contacts cut down to a manifold: a flat patch keeps its corners and its
/// deepest point, points facing other ways are kept apart, small sets are untouched. Thousands of
/// points are first thinned to the deepest per grid cell and normal direction (the earliest of
/// equally deep ones, a NaN depth the shallowest), in their order: checked against a reference
/// that groups them in a std::map.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>

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

TEST(ContactReduction, ThinningKeepsTheDeepestPerCellAndDirection) {
  // 5000 points on a 0.2 m x 0.1 m patch at z = 0, normals up or down, depths on a few levels
  // (ties), a few NaN; at most 17 x 17 x 2 keys survive, fewer than max_points, so the thinned
  // set is the result
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<ShapeContact> points;
  for (int i = 0; i < 5000; ++i) {
    const real phi = i % 97 == 0 ? std::numeric_limits<real>::quiet_NaN() : real(-0.001 * std::floor(4 * u(rng)));
    points.push_back({Vec3(real(0.2 * u(rng)), real(0.1 * u(rng)), 0), u(rng) < 0.5 ? Vec3::UnitZ() : Vec3(-Vec3::UnitZ()), phi});
  }
  // the reference: per key the first point of least depth
  Vec3 lo = points[0].p_W, hi = points[0].p_W;
  for (const ShapeContact& p : points) lo = lo.cwiseMin(p.p_W), hi = hi.cwiseMax(p.p_W);
  const real cell = (hi - lo).norm() / 16;
  std::map<std::array<int, 4>, size_t> deepest;
  for (size_t i = 0; i < points.size(); ++i) {
    const ShapeContact& p = points[i];
    std::array<int, 4> key{};
    for (int a = 0; a < 3; ++a) key[a] = std::min(16, static_cast<int>(std::floor((p.p_W[a] - lo[a]) / cell)));
    key[3] = p.n_W.z() < 0;
    const auto depth = [](real phi) { return std::isnan(phi) ? std::numeric_limits<real>::infinity() : phi; };
    auto [it, fresh] = deepest.emplace(key, i);
    if (!fresh && depth(p.phi) < depth(points[it->second].phi)) it->second = i;
  }
  std::vector<size_t> kept;
  for (const auto& [key, i] : deepest) kept.push_back(i);
  std::sort(kept.begin(), kept.end());
  ASSERT_LE(kept.size(), 600u);
  std::vector<ShapeContact> reduced = points;
  reduce_contacts(reduced, 600);
  ASSERT_EQ(reduced.size(), kept.size());
  for (size_t k = 0; k < kept.size(); ++k) {
    EXPECT_EQ(reduced[k].p_W, points[kept[k]].p_W) << k;
    EXPECT_EQ(reduced[k].n_W, points[kept[k]].n_W) << k;
  }
  // a second call (the working storage reused) gives the same
  std::vector<ShapeContact> again = points;
  reduce_contacts(again, 600);
  ASSERT_EQ(again.size(), reduced.size());
  for (size_t k = 0; k < again.size(); ++k) EXPECT_EQ(again[k].p_W, reduced[k].p_W) << k;
}

}  // namespace
}  // namespace superdex::physics::test

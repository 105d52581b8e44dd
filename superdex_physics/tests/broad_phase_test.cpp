/// @file broad_phase_test.cpp
/// The broad phase: a collider's world bounds enclose exactly its posed corners, and its sweep
/// bound uses the bounds' corner farthest from the link origin.

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "collision_detection.h"
#include "scene_data.h"

namespace superdex::physics::test {
namespace {

// The eight corners of local bounds.
std::array<Vec3, 8> corners(const Aabb& box) {
  std::array<Vec3, 8> out;
  for (int k = 0; k < 8; ++k)
    out[k] = Vec3(k & 1 ? box.max.x() : box.min.x(), k & 2 ? box.max.y() : box.min.y(), k & 4 ? box.max.z() : box.min.z());
  return out;
}

SpatialTransform random_pose(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1, 1);
  const Vec3 axis = Vec3(u(rng), u(rng), u(rng)).normalized();
  return {Quat(Eigen::AngleAxis<real>(3 * u(rng), axis)).toRotationMatrix(), Vec3(u(rng), u(rng), u(rng))};
}

Aabb random_bounds(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1, 1), size(0.01, 0.5);
  Aabb box;
  box.min = Vec3(u(rng), u(rng), u(rng));
  box.max = box.min + Vec3(size(rng), size(rng), size(rng));
  return box;
}

TEST(BroadPhase, WorldBoundsAreTheBoundsOfThePosedCorners) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 50; ++trial) {
    const Aabb local = random_bounds(rng);
    const SpatialTransform X = random_pose(rng);
    Aabb expected;
    for (const Vec3& c : corners(local)) expected.extend(X.R * c + X.p);
    const Aabb bounds = world_bounds(local, X);
    EXPECT_LT((bounds.min - expected.min).norm(), 1e-12) << "trial " << trial;
    EXPECT_LT((bounds.max - expected.max).norm(), 1e-12) << "trial " << trial;
  }
}

TEST(BroadPhase, SweepBoundIsSpeedPlusAngularSpeedTimesTheFarthestCorner) {
  std::mt19937 rng(11);
  const real dt = real(0.004);
  for (int trial = 0; trial < 50; ++trial) {
    LinkCollider col;
    col.shape = BoxShape{Vec3(0.1, 0.2, 0.3)};
    col.aabb_S = random_bounds(rng);
    col.X_LS = random_pose(rng);
    Articulation a;
    a.model.nv = 6;
    const Vec6 V = Vec6::Random();
    a.kin.V_L = {V};
    double reach = 0;
    for (const Vec3& c : corners(col.aabb_S)) reach = std::max(reach, static_cast<double>((col.X_LS.R * c + col.X_LS.p).norm()));
    const double expected = dt * (V.head<3>().norm() + V.tail<3>().norm() * reach);
    EXPECT_NEAR(collider_sweep(a, col, dt), expected, 1e-12) << "trial " << trial;
  }
}

}  // namespace
}  // namespace superdex::physics::test

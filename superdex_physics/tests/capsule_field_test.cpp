/// @file capsule_field_test.cpp
/// A capsule against a box touches it through the balls along its core, no further apart than
/// its radius. The narrow phase skips the balls that the distance it measured at a neighbour
/// proves out of contact; over many poses around the box (crossing a face, an edge, grazing the
/// margin, far) its contacts must be exactly those of every ball queried, with the box's distance
/// computed here from its definition.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "collision/collision_detection.h"

namespace superdex::physics::test {
namespace {

// Signed distance from p (box frame) to the box of half extents h: outside, the Euclidean
// distance to its nearest point; inside, minus the distance to its nearest face.
real box_distance_reference(const Vec3& h, const Vec3& p) {
  Vec3 nearest;
  for (int i = 0; i < 3; ++i) nearest[i] = std::clamp(p[i], -h[i], h[i]);
  if (nearest != p) return (p - nearest).norm();
  real inside = std::numeric_limits<real>::infinity();
  for (int i = 0; i < 3; ++i) inside = std::min(inside, h[i] - std::abs(p[i]));
  return -inside;
}

struct ExpectedContact {
  Vec3 centre_W;
  real phi;
};

// Every ball of the capsule (ends, and interior balls no further apart than the radius, at most
// 16 segments) against a field given as a world-point distance: those within the margin.
template <class Distance>
std::vector<ExpectedContact> every_ball(const CapsuleShape& cap, const SpatialTransform& X_WC, real margin, Distance distance_W) {
  const int segments = std::min(16, std::max(1, static_cast<int>(std::ceil(2 * cap.half_length / cap.radius))));
  std::vector<ExpectedContact> out;
  for (int k = 0; k <= segments; ++k) {
    const Vec3 c_W = X_WC.R * Vec3(0, 0, -cap.half_length + 2 * cap.half_length * k / segments) + X_WC.p;
    const real phi = distance_W(c_W) - cap.radius;
    if (phi < margin) out.push_back({c_W, phi});
  }
  return out;
}

SpatialTransform random_pose(std::mt19937& rng, real spread) {
  std::uniform_real_distribution<real> u(-1, 1);
  const Vec3 axis = Vec3(u(rng), u(rng), u(rng)).normalized();
  return {Quat(Eigen::AngleAxis<real>(3 * u(rng), axis)).toRotationMatrix(), spread * Vec3(u(rng), u(rng), u(rng))};
}

// Checks the narrow phase's contacts (a = capsule, b = field) and the swapped call against the
// expected ones: same count, phi, and points on the line through each expected centre.
void expect_same(const LinkCollider& capsule, const SpatialTransform& X_WC, const LinkCollider& field,
                 const SpatialTransform& X_WF, real margin, const std::vector<ExpectedContact>& expected, int pose) {
  for (const bool swapped : {false, true}) {
    std::vector<ShapeContact> got;
    if (swapped) collide_shapes(field, X_WF, capsule, X_WC, margin, got);
    else collide_shapes(capsule, X_WC, field, X_WF, margin, got);
    ASSERT_EQ(got.size(), expected.size()) << "pose " << pose << (swapped ? " (swapped)" : "");
    const real r = std::get<CapsuleShape>(capsule.shape).radius;
    for (size_t i = 0; i < got.size(); ++i) {
      EXPECT_NEAR(got[i].phi, expected[i].phi, 1e-12) << "pose " << pose;
      // the point lies r + phi / 2 from the ball's centre, against the normal (from the field
      // to the capsule; flipped when the capsule is b)
      const Vec3 n = swapped ? Vec3(-got[i].n_W) : got[i].n_W;
      EXPECT_LT((got[i].p_W - (expected[i].centre_W - n * (r + expected[i].phi / 2))).norm(), 1e-12) << "pose " << pose;
    }
  }
}

TEST(CapsuleAgainstField, SkippingBallsKeepsExactlyTheContactsOfEveryBall) {
  std::mt19937 rng(7);
  LinkCollider box;
  const Vec3 h(0.06, 0.04, 0.09);
  box.shape = BoxShape{h};
  LinkCollider capsule;
  std::uniform_real_distribution<real> unit(0, 1);
  int touching = 0, partial = 0;
  for (int pose = 0; pose < 4000; ++pose) {
    // capsules of 2 to 17 balls, posed all around the box and through it
    const CapsuleShape cap{real(0.005) + real(0.02) * unit(rng), real(0.01) + real(0.15) * unit(rng)};
    capsule.shape = cap;
    const SpatialTransform X_WB = random_pose(rng, 0.05);
    const SpatialTransform X_WC = random_pose(rng, 0.2);
    const real margin = pose % 2 ? real(0.01) : real(0);
    const auto expected = every_ball(cap, X_WC, margin, [&](const Vec3& p_W) {
      return box_distance_reference(h, X_WB.R.transpose() * (p_W - X_WB.p));
    });
    touching += !expected.empty();
    const int segments = std::min(16, std::max(1, static_cast<int>(std::ceil(2 * cap.half_length / cap.radius))));
    partial += !expected.empty() && static_cast<int>(expected.size()) <= segments;
    expect_same(capsule, X_WC, box, X_WB, margin, expected, pose);
  }
  // the poses cover capsules clear of the box, and capsules with some of their balls in contact
  EXPECT_GT(touching, 400);
  EXPECT_GT(partial, 300);
}

}  // namespace
}  // namespace superdex::physics::test

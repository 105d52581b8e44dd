/// @file constraint_terms_test.cpp
/// A constraint's rows are the rates of its deviation: for every kind, sides at random frames
/// moving at random spatial velocities, the deviation's change over a short time (central
/// differences of the deviation of the moved frames) equals minus each row's rate g_a . V_a +
/// g_b . V_b (equalities: the deviation closes at the row's rate), or plus it (limits: C grows at
/// the rate). Exact for points; rotations match to first order in the deviation's angle.

#include <gtest/gtest.h>

#include <random>

#include "constraint/constraint_terms.h"
#include "core/spatial.h"

namespace superdex::physics {
namespace {

struct Motion {
  Vec6 V;     // the link origin's velocity and the angular velocity (world)
  Vec3 v_node;  // a node side's velocity
};

// The side moved for a time h at its motion.
ConstraintSide moved(const ConstraintSide& s, const Motion& m, real h) {
  ConstraintSide out = s;
  out.X_WL.translation += h * m.V.head<3>();
  out.X_WL.rotation = (quat_exp(h * m.V.tail<3>()) * s.X_WL.rotation).normalized();
  out.node_W += h * m.v_node;
  return out;
}

class ConstraintRates : public ::testing::Test {
 protected:
  std::mt19937 rng{7};
  real uniform(real lo, real hi) { return std::uniform_real_distribution<real>(lo, hi)(rng); }
  Vec3 vec(real scale) { return Vec3(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)) * scale; }

  ConstraintSide side() {
    ConstraintSide s;
    s.body = 0;
    s.X_WL = {quat_exp(vec(2)), vec(1)};
    s.node_W = vec(1);
    return s;
  }
  Motion motion() { return {(Vec6() << vec(1), vec(1)).finished(), vec(1)}; }

  // Checks each row of `c` against the deviation's central difference; `components` maps row k
  // to its deviation component and sign (+1 limits, -1 equalities); `tolerance` relative to
  // the rate's scale.
  void expect_rates(const ConstraintRecord& c, ConstraintSide a, ConstraintSide b, const std::vector<std::pair<int, real>>& components,
                    real tolerance) {
    ConstraintTerms t;
    t.a = a, t.b = b;
    constraint_terms(c, real(0.01), t);
    ASSERT_EQ(t.rows.size(), components.size()) << constraint_type_name(c.type);
    const Motion ma = motion(), mb = motion();
    const real h = real(1e-6);
    const std::vector<real> plus = constraint_deviation(c, moved(a, ma, h), moved(b, mb, h));
    const std::vector<real> minus = constraint_deviation(c, moved(a, ma, -h), moved(b, mb, -h));
    for (size_t k = 0; k < t.rows.size(); ++k) {
      const ConstraintRow& row = t.rows[k];
      const auto [i, sign] = components[k];
      const real rate = row.g_a.dot(a.soft >= 0 ? (Vec6() << ma.v_node, Vec3::Zero()).finished() : ma.V) +
                        row.g_b.dot(b.soft >= 0 ? (Vec6() << mb.v_node, Vec3::Zero()).finished() : mb.V);
      const real change = (plus[i] - minus[i]) / (2 * h);
      EXPECT_NEAR(change, sign * rate, tolerance * (1 + std::abs(rate))) << constraint_type_name(c.type) << " row " << k;
    }
  }
};

ConstraintRecord record(ConstraintType type) {
  ConstraintRecord c;
  c.type = type;
  c.stiffness = 100, c.damping = 1;
  return c;
}

TEST_F(ConstraintRates, PointConstraintsCloseAtTheirRowsRates) {
  for (int trial = 0; trial < 20; ++trial) {
    const ConstraintSide a = side(), b = side();
    ConstraintRecord pivot = record(ConstraintType::RigidPivotPosition);
    pivot.p_A = vec(0.3), pivot.target_position = pivot.old_target_position = vec(1);
    expect_rates(pivot, a, {}, {{0, -1}, {1, -1}, {2, -1}}, 1e-6);
    ConstraintRecord target = record(ConstraintType::RigidPivotToRigidTarget);
    target.p_A = vec(0.3), target.target_transform = target.old_target_transform = {quat_exp(vec(1)), vec(1)};
    expect_rates(target, a, {}, {{0, -1}, {1, -1}, {2, -1}}, 1e-6);
    ConstraintRecord ball = record(ConstraintType::RigidSphericalJoint);
    ball.p_A = vec(0.3), ball.p_B = vec(0.3);
    ball.actor_b = 1;
    expect_rates(ball, a, b, {{0, -1}, {1, -1}, {2, -1}}, 1e-6);
  }
}

TEST_F(ConstraintRates, ASliderClosesOffItsLineAndLimitsGrowAtTheirRowsRates) {
  for (int trial = 0; trial < 20; ++trial) {
    const ConstraintSide a = side(), b = side();
    ConstraintRecord slider = record(ConstraintType::RigidPrismaticJoint);
    slider.actor_b = 1;
    slider.axis_A = vec(1).normalized();
    slider.offset_A = vec(0.5);
    expect_rates(slider, a, b, {{0, -1}, {1, -1}}, 1e-6);
    // a bound the slider is beyond: the deviation's third component is the distance back
    // inside, which the limit row's C = s - min grows against (C = -deviation there)
    const Vec3 offset = a.X_WL.rotation.conjugate() * (b.X_WL.translation - a.X_WL.translation) - slider.offset_A;
    slider.min = slider.axis_A.dot(offset) + real(0.1);
    expect_rates(slider, a, b, {{0, -1}, {1, -1}, {2, -1}}, 1e-6);
  }
}

TEST_F(ConstraintRates, NodeConstraintsCloseAtTheirRowsRates) {
  for (int trial = 0; trial < 20; ++trial) {
    ConstraintSide node = side(), rigid = side();
    node.soft = 0, node.body = -1;
    ConstraintRecord position = record(ConstraintType::DeformableNodePosition);
    position.target_position = position.old_target_position = vec(1);
    expect_rates(position, node, {}, {{0, -1}, {1, -1}, {2, -1}}, 1e-6);
    ConstraintRecord tie = record(ConstraintType::DeformableNodeToRigid);
    tie.p_A = vec(0.3);
    tie.actor_b = 1;
    expect_rates(tie, rigid, node, {{0, -1}, {1, -1}, {2, -1}}, 1e-6);
  }
}

TEST_F(ConstraintRates, RotationConstraintsCloseAtTheirRowsRatesNearTheirTargets) {
  for (int trial = 0; trial < 20; ++trial) {
    const ConstraintSide a = side();
    ConstraintSide b = side();
    // a rotation error of about 1e-3 rad: the rows are the rates to first order in it
    ConstraintRecord pivot = record(ConstraintType::RigidPivotRotation);
    pivot.local_rotation = quat_exp(vec(1));
    pivot.target_rotation = pivot.old_target_rotation = (quat_exp(vec(1e-3)) * a.X_WL.rotation * pivot.local_rotation).normalized();
    expect_rates(pivot, a, {}, {{0, -1}, {1, -1}, {2, -1}}, 2e-3);
    // tracking: B near its target R_A T; its deviation is in A's joint axes, so compare in the
    // world by a joint frame of identity in the world
    ConstraintRecord tracking = record(ConstraintType::JointRotationTracking);
    tracking.actor_b = 1;
    tracking.target_rotation = tracking.old_target_rotation = quat_exp(vec(1));
    b.X_WL.rotation = (quat_exp(vec(1e-3)) * a.X_WL.rotation * tracking.target_rotation).normalized();
    tracking.J_A = a.X_WL.rotation.conjugate();
    ConstraintTerms t;
    t.a = a, t.b = b;
    constraint_terms(tracking, real(0.01), t);
    ASSERT_EQ(t.rows.size(), 3u);
    const Motion ma = motion(), mb = motion();
    const real h = real(1e-6);
    // the world deviation: J_A's world rotation (R_A J_A) moves with A, so map back by it
    const auto world = [&](const ConstraintSide& sa, const ConstraintSide& sb) {
      const std::vector<real> d = constraint_deviation(tracking, sa, sb);
      return Vec3(sa.X_WL.rotation * tracking.J_A * Vec3(d[0], d[1], d[2]));
    };
    const Vec3 change = (world(moved(a, ma, h), moved(b, mb, h)) - world(moved(a, ma, -h), moved(b, mb, -h))) / (2 * h);
    for (int k = 0; k < 3; ++k) {
      const real rate = t.rows[k].g_a.dot(ma.V) + t.rows[k].g_b.dot(mb.V);
      EXPECT_NEAR(change[k], -rate, 2e-3 * (1 + std::abs(rate))) << "tracking row " << k;
    }
  }
}

TEST_F(ConstraintRates, RotationRangeLimitsGrowAtTheirRowsRatesNearTheRest) {
  for (int trial = 0; trial < 20; ++trial) {
    const ConstraintSide a = side();
    ConstraintSide b = side();
    ConstraintRecord range = record(ConstraintType::JointRotationRange);
    range.actor_b = 1;
    range.J_A = quat_exp(vec(1));
    range.J_B = quat_exp(vec(1));
    // B's joint frame about 1e-3 rad from A's, beyond upper bounds of -0.5 rad on every axis (the
    // lower bounds beyond reach: no rows); the deviation is then C = upper - phi per axis
    b.X_WL.rotation = (a.X_WL.rotation * range.J_A * quat_exp(vec(1e-3)) * range.J_B.conjugate()).normalized();
    range.lower = Vec3::Constant(-4);
    range.upper = Vec3::Constant(real(-0.5));
    expect_rates(range, a, b, {{0, 1}, {1, 1}, {2, 1}}, 2e-3);
  }
}

// Joint targets act on the joint's DOF velocities: a 1-DOF joint's value moves at its velocity
// qdot, a 3-D joint's rotation turns by exp(h w) in its child frame (w its three DOF velocities).
TEST_F(ConstraintRates, JointTargetsCloseAtTheirRowsRates) {
  for (int trial = 0; trial < 20; ++trial) {
    ConstraintSide a = side();
    a.dof = 2;
    a.q_dof = uniform(-3, 3);
    ConstraintRecord single = record(ConstraintType::ArticulatedSingleDofTarget);
    single.dof = 2;
    single.target_value = single.old_target_value = uniform(-3, 3);
    const real qdot = uniform(-1, 1);
    ConstraintTerms t;
    t.a = a;
    constraint_terms(single, real(0.01), t);
    ASSERT_EQ(t.rows.size(), 1u);
    const real h = real(1e-6);
    ConstraintSide plus = a, minus = a;
    plus.q_dof += h * qdot, minus.q_dof -= h * qdot;
    const real change = (constraint_deviation(single, plus, {})[0] - constraint_deviation(single, minus, {})[0]) / (2 * h);
    EXPECT_NEAR(change, -t.rows[0].g_a.dot(Vec6::Unit(0) * qdot), 1e-6);
    // the ball: about 1e-3 rad from its target
    ConstraintRecord ball = record(ConstraintType::Articulated3dRotationTarget);
    ball.dof = 3;
    a.R_joint = quat_exp(vec(2));
    ball.target_rotation = ball.old_target_rotation = (a.R_joint * quat_exp(vec(1e-3))).normalized();
    t.a = a;
    constraint_terms(ball, real(0.01), t);
    ASSERT_EQ(t.rows.size(), 3u);
    const Vec3 w = vec(1);
    plus = a, minus = a;
    plus.R_joint = (a.R_joint * quat_exp(h * w)).normalized();
    minus.R_joint = (a.R_joint * quat_exp(-h * w)).normalized();
    const std::vector<real> dp = constraint_deviation(ball, plus, {}), dm = constraint_deviation(ball, minus, {});
    for (int k = 0; k < 3; ++k) {
      const real rate = t.rows[k].g_a.dot((Vec6() << w, Vec3::Zero()).finished());
      EXPECT_NEAR((dp[k] - dm[k]) / (2 * h), -rate, 2e-3 * (1 + std::abs(rate))) << "ball row " << k;
    }
  }
}

TEST_F(ConstraintRates, WithoutStiffnessAndDampingAConstraintHasNoRows) {
  ConstraintRecord c = record(ConstraintType::RigidPivotPosition);
  c.stiffness = c.damping = 0;
  ConstraintTerms t;
  t.a = side();
  constraint_terms(c, real(0.01), t);
  EXPECT_TRUE(t.rows.empty());
}

}  // namespace
}  // namespace superdex::physics

/// @file step_guard_test.cpp
/// Numerical faults in Scene::step (step_guard.h): under Raise a non-finite result throws naming
/// the actor and quantity and leaves the scene's state bitwise as it was; under WarnAndClamp the
/// faulty body stops where it was (its pose and velocity as queried too, also when only its
/// positions overflow), the others step, and the fault is reported as data.

#include <gmock/gmock.h>

#include <limits>

#include "superdex/physics/error.h"
#include "test_helpers.h"

namespace superdex::physics::test {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;

struct TwoBalls {
  Scene scene;
  ActorHandle calm, wild;
};

// a free ball, and far from it a second one moving at the largest finite speed and pushed further:
// its next velocity overflows the scalar type
TwoBalls two_balls() {
  TwoBalls b{z_up_scene("guarded"), 0, 0};
  const ShapeHandle sphere = create_shape(SphereShape{Vec3::Zero(), real(0.1)});
  Transform X;
  X.translation = Vec3(0, 0, 2);
  b.calm = b.scene.create_rigid_actor(rigid_params("calm", sphere, X, real(1)));
  X.translation = Vec3(5, 0, 2);
  // without a collider: its swept bounds would otherwise reach the calm ball and join its island
  RigidActorParams wild = rigid_params("wild", sphere, X, real(1));
  wild.collider_type = ColliderType::None;
  b.wild = b.scene.create_rigid_actor(wild);
  const real huge = std::numeric_limits<real>::max();
  b.scene.set_velocity(b.wild, Vec3(huge, 0, 0), Vec3::Zero());
  b.scene.set_external_forces_on_dofs(b.wild, {0}, {huge});
  return b;
}

class StepGuardTest : public EngineTest {};

TEST_F(StepGuardTest, RaiseIsTheDefaultNamesActorAndQuantityAndCommitsNothing) {
  TwoBalls b = two_balls();
  EXPECT_EQ(b.scene.numerical_fault_policy(), NumericalFaultPolicy::Raise);
  std::vector<std::uint8_t> before, after;
  b.scene.capture_state_to_bytes(before);
  try {
    b.scene.step(real(0.01));
    FAIL() << "the step should have raised";
  } catch (const Error& e) {
    EXPECT_THAT(std::string(e.what()), AllOf(HasSubstr("scene 'guarded', actor 'wild'"), HasSubstr("became non-finite"),
                                             HasSubstr("keeps its last good state")));
    EXPECT_THAT(std::string(e.what()), ::testing::Not(HasSubstr("'calm'")));
  }
  b.scene.capture_state_to_bytes(after);
  EXPECT_EQ(after, before);
  EXPECT_EQ(b.scene.total_simulation_time(), 0);
}

TEST_F(StepGuardTest, WarnAndClampStopsTheFaultyBodyAndStepsTheOthers) {
  TwoBalls b = two_balls();
  b.scene.set_numerical_fault_policy(NumericalFaultPolicy::WarnAndClamp);
  const Vec3 wild_before = b.scene.root_transform(b.wild).translation;
  b.scene.step(real(0.01));
  ASSERT_EQ(b.scene.last_numerical_faults().size(), 1u);
  const NumericalFault f = b.scene.last_numerical_faults()[0];
  EXPECT_EQ(f.actor, b.wild);
  EXPECT_THAT(f.message, HasSubstr("actor 'wild'"));
  EXPECT_EQ(b.scene.root_transform(b.wild).translation, wild_before);
  EXPECT_EQ(b.scene.velocity(b.wild), Vec6::Zero());
  EXPECT_LT(b.scene.root_transform(b.calm).translation.z(), 2);  // fell under gravity
  EXPECT_NEAR(b.scene.total_simulation_time(), 0.01, 1e-12);
  // once the force is gone the next step is clean (the clamped ball has zero velocity)
  b.scene.clear_external_forces(b.wild);
  b.scene.step(real(0.01));
  EXPECT_TRUE(b.scene.last_numerical_faults().empty());
}

TEST_F(StepGuardTest, WarnAndClampOfOverflowingPositionsLeavesPoseAndVelocityAtTheLastGoodState) {
  // a free ball near the largest finite coordinate, moving on: its velocity stays finite, its
  // next position overflows (only the articulation's own check sees it, not its island's)
  TwoBalls b = two_balls();
  b.scene.set_numerical_fault_policy(NumericalFaultPolicy::WarnAndClamp);
  b.scene.clear_external_forces(b.wild);
  Transform X;
  X.translation = Vec3(real(0.9) * std::numeric_limits<real>::max(), 0, 2);
  b.scene.set_root_transform(b.wild, X);
  b.scene.set_velocity(b.wild, Vec3(real(0.5) * std::numeric_limits<real>::max(), 0, 0), Vec3::Zero());
  b.scene.step(real(1));
  ASSERT_EQ(b.scene.last_numerical_faults().size(), 1u);
  EXPECT_EQ(b.scene.last_numerical_faults()[0].quantity, "positions");
  // the queries read the clamped state: its last position, at rest
  EXPECT_EQ(b.scene.root_transform(b.wild).translation, X.translation);
  EXPECT_EQ(b.scene.velocity(b.wild), Vec6::Zero());
  EXPECT_LT(b.scene.root_transform(b.calm).translation.z(), 2);
}

}  // namespace
}  // namespace superdex::physics::test

/// @file scene_batch_test.cpp
/// SceneBatch (scene_batch.h): scenes stepped on two worker threads give bitwise the trajectory
/// of one scene stepped by hand with the same servo law and forces; reset restores the captured
/// state; the velocity drive reaches its command; bad specs throw naming the field.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "superdex/physics/engine.h"
#include "superdex/physics/error.h"
#include "superdex/physics/scene.h"
#include "superdex/robotics/scene_batch.h"
#include "velocity_servo_law.h"

namespace superdex::robotics::test {
namespace {

using physics::ArticulationDesc;
using physics::JointDesc;
using physics::JointType;
using physics::LinkDesc;
using physics::real;
using physics::Vec3;
using physics::VecX;
using ::testing::HasSubstr;

// a welded base and a double pendulum swinging about y under gravity: 2 DOFs, 3 links
ActorHandle add_pendulum(Scene& scene) {
  ArticulationDesc d;
  d.name = "pendulum";
  for (int i = 0; i < 3; ++i) {
    LinkDesc l;
    l.name = "link" + std::to_string(i);
    l.parent_link = i - 1;
    l.mass = 1;
    l.center_of_mass = Vec3(0.1, 0, 0);
    l.moment_of_inertia = std::array<real, 6>{0.001, 0, 0, 0.004, 0, 0.004};
    d.links.push_back(l);
    JointDesc j;
    j.name = "joint" + std::to_string(i);
    j.type = i == 0 ? JointType::Hard : JointType::Revolute;
    j.axis = Vec3::UnitY();
    j.parent_link_from_joint.translation = Vec3(i == 0 ? 0 : 0.2, 0, i == 0 ? 1 : 0);
    d.joints.push_back(j);
  }
  d.default_pose = {0.3, -0.2};
  return scene.create_articulated_actor(d, "scene_batch_test");
}

SceneBatchSpec servo_spec() {
  SceneBatchSpec s;
  s.mode = BatchActionMode::VelocityServo;
  s.action_dofs = {0, 1};
  s.servo_k_p = {4, 2};
  s.servo_k_i = {80, 40};
  s.servo_effort_limit = {6, 3};
  s.servo_profile_accel = {20, 20};
  s.observed_link = 2;
  s.dt = 0.004;
  s.substeps = 2;
  return s;
}

class Batch : public ::testing::Test {
 protected:
  void SetUp() override { physics::initialize(2); }
  void TearDown() override { physics::shutdown(); }
  std::vector<SceneBatchMember> make_members(int n) {
    std::vector<SceneBatchMember> m;
    for (int k = 0; k < n; ++k) {
      Scene scene = physics::create_scene("s" + std::to_string(k));
      m.push_back({scene, add_pendulum(scene), 0});
    }
    return m;
  }
};

TEST_F(Batch, ServoScenesOnTwoThreadsEqualOneSceneSteppedByHand) {
  const SceneBatchSpec spec = servo_spec();
  SceneBatch batch(spec, make_members(3));
  Scene ref = physics::create_scene("reference");
  const ActorHandle art = add_pendulum(ref);
  servo::VelocityServoLaw laws[2];
  for (int j = 0; j < 2; ++j) laws[j].params = {spec.servo_k_p[j], spec.servo_k_i[j], spec.servo_effort_limit[j], spec.servo_profile_accel[j]};

  std::vector<real> obs(3 * batch.obs_size());
  for (int t = 0; t < 50; ++t) {
    const double goal[2] = {1.5 * std::sin(0.1 * t), -std::cos(0.07 * t)};
    const std::vector<double> actions = {goal[0], goal[1], goal[0], goal[1], goal[0], goal[1]};
    batch.step(actions.data(), obs.data());
    for (int s = 0; s < spec.substeps; ++s) {
      const VecX v = ref.joint_velocities(art);
      std::vector<real> efforts = {static_cast<real>(laws[0].step(goal[0], v[0], spec.dt)),
                                   static_cast<real>(laws[1].step(goal[1], v[1], spec.dt))};
      ref.set_external_forces_on_dofs(art, {0, 1}, efforts);
      ref.step(static_cast<real>(spec.dt));
    }
    const VecX q = ref.pose(art), v = ref.joint_velocities(art);
    const Vec3 p = ref.link_transforms(art)[2].translation;
    for (int k = 0; k < 3; ++k) {
      const real* row = obs.data() + k * batch.obs_size();
      ASSERT_EQ(row[0], q[0]) << "step " << t << " scene " << k;
      ASSERT_EQ(row[1], q[1]);
      ASSERT_EQ(row[2], v[0]);
      ASSERT_EQ(row[3], v[1]);
      ASSERT_EQ(row[4], p[0]);
      ASSERT_EQ(row[6], p[2]);
    }
  }
  EXPECT_GT(std::abs(obs[0] - real(0.3)), 0.05) << "the servos moved the pendulum";
}

TEST_F(Batch, ResetRestoresTheCapturedStateAndSetsThePose) {
  SceneBatch batch(servo_spec(), make_members(2));
  std::vector<real> initial(2 * batch.obs_size()), obs(initial.size());
  batch.observe(initial.data());
  const std::vector<double> actions = {2, -2, 1, 1};
  for (int t = 0; t < 20; ++t) batch.step(actions.data(), obs.data());
  ASSERT_NE(obs[0], initial[0]);
  batch.reset({0, 1}, nullptr, obs.data());
  EXPECT_EQ(obs, initial);
  const double q0[2] = {0.5, -0.4};
  batch.reset({1}, q0, obs.data());
  EXPECT_EQ(obs[batch.obs_size()], real(0.5));
  EXPECT_EQ(obs[batch.obs_size() + 1], real(-0.4));
  EXPECT_EQ(obs[0], initial[0]) << "row 0 untouched";
}

TEST_F(Batch, VelocityDriveReachesItsCommand) {
  SceneBatchSpec s;
  s.mode = BatchActionMode::VelocityDrive;
  s.action_dofs = {0, 1};
  s.drive_stiffness = {400, 400};
  s.drive_damping = {20, 20};
  s.drive_max_effort = {-1, -1};
  s.observed_link = 2;
  s.dt = 0.002;
  s.substeps = 5;
  SceneBatch batch(s, make_members(2));
  std::vector<real> obs(2 * batch.obs_size());
  batch.reset({0, 1}, nullptr, obs.data());
  const real q_start = obs[0];
  const std::vector<double> actions = {0.5, -0.25, 0.5, -0.25};
  for (int t = 0; t < 50; ++t) batch.step(actions.data(), obs.data());  // 0.5 s
  EXPECT_NEAR(obs[2], 0.5, 0.01);
  EXPECT_NEAR(obs[3], -0.25, 0.01);
  EXPECT_NEAR(obs[0] - q_start, 0.25, 0.02) << "the angle grows by command x time";
}

TEST_F(Batch, BadSpecsThrowNamingTheField) {
  SceneBatchSpec s = servo_spec();
  s.action_dofs = {0, 7};
  EXPECT_THAT([&] { SceneBatch(s, make_members(1)); },
              ::testing::ThrowsMessage<Error>(HasSubstr("spec.action_dofs[1] = 7 is out of range")));
  s = servo_spec();
  s.servo_k_i = {1};
  EXPECT_THAT([&] { SceneBatch(s, make_members(1)); }, ::testing::ThrowsMessage<Error>(HasSubstr("spec.servo_k_i has 1 entries")));
  s = servo_spec();
  s.observed_link = 3;
  EXPECT_THAT([&] { SceneBatch(s, make_members(1)); }, ::testing::ThrowsMessage<Error>(HasSubstr("spec.observed_link = 3")));
  EXPECT_THAT([&] { SceneBatch(servo_spec(), {}); }, ::testing::ThrowsMessage<Error>(HasSubstr("members is empty")));
  std::vector<SceneBatchMember> members = make_members(2);
  members[1].articulation = 12345;
  EXPECT_THAT([&] { SceneBatch(servo_spec(), members); },
              ::testing::ThrowsMessage<Error>(HasSubstr("members[1]: articulation 12345 is not an articulated actor")));
  SceneBatch batch(servo_spec(), make_members(2));
  std::vector<real> obs(2 * batch.obs_size());
  EXPECT_THAT([&] { batch.reset({0, 2}, nullptr, obs.data()); }, ::testing::ThrowsMessage<Error>(HasSubstr("index 2 is out of range")));
  EXPECT_THAT([&] { batch.reset({1, 1}, nullptr, obs.data()); }, ::testing::ThrowsMessage<Error>(HasSubstr("index 1 appears twice")));
}

}  // namespace
}  // namespace superdex::robotics::test

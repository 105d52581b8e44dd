/// @file scene_batch_test.cpp
/// SceneBatch (scene_batch.h): scenes stepped on two worker threads give bitwise the trajectory
/// of one scene stepped by hand with the same servo law and forces; reset restores the captured
/// state; the velocity drive reaches its command; the C++ tasks give their documented target
/// points and rewards; bad specs throw naming the field.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "superdex/physics/engine.h"
#include "superdex/physics/error.h"
#include "superdex/physics/scene.h"
#include "superdex/robotics/scene_batch.h"
#include "batch_task.h"
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

// a new scene with the Z-up gravity the pendulum swings under (a new scene's default gravity
// is along -Y: parallel to its joint axes, it would exert no torque)
Scene z_up_scene(const std::string& name) {
  Scene scene = physics::create_scene(name);
  scene.set_gravity(Vec3(0, 0, real(-9.81)));
  return scene;
}

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
      Scene scene = z_up_scene("s" + std::to_string(k));
      m.push_back({scene, add_pendulum(scene), 0});
    }
    return m;
  }
};

TEST_F(Batch, ServoScenesOnTwoThreadsEqualOneSceneSteppedByHand) {
  const SceneBatchSpec spec = servo_spec();
  SceneBatch batch(spec, make_members(3));
  Scene ref = z_up_scene("reference");
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

BatchTask circle_task() {
  BatchTask task;
  task.kind = BatchTaskKind::CircleTracking;
  task.center = {0.1, -0.2, 0.9};
  task.radius = 0.15;
  task.omega = 2.5;
  task.force_target = 0.5;
  task.force_weight = 0.7;
  return task;
}

TEST_F(Batch, CircleTaskWritesItsTargetPointAndRewardAfterEachStep) {
  SceneBatchSpec spec = servo_spec();
  spec.task = circle_task();
  SceneBatch batch(spec, make_members(2));
  ASSERT_EQ(batch.obs_size(), 2 * 2 + 6 + 3);
  ASSERT_EQ(batch.params_size(), 1);
  const int m = batch.obs_size();
  std::vector<real> obs(2 * m);
  std::vector<double> reward(2, 99);
  const double phase[2] = {0.4, -2.0};
  batch.reset({0, 1}, nullptr, obs.data(), phase);
  const double control_dt = spec.dt * spec.substeps;
  const std::vector<double> actions = {1, -1, -0.5, 0.5};
  for (int t = 0; t <= 12; ++t) {
    if (t > 0) batch.step(actions.data(), obs.data(), reward.data());
    for (int k = 0; k < 2; ++k) {
      const real* row = obs.data() + k * m;
      // x*(t) = c + r (cos theta, 0, sin theta), theta = omega t T + phase, and the reward's tracking term
      const double theta = spec.task.omega * t * control_dt + phase[k];
      const double x = 0.1 + 0.15 * std::cos(theta), z = 0.9 + 0.15 * std::sin(theta);
      EXPECT_NEAR(row[10], x, 1e-6) << "step " << t << " scene " << k;
      EXPECT_EQ(row[11], real(-0.2));
      EXPECT_NEAR(row[12], z, 1e-6);
      // no contact actor: no force term
      if (t > 0) EXPECT_NEAR(reward[k], -std::sqrt(std::pow(row[4] - x, 2) + std::pow(row[6] - z, 2)) / 0.15, 1e-5);
    }
  }
  // a reset restarts the task's time at the new phase; the other row keeps its time
  const double phase1 = 1.0;
  batch.reset({1}, nullptr, obs.data(), &phase1);
  EXPECT_NEAR(obs[m + 10], 0.1 + 0.15 * std::cos(1.0), 1e-6);
  EXPECT_NEAR(obs[m + 12], 0.9 + 0.15 * std::sin(1.0), 1e-6);
  EXPECT_NEAR(obs[10], 0.1 + 0.15 * std::cos(2.5 * 12 * control_dt + 0.4), 1e-6);
}

TEST(BatchTask, CircleRewardRegulatesTheForceOnlyInContact) {
  const BatchTask task = circle_task();
  const double phase = 0.3;
  // n = 1 action column: [q | v | p_WE (3) | f_C_W (3) | target (3)]
  real row[11] = {0, 0, 0.2f, 0.0f, 0.95f, 0, 0, 0, 0, 0, 0};
  const double t = 0.8, theta = 2.5 * t + phase;
  const double x = 0.1 + 0.15 * std::cos(theta), z = 0.9 + 0.15 * std::sin(theta);
  const double tracking = std::hypot(double(row[2]) - x, double(row[4]) - z) / 0.15;
  EXPECT_NEAR(write_task_columns_and_reward(task, &phase, t, 1, row), -tracking, 1e-12) << "no force, no force term";
  row[5] = 0.3f, row[6] = -0.1f, row[7] = 1.25f;  // pressing with 1.25 N: 0.75 N over the 0.5 N target
  EXPECT_NEAR(write_task_columns_and_reward(task, &phase, t, 1, row), -tracking - 0.7 * (double(1.25f) - 0.5) / 0.5, 1e-12);
  row[7] = 0;  // touching sideways: f_z 0.5 N under the target
  EXPECT_NEAR(write_task_columns_and_reward(task, &phase, t, 1, row), -tracking - 0.7 * 1.0, 1e-12);
}

TEST(BatchTask, GoalRewardIsDistanceAndForce) {
  BatchTask task;
  task.kind = BatchTaskKind::GoalReach;
  task.force_weight = 0.01;
  const double goal[3] = {0.45, 0.1, 0.42};
  // n = 2 action columns
  real row[13] = {0, 0, 0, 0, 0.5f, 0.0f, 0.5f, 3.0f, 0.0f, 4.0f, 0, 0, 0};
  const double d = std::sqrt(std::pow(double(0.5f) - 0.45, 2) + 0.01 + std::pow(double(0.5f) - 0.42, 2));
  EXPECT_NEAR(write_task_columns_and_reward(task, goal, 7.0, 2, row), -d - 0.01 * 5.0, 1e-12);
  EXPECT_EQ(row[10], real(0.45));
  EXPECT_EQ(row[11], real(0.1));
  EXPECT_EQ(row[12], real(0.42));
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
  s = servo_spec();
  s.task = circle_task();
  s.task.radius = 0;
  EXPECT_THAT([&] { SceneBatch(s, make_members(1)); }, ::testing::ThrowsMessage<Error>(HasSubstr("spec.task.radius must be a positive")));
  s.task = circle_task();
  s.task.force_target = -1;
  EXPECT_THAT([&] { SceneBatch(s, make_members(1)); }, ::testing::ThrowsMessage<Error>(HasSubstr("spec.task.force_target")));
  s.task = BatchTask{};
  s.task.kind = BatchTaskKind::GoalReach;
  s.task.force_weight = std::nan("");
  EXPECT_THAT([&] { SceneBatch(s, make_members(1)); }, ::testing::ThrowsMessage<Error>(HasSubstr("spec.task.force_weight must be finite")));
  s.task.kind = static_cast<BatchTaskKind>(9);
  EXPECT_THAT([&] { SceneBatch(s, make_members(1)); }, ::testing::ThrowsMessage<Error>(HasSubstr("spec.task.kind")));
  SceneBatch batch(servo_spec(), make_members(2));
  std::vector<real> obs(2 * batch.obs_size());
  EXPECT_THAT([&] { batch.reset({0, 2}, nullptr, obs.data()); }, ::testing::ThrowsMessage<Error>(HasSubstr("index 2 is out of range")));
  EXPECT_THAT([&] { batch.reset({1, 1}, nullptr, obs.data()); }, ::testing::ThrowsMessage<Error>(HasSubstr("index 1 appears twice")));
}

}  // namespace
}  // namespace superdex::robotics::test

/// @file pipeline_test.cpp
/// The bot pipeline run inside Scene::step (context.h): command merging, rates, the forces it
/// applies (actuator efforts, commanded efforts on DOFs without an actuator), automatic and
/// forced activation, and the lifetimes of its scene callbacks when the bot, the context or
/// the scene goes first. Bots are built in code: a welded base and two revolute links.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "superdex/physics/engine.h"
#include "superdex/physics/error.h"
#include "superdex/physics/scene.h"
#include "superdex/robotics/context.h"

namespace superdex::robotics::test {
namespace {

using physics::JointDesc;
using physics::JointType;
using physics::LinkDesc;
using physics::real;
using physics::Vec3;
using ::testing::HasSubstr;

// a welded base and two links turning about z (no gravity torque): 2 DOFs
BotPrefab two_joint_prefab() {
  BotPrefab p;
  p.articulation.name = "two";
  for (int i = 0; i < 3; ++i) {
    LinkDesc l;
    l.name = "link" + std::to_string(i);
    l.parent_link = i - 1;
    l.mass = 1;
    l.moment_of_inertia = std::array<real, 6>{0.01, 0, 0, 0.01, 0, 0.01};
    p.articulation.links.push_back(l);
    JointDesc j;
    j.name = "joint" + std::to_string(i);
    j.type = i == 0 ? JointType::Hard : JointType::Revolute;
    j.axis = Vec3::UnitZ();
    j.parent_link_from_joint.translation = Vec3(0.1, 0, 0);
    p.articulation.joints.push_back(j);
  }
  p.sensors.resize(3);
  p.actuators.resize(3);
  return p;
}

// A sensor that counts its updates and records their dt.
class CountingSensor : public SensorComponent {
 public:
  std::vector<real>* dts;
  explicit CountingSensor(std::vector<real>* d) : dts(d) {}
  void reset() override {}
  void update(const Tick& tick) override { dts->push_back(tick.dt); }
  VecX signal() const override { return VecX::Constant(1, static_cast<real>(dts->size())); }
};

class Pipeline : public ::testing::Test {
 protected:
  void SetUp() override {
    physics::initialize(0);
    scene = physics::create_scene("pipeline");
    scene.set_gravity(Vec3(0, 0, -9.81));
  }
  void TearDown() override { physics::shutdown(); }
  physics::Scene scene{0};
};

TEST(DofCommands, MergeReplacesPositionsAndAddsEfforts) {
  DofCommands a, b;
  a.clear(2);
  b.clear(2);
  a.set_position(0, 1);
  a.set_effort(1, 2);
  b.set_position(0, 3);
  b.set_effort(1, 0.5);
  b.set_velocity(1, 4);
  a.merge(b);
  EXPECT_EQ(*a.at(0).position, 3);
  EXPECT_FALSE(a.at(0).effort.has_value());
  EXPECT_EQ(*a.at(1).effort, 2.5);
  EXPECT_EQ(*a.at(1).velocity, 4);
  EXPECT_THROW(a.set_effort(2, 1), Error);
}

TEST_F(Pipeline, ControllerEffortsGoToActuatorsOrDirectlyToTheirDofs) {
  Context ctx;
  BotPrefab prefab = two_joint_prefab();
  // an ideal actuator on link 1 doubling nothing: kp = kd = 0 passes the effort command
  prefab.actuators[1].push_back({"IDEAL_PD", "drive", "{\"effort_limit\": 0.5}", {}});
  const BotHandle bot = ctx.create_bot(scene, prefab, nullptr);
  EXPECT_TRUE(ctx.is_pipeline_active(bot)) << "an actuator that takes part switches it on";
  const ActorHandle arm = ctx.bot(bot).articulation;
  ComponentArgs args{scene, arm, "{\"effort\": [2.0, 3.0]}", nullptr};
  ctx.create(ComponentKind::Controller, "JOINT_COMMAND", args, "cmd", bot);
  scene.step(real(0.001));
  // DOF 0 through the actuator (limited to 0.5), DOF 1 directly
  EXPECT_NEAR(scene.external_forces(arm)[0], 0.5, 1e-6);
  EXPECT_NEAR(scene.external_forces(arm)[1], 3.0, 1e-6);
}

TEST_F(Pipeline, ComponentsRunAtTheirRate) {
  Context ctx;
  std::vector<real> dts;
  ctx.register_type(ComponentKind::Sensor, "COUNT", [&](const ComponentArgs&) {
    auto s = std::make_unique<CountingSensor>(&dts);
    s->set_rate(100);  // every 10 ms
    return s;
  });
  BotPrefab prefab = two_joint_prefab();
  prefab.sensors[2].push_back({"COUNT", "count", "", {}});
  const BotHandle bot = ctx.create_bot(scene, prefab, nullptr);
  for (int i = 0; i < 40; ++i) scene.step(real(0.0025));  // 0.1 s
  // due at 2.5 ms (first), then every 10 ms: 12.5, 22.5, ..., 92.5 ms
  ASSERT_EQ(dts.size(), 10u);
  for (real dt : dts) EXPECT_NEAR(dt, 0.01, 1e-6);
  EXPECT_EQ(ctx.sensor_signal(ctx.bot(bot).sensors[0])[0], 10);
}

TEST_F(Pipeline, AutomaticEnabledDisabled) {
  Context ctx;
  const BotHandle bot = ctx.create_bot(scene, two_joint_prefab(), nullptr);
  EXPECT_FALSE(ctx.is_pipeline_active(bot));
  ctx.set_pipeline_mode(bot, PipelineMode::Enabled);
  EXPECT_TRUE(ctx.is_pipeline_active(bot));
  ctx.set_pipeline_mode(bot, PipelineMode::Automatic);
  EXPECT_FALSE(ctx.is_pipeline_active(bot));
  const ActorHandle arm = ctx.bot(bot).articulation;
  const ComponentHandle c = ctx.create(ComponentKind::Controller, "BASIC_JSC_PD", {scene, arm, "", nullptr}, "jsc");
  EXPECT_TRUE(ctx.is_pipeline_active(bot)) << "a context-level controller on the bot's articulation joins it";
  scene.step(real(0.001));
  ctx.set_pipeline_mode(bot, PipelineMode::Disabled);
  EXPECT_FALSE(ctx.is_pipeline_active(bot));
  EXPECT_EQ(scene.external_forces(arm).norm(), 0) << "its forces stop with it";
  ctx.set_pipeline_mode(bot, PipelineMode::Automatic);
  ctx.destroy(ComponentKind::Controller, c);
  EXPECT_FALSE(ctx.is_pipeline_active(bot));
}

TEST_F(Pipeline, ContextDestroyedBeforeTheScene) {
  auto ctx = std::make_unique<Context>();
  const BotHandle bot = ctx->create_bot(scene, two_joint_prefab(), nullptr);
  const ActorHandle arm = ctx->bot(bot).articulation;
  ctx->create(ComponentKind::Controller, "JOINT_COMMAND", {scene, arm, "{\"effort\": [1, 1]}", nullptr}, "cmd", bot);
  scene.step(real(0.001));
  EXPECT_NEAR(scene.external_forces(arm)[0], 1.0, 1e-6);
  ctx.reset();
  scene.step(real(0.001));  // no callback into the freed context
  EXPECT_EQ(scene.external_forces(arm).norm(), 0);
  EXPECT_EQ(scene.num_step_callbacks(), 0u);
}

TEST_F(Pipeline, SceneDestroyedBeforeTheContext) {
  auto ctx = std::make_unique<Context>();
  BotPrefab prefab = two_joint_prefab();
  prefab.sensors[1].push_back({"CONTACT_FORCE", "cf", "", {}});
  const BotHandle bot = ctx->create_bot(scene, prefab, nullptr);
  const BotHandle other = ctx->create_bot(scene, prefab, nullptr);
  scene.step(real(0.001));
  physics::destroy_scene(scene.handle());
  ctx->destroy_bot(bot);  // nothing left in the scene to touch
  EXPECT_FALSE(ctx->has_bot(bot));
  EXPECT_TRUE(ctx->has_bot(other));
  ctx.reset();
}

TEST_F(Pipeline, DestroyBotCancelsItsCallbacks) {
  Context ctx;
  BotPrefab prefab = two_joint_prefab();
  prefab.sensors[1].push_back({"JOINT_STATE", "js", "", {}});
  const BotHandle bot = ctx.create_bot(scene, prefab, nullptr);
  ASSERT_TRUE(ctx.is_pipeline_active(bot));
  ctx.destroy_bot(bot);
  EXPECT_EQ(scene.num_step_callbacks(), 0u);
  scene.step(real(0.001));
}

TEST_F(Pipeline, ActuatorOnAJointWithoutOneDofIsRefused) {
  Context ctx;
  BotPrefab prefab = two_joint_prefab();
  prefab.actuators[0].push_back({"VELOCITY_SERVO", "servo", "", {}});
  try {
    ctx.create_bot(scene, prefab, nullptr);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("link 'link0' has joint 'joint0' (Hard, 0 DOFs)"));
  }
  EXPECT_TRUE(scene.actors().empty()) << "create_bot failed as a whole";
}

}  // namespace
}  // namespace superdex::robotics::test

/// @file component_api_test.cpp
/// The component API added for the SuperDex surface: camera and JSC PD params (validation and
/// JSON), sensor poses resolved through their actor, ownership inferred from the actor, and
/// bots built with add_link and declared components.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "superdex/physics/engine.h"
#include "superdex/physics/error.h"
#include "superdex/physics/scene.h"
#include "superdex/robotics/context.h"
#include "superdex/robotics/controller_basic_jsc_pd.h"
#include "superdex/robotics/sensor_camera.h"

namespace superdex::robotics::test {
namespace {

using physics::JointDesc;
using physics::JointType;
using physics::real;
using physics::Vec3;
using ::testing::HasSubstr;

// the message of the superdex::Error `f` throws ("" if none)
template <class F>
std::string error_of(F f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(CameraSensorParams, ValidationNamesTheField) {
  CameraSensorParams p;
  EXPECT_EQ(error_of([&] { p.validate("cam"); }), "");
  p.fov_vertical_deg = 180;
  EXPECT_THAT(error_of([&] { p.validate("cam"); }), HasSubstr("cam: fov_vertical_deg must be in [0, 180)"));
  p = {};
  p.near_clip = 2, p.far_clip = 1;
  EXPECT_THAT(error_of([&] { p.validate("cam"); }), HasSubstr("far_clip must be greater than near_clip"));
  p = {};
  p.up_axis_local = Vec3::Zero();
  EXPECT_THAT(error_of([&] { p.validate("cam"); }), HasSubstr("up_axis_local must be a finite, non-zero direction"));
}

TEST(CameraSensorParams, JsonRoundTripAndIntrinsics) {
  CameraSensorParams p;
  p.name = "front", p.image_width = 200, p.image_height = 100, p.fov_vertical_deg = 90, p.look_at = Vec3(1, 2, 3);
  EXPECT_EQ(CameraSensorParams::from_json_text(p.to_json_text(), "t"), p);
  const auto k = p.pinhole_intrinsics();
  EXPECT_NEAR(k[1], 50.0, 1e-9);  // h/2 / tan(45 deg)
  EXPECT_EQ(k[2], 100.0);
  EXPECT_THAT(error_of([] { CameraSensorParams{}.pinhole_intrinsics(); }), HasSubstr("must be set"));
  EXPECT_THAT(error_of([] { CameraSensorParams::from_json_text(R"({"lookAt": [1, 2]})", "t"); }), HasSubstr("params.lookAt"));
}

TEST(ControllerBasicJscPdParams, JsonKeepsOnlyGivenFields) {
  const auto p = ControllerBasicJscPdParams::from_json_text(R"({"kp": 5, "kd": [1, 2]})", "t");
  EXPECT_EQ(p.kp, std::vector<real>{5});
  EXPECT_EQ(p.kd, (std::vector<real>{1, 2}));
  EXPECT_TRUE(p.saturation.empty() && p.deadband.empty());
  EXPECT_EQ(ControllerBasicJscPdParams::from_json_text(p.to_json_text(), "t"), p);
  EXPECT_THAT(error_of([] { ControllerBasicJscPdParams::from_json_text(R"({"rate": 5})", "t"); }), HasSubstr("params.rate"));
}

class ComponentApi : public ::testing::Test {
 protected:
  void SetUp() override {
    physics::initialize(0);
    scene = physics::create_scene("component api");
    scene.set_gravity(Vec3(0, 0, -9.81));
  }
  void TearDown() override { physics::shutdown(); }

  // a welded base and one link turning about y, with a camera declared on the link
  BotPrefab pendulum() {
    BotPrefab p;
    p.articulation.name = "pendulum";
    BotLinkPrefab base;
    base.name = "base", base.mass = 1, base.moment_of_inertia = std::array<real, 6>{0.01, 0, 0, 0.01, 0, 0.01};
    JointDesc weld;
    weld.name = "weld", weld.type = JointType::Hard;
    add_link(p, base, weld);
    BotLinkPrefab rod = base;
    rod.name = "rod", rod.parent_link = 0, rod.center_of_mass = Vec3(0, 0, -0.5);
    rod.sensors.push_back({CameraSensor::kTypeName, "tip", physics::Transform{physics::Quat::Identity(), Vec3(0, 0, -0.5)}, ""});
    JointDesc hinge;
    hinge.name = "hinge", hinge.axis = Vec3::UnitY();
    add_link(p, rod, hinge);
    return p;
  }

  Scene scene{0};
};

TEST_F(ComponentApi, DeclaredCameraFollowsItsLink) {
  Context ctx;
  const BotHandle bot = ctx.create_bot(scene, pendulum(), nullptr);
  ASSERT_EQ(ctx.bot(bot).sensors.size(), 1u);
  const ComponentHandle cam = ctx.bot(bot).sensors[0];
  EXPECT_NE(dynamic_cast<const CameraSensor*>(ctx.component(ComponentKind::Sensor, cam).impl.get()), nullptr);
  const ActorHandle rod = scene.nested_link_actors(ctx.bot(bot).articulation)[1];
  auto expected = [&] { return (scene.root_transform(rod) * physics::Transform{physics::Quat::Identity(), Vec3(0, 0, -0.5)}).translation; };
  EXPECT_TRUE(ctx.sensor_world_transform(cam).translation.isApprox(expected()));
  VecX q(1);
  q << 0.7;
  scene.set_pose(ctx.bot(bot).articulation, q);
  for (int i = 0; i < 50; ++i) scene.step(0.005);
  EXPECT_TRUE(ctx.sensor_world_transform(cam).translation.isApprox(expected(), 1e-9));
  EXPECT_GT(std::abs(ctx.sensor_world_transform(cam).translation.x()), 0.05);
}

TEST_F(ComponentApi, ComponentsOnABotActorBelongToIt) {
  Context ctx;
  const BotHandle bot = ctx.create_bot(scene, pendulum(), nullptr);
  const ActorHandle rod = scene.nested_link_actors(ctx.bot(bot).articulation)[1];
  ComponentArgs on_rod{scene, rod, "", nullptr, {}};
  const ComponentHandle extra = ctx.create(ComponentKind::Sensor, CameraSensor::kTypeName, on_rod, "extra");
  EXPECT_EQ(ctx.component(ComponentKind::Sensor, extra).bot, bot);
  EXPECT_EQ(ctx.bot(bot).sensors.size(), 2u);
  EXPECT_EQ(ctx.bot_of_actor(scene, rod), bot);
  EXPECT_EQ(ctx.find_bots_by_name("pendulum"), std::vector<BotHandle>{bot});
  ctx.destroy_bot(bot);
  EXPECT_FALSE(ctx.has_component(ComponentKind::Sensor, extra));
}

TEST_F(ComponentApi, JscPdParamsOnALiveController) {
  Context ctx;
  const BotHandle bot = ctx.create_bot(scene, pendulum(), nullptr);
  ComponentArgs args{scene, ctx.bot(bot).articulation, "", nullptr, {}};
  const ComponentHandle h = ctx.create(ComponentKind::Controller, ControllerBasicJscPd::kTypeName, args, "jsc", bot);
  auto* jsc = dynamic_cast<ControllerBasicJscPd*>(ctx.component(ComponentKind::Controller, h).impl.get());
  ASSERT_NE(jsc, nullptr);
  EXPECT_EQ(jsc->params().kp, std::vector<real>{100});
  ControllerBasicJscPdParams p;
  p.kp = {1, 2};
  EXPECT_THAT(error_of([&] { jsc->set_params(p); }), HasSubstr("params.kp: expected 1 value (one per joint DOF), got 2"));
  ctx.configure_from_scene_entry(ComponentKind::Controller, h, R"({"kd": 3})", "");
  EXPECT_EQ(jsc->params().kd, std::vector<real>{3});
  EXPECT_THAT(error_of([&] { ctx.configure_from_scene_entry(ComponentKind::Controller, h, "absent.json", ""); }),
              HasSubstr("param_args: params file"));
}

}  // namespace
}  // namespace superdex::robotics::test

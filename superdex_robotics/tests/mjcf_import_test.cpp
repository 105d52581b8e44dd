/// @file mjcf_import_test.cpp
/// MJCF import (import/mjcf_import.cpp) on small models written inline: how MuJoCo's world of
/// trees becomes bots (the world bot, one bot per free body), multi-joint bodies as chains,
/// joint ref as the default pose, default classes and childclass, <include>, contact filters
/// and exclusions as contact overrides, and what is not imported named in warnings. The mass
/// matrices and bias forces are checked against MuJoCo itself in test_mjcf_mujoco.py.

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "superdex/physics/error.h"
#include "superdex/robotics/mjcf_import.h"

namespace superdex::robotics::test {
namespace {

namespace fs = std::filesystem;
using physics::JointType;
using physics::real;
using ::testing::HasSubstr;

// A folder of its own per test, removed afterwards.
class MjcfImport : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("superdex_mjcf_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string write(const std::string& name, const std::string& text) {
    std::ofstream(dir_ / name) << text;
    return (dir_ / name).string();
  }
  fs::path dir_;
};

int link_index(const BotPrefab& bot, const std::string& name) {
  const auto& links = bot.articulation.links;
  for (size_t i = 0; i < links.size(); ++i)
    if (links[i].name == name) return static_cast<int>(i);
  return -1;
}

bool has_override(const BotPrefab& bot, const std::string& a, const std::string& b, bool enable) {
  for (const auto& o : bot.articulation.contact_overrides)
    if (((o.link_a == a && o.link_b == b) || (o.link_a == b && o.link_b == a)) && o.enable == enable) return true;
  return false;
}

constexpr const char* kModel = R"(<mujoco model="walker">
  <compiler angle="degree"/>
  <option gravity="0 0 -3"/>
  <default>
    <joint damping="0.5"/>
    <default class="leg"><joint armature="0.02" range="-45 45"/><geom type="capsule" size="0.03"/></default>
  </default>
  <worldbody>
    <geom name="floor" type="plane" size="5 5 0.1"/>
    <body name="torso" pos="0 0 1" quat="0 0 0 1">
      <freejoint name="root"/>
      <geom type="box" size="0.1 0.1 0.1"/>
      <body name="thigh" childclass="leg">
        <joint name="hip_x" axis="1 0 0"/>
        <joint name="hip_y" axis="0 1 0" ref="30"/>
        <geom fromto="0 0 0 0 0 -0.4"/>
        <body name="shin" pos="0 0 -0.4">
          <joint name="knee" axis="0 1 0" class="main"/>
          <geom fromto="0 0 0 0 0 -0.4" contype="2" conaffinity="2"/>
        </body>
      </body>
    </body>
    <body name="door_frame" pos="2 0 0">
      <geom type="box" size="0.05 0.5 1"/>
      <body name="door" pos="0 0.5 0"><joint name="door_hinge"/><geom type="box" size="0.02 0.45 0.9"/></body>
    </body>
  </worldbody>
  <contact><exclude body1="door_frame" body2="door"/></contact>
  <tendon><fixed name="cable"><joint joint="hip_x" coef="1"/></fixed><spatial name="rope"><site site="a"/><site site="b"/></spatial></tendon>
  <actuator><motor joint="knee"/></actuator>
</mujoco>
)";

TEST_F(MjcfImport, WorldAndFreeBodiesBecomeBots) {
  std::vector<std::string> warnings;
  const MjcfModel model = load_mjcf(write("walker.xml", kModel), &warnings);
  EXPECT_EQ(model.name, "walker");
  EXPECT_EQ(model.gravity, physics::Vec3(0, 0, -3));
  ASSERT_EQ(model.bots.size(), 2u);
  // the world: its plane on a welded root, the door frame welded to it, the door on its hinge
  const BotPrefab& world = model.bots[0];
  ASSERT_EQ(world.articulation.links.size(), 3u);
  EXPECT_EQ(world.articulation.links[0].name, "world");
  EXPECT_EQ(world.articulation.joints[0].type, JointType::Hard);
  EXPECT_TRUE(std::holds_alternative<physics::PlaneShape>(*world.articulation.links[0].shape));
  EXPECT_EQ(world.articulation.joints[1].type, JointType::Hard);
  EXPECT_EQ(world.articulation.joints[2].name, "door_hinge");
  // the free body: a bot of its own, placed at the body's pose
  const BotPrefab& walker = model.bots[1];
  EXPECT_EQ(walker.articulation.joints[0].type, JointType::Free);
  EXPECT_EQ(walker.articulation.joints[0].name, "root");
  EXPECT_NEAR(walker.articulation.world_from_root.translation.z(), 1, 1e-12);
  EXPECT_NEAR(std::abs(walker.articulation.world_from_root.rotation.z()), 1, 1e-12);
  // the knee's motor: an IDEAL_PD actuator on the knee's link that passes its effort through
  const int shin = link_index(walker, "shin");
  ASSERT_EQ(walker.actuators[shin].size(), 1u);
  EXPECT_EQ(walker.actuators[shin][0].type, "IDEAL_PD");
  EXPECT_EQ(walker.actuators[shin][0].name, "<motor joint='knee'>");
  EXPECT_THAT(walker.actuators[shin][0].params, HasSubstr("\"kp\": 0, \"kd\": 0, \"effort_limit\": -1"));
  // the fixed tendon is the walker's; the spatial one, not imported, is named in a warning
  ASSERT_EQ(walker.articulation.fixed_tendons.size(), 1u);
  EXPECT_EQ(walker.articulation.fixed_tendons[0].joints, std::vector<std::string>{"hip_x"});
  EXPECT_TRUE(std::any_of(warnings.begin(), warnings.end(), [](const std::string& w) { return w.find("spatial tendons are not imported: 'rope'") != std::string::npos; }));
}

TEST_F(MjcfImport, BodyWithSeveralJointsIsAChainAndRefIsTheDefaultPose) {
  std::vector<std::string> warnings;
  const BotPrefab walker = load_mjcf(write("walker.xml", kModel), &warnings).bots[1];
  const auto& links = walker.articulation.links;
  const auto& joints = walker.articulation.joints;
  ASSERT_EQ(links.size(), 4u);
  EXPECT_EQ(links[1].name, "thigh/hip_x");  // the intermediate link, negligible mass
  EXPECT_LT(*links[1].mass, 1e-6 * *links[2].mass);
  EXPECT_EQ(links[2].name, "thigh");
  EXPECT_EQ(joints[1].name, "hip_x");
  EXPECT_EQ(joints[2].name, "hip_y");
  EXPECT_EQ(links[2].parent_link, 1);
  // the class's range in degrees, its armature, the main class's damping
  ASSERT_TRUE(joints[2].max_limit.has_value());
  EXPECT_NEAR(joints[2].axis.dot(*joints[2].max_limit), M_PI / 4, 1e-12);
  EXPECT_NEAR(joints[2].armature, 0.02, 1e-12);
  EXPECT_NEAR(joints[2].viscous_friction, 0.5, 1e-12);
  // class="main" on the knee: no armature, no range
  EXPECT_EQ(joints[3].armature, 0);
  EXPECT_FALSE(joints[3].max_limit.has_value());
  // ref: the bot starts at q = ref (root DOFs excluded), the joint frame turned back by it
  ASSERT_EQ(walker.articulation.default_pose.size(), 3u);
  EXPECT_NEAR(walker.articulation.default_pose[1], M_PI / 6, 1e-12);
  EXPECT_NEAR(Eigen::AngleAxis<real>(joints[2].parent_link_from_joint.rotation).angle(), M_PI / 6, 1e-6);
  // the capsule from fromto: mass of a capsule of radius 0.03 and length 0.4 at 1000 kg/m^3
  const double r = 0.03, h = 0.4;
  EXPECT_NEAR(*links[2].mass, 1000 * (M_PI * r * r * h + 4.0 / 3 * M_PI * r * r * r), 1e-9);
  EXPECT_NEAR(links[2].center_of_mass->z(), -0.2, 1e-12);
}

TEST_F(MjcfImport, ContactFiltersAndExclusionsBecomeOverrides) {
  std::vector<std::string> warnings;
  const MjcfModel model = load_mjcf(write("walker.xml", kModel), &warnings);
  // contype 2 / conaffinity 2 against 1 / 1: the shin never touches the torso
  EXPECT_TRUE(has_override(model.bots[1], "shin", "torso", false));
  // <exclude>: the door does not touch its frame; the door (on a joint below the world's
  // rigid body) collides with the floor, as in MuJoCo
  EXPECT_TRUE(has_override(model.bots[0], "door_frame", "door", false));
  EXPECT_TRUE(has_override(model.bots[0], "world", "door", true));
}

TEST_F(MjcfImport, IncludesAreExpandedFromTheModelsFolder) {
  write("leg.xml", R"(<mujocoinclude><body name="leg"><joint name="j"/><geom size="0.1"/></body></mujocoinclude>)");
  const std::string path = write("main.xml", R"(<mujoco><worldbody><include file="leg.xml"/></worldbody></mujoco>)");
  std::vector<std::string> warnings;
  const MjcfModel model = load_mjcf(path, &warnings);
  ASSERT_EQ(model.bots.size(), 1u);
  EXPECT_EQ(link_index(model.bots[0], "leg"), 1);
  EXPECT_EQ(model.name, "main");
}

TEST_F(MjcfImport, ErrorsNameTheFileLineAndElement) {
  const std::string path = write("bad.xml", "<mujoco>\n<worldbody>\n<body name=\"b\"><joint name=\"j\" type=\"screw\"/></body>\n</worldbody>\n</mujoco>\n");
  try {
    load_mjcf(path, nullptr);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr(path + ": line 3: <body name='b'>/<joint name='j'>: unknown joint type 'screw'"));
  }
  EXPECT_THROW(load_mjcf(write("cycle.xml", "<mujoco><include file=\"cycle.xml\"/></mujoco>"), nullptr), Error);
}

}  // namespace
}  // namespace superdex::robotics::test

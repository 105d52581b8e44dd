/// @file urdf_import_test.cpp
/// URDF import (urdf_import.cpp) on small URDFs written inline: the joint types and their
/// parameters, the depth-first link order, rpy and inertia rotations against hand-computed
/// matrices, massless links, the "world" root link, collision and visual geometry with
/// package://, relative, file:// and $ROS_PACKAGE_PATH mesh paths, and every rejected input
/// with a message naming the file and the element. Imported prefabs are also built in a
/// scene, and their link poses checked against the URDF's kinematics.

#include <Eigen/Eigenvalues>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include "superdex/physics/engine.h"
#include "superdex/physics/error.h"
#include "superdex/physics/scene.h"
#include "superdex/robotics/bot_prefab.h"

namespace superdex::robotics::test {
namespace {

namespace fs = std::filesystem;
using physics::JointType;
using physics::real;
using physics::Vec3;
using ::testing::AllOf;
using ::testing::HasSubstr;
using ::testing::Not;

// ------------------------------------------------------------------------------------
// helpers

/// A temporary directory, removed with its contents after the test.
class TempDir {
 public:
  TempDir() {
    static int counter = 0;
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = fs::temp_directory_path() / ("superdex_urdf_" + std::string(info ? info->name() : "test") + "_" +
                                         std::to_string(::getpid()) + "_" + std::to_string(counter++));
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

/// Writes `content` to `path`, creating the folders, and returns the path.
std::string write_file(const fs::path& path, const std::string& content) {
  fs::create_directories(path.parent_path());
  std::ofstream(path, std::ios::binary) << content;
  return path.string();
}

/// A unit cube (half side 0.5) centred at the origin, as OBJ text.
const char* kCubeObj =
    "v -0.5 -0.5 -0.5\nv 0.5 -0.5 -0.5\nv -0.5 0.5 -0.5\nv 0.5 0.5 -0.5\n"
    "v -0.5 -0.5 0.5\nv 0.5 -0.5 0.5\nv -0.5 0.5 0.5\nv 0.5 0.5 0.5\n"
    "f 1 3 2\nf 2 3 4\nf 5 6 7\nf 6 8 7\nf 1 2 5\nf 2 6 5\nf 3 7 4\nf 4 7 8\nf 1 5 3\nf 3 5 7\nf 2 4 6\nf 4 8 6\n";

/// An inertial block with a diagonal inertia.
std::string inertial(double mass = 1.0, const std::string& origin = "") {
  return "<inertial>" + origin + "<mass value=\"" + std::to_string(mass) +
         "\"/><inertia ixx=\"0.01\" ixy=\"0\" ixz=\"0\" iyy=\"0.01\" iyz=\"0\" izz=\"0.01\"/></inertial>";
}

std::string link(const std::string& name, const std::string& body = inertial()) {
  return "<link name=\"" + name + "\">" + body + "</link>\n";
}

std::string joint(const std::string& name, const std::string& type, const std::string& parent, const std::string& child,
                  const std::string& body = "") {
  return "<joint name=\"" + name + "\" type=\"" + type + "\"><parent link=\"" + parent + "\"/><child link=\"" + child +
         "\"/>" + body + "</joint>\n";
}

std::string robot(const std::string& body, const std::string& name = "bot") {
  return "<?xml version=\"1.0\"?>\n<robot name=\"" + name + "\">\n" + body + "</robot>\n";
}

int link_index(const BotPrefab& p, const std::string& name) {
  for (size_t i = 0; i < p.articulation.links.size(); ++i)
    if (p.articulation.links[i].name == name) return static_cast<int>(i);
  ADD_FAILURE() << "no link named " << name;
  return -1;
}

const physics::JointDesc& joint_of(const BotPrefab& p, const std::string& link_name) {
  return p.articulation.joints.at(link_index(p, link_name));
}

/// Rotation matrices about the axes, written out.
Eigen::Matrix3d rot_x(double a) {
  Eigen::Matrix3d R;
  R << 1, 0, 0, 0, std::cos(a), -std::sin(a), 0, std::sin(a), std::cos(a);
  return R;
}
Eigen::Matrix3d rot_y(double a) {
  Eigen::Matrix3d R;
  R << std::cos(a), 0, std::sin(a), 0, 1, 0, -std::sin(a), 0, std::cos(a);
  return R;
}
Eigen::Matrix3d rot_z(double a) {
  Eigen::Matrix3d R;
  R << std::cos(a), -std::sin(a), 0, std::sin(a), std::cos(a), 0, 0, 0, 1;
  return R;
}

Eigen::Matrix3d rotation_of(const physics::Transform& X) { return X.rotation.toRotationMatrix().cast<double>(); }

Eigen::Matrix3d inertia_of(const physics::LinkDesc& L) {
  const auto& c = *L.moment_of_inertia;
  Eigen::Matrix3d I;
  I << c[0], c[1], c[2], c[1], c[3], c[4], c[2], c[4], c[5];
  return I;
}

/// Writes URDFs to a temporary folder and imports them; an SDF cache inside it; a running engine.
class UrdfImport : public ::testing::Test {
 protected:
  void SetUp() override {
    setenv("SUPERDEX_CACHE_DIR", (dir_.path() / "sdf_cache").c_str(), 1);
    physics::initialize(0);
  }
  void TearDown() override {
    physics::shutdown();
    unsetenv("SUPERDEX_CACHE_DIR");
  }

  std::string write(const std::string& relative, const std::string& text) { return write_file(dir_.path() / relative, text); }

  BotPrefab load(const std::string& urdf, const std::string& relative = "robot.urdf") {
    warnings_.clear();
    return load_bot_prefab_from_urdf(write(relative, urdf), &warnings_);
  }

  /// The same with the root welded to the world.
  BotPrefab load_fixed(const std::string& urdf) {
    warnings_.clear();
    return load_bot_prefab_from_urdf(write("robot.urdf", urdf), &warnings_, UrdfImportOptions{.fixed_base = true});
  }

  /// The message of the superdex::Error that importing `urdf` throws ("" if none).
  std::string error_of(const std::string& urdf, const std::string& relative = "robot.urdf") {
    const std::string path = write(relative, urdf);
    try {
      load_bot_prefab_from_urdf(path, &warnings_);
    } catch (const Error& e) {
      return e.what();
    }
    ADD_FAILURE() << "importing did not throw:\n" << urdf;
    return "";
  }

  std::string all_warnings() const {
    std::string s;
    for (const auto& w : warnings_) s += w + "\n";
    return s;
  }

  /// Builds the prefab's articulation in a new scene.
  physics::ActorHandle build(const BotPrefab& p) {
    scene_ = physics::create_scene("urdf");
    return scene_->create_articulated_actor(p.articulation, p.source);
  }

  TempDir dir_;
  std::vector<std::string> warnings_;
  std::optional<physics::Scene> scene_;
};

// ------------------------------------------------------------------------------------
// joints and links

TEST_F(UrdfImport, JointTypesLimitsDynamicsAndPrefabFields) {
  const std::string urdf = robot(
      link("base") + link("a") + link("b") + link("c") + link("d") +
          joint("j_rev", "revolute", "base", "a",
                "<axis xyz=\"0 0 2\"/><limit lower=\"-1.5\" upper=\"0.5\" effort=\"12\" velocity=\"3\"/>"
                "<dynamics damping=\"0.25\" friction=\"0.75\"/>") +
          joint("j_cont", "continuous", "a", "b", "<axis xyz=\"0 1 0\"/><limit effort=\"7\" velocity=\"1\"/>") +
          joint("j_pri", "prismatic", "b", "c", "<axis xyz=\"0 -1 0\"/><limit lower=\"0\" upper=\"0.04\" effort=\"100\" velocity=\"0.2\"/>") +
          joint("j_fix", "fixed", "c", "d", "<origin xyz=\"0 0 0.1\"/>"),
      "my_robot");
  const BotPrefab p = load(urdf);
  const auto& art = p.articulation;
  EXPECT_EQ(p.name(), "my_robot");
  EXPECT_EQ(p.source, (dir_.path() / "robot.urdf").string());
  EXPECT_EQ(fs::path(p.base_dir), dir_.path());
  ASSERT_EQ(art.links.size(), 5u);
  ASSERT_EQ(art.joints.size(), 5u);
  EXPECT_TRUE(art.default_pose.empty());
  EXPECT_EQ(p.sensors.size(), 5u);
  EXPECT_EQ(p.actuators.size(), 5u);
  for (size_t i = 0; i < 5; ++i) EXPECT_TRUE(p.sensors[i].empty() && p.actuators[i].empty());

  // the root: a floating base, on a Free joint named "world_joint"
  EXPECT_EQ(art.links[0].name, "base");
  EXPECT_EQ(art.links[0].parent_link, -1);
  EXPECT_EQ(art.joints[0].type, JointType::Free);
  EXPECT_EQ(art.joints[0].name, "world_joint");

  // revolute: normalised axis, limits as vectors along it, effort, damping -> viscous, friction -> Coulomb
  const auto& rev = joint_of(p, "a");
  EXPECT_EQ(rev.name, "j_rev");
  EXPECT_EQ(rev.type, JointType::Revolute);
  EXPECT_TRUE(rev.axis.isApprox(Vec3(0, 0, 1)));
  ASSERT_TRUE(rev.min_limit && rev.max_limit);
  EXPECT_TRUE(rev.min_limit->isApprox(Vec3(0, 0, -1.5)));
  EXPECT_TRUE(rev.max_limit->isApprox(Vec3(0, 0, 0.5)));
  EXPECT_DOUBLE_EQ(rev.effort_limit, 12);
  EXPECT_DOUBLE_EQ(rev.viscous_friction, 0.25);
  EXPECT_DOUBLE_EQ(rev.coulomb_friction, 0.75);
  EXPECT_DOUBLE_EQ(rev.armature, 0);

  // continuous: revolute without limits
  const auto& cont = joint_of(p, "b");
  EXPECT_EQ(cont.type, JointType::Revolute);
  EXPECT_TRUE(cont.axis.isApprox(Vec3(0, 1, 0)));
  EXPECT_FALSE(cont.min_limit.has_value());
  EXPECT_FALSE(cont.max_limit.has_value());
  EXPECT_DOUBLE_EQ(cont.effort_limit, 7);
  EXPECT_DOUBLE_EQ(cont.viscous_friction, 0);

  // prismatic: limit value = axis . vector
  const auto& pri = joint_of(p, "c");
  EXPECT_EQ(pri.type, JointType::Prismatic);
  ASSERT_TRUE(pri.min_limit && pri.max_limit);
  EXPECT_NEAR(pri.axis.dot(*pri.min_limit), 0, 1e-15);
  EXPECT_NEAR(pri.axis.dot(*pri.max_limit), 0.04, 1e-15);
  EXPECT_TRUE(pri.max_limit->isApprox(Vec3(0, -0.04, 0)));

  // fixed: Hard, placed by its origin
  const auto& fix = joint_of(p, "d");
  EXPECT_EQ(fix.type, JointType::Hard);
  EXPECT_TRUE(fix.parent_link_from_joint.translation.isApprox(Vec3(0, 0, 0.1)));
  EXPECT_TRUE(warnings_.empty()) << all_warnings();

  // the engine accepts the description: 3 joint DOFs behind the floating base's 6
  const auto art_handle = build(p);
  EXPECT_EQ(scene_->num_dofs(art_handle), 6 + 3);
}

TEST_F(UrdfImport, DefaultAxisIsX) {
  const BotPrefab p = load(robot(link("base") + link("a") +
                                 joint("j", "revolute", "base", "a", "<limit lower=\"-1\" upper=\"1\" effort=\"1\" velocity=\"1\"/>")));
  EXPECT_TRUE(joint_of(p, "a").axis.isApprox(Vec3(1, 0, 0)));
}

TEST_F(UrdfImport, LinksAreOrderedDepthFirstWithParentsFirst) {
  // links and joints declared in a scrambled order; the tree is
  // root -> {arm -> {hand -> finger}, leg -> foot}, children in joint document order
  const std::string fixed_body = "";
  const BotPrefab p = load(robot(link("foot") + link("hand") + link("leg") + link("finger") + link("root") + link("arm") +
                                 joint("j_hand", "fixed", "arm", "hand") + joint("j_arm", "fixed", "root", "arm") +
                                 joint("j_foot", "fixed", "leg", "foot") + joint("j_finger", "fixed", "hand", "finger") +
                                 joint("j_leg", "fixed", "root", "leg")));
  std::vector<std::string> names;
  for (const auto& L : p.articulation.links) names.push_back(L.name);
  EXPECT_EQ(names, (std::vector<std::string>{"root", "arm", "hand", "finger", "leg", "foot"}));
  const auto& links = p.articulation.links;
  for (size_t i = 1; i < links.size(); ++i) EXPECT_LT(links[i].parent_link, static_cast<int>(i)) << links[i].name;
  EXPECT_EQ(links[link_index(p, "finger")].parent_link, link_index(p, "hand"));
  EXPECT_EQ(links[link_index(p, "foot")].parent_link, link_index(p, "leg"));
  EXPECT_EQ(links[link_index(p, "leg")].parent_link, 0);
  EXPECT_EQ(joint_of(p, "foot").name, "j_foot");
}

TEST_F(UrdfImport, RootJointNameAvoidsClashes) {
  const BotPrefab p = load(robot(link("base") + link("a") + joint("world_joint", "fixed", "base", "a")));
  EXPECT_EQ(p.articulation.joints[0].name, "world_joint_1");
}

TEST_F(UrdfImport, FixedBaseOptionWeldsTheRoot) {
  const std::string path = write("robot.urdf", robot(link("base") + link("a") + joint("j", "continuous", "base", "a")));
  const BotPrefab fixed = load_bot_prefab_from_urdf(path, &warnings_, UrdfImportOptions{.fixed_base = true});
  EXPECT_EQ(fixed.articulation.joints[0].type, JointType::Hard);
  EXPECT_EQ(fixed.articulation.joints[0].name, "world_joint");
  // the floating base adds six DOFs in front of the joint's one
  const BotPrefab floating = load_bot_prefab_from_urdf(path, &warnings_);
  EXPECT_EQ(floating.articulation.joints[0].type, JointType::Free);
  const auto fixed_actor = build(fixed);
  EXPECT_EQ(scene_->num_dofs(fixed_actor), 1);
  const auto floating_actor = build(floating);
  EXPECT_EQ(scene_->num_dofs(floating_actor), 7);
}

TEST_F(UrdfImport, RpyIsFixedAxisRollPitchYaw) {
  const double roll = 0.3, pitch = -0.5, yaw = 1.2;
  const BotPrefab p = load_fixed(robot(link("base") + link("a") + link("b") +
                                 joint("j1", "fixed", "base", "a", "<origin xyz=\"0.1 -0.2 0.3\" rpy=\"0.3 -0.5 1.2\"/>") +
                                 joint("j2", "continuous", "a", "b", "<origin xyz=\"0.5 0 0\" rpy=\"0 0 1.5707963267948966\"/><axis xyz=\"0 0 1\"/>")));
  const physics::Transform& X = joint_of(p, "a").parent_link_from_joint;
  const Eigen::Matrix3d want = rot_z(yaw) * rot_y(pitch) * rot_x(roll);
  EXPECT_TRUE(rotation_of(X).isApprox(want, 1e-14)) << rotation_of(X) << "\nexpected\n" << want;
  EXPECT_TRUE(X.translation.isApprox(Vec3(0.1, -0.2, 0.3)));

  // the engine places the links accordingly: X_WB = X_PJ1 * X_PJ2 * Rz(q)
  const auto h = build(p);
  const double q = 0.7;
  physics::VecX pose(1);
  pose << q;
  scene_->set_pose(h, pose);
  const std::vector<physics::Transform> X_WL = scene_->link_transforms(h);
  ASSERT_EQ(X_WL.size(), 3u);
  const Eigen::Matrix3d R_WA = want;
  const Eigen::Vector3d p_WA(0.1, -0.2, 0.3);
  const Eigen::Matrix3d R_WB = R_WA * rot_z(EIGEN_PI / 2) * rot_z(q);
  const Eigen::Vector3d p_WB = p_WA + R_WA * Eigen::Vector3d(0.5, 0, 0);
  EXPECT_TRUE(rotation_of(X_WL[1]).isApprox(R_WA, 1e-12));
  EXPECT_TRUE(X_WL[1].translation.isApprox(p_WA, 1e-12));
  EXPECT_TRUE(rotation_of(X_WL[2]).isApprox(R_WB, 1e-12));
  EXPECT_TRUE(X_WL[2].translation.isApprox(p_WB, 1e-12));
}

TEST_F(UrdfImport, InertialIsRotatedIntoTheLinkFrame) {
  const std::string body =
      "<inertial><origin xyz=\"0.1 0.2 0.3\" rpy=\"0.4 0.5 -0.6\"/><mass value=\"2.5\"/>"
      "<inertia ixx=\"0.3\" ixy=\"0.01\" ixz=\"-0.02\" iyy=\"0.4\" iyz=\"0.03\" izz=\"0.5\"/></inertial>";
  const std::string quarter_turn =
      "<inertial><origin rpy=\"0 0 1.5707963267948966\"/><mass value=\"1\"/>"
      "<inertia ixx=\"1\" ixy=\"0\" ixz=\"0\" iyy=\"2\" iyz=\"0\" izz=\"3\"/></inertial>";
  const BotPrefab p = load(robot(link("base", body) + link("a", quarter_turn) + joint("j", "fixed", "base", "a")));
  const auto& L = p.articulation.links[0];
  ASSERT_TRUE(L.mass && L.center_of_mass && L.moment_of_inertia);
  EXPECT_DOUBLE_EQ(*L.mass, 2.5);
  EXPECT_TRUE(L.center_of_mass->isApprox(Vec3(0.1, 0.2, 0.3)));
  Eigen::Matrix3d I;
  I << 0.3, 0.01, -0.02, 0.01, 0.4, 0.03, -0.02, 0.03, 0.5;
  const Eigen::Matrix3d R = rot_z(-0.6) * rot_y(0.5) * rot_x(0.4);
  EXPECT_TRUE(inertia_of(L).isApprox(R * I * R.transpose(), 1e-14)) << inertia_of(L);
  // a quarter turn about z swaps the x and y moments
  const Eigen::Matrix3d I_a = inertia_of(p.articulation.links[1]);
  EXPECT_TRUE(I_a.isApprox(Eigen::Vector3d(2, 1, 3).asDiagonal().toDenseMatrix(), 1e-14)) << I_a;
  EXPECT_TRUE(p.articulation.links[1].center_of_mass->isZero());
}

TEST_F(UrdfImport, MasslessLinksGetANegligibleMass) {
  // a tool frame without <inertial>, a flange with mass 0, and a massless link that moves
  // but carries a massive link welded to it
  const std::string zero_mass =
      "<inertial><mass value=\"0\"/><inertia ixx=\"0\" ixy=\"0\" ixz=\"0\" iyy=\"0\" iyz=\"0\" izz=\"0\"/></inertial>";
  const BotPrefab p = load_fixed(robot(
      link("base") + link("arm") + link("flange", zero_mass) + link("tool", "") + link("wrist", "") + link("hand") +
      joint("j_arm", "continuous", "base", "arm", "<axis xyz=\"0 1 0\"/>") +
      joint("j_flange", "fixed", "arm", "flange", "<origin xyz=\"1 0 0\"/>") +
      joint("j_tool", "fixed", "flange", "tool", "<origin xyz=\"0.1 0 0\"/>") +
      joint("j_wrist", "continuous", "arm", "wrist", "<axis xyz=\"1 0 0\"/>") +
      joint("j_hand", "fixed", "wrist", "hand", "<origin xyz=\"0 0 0.2\"/>")));
  for (const char* name : {"flange", "tool", "wrist"}) {
    const auto& L = p.articulation.links[link_index(p, name)];
    ASSERT_TRUE(L.mass && L.moment_of_inertia && L.center_of_mass) << name;
    EXPECT_DOUBLE_EQ(*L.mass, 1e-9) << name;
    EXPECT_TRUE(inertia_of(L).isApprox(1e-12 * Eigen::Matrix3d::Identity())) << name;
    EXPECT_TRUE(L.center_of_mass->isZero()) << name;
  }
  // the engine accepts it, and the tool's 1e-9 kg at 1.1 m changes the inertia about j_arm
  // by about 1e-9 kg m^2 only
  const auto h = build(p);
  const physics::MatX M = scene_->mass_matrix(h);
  ASSERT_EQ(M.rows(), 2);
  // arm: 0.01 about its origin; wrist + hand: 1 kg at (0, 0, 0.2): 0.01 + 0.04 about y;
  // flange and tool: 1e-9 kg at 1 m and 1.1 m, plus 1e-12 for each massless link
  EXPECT_NEAR(M(0, 0) - (0.01 + 0.01 + 0.04), 1e-9 * (1 + 1.21) + 3e-12, 1e-15);
}

// An <inertia> with principal moments (a, b, c) about its axes.
std::string inertial_moments(double a, double b, double c) {
  return "<inertial><mass value=\"2\"/><inertia ixx=\"" + std::to_string(a) + "\" ixy=\"0\" ixz=\"0\" iyy=\"" + std::to_string(b) +
         "\" iyz=\"0\" izz=\"" + std::to_string(c) + "\"/></inertial>";
}

TEST_F(UrdfImport, UnphysicalInertiasAreRepairedWithAWarning) {
  // a point mass (all moments zero), a rod-like inertia with round-off below zero, and moments
  // breaking the triangle inequality (0.001 + 0.002 < 0.01)
  const BotPrefab p = load(robot(link("base") + link("point", inertial_moments(0, 0, 0)) +
                                 link("rod", "<inertial><mass value=\"1\"/><inertia ixx=\"-1e-20\" ixy=\"0\" ixz=\"0\" "
                                             "iyy=\"0.5\" iyz=\"0\" izz=\"0.5\"/></inertial>") +
                                 link("flat", inertial_moments(0.001, 0.002, 0.01)) + joint("j1", "fixed", "base", "point") +
                                 joint("j2", "continuous", "base", "rod") + joint("j3", "continuous", "rod", "flat")));
  const std::string w = all_warnings();
  EXPECT_THAT(w, HasSubstr("<link name='point'>/<inertial>/<inertia>: link 'point': the inertia must be positive definite"));
  EXPECT_THAT(w, HasSubstr("link 'rod': the inertia must be positive definite"));
  EXPECT_THAT(w, HasSubstr("link 'flat': the inertia is not physically valid: principal moments violate the triangle inequality"));
  EXPECT_THAT(w, Not(HasSubstr("link 'base'")));
  // nearest physical moments: raised to 1e-6 of the largest (1e-9 kg m^2 when none is
  // positive), the largest lowered to the sum of the other two
  const auto moments = [&](const char* name) {
    return Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(inertia_of(p.articulation.links[link_index(p, name)])).eigenvalues();
  };
  EXPECT_TRUE(moments("point").isApprox(Eigen::Vector3d(1e-9, 1e-9, 1e-9), 1e-5)) << moments("point").transpose();
  EXPECT_TRUE(moments("rod").isApprox(Eigen::Vector3d(5e-7, 0.5, 0.5), 1e-5)) << moments("rod").transpose();
  EXPECT_TRUE(moments("flat").isApprox(Eigen::Vector3d(0.001, 0.002, 0.003), 1e-5)) << moments("flat").transpose();
  EXPECT_DOUBLE_EQ(*p.articulation.links[link_index(p, "flat")].mass, 2.0);  // the mass is kept
  // and the engine builds and steps it
  const auto h = build(p);
  scene_->step(0.01);
  EXPECT_TRUE(scene_->mass_matrix(h).allFinite());
}

TEST_F(UrdfImport, ZeroMassWithARotationalInertiaKeepsTheInertia) {
  // a foot of mass 0 that still gives a rotational inertia (as example-robot-data's bolt does):
  // kept, as Pinocchio keeps it, on the negligible mass at the inertial origin
  const std::string foot =
      "<inertial><origin xyz=\"0 0 0.05\"/><mass value=\"0\"/>"
      "<inertia ixx=\"5e-7\" ixy=\"0\" ixz=\"0\" iyy=\"8e-7\" iyz=\"0\" izz=\"4e-7\"/></inertial>";
  const BotPrefab p = load_fixed(robot(link("base") + link("leg") + link("foot", foot) +
                                       joint("j_leg", "continuous", "base", "leg", "<axis xyz=\"0 1 0\"/>") +
                                       joint("j_foot", "continuous", "leg", "foot", "<axis xyz=\"1 0 0\"/>")));
  const auto& L = p.articulation.links[link_index(p, "foot")];
  ASSERT_TRUE(L.mass && L.moment_of_inertia && L.center_of_mass);
  EXPECT_DOUBLE_EQ(*L.mass, 1e-9);
  EXPECT_TRUE(inertia_of(L).isApprox(Eigen::Vector3d(5e-7, 8e-7, 4e-7).asDiagonal().toDenseMatrix(), 1e-6));
  EXPECT_TRUE(L.center_of_mass->isApprox(Vec3(0, 0, real(0.05))));
  EXPECT_TRUE(warnings_.empty()) << all_warnings();
  // the foot's own hinge sees its inertia about x, not a negligible one
  const auto h = build(p);
  EXPECT_NEAR(scene_->mass_matrix(h)(1, 1), 5e-7 + 1e-9 * 0.05 * 0.05, 1e-12);
}

TEST_F(UrdfImport, MasslessIntermediateFramesOfAMultiAxisJointMove) {
  // a hip made of three single-axis joints through two massless frames, carrying a 1 kg leg
  const BotPrefab p = load_fixed(robot(link("pelvis") + link("hip_z", "") + link("hip_x", "") + link("leg") +
                                 joint("z", "continuous", "pelvis", "hip_z", "<axis xyz=\"0 0 1\"/>") +
                                 joint("x", "continuous", "hip_z", "hip_x", "<axis xyz=\"1 0 0\"/>") +
                                 joint("y", "continuous", "hip_x", "leg", "<axis xyz=\"0 1 0\"/>")));
  const auto h = build(p);
  // the leg's 0.01 kg m^2 about each axis, and 1e-12 per massless frame on the axes that move it
  const physics::MatX M = scene_->mass_matrix(h);
  ASSERT_EQ(M.rows(), 3);
  EXPECT_NEAR(M(0, 0), 0.01 + 2e-12, 1e-12);
  EXPECT_NEAR(M(2, 2), 0.01, 1e-12);
  EXPECT_GT(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(M.cast<double>()).eigenvalues().minCoeff(), 0.005);
}

TEST_F(UrdfImport, WorldLinkWithFixedJointIsDropped) {
  const BotPrefab p = load(robot(link("world", "") + link("base") + link("a") +
                                 joint("world_joint", "fixed", "world", "base", "<origin xyz=\"0 0 0.5\" rpy=\"0 0 0.3\"/>") +
                                 joint("j", "continuous", "base", "a")));
  const auto& art = p.articulation;
  ASSERT_EQ(art.links.size(), 2u);
  EXPECT_EQ(art.links[0].name, "base");
  EXPECT_EQ(art.joints[0].name, "world_joint");
  EXPECT_EQ(art.joints[0].type, JointType::Hard);
  EXPECT_TRUE(art.joints[0].parent_link_from_joint.translation.isApprox(Vec3(0, 0, 0.5)));
  EXPECT_TRUE(rotation_of(art.joints[0].parent_link_from_joint).isApprox(rot_z(0.3), 1e-14));
  const auto h = build(p);
  EXPECT_TRUE(scene_->link_transforms(h)[0].translation.isApprox(Vec3(0, 0, 0.5)));
}

TEST_F(UrdfImport, WorldLinkWithFloatingJointMakesAFreeRoot) {
  const BotPrefab p = load(robot(link("world", "") + link("body") + link("wheel") +
                                 joint("float", "floating", "world", "body") +
                                 joint("axle", "continuous", "body", "wheel", "<axis xyz=\"0 1 0\"/>")));
  const auto& art = p.articulation;
  ASSERT_EQ(art.links.size(), 2u);
  EXPECT_EQ(art.links[0].name, "body");
  EXPECT_EQ(art.joints[0].name, "float");
  EXPECT_EQ(art.joints[0].type, JointType::Free);
  const auto h = build(p);
  EXPECT_EQ(scene_->num_dofs(h), 7);
}

TEST_F(UrdfImport, WorldLinkOnAMovingJointStaysAsAWeldedLink) {
  const BotPrefab p = load(robot(link("world", "") + link("pendulum") +
                                 joint("hinge", "continuous", "world", "pendulum", "<axis xyz=\"0 1 0\"/>")));
  const auto& art = p.articulation;
  ASSERT_EQ(art.links.size(), 2u);
  EXPECT_EQ(art.links[0].name, "world");
  // a root named "world" is welded to the world whatever the options
  EXPECT_EQ(art.joints[0].type, JointType::Hard);
  EXPECT_EQ(art.joints[0].name, "world_joint");
  EXPECT_EQ(art.joints[1].name, "hinge");
  EXPECT_DOUBLE_EQ(*art.links[0].mass, 1e-9);
  build(p);
}

TEST_F(UrdfImport, MimicBecomesACoupling) {
  const BotPrefab p = load(robot(link("base") + link("a") + link("b") +
                                 joint("j1", "continuous", "base", "a") +
                                 joint("j2", "continuous", "base", "b", "<mimic joint=\"j1\" multiplier=\"-1\" offset=\"0.25\"/>")));
  EXPECT_EQ(p.articulation.joints.size(), 3u);
  ASSERT_EQ(p.articulation.couplings.size(), 1u);
  const physics::JointCoupling& c = p.articulation.couplings[0];
  EXPECT_EQ(c.joint, "j2");
  EXPECT_EQ(c.leader, "j1");
  EXPECT_EQ(c.ratio, -1);
  EXPECT_EQ(c.offset, real(0.25));
  EXPECT_THAT(all_warnings(), Not(HasSubstr("mimic")));
  build(p);
  // a mimic of a joint that does not exist: ignored, named in a warning
  const BotPrefab q = load(robot(link("base") + link("a") + joint("j2", "continuous", "base", "a", "<mimic joint=\"nope\"/>")));
  EXPECT_TRUE(q.articulation.couplings.empty());
  EXPECT_THAT(all_warnings(), HasSubstr("<mimic> is ignored: it refers to joint 'nope', which is not defined"));
}

// ------------------------------------------------------------------------------------
// geometry

TEST_F(UrdfImport, PrimitiveCollisionShapes) {
  const std::string box =
      "<collision><origin xyz=\"0.1 0.2 0.3\" rpy=\"0 0 1.5707963267948966\"/><geometry><box size=\"0.2 0.4 0.6\"/></geometry></collision>"
      "<collision><geometry><sphere radius=\"1\"/></geometry></collision>";
  const std::string sphere = "<collision><geometry><sphere radius=\"0.25\"/></geometry></collision>";
  const std::string cylinder = "<collision><geometry><cylinder radius=\"0.1\" length=\"0.5\"/></geometry></collision>";
  const std::string capsule = "<collision><geometry><capsule radius=\"0.1\" length=\"0.5\"/></geometry></collision>";
  const BotPrefab p = load(robot(link("base", inertial() + box) + link("s", inertial() + sphere) +
                                 link("c", inertial() + cylinder) + link("k", inertial() + capsule) +
                                 joint("js", "fixed", "base", "s") + joint("jc", "fixed", "base", "c") +
                                 joint("jk", "fixed", "base", "k")));
  const auto& links = p.articulation.links;
  const auto& L0 = links[link_index(p, "base")];
  ASSERT_TRUE(L0.shape.has_value());
  ASSERT_TRUE(std::holds_alternative<physics::BoxShape>(*L0.shape));
  EXPECT_TRUE(std::get<physics::BoxShape>(*L0.shape).half_extents.isApprox(Vec3(0.1, 0.2, 0.3)));
  EXPECT_TRUE(L0.link_from_shape.translation.isApprox(Vec3(0.1, 0.2, 0.3)));
  EXPECT_TRUE(rotation_of(L0.link_from_shape).isApprox(rot_z(EIGEN_PI / 2), 1e-14));
  // compound collision: the second <collision> (a unit sphere at the link origin) is kept
  ASSERT_EQ(L0.extra_shapes.size(), 1u);
  ASSERT_TRUE(std::holds_alternative<physics::SphereShape>(L0.extra_shapes[0].shape));
  EXPECT_DOUBLE_EQ(std::get<physics::SphereShape>(L0.extra_shapes[0].shape).radius, 1.0);
  EXPECT_TRUE(L0.extra_shapes[0].link_from_shape.translation.isZero());
  EXPECT_TRUE(warnings_.empty()) << all_warnings();

  const auto& Ls = links[link_index(p, "s")];
  ASSERT_TRUE(Ls.shape && std::holds_alternative<physics::SphereShape>(*Ls.shape));
  EXPECT_DOUBLE_EQ(std::get<physics::SphereShape>(*Ls.shape).radius, 0.25);

  // a cylinder is a closed prism mesh: radius 0.1, z from -0.25 to 0.25
  const auto& Lc = links[link_index(p, "c")];
  ASSERT_TRUE(Lc.shape && std::holds_alternative<physics::MeshShape>(*Lc.shape));
  const auto& mesh = std::get<physics::MeshShape>(*Lc.shape);
  ASSERT_TRUE(mesh.mesh && mesh.sdf);
  EXPECT_TRUE(mesh.convex);
  double max_r = 0, min_z = 1, max_z = -1;
  for (const Vec3& v : mesh.mesh->vertices) {
    max_r = std::max(max_r, double(v.head<2>().norm()));
    min_z = std::min(min_z, double(v.z()));
    max_z = std::max(max_z, double(v.z()));
  }
  EXPECT_NEAR(max_r, 0.1, 1e-12);
  EXPECT_NEAR(min_z, -0.25, 1e-12);
  EXPECT_NEAR(max_z, 0.25, 1e-12);

  const auto& Lk = links[link_index(p, "k")];
  ASSERT_TRUE(Lk.shape && std::holds_alternative<physics::CapsuleShape>(*Lk.shape));
  EXPECT_DOUBLE_EQ(std::get<physics::CapsuleShape>(*Lk.shape).half_length, 0.25);

  // the links' masses are the inertials', not the shapes'
  EXPECT_DOUBLE_EQ(*Lc.mass, 1.0);
  build(p);
}

// A mesh link: collision and visual meshes named by `filename`.
std::string mesh_link(const std::string& name, const std::string& filename, const std::string& scale = "") {
  const std::string s = scale.empty() ? "" : " scale=\"" + scale + "\"";
  return link(name, inertial() + "<visual><geometry><mesh filename=\"" + filename + "\"" + s +
                        "/></geometry></visual><collision><geometry><mesh filename=\"" + filename + "\"" + s +
                        "/></geometry></collision>");
}

TEST_F(UrdfImport, MirroredMeshesAreMirroredAndFaceOutward) {
  // a box [0, 1] x [0, 2] x [0, 3] (off-centre, so that mirroring moves it), scaled by -1 in y
  const std::string box =
      "v 0 0 0\nv 1 0 0\nv 0 2 0\nv 1 2 0\nv 0 0 3\nv 1 0 3\nv 0 2 3\nv 1 2 3\n"
      "f 1 3 2\nf 2 3 4\nf 5 6 7\nf 6 8 7\nf 1 2 5\nf 2 6 5\nf 3 7 4\nf 4 7 8\nf 1 5 3\nf 3 5 7\nf 2 4 6\nf 4 8 6\n";
  write("meshes/box.obj", box);
  const BotPrefab p = load(robot(mesh_link("base", "meshes/box.obj", "1 -1 1")));
  const auto* mesh = std::get_if<physics::MeshShape>(&*p.articulation.links[0].shape);
  ASSERT_NE(mesh, nullptr);
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e9), hi = -lo;
  double volume = 0;
  for (const auto& v : mesh->mesh->vertices) lo = lo.cwiseMin(v.cast<double>()), hi = hi.cwiseMax(v.cast<double>());
  for (const auto& t : mesh->mesh->triangles) {
    const Eigen::Vector3d a = mesh->mesh->vertices[t[0]].cast<double>(), b = mesh->mesh->vertices[t[1]].cast<double>(),
                          c = mesh->mesh->vertices[t[2]].cast<double>();
    volume += a.dot(b.cross(c)) / 6;
  }
  EXPECT_TRUE(lo.isApprox(Eigen::Vector3d(0, -2, 0))) << lo.transpose();
  EXPECT_TRUE(hi.isApprox(Eigen::Vector3d(1, 0, 3))) << hi.transpose();
  EXPECT_NEAR(volume, 6.0, 1e-9);  // outward: a positive enclosed volume
  EXPECT_THAT(error_of(robot(mesh_link("base", "meshes/box.obj", "1 0 1"))), HasSubstr("attribute 'scale' must be finite and non-zero"));
}

Eigen::AlignedBox3d bounds(const physics::LinkDesc& L) {
  Eigen::AlignedBox3d box;
  for (const Vec3& v : std::get<physics::MeshShape>(*L.shape).mesh->vertices) box.extend(v.cast<double>());
  return box;
}

TEST_F(UrdfImport, PackageUrisAreFoundUpwardFromTheUrdf) {
  // <tmp>/share/my_pkg/{urdf/robot.urdf, meshes/cube.obj} and <tmp>/share/other_pkg/meshes/cube.obj
  const std::string cube = write("share/my_pkg/meshes/cube.obj", kCubeObj);
  const std::string other = write("share/other_pkg/meshes/cube.obj", kCubeObj);
  const BotPrefab p = load(robot(mesh_link("base", "package://my_pkg/meshes/cube.obj", "2 1 0.5") +
                                 mesh_link("a", "package://other_pkg/meshes/cube.obj") + joint("j", "fixed", "base", "a")),
                           "share/my_pkg/urdf/robot.urdf");
  const auto& L0 = p.articulation.links[0];
  // found in the folder named my_pkg above the URDF; the scale is baked into the vertices
  EXPECT_EQ(fs::path(L0.shape_file), fs::path(cube));
  EXPECT_EQ(fs::path(L0.render_model), fs::path(cube));
  EXPECT_TRUE(L0.render_model_scale.isApprox(Vec3(2, 1, 0.5)));
  EXPECT_TRUE(L0.shape_scale.isApprox(Vec3::Ones()));
  EXPECT_TRUE(bounds(L0).max().isApprox(Eigen::Vector3d(1, 0.5, 0.25)));
  // other_pkg: found in a folder above the URDF that contains it
  EXPECT_EQ(fs::path(p.articulation.links[1].shape_file), fs::path(other));
  EXPECT_TRUE(warnings_.empty()) << all_warnings();
  build(p);
}

TEST_F(UrdfImport, RelativeAndFileUris) {
  const std::string cube = write("meshes/cube.obj", kCubeObj);
  const std::string abs = write("elsewhere/box.obj", kCubeObj);
  const BotPrefab p = load(robot(mesh_link("base", "../meshes/cube.obj", "0.1 0.1 0.1") +
                                 mesh_link("a", "file://" + abs) + joint("j", "fixed", "base", "a")),
                           "urdf/robot.urdf");
  EXPECT_EQ(fs::path(p.articulation.links[0].shape_file), fs::path(cube));
  EXPECT_TRUE(bounds(p.articulation.links[0]).max().isApprox(Eigen::Vector3d(0.05, 0.05, 0.05)));
  EXPECT_EQ(fs::path(p.articulation.links[1].shape_file), fs::path(abs));
  EXPECT_EQ(fs::path(p.articulation.links[1].render_model), fs::path(abs));
}

TEST_F(UrdfImport, RosPackagePathIsSearched) {
  const std::string cube = write("ros/ws/src/far_pkg/meshes/cube.obj", kCubeObj);
  const std::string old = std::getenv("ROS_PACKAGE_PATH") ? std::getenv("ROS_PACKAGE_PATH") : "";
  setenv("ROS_PACKAGE_PATH", ("/nonexistent:" + (dir_.path() / "ros/ws/src").string()).c_str(), 1);
  std::optional<BotPrefab> p;
  EXPECT_NO_THROW(p = load(robot(mesh_link("base", "package://far_pkg/meshes/cube.obj")), "urdf/robot.urdf"));
  if (old.empty()) unsetenv("ROS_PACKAGE_PATH");
  else setenv("ROS_PACKAGE_PATH", old.c_str(), 1);
  ASSERT_TRUE(p);
  EXPECT_EQ(fs::path(p->articulation.links[0].shape_file), fs::path(cube));
}

TEST_F(UrdfImport, UnsupportedCollisionMeshFormatLeavesTheLinkWithoutColliderWithAWarning) {
  write("meshes/part.fbx", "Kaydara FBX Binary");
  const BotPrefab p = load(robot(mesh_link("base", "meshes/part.fbx")));
  const auto& L = p.articulation.links[0];
  EXPECT_FALSE(L.shape.has_value());
  EXPECT_EQ(fs::path(L.render_model), dir_.path() / "meshes/part.fbx");
  EXPECT_THAT(all_warnings(), HasSubstr("link 'base': collision mesh"));
  EXPECT_THAT(all_warnings(), HasSubstr("part.fbx"));
  EXPECT_THAT(all_warnings(), HasSubstr("the link has no collider"));
  build(p);
}

TEST_F(UrdfImport, BrokenDaeCollisionMeshIsAnError) {
  write("meshes/part.dae", "<COLLADA/>");
  EXPECT_THAT(error_of(robot(mesh_link("base", "meshes/part.dae"))),
              AllOf(HasSubstr("link 'base': collision mesh"), HasSubstr("part.dae: cannot read")));
}

TEST_F(UrdfImport, MissingVisualMeshIsAWarning) {
  const BotPrefab p = load(robot(link("base", inertial() + "<visual><origin xyz=\"0 0 1\"/><geometry><mesh filename=\"gone.obj\"/></geometry></visual>")));
  EXPECT_TRUE(p.articulation.links[0].render_model.empty());
  EXPECT_THAT(all_warnings(), HasSubstr("link 'base': visual mesh 'gone.obj' not found"));
}

TEST_F(UrdfImport, VisualOriginIsIgnoredWithAWarning) {
  write("cube.obj", kCubeObj);
  const BotPrefab p = load(robot(link("base", inertial() + "<visual><origin rpy=\"0 0 3.14\"/><geometry><mesh filename=\"cube.obj\"/></geometry></visual>")));
  EXPECT_FALSE(p.articulation.links[0].render_model.empty());
  EXPECT_THAT(all_warnings(), HasSubstr("the <origin> of the visual mesh is ignored"));
}

// ------------------------------------------------------------------------------------
// errors: each names the file and the element

TEST_F(UrdfImport, MissingCollisionMeshIsAnErrorNamingTheLinkAndPath) {
  const std::string msg = error_of(robot(mesh_link("base", "package://nowhere_pkg/meshes/x.stl")));
  EXPECT_THAT(msg, HasSubstr("robot.urdf"));
  EXPECT_THAT(msg, HasSubstr("link 'base'"));
  EXPECT_THAT(msg, HasSubstr("collision mesh 'package://nowhere_pkg/meshes/x.stl' not found"));
  EXPECT_THAT(error_of(robot(mesh_link("base", "meshes/none.obj"))), HasSubstr("meshes/none.obj"));
}

TEST_F(UrdfImport, MalformedCollisionMeshIsAnError) {
  write("bad.obj", "v 0 0 0\nf 1 2 3\n");
  const std::string msg = error_of(robot(mesh_link("base", "bad.obj")));
  EXPECT_THAT(msg, HasSubstr("link 'base': collision mesh"));
  EXPECT_THAT(msg, HasSubstr("bad.obj"));
}

TEST_F(UrdfImport, FileErrors) {
  EXPECT_THROW(load_bot_prefab_from_urdf((dir_.path() / "absent.urdf").string(), nullptr), Error);
  try {
    load_bot_prefab_from_urdf((dir_.path() / "absent.urdf").string(), nullptr);
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("absent.urdf: cannot open"));
  }
  EXPECT_THAT(error_of("<robot name='x'><link name='a'></robot>"), HasSubstr("not a valid XML file"));
  EXPECT_THAT(error_of("this is not xml"), HasSubstr("robot.urdf: not a valid XML file"));
  EXPECT_THAT(error_of("<?xml version=\"1.0\"?><sdf version='1.6'/>"), HasSubstr("root element is <sdf>, expected <robot>"));
  EXPECT_THAT(error_of("<robot name='x'></robot>"), HasSubstr("the robot has no <link>"));
}

TEST_F(UrdfImport, ARobotWithoutANameIsNamedAfterItsFile) {
  const BotPrefab p = load("<robot>" + link("base") + "</robot>", "my_arm.urdf");
  EXPECT_EQ(p.name(), "my_arm");
  EXPECT_THAT(all_warnings(), HasSubstr("<robot>: the robot has no name; naming it 'my_arm' after its file"));
}

TEST_F(UrdfImport, MissingRequiredAttributes) {
  EXPECT_THAT(error_of(robot("<link/>")), HasSubstr("<link>: missing required attribute 'name'"));
  EXPECT_THAT(error_of(robot(link("a") + link("b") + "<joint name='j'><parent link='a'/><child link='b'/></joint>")),
              HasSubstr("<joint name='j'>: missing required attribute 'type'"));
  EXPECT_THAT(error_of(robot(link("a") + link("b") + "<joint name='j' type='fixed'><child link='b'/></joint>")),
              HasSubstr("<joint name='j'>: missing required element <parent>"));
  EXPECT_THAT(error_of(robot(link("a") + link("b") + "<joint name='j' type='fixed'><parent/><child link='b'/></joint>")),
              HasSubstr("<joint name='j'>/<parent>: missing required attribute 'link'"));
  EXPECT_THAT(error_of(robot(link("a", "<inertial><mass/><inertia ixx='1' ixy='0' ixz='0' iyy='1' iyz='0' izz='1'/></inertial>"))),
              HasSubstr("<link name='a'>/<inertial>/<mass>: missing required attribute 'value'"));
  EXPECT_THAT(error_of(robot(link("a", "<inertial><mass value='1'/><inertia ixx='1' ixy='0' iyy='1' iyz='0' izz='1'/></inertial>"))),
              HasSubstr("<inertia>: missing required attribute 'ixz'"));
  EXPECT_THAT(error_of(robot(link("a", "<inertial><mass value='1'/></inertial>"))),
              HasSubstr("<link name='a'>/<inertial>: missing required element <inertia>"));
  EXPECT_THAT(error_of(robot(link("a", inertial() + "<collision><geometry><box/></geometry></collision>"))),
              HasSubstr("<link name='a'>/<collision>/<geometry>/<box>: missing required attribute 'size'"));
  EXPECT_THAT(error_of(robot(link("a", inertial() + "<collision><geometry><mesh/></geometry></collision>"))),
              HasSubstr("<mesh>: missing required attribute 'filename'"));
  EXPECT_THAT(error_of(robot(link("a", inertial() + "<collision><geometry/></collision>"))),
              HasSubstr("<geometry>: expected one of <box>, <sphere>, <cylinder> or <mesh>"));
  EXPECT_THAT(error_of(robot(link("a", inertial() + "<collision/>"))), HasSubstr("<collision>: missing required element <geometry>"));
  EXPECT_THAT(error_of(robot(link("a", inertial() + "<collision><geometry><cone radius='1'/></geometry></collision>"))),
              HasSubstr("unknown geometry <cone>"));
  // revolute and prismatic joints need a <limit> with an effort and a velocity
  EXPECT_THAT(error_of(robot(link("a") + link("b") + joint("j", "revolute", "a", "b"))),
              HasSubstr("<joint name='j'>: a revolute joint needs a <limit>"));
  EXPECT_THAT(error_of(robot(link("a") + link("b") + joint("j", "prismatic", "a", "b", "<limit lower='0' upper='1' velocity='1'/>"))),
              HasSubstr("<joint name='j'>/<limit>: missing required attribute 'effort'"));
}

TEST_F(UrdfImport, LineNumbersAreReported) {
  EXPECT_THAT(error_of(robot(link("a") + "\n\n" + link("b") + joint("j", "bogus", "a", "b"))), HasSubstr("robot.urdf: line 7: <joint name='j'>"));
}

TEST_F(UrdfImport, UnknownAndUnsupportedJointTypes) {
  EXPECT_THAT(error_of(robot(link("a") + link("b") + joint("j", "screw", "a", "b"))),
              HasSubstr("<joint name='j'>: unknown joint type 'screw'"));
  EXPECT_THAT(error_of(robot(link("a") + link("b") + joint("slider", "planar", "a", "b"))),
              HasSubstr("unsupported joint type 'planar' in joint 'slider'"));
  // floating joints: only from a bare "world" root
  EXPECT_THAT(error_of(robot(link("a") + link("b") + joint("fly", "floating", "a", "b"))),
              HasSubstr("floating joint 'fly' is only supported as the robot's root joint"));
  EXPECT_THAT(error_of(robot(link("world", "") + link("a") + link("b") + joint("w", "fixed", "world", "a") +
                             joint("fly", "floating", "a", "b"))),
              HasSubstr("floating joint 'fly'"));
}

TEST_F(UrdfImport, TreeErrors) {
  EXPECT_THAT(error_of(robot(link("a") + link("b") + joint("j", "fixed", "a", "ghost"))),
              HasSubstr("<joint name='j'>/<child>: refers to link 'ghost', which is not defined"));
  EXPECT_THAT(error_of(robot(link("a") + link("b") + joint("j", "fixed", "phantom", "b"))),
              HasSubstr("<parent>: refers to link 'phantom'"));
  EXPECT_THAT(error_of(robot(link("a") + link("b") + link("c") + joint("j1", "fixed", "a", "c") + joint("j2", "fixed", "b", "c"))),
              HasSubstr("<joint name='j2'>: link 'c' has two parents: it is the child of joint 'j1' and of joint 'j2'"));
  // a cycle next to a proper root, and a cycle with no root at all
  const std::string cycle_msg = error_of(robot(link("root") + link("a") + link("b") + link("c") + joint("j0", "fixed", "root", "a") +
                                               joint("j1", "fixed", "b", "c") + joint("j2", "fixed", "c", "b")));
  EXPECT_THAT(cycle_msg, HasSubstr("the joints form a cycle"));
  EXPECT_THAT(cycle_msg, HasSubstr("'b'"));
  EXPECT_THAT(cycle_msg, HasSubstr("'c'"));
  EXPECT_THAT(error_of(robot(link("a") + link("b") + joint("j1", "fixed", "a", "b") + joint("j2", "fixed", "b", "a"))),
              HasSubstr("no root link: the joints form a cycle"));
  EXPECT_THAT(error_of(robot(link("a") + joint("self", "fixed", "a", "a"))), HasSubstr("the joints form a cycle: link 'a' is its own parent"));
  EXPECT_THAT(error_of(robot(link("a") + link("b") + link("c") + joint("j", "fixed", "a", "b"))),
              HasSubstr("several root links (links that are no joint's child): 'a', 'c'"));
  EXPECT_THAT(error_of(robot(link("a") + link("a"))), HasSubstr("duplicate link name 'a'"));
  EXPECT_THAT(error_of(robot(link("a") + link("b") + link("c") + joint("j", "fixed", "a", "b") + joint("j", "fixed", "a", "c"))),
              HasSubstr("duplicate joint name 'j'"));
}

TEST_F(UrdfImport, MalformedNumbers) {
  EXPECT_THAT(error_of(robot(link("a") + link("b") + joint("j", "fixed", "a", "b", "<origin xyz='1 2 x'/>"))),
              HasSubstr("<joint name='j'>/<origin>: attribute 'xyz': malformed number 'x' in \"1 2 x\""));
  EXPECT_THAT(error_of(robot(link("a") + link("b") + joint("j", "fixed", "a", "b", "<origin rpy='1 2'/>"))),
              HasSubstr("attribute 'rpy': expected 3 numbers, got \"1 2\""));
  EXPECT_THAT(error_of(robot(link("a", "<inertial><mass value='1kg'/><inertia ixx='1' ixy='0' ixz='0' iyy='1' iyz='0' izz='1'/></inertial>"))),
              HasSubstr("<mass>: attribute 'value': malformed number '1kg'"));
  EXPECT_THAT(error_of(robot(link("a") + link("b") + joint("j", "revolute", "a", "b", "<limit lower='-1' upper='nan' effort='1' velocity='1'/>"))),
              HasSubstr("attribute 'upper': malformed number 'nan'"));
  EXPECT_THAT(error_of(robot(link("a", inertial() + "<collision><geometry><sphere radius='-1'/></geometry></collision>"))),
              HasSubstr("<sphere>: attribute 'radius' must be positive"));
}

TEST_F(UrdfImport, PhysicallyInvalidValues) {
  EXPECT_THAT(error_of(robot(link("a") + link("b") + joint("j", "revolute", "a", "b", "<limit lower='1' upper='-1' effort='1' velocity='1'/>"))),
              HasSubstr("<joint name='j'>/<limit>: the lower limit 1 exceeds the upper limit -1"));
  EXPECT_THAT(error_of(robot(link("a") + link("b") + joint("j", "revolute", "a", "b", "<axis xyz='0 0 0'/><limit effort='1' velocity='1'/>"))),
              HasSubstr("<axis>: the joint axis must not be zero"));
  EXPECT_THAT(error_of(robot(link("a", "<inertial><mass value='-1'/><inertia ixx='1' ixy='0' ixz='0' iyy='1' iyz='0' izz='1'/></inertial>"))),
              HasSubstr("the mass must not be negative"));
}

TEST_F(UrdfImport, MasslessLinkOnAMovingJointIsAnError) {
  const std::string msg = error_of(robot(link("base") + link("ghost", "") + link("frame", "") +
                                         joint("spin", "continuous", "base", "ghost") + joint("weld", "fixed", "ghost", "frame")));
  EXPECT_THAT(msg, HasSubstr("<joint name='spin'>: link 'ghost' has no inertial but moves on joint 'spin', and neither a closed "
                             "collision shape nor any link it carries gives it mass"));
  EXPECT_THAT(error_of(robot(link("world", "") + link("body", "") + joint("fly", "floating", "world", "body"))),
              HasSubstr("link 'body' has no inertial but moves on joint 'fly'"));
}

TEST_F(UrdfImport, MasslessMovingLinkTakesItsMassFromItsCollisionShape) {
  // a finger without <inertial>: a 0.02 x 0.02 x 0.1 m box centred 0.05 m along z
  const std::string finger = "<collision><origin xyz='0 0 0.05'/><geometry><box size='0.02 0.02 0.1'/></geometry></collision>";
  const BotPrefab p = load_fixed(robot(link("palm") + link("finger", finger) + joint("knuckle", "revolute", "palm", "finger",
                                                                                      "<limit lower='0' upper='1' effort='1' velocity='1'/>")));
  EXPECT_THAT(all_warnings(), HasSubstr("link 'finger' has no inertial but moves on joint 'knuckle': its mass and inertia are computed "
                                        "from its collision shape at 1000 kg/m^3"));
  const auto art = build(p);
  // m = 1000 kg/m^3 x 4e-5 m^3; about the knuckle axis (x): m (b^2 + c^2) / 12 + m d^2 with d = 0.05 m
  const real m = 1000 * 0.02 * 0.02 * 0.1;
  EXPECT_NEAR(scene_->mass(scene_->nested_link_actors(art)[1]), m, 1e-9);
  const physics::MatX M = scene_->mass_matrix(art);
  EXPECT_NEAR(M(0, 0), m * (0.02 * 0.02 + 0.1 * 0.1) / 12 + m * 0.05 * 0.05, 1e-9);
}

}  // namespace
}  // namespace superdex::robotics::test

#pragma once
/// @file test_helpers.h
/// Shared pieces of the GoogleTest suites: an engine fixture (initialize / shutdown around
/// every test), a Z-up scene, params of rigid actors, and small builders for link and joint
/// descriptions.

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>
#include <optional>
#include <string>

#include "superdex/physics/articulation_desc.h"
#include "superdex/physics/engine.h"
#include "superdex/physics/scene.h"

namespace superdex::physics::test {

constexpr double kPi = std::numbers::pi;
constexpr double kG = 9.81;  // the magnitude of the Z-up gravity the suites set (z_up_scene)

/// Starts a single-threaded engine before each test and shuts it down after.
class EngineTest : public ::testing::Test {
 protected:
  void SetUp() override { initialize(0); }
  void TearDown() override { shutdown(); }
};

/// A new scene with gravity (0, 0, -kG): the suites' worlds are Z-up (robot files are), while a
/// new scene's default gravity is SuperDex's (0, -9.8, 0) (kDefaultGravity).
inline Scene z_up_scene(const std::string& name) {
  Scene scene = create_scene(name);
  scene.set_gravity(Vec3(0, 0, real(-kG)));
  return scene;
}

/// The params of a dynamic rigid actor carrying `shape` at X_WL: its mass `mass` (kg) when
/// given, else from the default density (kDefaultDensity) and the shape's volume; centre of
/// mass and inertia from the shape, contact params at their defaults, layer "".
inline RigidActorParams rigid_params(const std::string& name, const ShapeHandle& shape, const Transform& X_WL = Transform::identity(),
                                     std::optional<real> mass = std::nullopt) {
  RigidActorParams p;
  p.name = name;
  p.shape = shape;
  p.world_from_local = X_WL;
  p.mass = mass;
  return p;
}

/// The params of a static rigid actor carrying `shape` at X_WL.
inline RigidActorParams static_params(const std::string& name, const ShapeHandle& shape, const Transform& X_WL = Transform::identity()) {
  RigidActorParams p = rigid_params(name, shape, X_WL);
  p.is_static = true;
  return p;
}

/// A link with explicit mass, centre of mass and diagonal inertia about the COM.
inline LinkDesc make_link(const std::string& name, int parent, real mass, const Vec3& com, const Vec3& inertia_diag) {
  LinkDesc link;
  link.name = name;
  link.parent_link = parent;
  link.mass = mass;
  link.center_of_mass = com;
  link.moment_of_inertia = std::array<real, 6>{inertia_diag.x(), 0, 0, inertia_diag.y(), 0, inertia_diag.z()};
  return link;
}

/// A joint of the given type and axis, placed at `X_PJ` in its parent link.
inline JointDesc make_joint(const std::string& name, JointType type, const Vec3& axis = Vec3::UnitZ(),
                            const Transform& X_PJ = Transform::identity()) {
  JointDesc joint;
  joint.name = name;
  joint.type = type;
  joint.axis = axis;
  joint.parent_link_from_joint = X_PJ;
  return joint;
}

/// A welded base (link 0) plus one 1-DOF link of `type` about/along `axis`, whose COM sits
/// at `com` in the link frame. Returns the description; callers tweak joints[1].
inline ArticulationDesc one_dof_desc(JointType type, const Vec3& axis, real mass, const Vec3& com,
                                     const Vec3& inertia_diag) {
  ArticulationDesc desc;
  desc.name = "one_dof";
  desc.links = {make_link("base", -1, 1, Vec3::Zero(), Vec3::Constant(real(0.01))),
                make_link("arm", 0, mass, com, inertia_diag)};
  desc.joints = {make_joint("weld", JointType::Hard), make_joint("dof", type, axis)};
  return desc;
}

}  // namespace superdex::physics::test

#pragma once
/// @file test_helpers.h
/// Shared pieces of the GoogleTest suites: an engine fixture (initialize / shutdown around
/// every test) and small builders for link and joint descriptions.

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>
#include <string>

#include "superdex/physics/articulation_desc.h"
#include "superdex/physics/engine.h"
#include "superdex/physics/scene.h"

namespace superdex::physics::test {

constexpr double kPi = std::numbers::pi;
constexpr double kG = 9.81;  // the engine's default gravity magnitude

/// Starts a single-threaded engine before each test and shuts it down after.
class EngineTest : public ::testing::Test {
 protected:
  void SetUp() override { initialize(0); }
  void TearDown() override { shutdown(); }
};

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

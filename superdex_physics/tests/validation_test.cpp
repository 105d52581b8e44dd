/// @file validation_test.cpp
/// Misuse raises superdex::Error with a message naming the offending field or argument:
/// bad articulation descriptions, bad force arguments, unknown handles, a bad time step and a
/// destroyed scene.

#include <gmock/gmock.h>

#include <limits>

#include "superdex/physics/error.h"
#include "test_helpers.h"

namespace superdex::physics::test {
namespace {

using ::testing::HasSubstr;

/// Expects `statement` to throw superdex::Error whose message contains every substring given.
#define EXPECT_ERROR(statement, ...)                                          \
  do {                                                                        \
    try {                                                                     \
      statement;                                                              \
      ADD_FAILURE() << "no superdex::Error from: " #statement;                \
    } catch (const superdex::Error& e) {                                      \
      for (const char* s : {__VA_ARGS__}) EXPECT_THAT(e.what(), HasSubstr(s)); \
    }                                                                         \
  } while (0)

/// Three-link chain base -> a -> b with revolute joints; tests break one field each.
ArticulationDesc valid_chain() {
  ArticulationDesc d;
  d.name = "chain";
  d.links = {make_link("base", -1, 1, Vec3::Zero(), Vec3::Constant(real(0.1))),
             make_link("a", 0, 1, Vec3(0, 0, -0.5), Vec3::Constant(real(0.1))),
             make_link("b", 1, 1, Vec3(0, 0, -0.5), Vec3::Constant(real(0.1)))};
  d.joints = {make_joint("weld", JointType::Hard), make_joint("ja", JointType::Revolute, Vec3::UnitY()),
              make_joint("jb", JointType::Revolute, Vec3::UnitY())};
  return d;
}

class ValidationTest : public EngineTest {
 protected:
  void SetUp() override {
    EngineTest::SetUp();
    scene_ = std::make_unique<Scene>(create_scene("validation"));
  }
  Scene& scene() { return *scene_; }
  std::unique_ptr<Scene> scene_;
};

TEST_F(ValidationTest, ValidChainIsAccepted) {
  EXPECT_NO_THROW(scene().create_articulated_actor(valid_chain(), "ok.superdex_bot"));
}

TEST_F(ValidationTest, NegativeMassNamesTheLink) {
  ArticulationDesc d = valid_chain();
  d.links[2].mass = -1;
  EXPECT_ERROR(scene().create_articulated_actor(d, "bot.superdex_bot"), "bot.superdex_bot", "links[2].mass");
}

TEST_F(ValidationTest, BadExtraShapeNamesTheLinkAndIndex) {
  ArticulationDesc d = valid_chain();
  d.links[1].extra_shapes.push_back({SphereShape{Vec3::Zero(), real(0.1)}, Transform{}, ""});
  d.links[1].extra_shapes.push_back({SphereShape{Vec3::Zero(), real(-1)}, Transform{}, ""});
  EXPECT_ERROR(scene().create_articulated_actor(d, "bot.superdex_bot"), "bot.superdex_bot", "links[1].extraShapes[1].shape");
  d.links[1].extra_shapes[1].shape = SphereShape{Vec3::Zero(), real(0.1)};
  d.links[1].extra_shapes[1].link_from_shape.rotation = Quat(0, 0, 0, 0);
  EXPECT_ERROR(scene().create_articulated_actor(d, "bot.superdex_bot"), "links[1].extraShapes[1].linkFromShape");
}

TEST_F(ValidationTest, NonPositiveDefiniteInertia) {
  ArticulationDesc d = valid_chain();
  d.links[1].moment_of_inertia = std::array<real, 6>{0.1, 0, 0, -0.1, 0, 0.1};
  EXPECT_ERROR(scene().create_articulated_actor(d, "bot"), "links[1].momentOfInertia", "positive definite");
  // singular (zero) inertia is not positive definite either
  d.links[1].moment_of_inertia = std::array<real, 6>{0, 0, 0, 0, 0, 0};
  EXPECT_ERROR(scene().create_articulated_actor(d, "bot"), "links[1].momentOfInertia", "positive definite");
}

TEST_F(ValidationTest, CycleInLinkTree) {
  ArticulationDesc d = valid_chain();
  d.links[1].parent_link = 2;  // a -> b -> a
  EXPECT_ERROR(scene().create_articulated_actor(d, "bot"), "parentLink", "cycle");
}

TEST_F(ValidationTest, MissingOrUnknownParent) {
  ArticulationDesc d = valid_chain();
  d.links[2].parent_link = -1;
  EXPECT_ERROR(scene().create_articulated_actor(d, "bot"), "links[2].parentLink");
  d.links[2].parent_link = 7;
  EXPECT_ERROR(scene().create_articulated_actor(d, "bot"), "links[2].parentLink", "does not exist");
}

TEST_F(ValidationTest, FreeJointOnlyAtRoot) {
  ArticulationDesc d = valid_chain();
  d.joints[2].type = JointType::Free;
  EXPECT_ERROR(scene().create_articulated_actor(d, "bot"), "joints[2]", "Free");
}

TEST_F(ValidationTest, WrongDefaultPoseSize) {
  ArticulationDesc d = valid_chain();
  d.default_pose = {0.1, 0.2, 0.3};
  EXPECT_ERROR(scene().create_articulated_actor(d, "bot"), "defaultPose", "expected 2");
}

TEST_F(ValidationTest, ExternalForceDofOutOfRangeOrNaN) {
  const ActorHandle art = scene().create_articulated_actor(valid_chain(), "bot");
  EXPECT_ERROR(scene().set_external_forces_on_dofs(art, {2}, {1.0}), "dof_indices[0]", "out of range");
  EXPECT_ERROR(scene().set_external_forces_on_dofs(art, {0, -1}, {1.0, 1.0}), "dof_indices[1]", "out of range");
  const real nan = std::numeric_limits<real>::quiet_NaN();
  EXPECT_ERROR(scene().set_external_forces_on_dofs(art, {1}, {nan}), "force_values[0]", "not finite");
  // a rejected call leaves the previous forces untouched
  EXPECT_EQ(scene().external_forces(art).norm(), 0);
}

TEST_F(ValidationTest, UnknownAndDestroyedActorHandles) {
  EXPECT_ERROR(scene().pose(123456789), "123456789", "does not exist");
  const ActorHandle art = scene().create_articulated_actor(valid_chain(), "bot");
  const ActorHandle link = scene().nested_link_actors(art)[1];
  scene().destroy_actor(art);
  EXPECT_FALSE(scene().has_actor(art));
  EXPECT_ERROR(scene().pose(art), "does not exist");
  EXPECT_ERROR(scene().link_jacobian(link), "does not exist");
  EXPECT_ERROR(scene().destroy_actor(art), "does not exist");
}

TEST_F(ValidationTest, StateReadsIntoVectorsAndOneLinkTransform) {
  const ActorHandle art = scene().create_articulated_actor(valid_chain(), "chain");
  VecX pose0(2);
  pose0 << real(0.3), real(-0.7);
  scene().set_pose(art, pose0);
  VecX v0(2);
  v0 << real(1.5), real(-2);
  scene().set_joint_velocities(art, v0);
  // the reads into a given vector equal the returned ones, whatever the vector held before
  VecX q = VecX::Constant(5, real(9)), v;
  scene().pose(art, q);
  scene().joint_velocities(art, v);
  EXPECT_EQ(q, scene().pose(art));
  EXPECT_EQ(v, v0);
  const std::vector<Transform> all = scene().link_transforms(art);
  for (int link = 0; link < 3; ++link) {
    const Transform one = scene().link_transform(art, link);
    EXPECT_EQ(one.translation, all[link].translation) << "link " << link;
    EXPECT_EQ(one.rotation.coeffs(), all[link].rotation.coeffs()) << "link " << link;
  }
  EXPECT_ERROR(scene().link_transform(art, 3), "link_transform", "link 3", "3 links");
  EXPECT_ERROR(scene().link_transform(art, -1), "link_transform", "link -1");
}

TEST_F(ValidationTest, StepRejectsNegativeOrNonFiniteTimeStep) {
  EXPECT_ERROR(scene().step(-0.01), "time_step_sec", "-0.01");
  EXPECT_ERROR(scene().step(std::numeric_limits<real>::quiet_NaN()), "time_step_sec", "nan");
  EXPECT_ERROR(scene().step(std::numeric_limits<real>::infinity()), "time_step_sec", "inf");
  EXPECT_EQ(scene().total_simulation_time(), 0);
}

TEST_F(ValidationTest, ZeroStepIsAcceptedAndChangesNoState) {
  // a zero step (SuperDex's way to make registered queries readable) moves nothing
  const ActorHandle art = scene().create_articulated_actor(valid_chain(), "chain");
  VecX v0(2);
  v0 << real(1.5), real(-2);
  scene().set_joint_velocities(art, v0);
  const VecX q0 = scene().pose(art);
  EXPECT_NO_THROW(scene().step(0));
  EXPECT_EQ(scene().pose(art), q0);
  EXPECT_EQ(scene().joint_velocities(art), v0);
  EXPECT_EQ(scene().total_simulation_time(), 0);
  EXPECT_EQ(scene().last_time_step(), 0);
}

TEST_F(ValidationTest, SceneUnusableAfterDestroy) {
  const ActorHandle art = scene().create_articulated_actor(valid_chain(), "bot");
  destroy_scene(scene().handle());
  EXPECT_FALSE(scene_exists(scene().handle()));
  EXPECT_ERROR(scene().step(0.01), "does not exist");
  EXPECT_ERROR(scene().pose(art), "does not exist");
  EXPECT_ERROR(scene().gravity(), "does not exist");
  EXPECT_ERROR(destroy_scene(scene().handle()), "does not exist");
}

}  // namespace
}  // namespace superdex::physics::test

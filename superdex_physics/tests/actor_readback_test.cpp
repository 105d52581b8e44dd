/// @file actor_readback_test.cpp
/// Creation parameters read back from live actors (scene/actor_readback.cpp): what is read back
/// must be what created the actor (as given, or the analytic value the engine derived from it),
/// updated by the setters called since, and must create the same actor again.

#include <algorithm>
#include <set>

#include "superdex/physics/error.h"
#include "test_helpers.h"

namespace superdex::physics::test {
namespace {

class ActorReadbackTest : public EngineTest {};

Quaternion about_z(double angle) { return Quaternion(Eigen::AngleAxis<real>(real(angle), Vec3::UnitZ())); }

// A unit cube [0, 1]^3 in 5 tetrahedra, the middle one (1, 2, 4, 7) largest.
TetMesh cube_tets() {
  TetMesh m;
  for (int i = 0; i < 8; ++i) m.nodes.push_back(Vec3(i & 1, (i >> 1) & 1, (i >> 2) & 1));
  m.tets = {{0, 1, 2, 4}, {1, 3, 2, 7}, {1, 2, 4, 7}, {1, 5, 4, 7}, {2, 4, 7, 6}};
  for (auto& t : m.tets) {
    Mat3 D;
    D << m.nodes[t[1]] - m.nodes[t[0]], m.nodes[t[2]] - m.nodes[t[0]], m.nodes[t[3]] - m.nodes[t[0]];
    if (D.determinant() < 0) std::swap(t[1], t[2]);
  }
  return m;
}

TEST_F(ActorReadbackTest, RigidActorParamsAreTheGivenOnesAndCreateTheSameBody) {
  Scene scene = z_up_scene("rigid");
  RigidActorParams p = rigid_params("crate", create_shape(BoxShape{Vec3(0.1, 0.2, 0.3)}), Transform{about_z(0.4), Vec3(1, 2, 3)});
  p.density = 500;
  p.layer = "props";
  p.contact.coulomb_friction_coefficient = real(0.7);
  p.has_gravity = false;
  const ActorHandle h = scene.create_rigid_actor(p);
  scene.set_velocity(h, Vec3(1, 0, 0), Vec3(0, 0, 2));

  const RigidActorParams r = scene.rigid_actor_params(h);
  EXPECT_EQ(r.name, "crate");
  EXPECT_EQ(r.layer, "props");
  EXPECT_EQ(r.contact, p.contact);
  EXPECT_FALSE(r.has_gravity);
  EXPECT_FALSE(r.is_static);
  EXPECT_TRUE(r.world_from_local.translation.isApprox(Vec3(1, 2, 3)));
  EXPECT_NEAR(std::abs(r.world_from_local.rotation.dot(about_z(0.4))), 1, 1e-6);
  // analytic: m = rho V, box inertia m (b^2 + c^2) / 3 with half extents
  const double m = 500 * 0.2 * 0.4 * 0.6;
  EXPECT_NEAR(*r.mass, m, 1e-9 * m);
  EXPECT_NEAR(*r.density, 500, 1e-9);
  EXPECT_TRUE(r.center_of_mass->isZero(1e-12));
  EXPECT_NEAR((*r.moment_of_inertia)[0], m * (0.04 + 0.09) / 3, 1e-9);
  EXPECT_NEAR((*r.moment_of_inertia)[3], m * (0.01 + 0.09) / 3, 1e-9);
  EXPECT_NEAR((*r.moment_of_inertia)[5], m * (0.01 + 0.04) / 3, 1e-9);
  EXPECT_TRUE(r.linear_velocity->isApprox(Vec3(1, 0, 0), 1e-9));
  EXPECT_TRUE(r.angular_velocity->isApprox(Vec3(0, 0, 2), 1e-9));
  ASSERT_TRUE(r.shape.is_valid());
  EXPECT_TRUE(std::get<BoxShape>(shape_geometry(r.shape)).half_extents.isApprox(Vec3(0.1, 0.2, 0.3)));

  // a setter's change is read back; the params create the same body in another scene
  scene.set_density(h, 1000);
  EXPECT_NEAR(*scene.rigid_actor_params(h).mass, 2 * m, 1e-9 * m);
  Scene other = z_up_scene("other");
  const ActorHandle copy = other.create_rigid_actor(scene.rigid_actor_params(h));
  EXPECT_NEAR(other.mass(copy), scene.mass(h), 1e-12);
  EXPECT_TRUE(other.moment_of_inertia_local(copy).isApprox(scene.moment_of_inertia_local(h)));
  EXPECT_TRUE(other.velocity(copy).isApprox(scene.velocity(h), 1e-12));
  EXPECT_FALSE(other.has_gravity(copy));
  EXPECT_EQ(other.contact_layer(copy), "props");

  // a static actor has no mass properties to give
  const ActorHandle ground = scene.create_rigid_actor(static_params("ground", create_shape(PlaneShape{})));
  const RigidActorParams g = scene.rigid_actor_params(ground);
  EXPECT_TRUE(g.is_static);
  EXPECT_FALSE(g.mass.has_value());
  EXPECT_TRUE(std::holds_alternative<PlaneShape>(shape_geometry(g.shape)));
}

TEST_F(ActorReadbackTest, SoftActorParamsGiveTheRestMeshMaterialAndPins) {
  Scene scene = z_up_scene("soft");
  const ShapeHandle mesh = create_tet_mesh_shape(cube_tets(), "cube");
  SoftMaterial material;
  material.type = "StVK";
  material.youngs_modulus = real(3e5);
  material.poisson_ratio = real(0.25);
  material.density = 800;
  material.damping_alpha = real(0.5);
  const Transform X_WL{about_z(1.0), Vec3(0, 0, 2)};
  const ActorHandle h = scene.create_soft_actor("jelly", mesh, material, X_WL, {5, 0});
  scene.step(0.01);  // it sags and falls; the rest mesh stays what it was

  const SoftActorParams p = scene.soft_actor_params(h);
  EXPECT_EQ(p.name, "jelly");
  EXPECT_EQ(p.material.type, SoftMaterialType::StVenantKirchhoff);
  EXPECT_NEAR(p.material.st_venant_kirchhoff.youngs_modulus, 3e5, 1e-6);
  EXPECT_NEAR(p.material.st_venant_kirchhoff.poisson_ratio, 0.25, 1e-12);
  EXPECT_EQ(p.material.density, 800);
  EXPECT_EQ(p.material.mass_damping_coefficient, real(0.5));
  EXPECT_EQ(scene.soft_material_params(h), p.material) << "the getter reports the material the actor was made with";
  EXPECT_EQ(tet_mesh_shape(p.shape)->nodes, cube_tets().nodes);
  EXPECT_EQ(scene.soft_fixed_nodes(h), (std::vector<int>{0, 5}));
  EXPECT_EQ(scene.soft_reduced_modes(h), 0);
  EXPECT_TRUE(p.world_from_local.translation.isApprox(scene.root_transform(h).translation));
  // the params make a body of the same mass (density times the unit cube's volume)
  Scene other = z_up_scene("other");
  SoftActorParams again = p;
  again.shape = p.shape;
  EXPECT_NEAR(other.mass(other.create_soft_actor(again)), 800, 1e-9);

  EXPECT_THROW(scene.rigid_actor_params(h), Error);
  EXPECT_THROW(scene.soft_actor_params(scene.create_rigid_actor(rigid_params("b", create_shape(SphereShape{Vec3::Zero(), 1})))), Error);
}

TEST_F(ActorReadbackTest, ArticulationDescHasTheCurrentValuesAndRebuildsTheArticulation) {
  Scene scene = z_up_scene("arm");
  ArticulationDesc d = one_dof_desc(JointType::Revolute, Vec3::UnitY(), 1, Vec3(0.5, 0, 0), Vec3::Constant(real(1e-3)));
  d.world_from_root = Transform{about_z(0.3), Vec3(1, 0, 1)};
  d.links[1].shape = BoxShape{Vec3(0.25, 0.05, 0.05)};
  d.links[1].link_from_shape = Transform{Quaternion::Identity(), Vec3(0.25, 0, 0)};
  d.links[1].joint_from_link = Vec3(0, 0, 0.1);
  d.joints[1].min_limit = Vec3(0, -1, 0);
  d.joints[1].limit_stiffness = 300;
  d.default_pose = {0.2};
  d.contact_overrides = {{"base", "arm", true}};
  const ActorHandle h = scene.create_articulated_actor(d, "test");
  std::vector<ArticulatedJointFrictionParams> friction(2);
  friction[1].viscous = real(0.3);
  scene.set_joint_friction_params(h, friction);
  scene.set_joint_inertia_params(h, std::vector<real>{0, real(0.02)});
  for (int i = 0; i < 10; ++i) scene.step(0.01);

  const ArticulationDesc r = scene.articulation_desc(h);
  EXPECT_EQ(r.links[1].joint_from_link, d.links[1].joint_from_link);
  EXPECT_TRUE(r.links[1].link_from_shape.translation.isApprox(Vec3(0.25, 0, 0)));
  EXPECT_TRUE(std::get<BoxShape>(*r.links[1].shape).half_extents.isApprox(Vec3(0.25, 0.05, 0.05)));
  EXPECT_EQ(*r.links[1].mass, 1);
  EXPECT_EQ(r.joints[1].viscous_friction, real(0.3));
  EXPECT_EQ(r.joints[1].armature, real(0.02));
  EXPECT_EQ(r.joints[1].limit_stiffness, 300);
  EXPECT_EQ(r.default_pose, d.default_pose) << "the pose given at creation, not the current one";
  ASSERT_EQ(r.contact_overrides.size(), 1u);
  EXPECT_TRUE(r.world_from_root.translation.isApprox(Vec3(1, 0, 1)));
  EXPECT_NEAR(std::abs(r.world_from_root.rotation.dot(about_z(0.3))), 1, 1e-6);

  // rebuilt: the same masses and the same links at the default pose
  Scene other = z_up_scene("other");
  const ActorHandle copy = other.create_articulated_actor(r, "copy");
  EXPECT_NEAR(other.mass(copy), scene.mass(h), 1e-12);
  EXPECT_NEAR(other.pose(copy)[0], 0.2, 1e-12);
  EXPECT_NE(scene.pose(h)[0], 0.2) << "the original moved on";
  EXPECT_EQ(other.joint_inertia_params(copy), scene.joint_inertia_params(h));
  const Aabb a = other.aabb_local(other.nested_link_actors(copy)[1]), b = scene.aabb_local(scene.nested_link_actors(h)[1]);
  EXPECT_TRUE(a.min.isApprox(b.min, 1e-9) && a.max.isApprox(b.max, 1e-9));

  // a moved base is read back where it is now
  scene.set_root_transform(h, Transform{Quaternion::Identity(), Vec3(5, 5, 5)});
  const Transform X_WL0 = scene.link_transform(h, 0);
  const ArticulationDesc moved = scene.articulation_desc(h);
  const ActorHandle placed = other.create_articulated_actor(moved, "placed");
  EXPECT_TRUE(other.link_transform(placed, 0).translation.isApprox(X_WL0.translation, 1e-9));
}

TEST_F(ActorReadbackTest, FreeRootIsPlacedWhereTheRootLinkIsNow) {
  Scene scene = z_up_scene("free");
  ArticulationDesc d = one_dof_desc(JointType::Revolute, Vec3::UnitX(), 1, Vec3(0, 0, 0.5), Vec3::Constant(real(1e-2)));
  d.joints[0] = make_joint("float", JointType::Free, Vec3::UnitZ(), Transform{Quaternion::Identity(), Vec3(0, 0, 0.5)});
  d.world_from_root = Transform{Quaternion::Identity(), Vec3(0, 0, 3)};
  const ActorHandle h = scene.create_articulated_actor(d, "free");
  EXPECT_TRUE(scene.articulation_desc(h).world_from_root.translation == Vec3(0, 0, 3)) << "unmoved: the given placement";
  scene.set_velocity(h, Vec3(0, 0, 0), Vec3(1, 2, 0));
  for (int i = 0; i < 30; ++i) scene.step(0.01);
  const Transform X_WL0 = scene.link_transform(h, 0);
  Scene other = z_up_scene("other");
  const ActorHandle copy = other.create_articulated_actor(scene.articulation_desc(h), "copy");
  const Transform Y = other.link_transform(copy, 0);
  EXPECT_TRUE(Y.translation.isApprox(X_WL0.translation, 1e-9));
  EXPECT_NEAR(std::abs(Y.rotation.dot(X_WL0.rotation)), 1, 1e-9);
  EXPECT_TRUE(other.joint_velocities(copy).isZero(0)) << "velocities are not read back";
}

TEST_F(ActorReadbackTest, ActorContactRulesAndGravityFlags) {
  Scene scene = z_up_scene("rules");
  const ShapeHandle ball = create_shape(SphereShape{Vec3::Zero(), real(0.1)});
  const ActorHandle a = scene.create_rigid_actor(rigid_params("a", ball));
  const ActorHandle b = scene.create_rigid_actor(rigid_params("b", ball));
  RigidActorParams floating = rigid_params("c", ball);
  floating.has_gravity = false;
  const ActorHandle c = scene.create_rigid_actor(floating);
  EXPECT_TRUE(scene.actor_contact_rules().empty());
  scene.enable_actor_contact_symmetric(a, b, false, IncludeNestedActors::No);
  scene.enable_actor_contact_asymmetric(c, a, true, IncludeNestedActors::Yes);
  const std::vector<ActorContactRule> rules = scene.actor_contact_rules();
  const std::vector<ActorContactRule> expected = {
      {a, b, false, IncludeNestedActors::No}, {b, a, false, IncludeNestedActors::No}, {c, a, true, IncludeNestedActors::Yes}};
  EXPECT_EQ(std::set<std::int64_t>({rules[0].colliding, rules[1].colliding, rules[2].colliding}), std::set<std::int64_t>({a, b, c}));
  for (const ActorContactRule& e : expected) EXPECT_NE(std::find(rules.begin(), rules.end(), e), rules.end());
  scene.destroy_actor(b);
  EXPECT_EQ(scene.actor_contact_rules().size(), 1u) << "rules naming a destroyed actor are left out";
  EXPECT_TRUE(scene.has_gravity(a));
  EXPECT_FALSE(scene.has_gravity(c));
}

}  // namespace
}  // namespace superdex::physics::test

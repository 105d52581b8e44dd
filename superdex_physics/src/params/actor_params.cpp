// Names and validation of the actor params structs (actor_params.h).

#include "superdex/physics/params/actor_params.h"

#include "params/check.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

const char* actor_type_name(ActorType type) {
  switch (type) {
    case ActorType::None: return "None";
    case ActorType::Rigid: return "Rigid";
    case ActorType::Soft: return "Soft";
    case ActorType::Articulated: return "Articulated";
    case ActorType::Shell: return "Shell";
    case ActorType::Rod: return "Rod";
  }
  return "?";
}

const char* articulated_joint_type_name(ArticulatedJointType type) {
  switch (type) {
    case ArticulatedJointType::Free: return "Free";
    case ArticulatedJointType::Prismatic: return "Prismatic";
    case ArticulatedJointType::Revolute: return "Revolute";
    case ArticulatedJointType::Spherical: return "Spherical";
    case ArticulatedJointType::Hard: return "Hard";
    case ArticulatedJointType::Cycle: return "Cycle";
    case ArticulatedJointType::Invalid: return "Invalid";
  }
  return "?";
}

namespace {

void check_transform(const FieldCheck& c, const std::string& field, const TransformRT& X) {
  c.finite_vector(field + ".translation", X.translation);
  c.rotation(field + ".rotation", X.rotation);
}

void check_inertia(const FieldCheck& c, const std::optional<real>& density, const std::optional<real>& mass,
                   const std::optional<Real3>& com, const std::optional<Real6>& moi) {
  if (density) c.positive("density", *density);
  if (mass) c.positive("mass", *mass);
  if (com) c.finite_vector("center_of_mass", *com);
  if (moi) c.finite_vector("moment_of_inertia", *moi);
}

void check_subsampling(const FieldCheck& c, const std::optional<BoundarySubsamplingParams>& s) {
  if (s) c.in_range("boundary_subsampling.subsampling_density", s->subsampling_density, 0, 1);
}

}  // namespace

void validate(const GridSdfParams& p, const std::string& where) {
  const FieldCheck c(where);
  for (int i = 0; i < 3; ++i) c.positive("resolution_delta[" + std::to_string(i) + "]", p.resolution_delta[i]);
  c.non_negative("boundary_padding_dist", p.boundary_padding_dist);
  for (int i = 0; i < 3; ++i)
    if (p.min_grid_resolution[i] < 1) c.fail("min_grid_resolution[" + std::to_string(i) + "]", "must be >= 1, got " + std::to_string(p.min_grid_resolution[i]));
}

void validate(const RecenteringParams& p, const std::string& where) {
  const FieldCheck c(where);
  c.non_negative("rotation_epsilon_deg", p.rotation_epsilon_deg);
  c.non_negative("translation_epsilon", p.translation_epsilon);
}

void validate(const ArticulatedJointFrictionParams& p, const std::string& where) {
  const FieldCheck c(where);
  c.non_negative("viscous", p.viscous);
  c.non_negative("coulomb", p.coulomb);
  c.positive("falloff_vel", p.falloff_vel);
  c.non_negative("stiction_extra", p.stiction_extra);
  c.non_negative("stribeck_vel", p.stribeck_vel);
}

void validate(const RigidActorParams& p, const std::string& where) {
  const FieldCheck c(where);
  if (!p.shape.is_valid()) c.fail("shape", "is not set (a ShapeHandle from create_*_shape or load_shape_from_file is required)");
  check_transform(c, "world_from_local", p.world_from_local);
  if (p.collider_type == ColliderType::PointCloud) c.fail("collider_type", "POINT_CLOUD colliders are for rods and shells");
  validate(p.contact, where + ".contact");
  validate(p.sdf, where + ".sdf");
  check_inertia(c, p.density, p.mass, p.center_of_mass, p.moment_of_inertia);
  check_subsampling(c, p.boundary_subsampling);
  if (p.linear_velocity) c.finite_vector("linear_velocity", *p.linear_velocity);
  if (p.angular_velocity) c.finite_vector("angular_velocity", *p.angular_velocity);
  if (p.is_static && ((p.linear_velocity && !p.linear_velocity->isZero()) || (p.angular_velocity && !p.angular_velocity->isZero())))
    c.fail("linear_velocity", "a static actor cannot be given a velocity");
}

void validate(const SoftActorParams& p, const std::string& where) {
  const FieldCheck c(where);
  if (!p.shape.is_valid()) c.fail("shape", "is not set (a tetrahedral mesh shape is required)");
  check_transform(c, "world_from_local", p.world_from_local);
  validate(p.material, where + ".material");
  validate(p.contact, where + ".contact");
  if (!p.has_gravity && !p.has_inertia && !p.has_stress)
    c.fail("has_stress", "at least one of has_gravity, has_inertia and has_stress must be true");
}

void validate(const RodActorParams& p, const std::string& where) {
  const FieldCheck c(where);
  if (!p.shape.is_valid()) c.fail("shape", "is not set (a polyline model shape is required: generate_tubular_rod_model_data)");
  check_transform(c, "world_from_local", p.world_from_local);
  validate(p.contact, where + ".contact");
  const FieldCheck m(where + ".material");
  m.positive("linear_density", p.material.linear_density);
  m.non_negative("linear_rotational_inertia", p.material.linear_rotational_inertia);
  m.positive("axial_stiffness", p.material.axial_stiffness);
  m.non_negative("torsional_stiffness", p.material.torsional_stiffness);
  m.non_negative("flexural_stiffness[0]", p.material.flexural_stiffness[0]);
  m.non_negative("flexural_stiffness[1]", p.material.flexural_stiffness[1]);
  m.non_negative("mass_damping_coefficient", p.material.mass_damping_coefficient);
  m.non_negative("stiffness_damping_coefficient", p.material.stiffness_damping_coefficient);
  if (p.material.linear_rotational_inertia == 0 && p.material.torsional_stiffness == 0)
    m.fail("torsional_stiffness", "must be positive when linear_rotational_inertia is 0 (the twist would be free and massless)");
  if (p.use_contact_skin) c.fail("use_contact_skin", "rods do not touch other actors yet (keep it False)");
}

void validate(const ArticulatedActorParams& p, const std::string& where) {
  const FieldCheck c(where);
  check_transform(c, "world_from_root", p.world_from_root);
  if (p.links.empty()) c.fail("links", "must hold at least one link");
  if (p.joints.size() != p.links.size())
    c.fail("joints", "must hold one joint per link (" + std::to_string(p.links.size()) + "), got " + std::to_string(p.joints.size()));
  for (size_t i = 0; i < p.links.size(); ++i) {
    const ArticulatedLinkParams& l = p.links[i];
    const FieldCheck lc(where + ".links[" + std::to_string(i) + "]");
    if (l.parent_link < -1 || l.parent_link >= static_cast<int>(i))
      lc.fail("parent_link", "must be -1 (root) or the index of an earlier link, got " + std::to_string(l.parent_link));
    if ((l.parent_link == -1) != (i == 0)) lc.fail("parent_link", i == 0 ? "the first link is the root: it must be -1" : "only the first link can be the root (-1)");
    if (l.name.find('/') != std::string::npos) lc.fail("name", "must not contain '/', got '" + l.name + "'");
    check_transform(lc, "parent_joint_from_link", l.parent_joint_from_link);
    if (!l.parent_joint_from_link.rotation.normalized().isApprox(Quaternion::Identity(), real(1e-5)) &&
        !l.parent_joint_from_link.rotation.normalized().coeffs().isApprox(-Quaternion::Identity().coeffs(), real(1e-5)))
      lc.fail("parent_joint_from_link.rotation", "must be the identity (a link's frame is its joint's frame rotated by nothing)");
    if (l.collider_type == ColliderType::PointCloud || l.collider_type == ColliderType::Plane)
      lc.fail("collider_type", "links take NONE, AUTO, SPHERE, BOX, MESH or SDF colliders");
    validate(l.contact, lc.where() + ".contact");
    check_inertia(lc, l.density, l.mass, l.center_of_mass, l.moment_of_inertia);
    check_subsampling(lc, l.boundary_subsampling);
  }
  for (size_t i = 0; i < p.joints.size(); ++i) {
    const ArticulatedJointParams& j = p.joints[i];
    const FieldCheck jc(where + ".joints[" + std::to_string(i) + "]");
    if (j.type == ArticulatedJointType::Invalid) jc.fail("type", "is not set (INVALID): give FREE, PRISMATIC, REVOLUTE, SPHERICAL or HARD");
    if (j.type == ArticulatedJointType::Cycle) jc.fail("type", "CYCLE joints are given in `cycles`, not `joints`");
    if (j.type == ArticulatedJointType::Free && i != 0) jc.fail("type", "only the root joint (joints[0]) may be FREE");
    check_transform(jc, "parent_link_from_joint", j.parent_link_from_joint);
    jc.finite_vector("axis", j.axis);
    if ((j.type == ArticulatedJointType::Revolute || j.type == ArticulatedJointType::Prismatic) && j.axis.norm() < real(1e-9))
      jc.fail("axis", "must be a non-zero vector for a revolute or prismatic joint");
    validate(j.friction, jc.where() + ".friction");
    if (j.inertia) jc.non_negative("inertia", *j.inertia);
    if (j.min_limit) jc.finite_vector("min_limit", *j.min_limit);
    if (j.max_limit) jc.finite_vector("max_limit", *j.max_limit);
    // a 1-DOF joint's limits are their components along its axis (named here by their params
    // fields: the articulation model's own check names a bot file's minLimit)
    if ((j.type == ArticulatedJointType::Revolute || j.type == ArticulatedJointType::Prismatic) && j.min_limit && j.max_limit) {
      const Real3 axis = j.axis.normalized();
      const real lower = axis.dot(*j.min_limit), upper = axis.dot(*j.max_limit);
      if (lower > upper) jc.fail("min_limit", "the lower limit " + value_text(lower) + " exceeds the upper limit " + value_text(upper));
    }
    jc.non_negative("limit_stiffness", j.limit_stiffness);
    jc.non_negative("limit_damping", j.limit_damping);
  }
  if (!p.cycles.empty()) c.fail("cycles", "closed kinematic loops are not available yet");
  if (p.joint_velocities) c.finite_vector("joint_velocities", *p.joint_velocities);
  if (p.skin) {
    const FieldCheck sc(where + ".skin");
    if (!p.skin->shape.is_valid()) sc.fail("shape", "is not set: a skin needs a triangle mesh with skinning weights");
    validate(p.skin->contact, sc.where() + ".contact");
    check_subsampling(sc, p.skin->boundary_subsampling);
  }
}

void validate(const SoftSkinnedActorParams& p, const std::string& where) {
  const FieldCheck c(where);
  validate(p.skeleton_params, where + ".skeleton_params");
  if (p.soft_params.empty()) c.fail("soft_params", "must hold at least one soft actor's params");
  if (p.soft_attach_links.size() > 1 && p.soft_attach_links.size() != p.soft_params.size())
    c.fail("soft_attach_links", "must name one link for all soft bodies or one per soft body (" + std::to_string(p.soft_params.size()) +
                                    "), got " + std::to_string(p.soft_attach_links.size()));
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

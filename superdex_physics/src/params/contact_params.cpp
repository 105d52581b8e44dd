// ContactParams: names of collider types and validation (contact_params.h).

#include "superdex/physics/params/contact_params.h"

#include "params/check.h"
#include "superdex/physics/shape.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

const char* collider_type_name(ColliderType type) {
  switch (type) {
    case ColliderType::None: return "None";
    case ColliderType::Auto: return "Auto";
    case ColliderType::Sphere: return "Sphere";
    case ColliderType::Box: return "Box";
    case ColliderType::Mesh: return "Mesh";
    case ColliderType::Plane: return "Plane";
    case ColliderType::Sdf: return "Sdf";
    case ColliderType::PointCloud: return "PointCloud";
  }
  return "?";
}

ContactMaterial contact_material(const ContactParams& p) {
  ContactMaterial m;
  m.friction = p.coulomb_friction_coefficient;
  m.stiffness = p.contact_stiffness;
  m.dissipation_time = p.dissipation_time_scale;
  return m;
}

void validate(const ContactParams& p, const std::string& where) {
  const FieldCheck c(where);
  c.positive("penalty_coefficient", p.penalty_coefficient);
  c.non_negative("penalty_smoothing_half_distance", p.penalty_smoothing_half_distance);
  c.finite("penalty_threshold_default", p.penalty_threshold_default);
  c.non_negative("penalty_threshold_extra_padding", p.penalty_threshold_extra_padding);
  c.in_range("max_alignment_normals", p.max_alignment_normals, -1, 1);
  c.non_negative("viscous_friction_coefficient", p.viscous_friction_coefficient);
  c.non_negative("coulomb_friction_coefficient", p.coulomb_friction_coefficient);
  c.non_negative("friction_falloff_vel", p.friction_falloff_vel);
  c.non_negative("normal_viscous_damping_coefficient", p.normal_viscous_damping_coefficient);
  c.non_negative("distance_error_bound", p.distance_error_bound);
  c.positive("obj_scale", p.obj_scale);
  c.positive("colliding_penalty_length_scale", p.colliding_penalty_length_scale);
  c.non_negative("contact_stiffness", p.contact_stiffness);
  c.non_negative("dissipation_time_scale", p.dissipation_time_scale);
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

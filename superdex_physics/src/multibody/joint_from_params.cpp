// ArticulatedJointParams -> JointDesc (joint_from_params.h).

#include "multibody/joint_from_params.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

JointDesc joint_desc_from_params(const ArticulatedJointParams& j, int index) {
  JointDesc out;
  out.name = j.name.empty() ? "joint_" + std::to_string(index) : j.name;
  out.type = j.type;
  out.axis = j.axis.norm() > 0 ? Vec3(j.axis) : Vec3::UnitZ();
  out.parent_link_from_joint = j.parent_link_from_joint;
  out.min_limit = j.min_limit;
  out.max_limit = j.max_limit;
  out.coulomb_friction = j.friction.coulomb;
  out.viscous_friction = j.friction.viscous;
  out.armature = j.inertia.value_or(0);
  out.limit_stiffness = j.limit_stiffness;
  out.limit_damping = j.limit_damping;
  return out;
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

#pragma once
// SuperDex's ArticulatedJointParams as this engine's joint description (JointDesc).

#include "superdex/physics/articulation_desc.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

/// The description of joint `index` (its name when unnamed: "joint_<index>"); a zero axis
/// becomes +z. Friction keeps its Coulomb and viscous parts, the inertia is the armature.
JointDesc joint_desc_from_params(const ArticulatedJointParams& params, int index);

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

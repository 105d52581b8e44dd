#pragma once
// Forward kinematics, link Jacobians and position integration of an articulation.

#include "multibody/articulation_model.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

// X_J(q): the child link frame in the joint frame for joint `j` at positions `q_j`.
SpatialTransform joint_transform(const JointModel& j, const real* q_j);

// Link poses and spatial velocities from the state.
void update_kinematics(const ArticulationModel& model, const ArticulationState& state, ArticulationKinematics& kin);
// The same from positions q, velocities v and the pose of the root joint's parent frame X_W_base.
void update_kinematics(const ArticulationModel& model, const VecX& q, const VecX& v, const SpatialTransform& X_W_base,
                       ArticulationKinematics& kin);

// J_WL (6 x nv, linear rows first): maps generalized velocities to the velocity of the link
// origin and the link angular velocity, both in world axes. `kin` must be current.
void link_jacobian_world(const ArticulationModel& model, const ArticulationKinematics& kin, int link, MatXR& J_WL);

// q <- q (+) dt v: joint positions advanced by velocities v over dt, quaternions kept unit.
void integrate_positions(const ArticulationModel& model, VecX& q, const VecX& v, real dt);

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

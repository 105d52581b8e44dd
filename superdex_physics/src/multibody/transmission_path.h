#pragma once
// A transmission's displacement and its Jacobian at the articulation's current state: the
// linear sum over its joints, plus for a spatial tendon the length of its segments between
// waypoints less their length with every joint at zero (ArticulationModel::Transmission).

#include "multibody/articulation_model.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

// The summed length of the segments between waypoints, at link frames X_WL (m).
real segments_length(const ArticulationModel::Transmission& t, const std::vector<SpatialTransform>& X_WL);

// d (m) at the state and its kinematics.
real transmission_displacement(const ArticulationModel& model, const ArticulationState& state, const ArticulationKinematics& kin,
                               const ArticulationModel::Transmission& t);

// dd/dv over the articulation's DOFs at the kinematics' state.
VecX transmission_jacobian(const ArticulationModel& model, const ArticulationKinematics& kin, const ArticulationModel::Transmission& t);

// A McKibben muscle's tension (N, >= 0) and its derivative in the displacement (N/m) at
// displacement d (m) (McKibbenActuatorParams gives the model).
struct MuscleTension {
  real tension = 0, stiffness = 0;
};
MuscleTension mc_kibben_tension(const TransmissionActuator& act, real d);

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

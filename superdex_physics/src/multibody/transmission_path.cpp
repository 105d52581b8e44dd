// Transmission displacements and Jacobians (transmission_path.h).

#include "multibody/transmission_path.h"

#include <algorithm>
#include <cmath>

#include "multibody/kinematics.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace {

Vec3 waypoint_W(const ArticulationModel::Waypoint& w, const std::vector<SpatialTransform>& X_WL) {
  const SpatialTransform& X = X_WL[w.link];
  return X.R * w.p_L + X.p;
}

}  // namespace

real segments_length(const ArticulationModel::Transmission& t, const std::vector<SpatialTransform>& X_WL) {
  real L = 0;
  for (size_t k = 0; k + 1 < t.waypoints.size(); ++k)
    if (t.waypoints[k].to_next) L += (waypoint_W(t.waypoints[k + 1], X_WL) - waypoint_W(t.waypoints[k], X_WL)).norm();
  return L;
}

real transmission_displacement(const ArticulationModel&, const ArticulationState& state, const ArticulationKinematics& kin,
                               const ArticulationModel::Transmission& t) {
  real d = t.length(state.q);
  if (!t.waypoints.empty()) d += segments_length(t, kin.X_WL) - t.rest_length;
  return d;
}

VecX transmission_jacobian(const ArticulationModel& model, const ArticulationKinematics& kin, const ArticulationModel::Transmission& t) {
  VecX J = t.jacobian(model.nv);
  MatXR J_a, J_b;
  for (size_t k = 0; k + 1 < t.waypoints.size(); ++k) {
    if (!t.waypoints[k].to_next) continue;
    const ArticulationModel::Waypoint &a = t.waypoints[k], &b = t.waypoints[k + 1];
    const Vec3 p_a = waypoint_W(a, kin.X_WL), p_b = waypoint_W(b, kin.X_WL);
    const real length = (p_b - p_a).norm();
    if (!(length > 0)) continue;  // coincident waypoints: no direction, no rate to first order
    const Vec3 u = (p_b - p_a) / length;
    // a point's velocity along u: u . v_origin + ((p - o) x u) . w
    link_jacobian_world(model, kin, b.link, J_b);
    link_jacobian_world(model, kin, a.link, J_a);
    const Vec3 m_b = (p_b - kin.X_WL[b.link].p).cross(u), m_a = (p_a - kin.X_WL[a.link].p).cross(u);
    J += (J_b.topRows<3>().transpose() * u + J_b.bottomRows<3>().transpose() * m_b) -
         (J_a.topRows<3>().transpose() * u + J_a.bottomRows<3>().transpose() * m_a);
  }
  return J;
}

MuscleTension mc_kibben_tension(const TransmissionActuator& act, real d) {
  const real L = act.deflated_length + d;
  const real b2 = act.thread_length * act.thread_length;
  // the pressure term's scale: P_eff b^2 / (4 pi n^2) (N)
  const real c = std::max<real>(0, act.value - act.minimum_pressure) * b2 / (4 * real(M_PI) * act.wraps * act.wraps);
  const real tension = c * (3 * L * L / b2 - 1) + act.stiffness * d;
  // a muscle never pushes: below zero tension it is slack
  if (!(tension > 0)) return {};
  return {tension, c * 6 * L / b2 + act.stiffness};
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

// Dynamics terms and joint rows of one articulation for the implicit step.

#include "multibody/articulation_step.h"

#include <algorithm>
#include <numbers>

#include "multibody/dynamics.h"
#include "multibody/kinematics.h"
#include "multibody/transmission_path.h"
#include "core/spatial.h"
#include "solver/step_settings.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

real near_rigid_factor(const StepSettings& params) {
  constexpr real pi = std::numbers::pi_v<real>;
  return params.near_rigid_beta * params.near_rigid_beta / (4 * pi * pi);
}

namespace {

// Joint limit, drive and Coulomb friction rows, appended to t.joint_rows from A^-1's diagonal and
// t.v_free.
void joint_rows(const ArticulationModel& model, const ArticulationState& state, real dt, const StepSettings& params,
                ArticulationTerms& t) {
  std::vector<JointRow>& rows = t.joint_rows;
  const real near_rigid = near_rigid_factor(params);
  for (const JointModel& j : model.joints) {
    if (j.nv != 1) continue;
    const bool limited = j.has_lower || j.has_upper;
    if (!limited && j.coulomb <= 0 && !state.drives[j.v_offset].active()) continue;
    const int k = j.v_offset;
    const real q = state.q[j.q_offset];
    if (limited) {
      // compliant limit (SAP): impulse = dt k (-(phi + dt vc) - tau_d vc), floored at the near-rigid compliance
      real R_stiffness = 0, tau_d = dt;
      if (j.limit_stiffness > 0) {
        tau_d = j.limit_damping / j.limit_stiffness;
        R_stiffness = 1 / (dt * j.limit_stiffness * (dt + tau_d));
      }
      ConstraintBlock b;
      b.kind = BlockKind::Unilateral;
      for (const real sign : {real(1), real(-1)}) {
        if (!(sign > 0 ? j.has_lower : j.has_upper)) continue;
        // beyond the limit (vhat > 0): a near-rigid limit backs out no faster than the
        // depenetration bound; a compliant one is a spring whose force the bound must not cap
        b.vhat = -(sign > 0 ? q - j.lower : j.upper - q) / (dt + tau_d);
        if (j.limit_stiffness <= 0) b.vhat = std::min(b.vhat, params.max_depenetration_speed);
        // acts once sign * v < vhat (< 0 inside the limit): far from it when the free motion
        // keeps sign * v above vhat / 2
        JointRow row{k, sign, b};
        row.deferred = params.defer_inactive_joint_limits && b.vhat < 0 && sign * t.v_free[k] > b.vhat / 2;
        row.block.R = row.deferred ? R_stiffness : std::max(near_rigid * t.inverse_diagonal(k), R_stiffness);
        rows.push_back(std::move(row));
      }
    }
    // joint drive: impulse dt (K (q* - q - dt vc) + D (v* - vc)) = (vhat - vc) / R, clamped to dt max_effort
    const JointDrive& d = state.drives[k];
    if (d.active()) {
      ConstraintBlock b;
      b.kind = BlockKind::Bounded;
      const real per_velocity = dt * d.stiffness + d.damping;  // effort per unit of next velocity
      // floored only against ill-conditioning (far below near-rigid, so the spring stays exact)
      b.R = std::max(1 / (dt * per_velocity), real(1e-3) * near_rigid * t.inverse_diagonal(k));
      b.vhat = (d.stiffness * (d.target_position - q) + d.damping * d.target_velocity) / per_velocity;
      b.bound = d.max_effort >= 0 ? dt * d.max_effort : std::numeric_limits<real>::infinity();
      rows.push_back({k, 1, b, true});
    }
    if (j.coulomb > 0) {
      ConstraintBlock b;
      b.kind = BlockKind::Bounded;
      b.R = params.friction_sigma * t.inverse_diagonal(k);
      b.bound = dt * j.coulomb;
      rows.push_back({k, 1, b});
    }
  }
}

// Joint coupling rows: v[dof] - ratio v[leader] = vhat closing the relation's error within the
// step, near-rigid (regularised by the row's own compliance, as contacts are), unbounded.
void coupling_rows(const ArticulationModel& model, const ArticulationState& state, real dt, const StepSettings& params,
                   ArticulationTerms& t) {
  const real near_rigid = near_rigid_factor(params);
  for (const auto& c : model.couplings) {
    JointRow row;
    row.J = VecX::Zero(model.nv);
    row.J[c.dof] = 1;
    row.J[c.leader_dof] -= c.ratio;
    MatX X = row.J;
    const real w = compliance_diagonal(t.A_factor, X)[0];
    row.block.kind = BlockKind::Bounded;
    row.block.R = near_rigid * w;
    row.block.vhat = -(state.q[c.q] - c.ratio * state.q[c.leader_q] - c.offset) / dt;
    row.block.bound = std::numeric_limits<real>::infinity();
    t.joint_rows.push_back(std::move(row));
  }
}

// Fixed tendon limit rows: sign * (c . v) >= vhat closing the length's distance to its bound, as
// joint limits are (near-rigid, back no faster than the depenetration bound), deferred while the
// free motion stays well inside the range.
void tendon_limit_rows(const ArticulationModel& model, const ArticulationState& state, real dt, const StepSettings& params,
                       ArticulationTerms& t) {
  const real near_rigid = near_rigid_factor(params);
  for (const ArticulationModel::Tendon& tendon : model.tendons) {
    if (!tendon.has_lower && !tendon.has_upper) continue;
    const real L = tendon.length(state.q);
    const VecX J = tendon.jacobian(model.nv);
    const real rate_free = J.dot(t.v_free);
    // the tendon's compliance c^T A^-1 c, the same for either bound
    MatX X = J;
    const real w = compliance_diagonal(t.A_factor, X)[0];
    for (const real sign : {real(1), real(-1)}) {
      if (!(sign > 0 ? tendon.has_lower : tendon.has_upper)) continue;
      JointRow row;
      row.J = sign * J;
      row.block.kind = BlockKind::Unilateral;
      row.block.R = near_rigid * w;
      row.block.vhat = std::min(-(sign > 0 ? L - tendon.lower : tendon.upper - L) / dt, params.max_depenetration_speed);
      row.deferred = params.defer_inactive_joint_limits && row.block.vhat < 0 && sign * rate_free > row.block.vhat / 2;
      t.joint_rows.push_back(std::move(row));
    }
  }
}

// Fixed tendon springs and dampers, implicit: the tendon force f = K (rest - L(q+)) - D (c . v+)
// with L(q+) = L + dt c . v+ adds dt (dt K + D) c c^T to A and dt K (rest - L) c to r.
void tendon_springs(const ArticulationModel& model, const ArticulationState& state, real dt, ArticulationTerms& t) {
  for (const ArticulationModel::Tendon& tendon : model.tendons) {
    if (tendon.stiffness <= 0 && tendon.damping <= 0) continue;
    const real force = tendon.stiffness * (tendon.rest_length - tendon.length(state.q));
    const real per_rate = dt * (dt * tendon.stiffness + tendon.damping);
    for (size_t a = 0; a < tendon.dofs.size(); ++a) {
      t.r[tendon.dofs[a]] += dt * force * tendon.coefficients[a];
      for (size_t b = 0; b < tendon.dofs.size(); ++b)
        t.A(tendon.dofs[a], tendon.dofs[b]) += per_rate * tendon.coefficients[a] * tendon.coefficients[b];
    }
  }
}

// Force-controlled transmissions and McKibben muscles: the tension's joint efforts -f dd/dv (it
// shortens the transmission) into r; a muscle's tension is its energy's derivative, linearized
// over the step: f(d + dt J v+) = f + dt k J v+ adds dt^2 k J J^T to A.
void transmission_forces(const ArticulationModel& model, const ArticulationState& state, const ArticulationKinematics& kin, real dt,
                         ArticulationTerms& t) {
  for (size_t i = 0; i < model.transmissions.size(); ++i) {
    const TransmissionActuator& act = state.transmission_actuators[i];
    if (act.kind == TransmissionActuator::Kind::ForceControl) {
      t.r -= dt * act.value * transmission_jacobian(model, kin, model.transmissions[i]);
    } else if (act.kind == TransmissionActuator::Kind::McKibben) {
      const ArticulationModel::Transmission& path = model.transmissions[i];
      const MuscleTension m = mc_kibben_tension(act, transmission_displacement(model, state, kin, path));
      if (m.tension <= 0) continue;
      const VecX J = transmission_jacobian(model, kin, path);
      t.r -= dt * m.tension * J;
      t.A.noalias() += (dt * dt * m.stiffness) * J * J.transpose();
    }
  }
}

// Displacement-controlled transmissions: a row on the transmission's shortening rate, an
// implicit spring-damper as a joint drive is, that only pulls (unilateral) unless it may push.
void transmission_drive_rows(const ArticulationModel& model, const ArticulationState& state, const ArticulationKinematics& kin, real dt,
                             const StepSettings& params, ArticulationTerms& t) {
  for (size_t i = 0; i < model.transmissions.size(); ++i) {
    const TransmissionActuator& act = state.transmission_actuators[i];
    if (act.kind != TransmissionActuator::Kind::DisplacementControl || (act.stiffness <= 0 && act.damping <= 0)) continue;
    const ArticulationModel::Transmission& path = model.transmissions[i];
    JointRow row;
    // the row's rate is the shortening rate -dd/dt: a rope's tension acts along it
    row.J = -transmission_jacobian(model, kin, path);
    MatX X = row.J;
    const real w = compliance_diagonal(t.A_factor, X)[0];
    const real per_rate = dt * act.stiffness + act.damping;  // tension per unit of displacement rate
    row.block.kind = act.allow_compressive_force ? BlockKind::Bounded : BlockKind::Unilateral;
    // floored only against ill-conditioning (far below near-rigid, so the spring stays exact)
    row.block.R = std::max(1 / (dt * per_rate), real(1e-3) * near_rigid_factor(params) * w);
    row.block.vhat = act.stiffness * (transmission_displacement(model, state, kin, path) - act.value) / per_rate;
    row.block.bound = std::numeric_limits<real>::infinity();
    t.joint_rows.push_back(std::move(row));
  }
}

// A single free body's gyroscopic torque w x (I w), explicit in the bias forces, lets a tumbling
// body gain energy. Replace it by backward Euler on Euler's equations in the body frame,
// I (w2 - w1) + dt w2 x (I w2) = 0 (Newton), whose solution never gains kinetic energy
// (w2^T I w2 = w2^T I w1): the free motion's angular momentum becomes I w2 - dt (w1 x I w1)
// is removed from r. Exact for bodies whose centre of mass is the link origin; with an offset
// centre of mass only the term about the centre of mass is treated implicitly.
void implicit_gyroscopic(const ArticulationModel& model, const ArticulationState& state, real dt, VecX& r) {
  if (model.num_links != 1 || model.joints[0].type != JointType::Free) return;
  const Mat3& I = model.inertia[0].inertia_com;
  const Vec3 w1 = state.v.segment<3>(3);
  Vec3 w2 = w1;
  for (int it = 0; it < 4; ++it) {
    const Vec3 f = I * (w2 - w1) + dt * w2.cross(I * w2);
    const Mat3 df = I + dt * (skew(w2) * I - skew(I * w2));
    const Vec3 step = df.partialPivLu().solve(f);
    w2 -= step;
    if (step.norm() <= std::numeric_limits<real>::epsilon() * (1 + w2.norm())) break;
  }
  r.segment<3>(3) += I * (w2 - w1) + dt * w1.cross(I * w1);
}

// Link drive rows: per world axis, a bounded implicit spring-damper on the link origin's velocity
// (linear) or the link's angular velocity (angular), with the link Jacobian's rows.
void link_drive_rows(const ArticulationModel& model, const ArticulationState& state, const ArticulationKinematics& kin,
                     const TreeLDLT& A_factor, real dt, const StepSettings& params, std::vector<JointRow>& rows) {
  const real near_rigid = near_rigid_factor(params);
  for (int link = 0; link < model.num_links; ++link) {
    const LinkDrive& d = state.link_drives[link];
    if (!d.active()) continue;
    MatXR J;
    link_jacobian_world(model, kin, link, J);
    const SpatialTransform& X = kin.X_WL[link];
    const Vec3 position_error = d.target.translation - X.p;
    const Vec3 rotation_error = quat_log(d.target.rotation * Quat(X.R).conjugate());
    // the compliance J_i A^-1 J_i^T of each of the link Jacobian's six rows
    MatX Jt = J.transpose();
    const VecX w = compliance_diagonal(A_factor, Jt);
    for (int part = 0; part < 2; ++part) {
      const real K = part == 0 ? d.linear_stiffness : d.angular_stiffness;
      const real D = part == 0 ? d.linear_damping : d.angular_damping;
      if (K <= 0 && D <= 0) continue;
      const Vec3& error = part == 0 ? position_error : rotation_error;
      const Vec3& target_velocity = part == 0 ? d.target_linear_velocity : d.target_angular_velocity;
      const real limit = part == 0 ? d.max_force : d.max_torque;
      for (int axis = 0; axis < 3; ++axis) {
        JointRow row;
        row.J = J.row(3 * part + axis).transpose();
        if (row.J.squaredNorm() < real(1e-20)) continue;  // the articulation cannot move along it
        const real per_velocity = dt * K + D;
        row.block.kind = BlockKind::Bounded;
        row.block.R = std::max(1 / (dt * per_velocity), real(1e-3) * near_rigid * w[3 * part + axis]);
        row.block.vhat = (K * error[axis] + D * target_velocity[axis]) / per_velocity;
        row.block.bound = limit >= 0 ? dt * limit : std::numeric_limits<real>::infinity();
        rows.push_back(std::move(row));
      }
    }
  }
}

}  // namespace

void articulation_terms(const Articulation& a, const Vec3& g_W, real dt, const StepSettings& params, ArticulationTerms& t) {
  const ArticulationModel& model = a.model;
  t.joint_rows.clear();
  t.have_inverse_diagonal_ = false;
  if (model.nv == 0) {
    t.A.resize(0, 0);
    t.r.resize(0);
    t.v_free.resize(0);
    t.A_factor.compute(t.A, model.dof_parent);
    return;
  }
  mass_matrix(model, a.kin, t.A);
  bias_forces(model, a.state, a.kin, g_W, t.c);
  // (M + dt D) v+ = M v + dt (tau - c): viscous joint friction integrated implicitly
  if (model.nv <= SmallLLT::kSmall) {
    t.r.noalias() = t.A.lazyProduct(a.state.v);  // (Eigen's blocked kernel costs more to set up)
  } else {
    t.r.noalias() = t.A * a.state.v;
  }
  t.r.noalias() += dt * (a.state.tau_external - t.c);
  for (const JointModel& j : model.joints)
    for (int k = 0; k < j.nv; ++k) t.A(j.v_offset + k, j.v_offset + k) += dt * j.viscous;
  implicit_gyroscopic(model, a.state, dt, t.r);
  tendon_springs(model, a.state, dt, t);
  transmission_forces(model, a.state, a.kin, dt, t);
  t.A_factor.compute(t.A, model.dof_parent);
  t.v_free = t.r;
  t.A_factor.solve_in_place(t.v_free);
  joint_rows(model, a.state, dt, params, t);
  coupling_rows(model, a.state, dt, params, t);
  tendon_limit_rows(model, a.state, dt, params, t);
  transmission_drive_rows(model, a.state, a.kin, dt, params, t);
  link_drive_rows(model, a.state, a.kin, t.A_factor, dt, params, t.joint_rows);
}

real ArticulationTerms::inverse_diagonal(int k) const {
  if (!have_inverse_diagonal_) {
    A_factor.inverse_diagonal(A_inv_diagonal_);
    have_inverse_diagonal_ = true;
  }
  return A_inv_diagonal_[k];
}

real deferred_compliance(const ArticulationTerms& t, const JointRow& row, const StepSettings& params) {
  if (row.J.size() > 0) return row.block.R;  // a row over several DOFs has its floor already
  return std::max(row.block.R, near_rigid_factor(params) * t.inverse_diagonal(row.dof));
}

ArticulationTerms articulation_terms(const Articulation& a, const Vec3& g_W, real dt, const StepSettings& params) {
  ArticulationTerms t;
  articulation_terms(a, g_W, dt, params, t);
  return t;
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

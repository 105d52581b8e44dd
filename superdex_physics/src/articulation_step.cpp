// Assembly and solution of one articulation's implicit step.

#include "articulation_step.h"

#include <chrono>
#include <numbers>

#include "dynamics.h"
#include "kinematics.h"
#include "newton_solver.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// Joint limit and Coulomb friction rows. w_kk is the effective compliance (A^-1)_kk of DOF k.
void add_joint_rows(const ArticulationModel& model, const ArticulationState& state, const Eigen::LLT<MatX>& A_llt,
                    real dt, const SolverParams& params, ConstraintRows& rows) {
  struct Row {
    int dof;
    real sign;
    RowKind kind;
    real R, vhat, bound;
  };
  std::vector<Row> list;
  const int n = model.nv;
  auto compliance = [&](int k) {
    VecX e = VecX::Zero(n);
    e[k] = 1;
    return A_llt.solve(e)[k];
  };
  const real near_rigid = params.near_rigid_beta * params.near_rigid_beta / (4 * std::numbers::pi_v<real> * std::numbers::pi_v<real>);
  for (const JointModel& j : model.joints) {
    if (j.nv != 1) continue;
    const bool limited = j.has_lower || j.has_upper;
    if (!limited && j.coulomb <= 0) continue;
    const int k = j.v_offset;
    const real w = compliance(k);
    const real q = state.q[j.q_offset];
    if (limited) {
      // compliant limit (SAP): impulse = dt k (-(phi + dt vc) - tau_d vc), floored at the near-rigid compliance
      real R = near_rigid * w, tau_d = dt;
      if (j.limit_stiffness > 0) {
        tau_d = j.limit_damping / j.limit_stiffness;
        R = std::max(R, 1 / (dt * j.limit_stiffness * (dt + tau_d)));
      }
      if (j.has_lower) list.push_back({k, 1, RowKind::Unilateral, R, -(q - j.lower) / (dt + tau_d), 0});
      if (j.has_upper) list.push_back({k, -1, RowKind::Unilateral, R, -(j.upper - q) / (dt + tau_d), 0});
    }
    if (j.coulomb > 0) list.push_back({k, 1, RowKind::BoundedFriction, params.friction_sigma * w, 0, dt * j.coulomb});
  }
  rows.resize(static_cast<int>(list.size()), n);
  for (int i = 0; i < rows.size(); ++i) {
    rows.J(i, list[i].dof) = list[i].sign;
    rows.kind[i] = list[i].kind;
    rows.R[i] = list[i].R;
    rows.vhat[i] = list[i].vhat;
    rows.bound[i] = list[i].bound;
  }
}

}  // namespace

ArticulationStepResult step_articulation(const Articulation& a, const Vec3& g_W, real dt, const SolverParams& params) {
  const ArticulationModel& model = a.model;
  const ArticulationState& state = a.state;
  ArticulationStepResult out;
  out.q = state.q;
  out.v = state.v;
  if (model.nv == 0) return out;

  const auto t0 = Clock::now();
  const MatX M = mass_matrix(model, a.kin);
  const VecX c = bias_forces(model, state, a.kin, g_W);
  // momentum matrix with implicit viscous joint friction: (M + dt D) v+ = M v + dt (tau - c)
  MatX A = M;
  for (const JointModel& j : model.joints)
    for (int k = 0; k < j.nv; ++k) A(j.v_offset + k, j.v_offset + k) += dt * j.viscous;
  const VecX r = M * state.v + dt * (state.tau_external - c);
  Eigen::LLT<MatX> A_llt(A);
  ConstraintRows rows;
  add_joint_rows(model, state, A_llt, dt, params, rows);
  out.time_dynamics = seconds_since(t0);

  const auto t1 = Clock::now();
  ConvexResult sol = solve_convex(A, A_llt, r, rows, params);
  out.time_solve = seconds_since(t1);
  out.v = std::move(sol.v);
  out.iterations = sol.iterations;
  out.residual = sol.residual;
  out.converged = sol.converged;
  for (int i = 0; i < sol.gamma.size(); ++i) out.active_rows += sol.gamma[i] != 0;
  integrate_positions(model, out.q, out.v, dt);
  return out;
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

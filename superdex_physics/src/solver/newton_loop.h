#pragma once

#include <chrono>
#include <string>

#include "superdex/physics/log.h"
// Newton's method with exact line search for the convex implicit step (newton_solver.h), on any
// linear-algebra backend. An Algebra provides:
//
//   int n(), m(); diagonal(out);              variables and constraint rows, and the diagonal of A
//                                             (for scaling)
//   A_mul(x, out), J_mul(x, out), Jt_mul(y, out)
//                                             products with A and the constraint Jacobian, into
//                                             `out` (resized as needed; its storage is reused)
//   bool smooth();                            whether the objective has a smooth non-quadratic
//                                             part e(v) (soft bodies' elastic energy)
//   void add_smooth_gradient(v, g);           g += grad e(v)
//   void factor(blocks, G, v);                factors H = A + J^T G J + hess e(v)
//   real smooth_curvature(dv);                dv^T hess e(v) dv at the last factored v
//   solve(b, x);                              x = H^-1 b

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "solver/newton_solver.h"
#include "solver/step_settings.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

// The loop's vectors are w's (newton_solver.h), and so is its result, w.result.
//
// Sliding drift: in the cone model a contact slipping at |v_t| beyond its regularisation
// (R_t |gamma_t|) separates at mu times that speed. While params.drift_correction_iterations
// last, each iteration lowers every frictional contact's normal target by
// mu (|v_t| - R_t mu gamma_n) at the current iterate, so that at the solution a sliding contact
// keeps its normal target, with its friction on the cone (mu gamma_n): Coulomb's law without the
// drift. Sticking contacts (|v_t| = R_t |gamma_t| <= R_t mu gamma_n) get none. gamma_n is the
// last iterate's; the first iteration takes it at the start itself, uncorrected: with a warm
// start (the bodies' last velocities) a contact that slid in the last step starts from about
// the correction it ended with, so that the later iterations only refine it. The corrections
// stop once the residual is within 100 times the tolerance (a fixed point to that accuracy) or
// when the iterations run out; the problem is then convex and Newton converges. The corrections
// are not left to their fixed point alone: each Newton step predicts them from the step's
// linearization (predict_corrections below), which makes the pair converge like Newton's method.
template <class Algebra>
ConvexResult& newton(Algebra& alg, const VecX& r, const std::vector<ConstraintBlock>& given_blocks, const StepSettings& params,
                     const VecX& v_start, NewtonScratch& w) {
  const int n = alg.n();
  const int m = alg.m();
  const bool smooth = alg.smooth();
  ConvexResult& out = w.result;
  out.v = v_start;
  out.gamma.setZero(m);
  out.iterations = 0;
  out.residual = 0;
  out.converged = false;
  out.status = ConvergenceStatus::Stopped;
  out.line_search_iterations = 0;
  // the limits that end a solve before convergence (SolverParams): run time, step size, no
  // improvement, divergence
  const auto started = params.max_elapsed_time_seconds > 0 ? std::chrono::steady_clock::now() : std::chrono::steady_clock::time_point();
  real first_residual = -1, previous_residual = std::numeric_limits<real>::infinity();
  // diagonal scaling so that the stopping test is independent of units and masses
  VecX& D = w.D;
  alg.diagonal(D);
  D = D.cwiseMax(real(1e-12)).cwiseSqrt().cwiseInverse();
  const real r_norm = (D.asDiagonal() * r).norm();

  VecX &vc = w.vc, &grad = w.grad, &dv = w.dv, &dvc = w.dvc, &jc = w.jc, &smooth_grad = w.smooth_grad;
  VecX &Av_r = w.Av_r, &Adv = w.Adv;
  VecX& v_alpha = w.v_alpha;  // a line-search trial point
  for (VecX* x : {&vc, &dvc}) x->resize(m);
  for (VecX* x : {&grad, &dv, &jc, &smooth_grad, &Av_r, &Adv}) x->resize(n);
  std::vector<Eigen::Matrix<real, 3, 3>>& G = w.G;
  G.resize(given_blocks.size());

  // the blocks as this solve sees them: contacts' normal targets with their drift corrections
  std::vector<ConstraintBlock>& blocks = w.blocks;
  blocks = given_blocks;
  bool correcting = params.drift_correction_iterations > 0 &&
                    std::any_of(blocks.begin(), blocks.end(), [](const ConstraintBlock& b) { return b.kind == BlockKind::FrictionalContact; });
  // impulses and Hessian blocks at the current constraint velocities
  auto respond = [&](const VecX& velocities, VecX& gamma) {
    for (size_t k = 0; k < blocks.size(); ++k)
      block_response(blocks[k], velocities.data() + blocks[k].row, gamma.data() + blocks[k].row, G[k].data());
  };
  // a contact's slip beyond its friction regularisation at constraint velocities vc and the
  // impulses in out.gamma (m/s; > 0: sliding, whose drift the corrections remove)
  auto slip_of = [&](const ConstraintBlock& b) {
    return std::hypot(vc[b.row], vc[b.row + 1]) - b.R * b.bound * out.gamma[b.row + 2];
  };
  // lowers each contact's normal target by its drift at constraint velocities vc (impulses of
  // the last iterate in out.gamma); whether any target differs from its uncorrected one
  real correction_change = 0;  // the largest change of a target by the last corrections
  auto correct_drift = [&]() {
    bool corrected = false;
    correction_change = 0;
    for (size_t k = 0; k < blocks.size(); ++k) {
      ConstraintBlock& b = blocks[k];
      if (b.kind != BlockKind::FrictionalContact) continue;
      const real slip = slip_of(b);
      const real vhat = given_blocks[k].vhat - (slip > 0 ? b.bound * slip : real(0));
      correction_change = std::max(correction_change, std::abs(vhat - b.vhat));
      b.vhat = vhat;
      corrected = corrected || slip > 0;
    }
    return corrected;
  };
  // Newton on the corrections: after the Newton direction for the current targets, each sliding
  // contact's correction d_c = mu_c (|v_t| - R mu_c gamma_n) is linearized together with the
  // step, whose gradient changes with the targets (d grad / d d_e = J_e^T G_e e_n):
  //   d_c + dd_c = mu_c (s_c + w_c . (dvc_c - sum_e z_ec dd_e) + R mu_c G_c,nn dd_c),
  //   w_c = (t_c, 0) + R mu_c G_c e_n, t_c = v_t / |v_t|, z_e = J H^-1 J_e^T G_e e_n,
  // a small system for the sliding contacts' changes dd (one solve with H each). Its targets
  // replace the plain corrections'; the plain fixed point converges only linearly (by some 0.3
  // per iteration where friction couples the contacts). Up to kMaxPredicted sliding contacts;
  // with more, the plain corrections alone. Sets `predicted` when it sets the targets; returns
  // whether that changed the gradient.
  constexpr int kMaxPredicted = 8, kPredictionFailures = 6;
  using SmallMat = Eigen::Matrix<real, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxPredicted, kMaxPredicted>;
  using SmallVec = Eigen::Matrix<real, Eigen::Dynamic, 1, 0, kMaxPredicted, 1>;
  std::vector<int>& sliding = w.sliding;
  bool predicting = true, predicted = false;
  auto predict_corrections = [&]() {
    sliding.clear();
    for (size_t k = 0; k < blocks.size(); ++k) {
      const ConstraintBlock& b = blocks[k];
      if (b.kind != BlockKind::FrictionalContact || slip_of(b) <= 0) continue;
      if (sliding.size() == static_cast<size_t>(kMaxPredicted)) return false;
      sliding.push_back(static_cast<int>(k));
    }
    const int c = static_cast<int>(sliding.size());
    if (c == 0) return false;
    // the sliding contacts' velocities z_e (their rows of J) per unit change of contact e's
    // target: none for a contact apart
    VecX &y = w.pred_y, &Jty = w.pred_Jty, &s = w.pred_s;
    w.pred_z.resize(c);
    for (int e = 0; e < c; ++e) {
      const int k = sliding[e], r0 = blocks[k].row;
      if (G[k].col(2).isZero(0)) {
        w.pred_z[e].setZero(m);
        continue;
      }
      y.setZero(m);
      for (int i = 0; i < 3; ++i) y[r0 + i] = G[k](i, 2);
      alg.Jt_mul(y, Jty);
      alg.solve(Jty, s);
      alg.J_mul(s, w.pred_z[e]);
    }
    SmallMat M(c, c);
    SmallVec rhs(c), d(c);  // d: the current corrections
    for (int i = 0; i < c; ++i) {
      const ConstraintBlock& b = blocks[sliding[i]];
      const auto& G_i = G[sliding[i]];
      const int r0 = b.row;
      const real vt = std::hypot(vc[r0], vc[r0 + 1]);
      const Eigen::Matrix<real, 3, 1> w_i = Eigen::Matrix<real, 3, 1>(vc[r0] / vt, vc[r0 + 1] / vt, 0) + b.R * b.bound * G_i.col(2);
      d[i] = given_blocks[sliding[i]].vhat - b.vhat;
      rhs[i] = b.bound * (slip_of(b) + w_i.dot(dvc.template segment<3>(r0))) - d[i];
      for (int e = 0; e < c; ++e) M(i, e) = b.bound * w_i.dot(w.pred_z[e].template segment<3>(r0));
      M(i, i) += 1 - b.bound * b.bound * b.R * G_i(2, 2);
    }
    const SmallVec dd = M.partialPivLu().solve(rhs);
    if (!dd.allFinite()) return false;
    // the new targets, and the contacts' impulses at them (whether any is or was non-zero: if
    // none, the gradient is the same)
    bool gradient_changed = false;
    for (int i = 0; i < c; ++i) {
      const int k = sliding[i];
      ConstraintBlock& b = blocks[k];
      b.vhat = given_blocks[k].vhat - std::max(real(0), d[i] + dd[i]);
      auto gamma_k = out.gamma.template segment<3>(b.row);
      const bool acted = !gamma_k.isZero(0);
      block_response(b, vc.data() + b.row, gamma_k.data(), G[k].data());
      gradient_changed = gradient_changed || acted || !gamma_k.isZero(0);
    }
    predicted = true;
    return gradient_changed;
  };

  int failures = 0;
  real last_change = std::numeric_limits<real>::infinity();
  real best = std::numeric_limits<real>::infinity();
  int stalled = 0;
  // the line search's last trial evaluates the smooth gradient at its point; when that point is
  // the next iterate, the gradient carries over instead of being evaluated again
  bool smooth_grad_at_v = false;
  // the last step was shorter than rel_step_tolerance: the solve stops (Stopped) once the residual
  // at the iterate it reached has been evaluated, unless that residual has converged
  bool step_stalled = false;
  for (int it = 0; it <= params.max_newton_iterations; ++it) {
    if (m > 0) {
      alg.J_mul(out.v, vc);
      if (correcting && it > 0) {
        correct_drift();
        // a prediction works when the plain corrections after it move the targets less than half
        // as far as those before it; they stop after kPredictionFailures that do not in a row
        // (contacts switching between sliding and sticking or touching can make them cycle)
        if (predicted) failures = correction_change <= real(0.5) * last_change ? 0 : failures + 1;
        if (failures >= kPredictionFailures) predicting = false;
        last_change = correction_change;
      }
      respond(vc, out.gamma);
      // the first correction, at the start's own impulses
      if (correcting && it == 0 && correct_drift()) respond(vc, out.gamma);
      alg.Jt_mul(out.gamma, jc);
    } else {
      jc.setZero(n);
    }
    alg.A_mul(out.v, Av_r);
    Av_r -= r;
    grad = Av_r - jc;
    real scale = std::max(r_norm, (D.asDiagonal() * jc).norm());
    if (smooth) {
      if (!smooth_grad_at_v) {
        smooth_grad.setZero(n);
        alg.add_smooth_gradient(out.v, smooth_grad);
      }
      grad += smooth_grad;
      scale = std::max(scale, (D.asDiagonal() * smooth_grad).norm());
    }
    out.residual = (D.asDiagonal() * grad).norm();
    out.iterations = it;
    if (params.verbose)
      log(LogChannel::Verbose, "newton iteration " + std::to_string(it) + ": scaled residual " + std::to_string(out.residual));
    // the corrections stop near their fixed point, or when their iterations run out
    const real tolerance = params.absolute_tolerance + params.relative_tolerance * scale;
    if (correcting && (it + 1 >= params.drift_correction_iterations || out.residual <= 100 * tolerance)) correcting = false;
    if (out.residual <= tolerance) {
      out.converged = true;
      out.status = ConvergenceStatus::Converged;
      break;
    }
    if (first_residual < 0) first_residual = out.residual;
    if (params.explosion_control && (!(out.residual <= params.absolute_divergence_tolerance) ||
                                     (it > 0 && out.residual > params.relative_divergence_tolerance * first_residual))) {
      out.status = ConvergenceStatus::Diverged;
      break;
    }
    if (step_stalled) break;
    if (params.stop_if_no_improvement && out.residual >= previous_residual) break;
    previous_residual = out.residual;
    if (params.max_elapsed_time_seconds > 0 &&
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count() >= params.max_elapsed_time_seconds)
      break;
    if (smooth) {
      // Newton converges quadratically: two iterations in a row that do not halve the residual
      // mean it has reached the round-off floor of the elastic forces (float positions limit the
      // strain to about 1e-7 of the element size). Only once the residual is well below the first
      // one: a stiff rod's first iterations can raise it (the energy falls) on their way in
      const bool near_floor = out.residual <= real(0.01) * first_residual;
      stalled = out.residual < real(0.5) * best || !near_floor ? 0 : stalled + 1;
      best = std::min(best, out.residual);
      if (stalled >= 2) {
        out.converged = true;
        out.status = ConvergenceStatus::Converged;
        break;
      }
    } else if (!kUsesDoublePrecision && !correcting) {
      // in float, within 100 times the tolerance, three iterations in a row that do not halve the
      // residual have reached its round-off floor (that of stiff contacts can lie above the
      // tolerance): more only repeat it, and the solve ends Stopped
      stalled = out.residual < real(0.5) * best ? 0 : stalled + 1;
      best = std::min(best, out.residual);
      if (stalled >= 3 && out.residual <= 100 * tolerance) break;
    }
    if (it == params.max_newton_iterations) break;
    // Newton direction from the Hessian A + J^T G J (+ the smooth term's)
    alg.factor(given_blocks, G, out.v);
    alg.solve(grad, dv);
    dv = -dv;
    if (m > 0) alg.J_mul(dv, dvc);
    predicted = false;
    if (correcting && predicting && m > 0 && predict_corrections()) {
      // the gradient at the new targets, and the step from it with the same H (SPD, so a
      // descent direction for the new targets' problem)
      alg.Jt_mul(out.gamma, jc);
      grad = Av_r - jc;
      if (smooth) grad += smooth_grad;
      alg.solve(grad, dv);
      dv = -dv;
      alg.J_mul(dv, dvc);
    }
    // exact line search: phi'(alpha) is monotone; find its root in (0, 1]
    const real a0 = dv.dot(Av_r);
    alg.A_mul(dv, Adv);
    const real a1 = dv.dot(Adv);
    const real curvature = smooth ? alg.smooth_curvature(dv) : real(0);
    const real slope_ref = smooth ? std::abs(grad.dot(dv)) : std::abs(a0);
    // the contact problem is piecewise quadratic and its line search nearly exact; with the
    // elastic energy each trial costs a gradient evaluation, and a strong-Wolfe-like reduction
    // of the slope keeps Newton's convergence
    // (without it, to the round-off of phi' in the working precision: a tighter tolerance only
    // adds trials that bisect noise)
    const real line_search_tolerance = smooth ? real(0.05) : kUsesDoublePrecision ? real(1e-10) : real(1e-6);
    real evaluated_alpha = -1;  // the step at which smooth_grad was last evaluated
    // a block whose impulse is zero at both ends of the segment is zero along it (its zero set
    // is the minimizer set of its convex cost), so after the first trial (alpha = 1) only the
    // blocks live at either end are evaluated
    std::vector<int>& live = w.live;
    auto dphi = [&](real alpha, real& ddphi, bool all_blocks) {
      real d = a0 + alpha * a1, dd = a1 + curvature;
      // block k's terms at the trial point (its phi'' term d_k^T G_k d_k, for d_k its rows of
      // dvc); whether its impulse is non-zero there
      auto add_block = [&](size_t k) {
        const ConstraintBlock& b = blocks[k];
        const int r0 = b.row, s = b.size();
        real vc_k[3], gamma_k[3];
        for (int i = 0; i < s; ++i) vc_k[i] = vc[r0 + i] + alpha * dvc[r0 + i];
        block_response(b, vc_k, gamma_k, G[k].data());
        bool acts = false;
        for (int i = 0; i < s; ++i) d -= dvc[r0 + i] * gamma_k[i], acts = acts || gamma_k[i] != 0;
        if (s == 1) {
          dd += G[k](0, 0) * dvc[r0] * dvc[r0];
        } else {
          const Eigen::Matrix<real, 3, 1> d_k = dvc.template segment<3>(r0);
          dd += d_k.dot(G[k] * d_k);
        }
        return acts;
      };
      if (m > 0 && all_blocks) {
        live.clear();
        for (size_t k = 0; k < blocks.size(); ++k) {
          const bool acts_at_v = !out.gamma.segment(blocks[k].row, blocks[k].size()).isZero(0);
          if (add_block(k) || acts_at_v) live.push_back(static_cast<int>(k));
        }
      } else if (m > 0) {
        for (int k : live) add_block(k);
      }
      if (smooth) {
        v_alpha.noalias() = out.v + alpha * dv;
        smooth_grad.setZero(n);
        alg.add_smooth_gradient(v_alpha, smooth_grad);
        d += dv.dot(smooth_grad);
        evaluated_alpha = alpha;
      }
      ddphi = dd;
      return d;
    };
    real alpha = 1, dd = 0;
    real d = dphi(1, dd, /*all_blocks=*/true);
    if (d > 0) {
      // safeguarded Newton on phi' over [lo, hi], from alpha = 1
      real lo = 0, hi = 1;
      for (int ls = 0; ls < params.max_line_search_iterations; ++ls) {
        out.line_search_iterations = std::max(out.line_search_iterations, ls + 1);
        if (ls > 0) d = dphi(alpha, dd, false);
        if (std::abs(d) <= line_search_tolerance * (slope_ref + std::numeric_limits<real>::min())) break;
        (d > 0 ? hi : lo) = alpha;
        real next = dd > 0 ? alpha - d / dd : (lo + hi) / 2;
        if (!(next > lo && next < hi)) next = (lo + hi) / 2;
        if (hi - lo < std::max(real(1e-12), 8 * std::numeric_limits<real>::epsilon())) break;
        alpha = next;
      }
    }
    smooth_grad_at_v = smooth && evaluated_alpha == alpha;
    if (smooth_grad_at_v) {
      out.v.swap(v_alpha);  // the trial point itself, so that the kept gradient is exactly its own
    } else {
      out.v += alpha * dv;
    }
    if (alpha * dv.norm() <= 4 * std::numeric_limits<real>::epsilon() * (out.v.norm() + 1)) {
      // no further progress is possible at this precision
      if (m > 0) {
        alg.J_mul(out.v, vc);
        respond(vc, out.gamma);
      }
      out.iterations = it + 1;
      out.converged = true;
      out.status = ConvergenceStatus::Converged;
      break;
    }
    // the step no longer moves the solution: Stopped after the residual at the new iterate (whose
    // drift corrections may have changed) says whether it converged
    if (params.rel_step_tolerance > 0 && alpha * dv.norm() <= params.rel_step_tolerance * out.v.norm()) step_stalled = true;
  }
  return out;
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

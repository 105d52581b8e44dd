// Newton's method with exact line search for the convex implicit step (newton_solver.h).

#include "newton_solver.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace {

// Impulse gamma and curvature d(gamma)/d(-vc) of row i at constraint velocity vc.
inline void row_response(const ConstraintRows& rows, int i, real vc, real& gamma, real& curvature) {
  const real R = rows.R[i];
  if (rows.kind[i] == RowKind::Unilateral) {
    const real y = (rows.vhat[i] - vc) / R;
    gamma = y > 0 ? y : 0;
    curvature = y > 0 ? 1 / R : 0;
  } else {
    const real y = -vc / R, b = rows.bound[i];
    gamma = std::clamp(y, -b, b);
    curvature = std::abs(y) < b ? 1 / R : 0;
  }
}

}  // namespace

ConvexResult solve_convex(const MatX& A, const Eigen::LLT<MatX>& A_llt, const VecX& r, const ConstraintRows& rows,
                          const SolverParams& params) {
  const int n = static_cast<int>(A.rows());
  const int m = rows.size();
  ConvexResult out;
  out.v = A_llt.solve(r);
  out.gamma.setZero(m);
  // diagonal scaling so that the stopping test is independent of units and masses
  const VecX D = A.diagonal().cwiseMax(real(1e-12)).cwiseSqrt().cwiseInverse();
  const real r_norm = (D.asDiagonal() * r).norm();

  VecX vc(m), curvature(m), grad(n), dv(n), dvc(m);
  MatX H(n, n);
  for (int it = 0; it <= params.max_newton_iterations; ++it) {
    if (m > 0) vc.noalias() = rows.J * out.v;
    for (int i = 0; i < m; ++i) row_response(rows, i, vc[i], out.gamma[i], curvature[i]);
    VecX jc = m > 0 ? VecX(rows.J.transpose() * out.gamma) : VecX::Zero(n);
    grad.noalias() = A * out.v - r - jc;
    out.residual = (D.asDiagonal() * grad).norm();
    out.iterations = it;
    const real scale = std::max(r_norm, (D.asDiagonal() * jc).norm());
    if (out.residual <= params.absolute_tolerance + params.relative_tolerance * scale) {
      out.converged = true;
      break;
    }
    if (it == params.max_newton_iterations) break;
    // Newton direction from the Hessian A + J^T diag(curvature) J
    H = A;
    if (m > 0) H.noalias() += rows.J.transpose() * curvature.asDiagonal() * rows.J;
    Eigen::LLT<MatX> llt(H);
    dv = -llt.solve(grad);
    if (m > 0) dvc.noalias() = rows.J * dv;
    // exact line search: the directional derivative phi'(alpha) is monotone and piecewise linear
    const real a0 = dv.dot(A * out.v - r);
    const real a1 = dv.dot(A * dv);
    auto dphi = [&](real alpha, real* ddphi) {
      real d = a0 + alpha * a1, dd = a1;
      for (int i = 0; i < m; ++i) {
        real g, c;
        row_response(rows, i, vc[i] + alpha * dvc[i], g, c);
        d -= dvc[i] * g;
        dd += dvc[i] * dvc[i] * c;
      }
      if (ddphi) *ddphi = dd;
      return d;
    };
    real alpha = 1;
    if (dphi(1, nullptr) > 0) {
      // safeguarded Newton on phi' over [lo, hi]
      real lo = 0, hi = 1;
      alpha = 1;
      for (int ls = 0; ls < params.max_line_search_iterations; ++ls) {
        real dd;
        const real d = dphi(alpha, &dd);
        if (std::abs(d) <= real(1e-12) * (std::abs(a0) + 1e-30)) break;
        (d > 0 ? hi : lo) = alpha;
        real next = dd > 0 ? alpha - d / dd : (lo + hi) / 2;
        if (!(next > lo && next < hi)) next = (lo + hi) / 2;
        if (hi - lo < real(1e-12)) break;
        alpha = next;
      }
    }
    out.v += alpha * dv;
    if (alpha * dv.norm() <= std::numeric_limits<real>::epsilon() * (out.v.norm() + 1)) {
      // no further progress possible at this precision
      if (m > 0) vc.noalias() = rows.J * out.v;
      for (int i = 0; i < m; ++i) row_response(rows, i, vc[i], out.gamma[i], curvature[i]);
      out.iterations = it + 1;
      out.converged = true;
      break;
    }
  }
  return out;
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

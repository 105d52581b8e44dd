// Newton's method with exact line search for the convex implicit step (newton_solver.h).

#include "solver/newton_solver.h"

#include "solver/newton_loop.h"
#include "multibody/body_jacobian.h"
#include "solver/sparse_newton_system.h"
#include "solver/step_settings.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <memory>

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

void block_response(const ConstraintBlock& b, const real* vc, real* gamma, real* G) {
  switch (b.kind) {
    case BlockKind::Unilateral: {
      const real y = (b.vhat - vc[0]) / b.R;
      gamma[0] = y > 0 ? y : 0;
      G[0] = y > 0 ? 1 / b.R : 0;
      return;
    }
    case BlockKind::Bounded: {
      const real y = (b.vhat - vc[0]) / b.R;
      gamma[0] = std::clamp(y, -b.bound, b.bound);
      G[0] = std::abs(y) < b.bound ? 1 / b.R : 0;
      return;
    }
    case BlockKind::FrictionalContact: {
      const real Rt = b.R, Rn = b.Rn, mu = b.bound;
      const real yt0 = -vc[0] / Rt, yt1 = -vc[1] / Rt, yn = (b.vhat - vc[2]) / Rn;
      const real yr = std::sqrt(yt0 * yt0 + yt1 * yt1);
      Eigen::Map<Eigen::Matrix<real, 3, 3>> Gm(G);
      if (yr <= mu * yn) {
        // stiction: inside the cone
        gamma[0] = yt0, gamma[1] = yt1, gamma[2] = yn;
        Gm.setZero();
        Gm(0, 0) = Gm(1, 1) = 1 / Rt;
        Gm(2, 2) = 1 / Rn;
        return;
      }
      const real mu_tilde = mu * Rt / Rn;
      if (yn + mu_tilde * yr <= 0) {
        // separation
        gamma[0] = gamma[1] = gamma[2] = 0;
        Gm.setZero();
        return;
      }
      // sliding: projection onto the cone's surface
      const real denom = 1 + mu * mu_tilde;
      const real gn = (yn + mu_tilde * yr) / denom;
      const Eigen::Matrix<real, 2, 1> t(yt0 / yr, yt1 / yr);
      gamma[0] = mu * gn * t[0], gamma[1] = mu * gn * t[1], gamma[2] = gn;
      Eigen::Matrix<real, 3, 3> dP;
      const Eigen::Matrix<real, 2, 2> ttT = t * t.transpose();
      dP.topLeftCorner<2, 2>() = (mu * mu_tilde / denom) * ttT + (mu * gn / yr) * (Eigen::Matrix<real, 2, 2>::Identity() - ttT);
      dP.topRightCorner<2, 1>() = (mu / denom) * t;
      dP.bottomLeftCorner<1, 2>() = (mu_tilde / denom) * t.transpose();
      dP(2, 2) = 1 / denom;
      const Eigen::Matrix<real, 3, 1> Rinv(1 / Rt, 1 / Rt, 1 / Rn);
      Eigen::Matrix<real, 3, 3> H = dP * Rinv.asDiagonal();
      Gm = (H + H.transpose()) / 2;
      return;
    }
  }
}

SparseMat constraint_hessian(const std::vector<ConstraintBlock>& blocks, const std::vector<Eigen::Matrix<real, 3, 3>>& G,
                             const SparseRowMat& J, const SparseMat& Jt) {
  // G as a sparse block-diagonal matrix
  std::vector<Eigen::Triplet<real>> entries;
  for (size_t k = 0; k < blocks.size(); ++k) {
    const int r0 = blocks[k].row, s = blocks[k].size();
    for (int i = 0; i < s; ++i)
      for (int j = 0; j < s; ++j)
        if (G[k](i, j) != 0) entries.emplace_back(r0 + i, r0 + j, G[k](i, j));
  }
  SparseMat Gs(J.rows(), J.rows());
  Gs.setFromTriplets(entries.begin(), entries.end());
  return Jt * Gs * J;
}

namespace {

// Dense linear algebra for the Newton loop: A and J as dense matrices, Cholesky of H.
class DenseAlgebra {
 public:
  // up to this many variables, the Hessian's constraint part is added block by block
  static constexpr int kSmallHessian = 24;

  DenseAlgebra(const MatX& A, const MatXR& J, NewtonScratch& w)
      : A_(A), J_(J), H_(w.H), J_active_(w.J_active), GJ_(w.GJ), llt_(w.llt) {}
  int n() const { return static_cast<int>(A_.rows()); }
  int m() const { return static_cast<int>(J_.rows()); }
  void diagonal(VecX& out) const { out = A_.diagonal(); }
  // products: up to kSmallHessian variables in plain loops on A's and J's storage (Eigen's
  // kernels for dynamic sizes cost more to set up than they save at these sizes)
  void A_mul(const VecX& x, VecX& out) const {
    const int n = this->n();
    if (n > kSmallHessian) {
      out.noalias() = A_ * x;
      return;
    }
    // A column-major: out += A(:, c) x_c
    out.setZero(n);
    const real* A = A_.data();
    for (int c = 0; c < n; ++c) {
      const real x_c = x[c];
      for (int r = 0; r < n; ++r) out[r] += A[r + n * c] * x_c;
    }
  }
  void J_mul(const VecX& x, VecX& out) const {
    const int n = this->n(), m = this->m();
    if (n > kSmallHessian) {
      out.noalias() = J_ * x;
      return;
    }
    // J row-major: out_i = J(i, :) . x
    out.resize(m);
    const real* J = J_.data();
    for (int i = 0; i < m; ++i) {
      real sum = 0;
      for (int c = 0; c < n; ++c) sum += J[n * i + c] * x[c];
      out[i] = sum;
    }
  }
  void Jt_mul(const VecX& y, VecX& out) const {
    const int n = this->n(), m = this->m();
    if (n > kSmallHessian) {
      out.noalias() = J_.transpose() * y;
      return;
    }
    // out += J(i, :)^T y_i
    out.setZero(n);
    const real* J = J_.data();
    for (int i = 0; i < m; ++i) {
      const real y_i = y[i];
      if (y_i == 0) continue;
      for (int c = 0; c < n; ++c) out[c] += J[n * i + c] * y_i;
    }
  }
  // factors H = A + J^T G J (G block diagonal, of the given blocks)
  bool smooth() const { return false; }
  void add_smooth_gradient(const VecX&, VecX&) const {}
  real smooth_curvature(const VecX&) const { return 0; }
  void factor(const std::vector<ConstraintBlock>& blocks, const std::vector<Eigen::Matrix<real, 3, 3>>& G, const VecX&) {
    H_ = A_;
    // only the blocks with a non-zero G (the active ones: speculative contacts that stay apart
    // are often most rows) add to H
    auto active = [&](size_t k) {
      const int s = blocks[k].size();
      return !(G[k].topLeftCorner(s, s).array() == 0).all();
    };
    const int n = this->n();
    if (n <= kSmallHessian) {
      // small problems: each active block's J_b^T (G_b J_b) straight into H's lower triangle
      // (a blocked matrix product costs more in packing than it saves at these sizes)
      GJ_.resize(3, n);
      for (size_t k = 0; k < blocks.size(); ++k) {
        if (!active(k)) continue;
        const int r0 = blocks[k].row, s = blocks[k].size();
        // a contact on a free body alone (the commonest island): at fixed size, both triangles
        if (n == 6 && s == 3) {
          const Eigen::Map<const Eigen::Matrix<real, 3, 6, Eigen::RowMajor>> J_k(J_.row(r0).data());
          Eigen::Map<Mat6>(H_.data()).noalias() += J_k.transpose() * (G[k] * J_k);
          continue;
        }
        GJ_.topRows(s).noalias() = G[k].topLeftCorner(s, s) * J_.middleRows(r0, s);
        // H(r, c) += sum_i J(r0 + i, r) (G J)(i, c) for r >= c; J's rows are contiguous
        for (int i = 0; i < s; ++i) {
          const real* J_i = J_.row(r0 + i).data();
          const real* GJ_i = GJ_.row(i).data();
          for (int c = 0; c < n; ++c) {
            const real g = GJ_i[c];
            if (g == 0) continue;
            real* H_c = H_.col(c).data();
            for (int r = c; r < n; ++r) H_c[r] += g * J_i[r];
          }
        }
      }
    } else {
      // larger ones: the active blocks' rows packed together, one matrix product
      int m_active = 0;
      for (size_t k = 0; k < blocks.size(); ++k)
        if (active(k)) m_active += blocks[k].size();
      if (m_active > 0) {
        J_active_.resize(m_active, n);
        GJ_.resize(m_active, n);
        int row = 0;
        for (size_t k = 0; k < blocks.size(); ++k) {
          if (!active(k)) continue;
          const int r0 = blocks[k].row, s = blocks[k].size();
          J_active_.middleRows(row, s) = J_.middleRows(r0, s);
          GJ_.middleRows(row, s).noalias() = G[k].topLeftCorner(s, s) * J_.middleRows(r0, s);
          row += s;
        }
        // the lower triangle only: the Cholesky factorization reads no other
        H_.triangularView<Eigen::Lower>() += J_active_.transpose() * GJ_;
      }
    }
    llt_.compute(H_);
  }
  void solve(const VecX& b, VecX& x) const {
    x = b;
    llt_.solve_in_place(x);
  }

 private:
  const MatX& A_;
  const MatXR& J_;
  MatX& H_;
  MatXR &J_active_, &GJ_;
  SmallLLT& llt_;
};

// Large rigid islands by bodies: A's blocks, J by bodies, H by blocks (sparse_newton_system.h).
class BodyBlockAlgebra {
 public:
  BodyBlockAlgebra(std::span<const MatX* const> A_blocks, const BodyJacobian& J, SparseNewtonSystem& system)
      : A_(A_blocks), J_(J), system_(system) {}
  int n() const { return J_.cols(); }
  int m() const { return J_.rows(); }
  void diagonal(VecX& out) const {
    out.resize(n());
    for (size_t b = 0; b < A_.size(); ++b) out.segment(J_.body_start(b), A_[b]->rows()) = A_[b]->diagonal();
  }
  void A_mul(const VecX& x, VecX& out) const {
    out.resize(n());
    for (size_t b = 0; b < A_.size(); ++b) {
      const int o = J_.body_start(b), nb = static_cast<int>(A_[b]->rows());
      // a free body's block at its fixed size
      if (nb == 6) {
        out.segment<6>(o).noalias() = Eigen::Map<const Mat6>(A_[b]->data()) * x.segment<6>(o);
      } else {
        out.segment(o, nb).noalias() = *A_[b] * x.segment(o, nb);
      }
    }
  }
  void J_mul(const VecX& x, VecX& out) const { J_.multiply(x, out); }
  void Jt_mul(const VecX& y, VecX& out) const { J_.multiply_transposed(y, out); }
  bool smooth() const { return false; }
  void add_smooth_gradient(const VecX&, VecX&) const {}
  real smooth_curvature(const VecX&) const { return 0; }
  void factor(const std::vector<ConstraintBlock>&, const std::vector<Eigen::Matrix<real, 3, 3>>& G, const VecX&) {
    // the problem is given to the system when first needed: a solve that starts converged needs
    // no Newton matrix
    if (!prepared_) {
      system_.prepare(J_);
      for (size_t b = 0; b < A_.size(); ++b) system_.load_A(static_cast<int>(b), *A_[b]);
      prepared_ = true;
    }
    system_.factor(J_, G);
  }
  void solve(const VecX& b, VecX& x) const { system_.solve(b, x); }

 private:
  std::span<const MatX* const> A_;
  const BodyJacobian& J_;
  SparseNewtonSystem& system_;
  bool prepared_ = false;
};

}  // namespace

ConvexResult solve_convex(const MatX& A, const Eigen::LLT<MatX>& A_llt, const VecX& r, const ConstraintRows& rows,
                          const StepSettings& params) {
  NewtonScratch scratch;
  return solve_convex(A, r, rows, params, A_llt.solve(r), scratch);
}

ConvexResult& solve_convex(const MatX& A, const VecX& r, const ConstraintRows& rows, const StepSettings& params,
                           const VecX& v_start, NewtonScratch& scratch) {
  scratch.J = rows.J;
  return solve_convex(A, r, scratch.J, rows.blocks, params, v_start, scratch);
}

ConvexResult& solve_convex(const MatX& A, const VecX& r, const MatXR& J, const std::vector<ConstraintBlock>& blocks,
                           const StepSettings& params, const VecX& v_start, NewtonScratch& scratch) {
  DenseAlgebra alg(A, J, scratch);
  return newton(alg, r, blocks, params, v_start, scratch);
}

ConvexResult solve_convex(std::span<const MatX> A_blocks, const VecX& r, const BodyJacobian& J,
                          const std::vector<ConstraintBlock>& blocks, const StepSettings& params) {
  std::vector<const MatX*> A;
  VecX v_free(r.size());
  for (size_t b = 0; b < A_blocks.size(); ++b) {
    A.push_back(&A_blocks[b]);
    v_free.segment(J.body_start(static_cast<int>(b)), A_blocks[b].rows()) =
        A_blocks[b].llt().solve(r.segment(J.body_start(static_cast<int>(b)), A_blocks[b].rows()));
  }
  SparseNewtonSystem system;
  NewtonScratch scratch;
  return solve_convex(A, r, J, blocks, params, v_free, system, scratch);
}

ConvexResult& solve_convex(std::span<const MatX* const> A_blocks, const VecX& r, const BodyJacobian& J,
                           const std::vector<ConstraintBlock>& blocks, const StepSettings& params, const VecX& v_start,
                           SparseNewtonSystem& system, NewtonScratch& scratch) {
  BodyBlockAlgebra alg(A_blocks, J, system);
  return newton(alg, r, blocks, params, v_start, scratch);
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

// Newton systems of islands with soft bodies, by block elimination (soft_island_solver.h).

#include "soft/soft_island_solver.h"

#include <Eigen/Cholesky>

#include "solver/newton_loop.h"
#include "superdex/physics/error.h"
#include "solver/step_settings.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace {

class SoftAlgebra {
 public:
  SoftAlgebra(const MatX& A_rigid, const SparseRowMat& J, const std::vector<SoftStep*>& soft)
      : A_r_(A_rigid), J_(J), Jt_(J.transpose()), soft_(soft) {
    nr_ = static_cast<int>(A_r_.rows());
    n_ = nr_;
    for (SoftStep* s : soft_) {
      offset_.push_back(n_);
      n_ += s->size();
      K_.push_back(s->pattern.H);
      H_.push_back(s->pattern.H);
      B_.push_back(MatX::Zero(s->size(), nr_));
      B_factored_.push_back(MatX::Zero(s->size(), nr_));
    }
  }

  int n() const { return n_; }
  int m() const { return static_cast<int>(J_.rows()); }
  void diagonal(VecX& d) const {
    d.resize(n_);
    d.head(nr_) = A_r_.diagonal();
    for (size_t k = 0; k < soft_.size(); ++k) d.segment(offset_[k], soft_[k]->size()) = soft_[k]->A.diagonal();
  }
  void A_mul(const VecX& x, VecX& y) const {
    y.resize(n_);
    y.head(nr_).noalias() = A_r_ * x.head(nr_);
    for (size_t k = 0; k < soft_.size(); ++k)
      y.segment(offset_[k], soft_[k]->size()) = soft_[k]->A * x.segment(offset_[k], soft_[k]->size());
  }
  void J_mul(const VecX& x, VecX& out) const { out.noalias() = J_ * x; }
  void Jt_mul(const VecX& y, VecX& out) const { out.noalias() = Jt_ * y; }
  bool smooth() const { return true; }
  void add_smooth_gradient(const VecX& v, VecX& g) const {
    for (size_t k = 0; k < soft_.size(); ++k)
      soft_[k]->add_gradient(v.segment(offset_[k], soft_[k]->size()), g.segment(offset_[k], soft_[k]->size()));
  }
  real smooth_curvature(const VecX& dv) const {
    real c = 0;
    for (size_t k = 0; k < soft_.size(); ++k) {
      const auto d = dv.segment(offset_[k], soft_[k]->size());
      c += d.dot(K_[k] * d);
    }
    return c;
  }

  void factor(const std::vector<ConstraintBlock>& blocks, const std::vector<Eigen::Matrix<real, 3, 3>>& G, const VecX& v) {
    const SparseMat C = constraint_hessian(blocks, G, J_, Jt_);
    H_rr_ = A_r_;
    for (size_t k = 0; k < soft_.size(); ++k) {
      const SoftStep& s = *soft_[k];
      // the first iteration's Hessian is the one at the start of the step, already computed
      if (first_factor_) s.start_hessian(K_[k]);
      else s.hessian(v.segment(offset_[k], s.size()), K_[k]);
      // H_k = A_k + K_k: the same structure, so the values add up
      Eigen::Map<VecX>(H_[k].valuePtr(), H_[k].nonZeros()) =
          Eigen::Map<const VecX>(s.A.valuePtr(), s.A.nonZeros()) + Eigen::Map<const VecX>(K_[k].valuePtr(), K_[k].nonZeros());
      B_[k].setZero();
    }
    first_factor_ = false;
    // contact couplings: within a soft block (one node's 3 x 3 block, in the pattern), between a
    // soft block and the articulation DOFs, and among the articulation DOFs; the others (a
    // constraint between nodes of two soft bodies, or of one body's different elements) outside
    // the factored matrix, in E
    std::vector<Eigen::Triplet<real>> outside;
    for (int col = 0; col < n_; ++col) {
      const int kc = block_of(col);
      for (SparseMat::InnerIterator it(C, col); it; ++it) {
        const int row = static_cast<int>(it.row());
        const int kr = block_of(row);
        if (kc < 0 && kr < 0) {
          H_rr_(row, col) += it.value();
        } else if (kc >= 0 && kr < 0) {
          B_[kc](col - offset_[kc], row) += it.value();
        } else if (kc >= 0 && kr == kc) {
          const int slot = soft_[kc]->pattern.slot(row - offset_[kc], col - offset_[kc]);
          if (slot < 0) outside.emplace_back(row, col, it.value());
          else H_[kc].valuePtr()[slot] += it.value();
        } else if (kr >= 0 && kc >= 0) {
          outside.emplace_back(row, col, it.value());
        }
      }
    }
    coupled_ = !outside.empty();
    if (coupled_) {
      E_.resize(n_, n_);
      E_.setFromTriplets(outside.begin(), outside.end());
    }
    // after the first factorization of the solve, the matrix is solved by conjugate gradients
    // preconditioned by that factorization (solve()), and factored again only when they do not
    // converge in a few iterations
    if (factored_) {
      current_ = false;
      return;
    }
    factor_current();
  }

  void solve(const VecX& b, VecX& x) {
    if (coupled_) {
      // the factored matrix lacks E: conjugate gradients on the whole one, preconditioned by it
      // (E's rank is three per coupling constraint: a few iterations more), refactored once if
      // they stall; their last iterate otherwise (an inexact Newton direction)
      if (conjugate_gradients(b, x, kCoupledCgIterations) || current_) return;
      factor_current();
      conjugate_gradients(b, x, kCoupledCgIterations);
      return;
    }
    if (current_ || !conjugate_gradients(b, x, kCgIterations)) {
      if (!current_) factor_current();
      precondition(b, x);
    }
  }

 private:
  // Numeric factorization of each soft block of the current matrix on its cached symbolic
  // analysis, then the Schur complement S = H_rr - sum B_k^T H_k^-1 B_k of the articulation DOFs.
  void factor_current() {
    MatX S = H_rr_;
    for (size_t k = 0; k < soft_.size(); ++k) {
      const SparseCholesky& chol = soft_[k]->body.pattern->cholesky;
      if (!soft_[k]->body.pattern->cholesky.factorize(H_[k]))
        throw Error("soft actor '" + soft_[k]->body.model.name + "': the Newton system could not be factored");
      B_factored_[k] = B_[k];
      if (nr_ > 0) S.noalias() -= B_factored_[k].transpose() * chol.solve(B_factored_[k]);
    }
    if (nr_ > 0) S_llt_.compute(S);
    factored_ = current_ = true;
  }

  // x = M^-1 b with M the last factored matrix, by block elimination.
  void precondition(const VecX& b, VecX& x) const {
    x.resize(n_);
    if (nr_ > 0) {
      VecX br = b.head(nr_);
      for (size_t k = 0; k < soft_.size(); ++k)
        br.noalias() -= B_factored_[k].transpose() * soft_[k]->body.pattern->cholesky.solve(VecX(b.segment(offset_[k], soft_[k]->size())));
      x.head(nr_) = S_llt_.solve(br);
    }
    for (size_t k = 0; k < soft_.size(); ++k) {
      VecX bk = b.segment(offset_[k], soft_[k]->size());
      if (nr_ > 0) bk.noalias() -= B_factored_[k] * x.head(nr_);
      x.segment(offset_[k], soft_[k]->size()) = soft_[k]->body.pattern->cholesky.solve(bk);
    }
  }

  // y = H x with the current matrix.
  void multiply(const VecX& x, VecX& y) const {
    y.resize(n_);
    if (nr_ > 0) y.head(nr_).noalias() = H_rr_ * x.head(nr_);
    for (size_t k = 0; k < soft_.size(); ++k) {
      auto yk = y.segment(offset_[k], soft_[k]->size());
      yk.noalias() = H_[k] * x.segment(offset_[k], soft_[k]->size());
      if (nr_ > 0) {
        yk.noalias() += B_[k] * x.head(nr_);
        y.head(nr_).noalias() += B_[k].transpose() * x.segment(offset_[k], soft_[k]->size());
      }
    }
    if (coupled_) y.noalias() += E_ * x;
  }

  // Preconditioned conjugate gradients on H x = b; false when the residual is not below
  // kCgTolerance |b| within max_iterations.
  bool conjugate_gradients(const VecX& b, VecX& x, int max_iterations) {
    const real target = kCgTolerance * b.norm();
    x.setZero(n_);
    VecX r = b, z, p, q;
    precondition(r, z);
    p = z;
    real rz = r.dot(z);
    for (int i = 0; i < max_iterations; ++i) {
      multiply(p, q);
      const real pq = p.dot(q);
      if (!(pq > 0)) return false;
      const real alpha = rz / pq;
      x.noalias() += alpha * p;
      r.noalias() -= alpha * q;
      if (r.norm() <= target) return true;
      precondition(r, z);
      const real rz_next = r.dot(z);
      p = z + (rz_next / rz) * p;
      rz = rz_next;
    }
    return false;
  }

  // past a dozen iterations the matrix has moved too far from the factored one, and factoring it
  // is the cheaper way on; the tolerance is the Newton loop's default relative one, so that an
  // inexact direction costs no extra Newton iteration (the pressed duck and the soft blocks take
  // as many iterations as with direct solves, or fewer)
  static constexpr int kCgIterations = 12;
  static constexpr int kCoupledCgIterations = 100;
  static constexpr real kCgTolerance = kUsesDoublePrecision ? real(1e-8) : real(1e-5);

  // soft block of variable i, or -1 for an articulation DOF
  int block_of(int i) const {
    if (i < nr_) return -1;
    int k = static_cast<int>(offset_.size()) - 1;
    while (offset_[k] > i) --k;
    return k;
  }

  const MatX& A_r_;
  const SparseRowMat& J_;
  SparseMat Jt_;
  const std::vector<SoftStep*>& soft_;
  int nr_ = 0, n_ = 0;
  std::vector<int> offset_;
  std::vector<SparseMat> K_, H_;  // elastic Hessians and Newton blocks, per soft body
  MatX H_rr_;                     // the Newton matrix's articulation block
  std::vector<MatX> B_;           // couplings soft block x articulation DOFs
  std::vector<MatX> B_factored_;  // the couplings of the last factored matrix
  Eigen::LLT<MatX> S_llt_;        // its Schur complement
  bool first_factor_ = true;
  bool factored_ = false;         // a matrix of this solve has been factored
  bool current_ = false;          // and it is the current one
  bool coupled_ = false;          // the current matrix has couplings outside the factored one
  SparseMat E_;                   // those couplings (n x n)
};

}  // namespace

ConvexResult& solve_convex_with_soft(const MatX& A_rigid, const VecX& r, const ConstraintRows& rows,
                                    const std::vector<SoftStep*>& soft, const VecX& v_start, const StepSettings& params,
                                    NewtonScratch& scratch) {
  SoftAlgebra alg(A_rigid, rows.J, soft);
  return newton(alg, r, rows.blocks, params, v_start, scratch);
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

// Newton systems of islands with soft bodies, by block elimination (soft_island_solver.h).

#include "soft_island_solver.h"

#include <Eigen/Cholesky>

#include "newton_loop.h"
#include "superdex/physics/error.h"

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
    }
  }

  int n() const { return n_; }
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

  void factor(const ConstraintRows& rows, const std::vector<Eigen::Matrix<real, 3, 3>>& G, const VecX& v) {
    const SparseMat C = constraint_hessian(rows, G, J_, Jt_);
    MatX H_rr = A_r_;
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
    // contact couplings: within a soft block (one node's 3 x 3 block, in the pattern), between a
    // soft block and the articulation DOFs, and among the articulation DOFs
    for (int col = 0; col < n_; ++col) {
      const int kc = block_of(col);
      for (SparseMat::InnerIterator it(C, col); it; ++it) {
        const int row = static_cast<int>(it.row());
        const int kr = block_of(row);
        if (kc < 0 && kr < 0) {
          H_rr(row, col) += it.value();
        } else if (kc >= 0 && kr < 0) {
          B_[kc](col - offset_[kc], row) += it.value();
        } else if (kc >= 0 && kr == kc) {
          const int slot = soft_[kc]->pattern.slot(row - offset_[kc], col - offset_[kc]);
          if (slot < 0) throw Error("soft actor '" + soft_[kc]->body.model.name + "': a contact couples nodes of different elements");
          H_[kc].valuePtr()[slot] += it.value();
        } else if (kr >= 0 && kc >= 0) {
          throw Error("soft actors '" + soft_[kr]->body.model.name + "' and '" + soft_[kc]->body.model.name +
                      "' are coupled directly; soft-soft contact is not supported");
        }
      }
    }
    // numeric factorization of each soft block on its cached symbolic analysis, then the Schur
    // complement S = H_rr - sum B_k^T H_k^-1 B_k of the articulation DOFs
    for (size_t k = 0; k < soft_.size(); ++k) {
      const SparseCholesky& chol = soft_[k]->body.pattern->cholesky;
      if (!soft_[k]->body.pattern->cholesky.factorize(H_[k]))
        throw Error("soft actor '" + soft_[k]->body.model.name + "': the Newton system could not be factored");
      if (nr_ > 0) H_rr.noalias() -= B_[k].transpose() * chol.solve(B_[k]);
    }
    if (nr_ > 0) S_llt_.compute(H_rr);
    first_factor_ = false;
  }

  void solve(const VecX& b, VecX& x) const {
    x.resize(n_);
    if (nr_ > 0) {
      VecX br = b.head(nr_);
      for (size_t k = 0; k < soft_.size(); ++k)
        br.noalias() -= B_[k].transpose() * soft_[k]->body.pattern->cholesky.solve(VecX(b.segment(offset_[k], soft_[k]->size())));
      x.head(nr_) = S_llt_.solve(br);
    }
    for (size_t k = 0; k < soft_.size(); ++k) {
      VecX bk = b.segment(offset_[k], soft_[k]->size());
      if (nr_ > 0) bk.noalias() -= B_[k] * x.head(nr_);
      x.segment(offset_[k], soft_[k]->size()) = soft_[k]->body.pattern->cholesky.solve(bk);
    }
  }

 private:
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
  std::vector<MatX> B_;           // couplings soft block x articulation DOFs
  Eigen::LLT<MatX> S_llt_;
  bool first_factor_ = true;
};

}  // namespace

ConvexResult& solve_convex_with_soft(const MatX& A_rigid, const VecX& r, const ConstraintRows& rows,
                                    const std::vector<SoftStep*>& soft, const VecX& v_start, const SolverParams& params,
                                    NewtonScratch& scratch) {
  SoftAlgebra alg(A_rigid, rows.J, soft);
  return newton(alg, r, rows, params, v_start, scratch);
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

#pragma once
// The Newton matrix H = A + J^T G J of a large rigid island (newton_solver.h) by bodies: A is
// block diagonal (one dense block per body), J is given by bodies (body_jacobian.h), and H has a
// dense block for each body and for each pair of bodies that a constraint block couples. The
// block Cholesky analysis of that pattern (block_cholesky.h) is kept from problem to problem as
// long as the bodies are the same and no new pair is coupled; each Newton iteration only adds
// the dense J_p^T G_b J_q of the blocks whose Hessian changed into their bodies' blocks of H and
// refactors numerically.

#include <utility>
#include <vector>

#include "linalg/block_cholesky.h"
#include "multibody/body_jacobian.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

class SparseNewtonSystem {
 public:
  // Takes a new problem: J's structure, then each body's block of A (load_A). Keeps the analysis
  // when J has the same bodies as the last problem and couples no pair of them that it did not
  // analyse (and still couples most of those it did); otherwise analyses J's pattern anew.
  void prepare(const BodyJacobian& J);
  // A's block of `body` (its DOFs square), for the problem prepared.
  void load_A(int body, const MatX& A_body);
  // Factors A + J^T G J for the blocks' Hessian blocks G (J as prepared, with the same values
  // until the next prepare()); false when the matrix is not positive definite.
  bool factor(const BodyJacobian& J, const std::vector<Eigen::Matrix<real, 3, 3>>& G);
  // x = H^-1 b with the last factorization.
  void solve(const VecX& b, VecX& x) const;
  // How many analyses of a pattern this system has made (the first problem's included).
  int analyses() const { return analyses_; }

 private:
  // the value offsets in H of every block's pieces and pairs of pieces
  void locate_blocks(const BodyJacobian& J);

  std::vector<int> body_dofs_;                 // the analysed bodies' DOFs
  std::vector<std::pair<int, int>> pairs_;     // the analysed body pairs (i > j), sorted
  std::vector<int> structure_, scratch_structure_;  // the last problem's J structure (and the one before)
  std::vector<std::pair<int, int>> scratch_pairs_;
  // per block: for each piece, its body's diagonal block in H, then for each pair of pieces
  // (p, q), p > q, the stored block (the later body in elimination order first) and whether
  // the pieces are taken in swapped order; from where_start_[k]
  struct Where {
    int value = 0;         // value offset of H's stored block
    bool swapped = false;  // the stored block is (body q, body p): M = J_q^T G J_p
  };
  std::vector<Where> where_;
  std::vector<int> where_start_;
  BlockCholesky H_;                  // H's values, and its factor
  std::vector<double> A_values_;     // A's blocks in H's value order (zero elsewhere)
  // the Hessian blocks H's values were last written with; none when loaded_ is false (a new
  // problem: H is written from A)
  std::vector<Eigen::Matrix3d> G_loaded_;
  bool loaded_ = false;
  int analyses_ = 0;
  Eigen::Matrix<double, 3, Eigen::Dynamic> GJ_;  // factor()'s dG_b J_q of a block's piece
  mutable Eigen::VectorXd x_;        // solve()'s right-hand side and solution
};

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

// Newton matrices of large rigid islands by bodies (sparse_newton_system.h).

#include "solver/sparse_newton_system.h"

#include <algorithm>

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace {

// J's structure as one integer list: the bodies' DOFs, then each block's rows and bodies.
void structure_of(const BodyJacobian& J, std::vector<int>& out) {
  out.clear();
  out.push_back(J.num_bodies());
  for (int b = 0; b < J.num_bodies(); ++b) out.push_back(J.body_dofs(b));
  for (int k = 0; k < J.num_blocks(); ++k) {
    out.push_back(J.block_size(k));
    out.push_back(static_cast<int>(J.pieces(k).size()));
    for (const BodyJacobian::Piece& p : J.pieces(k)) out.push_back(p.body);
  }
}

}  // namespace

void SparseNewtonSystem::prepare(const BodyJacobian& J) {
  loaded_ = false;
  structure_of(J, scratch_structure_);
  const bool same = scratch_structure_ == structure_;
  structure_.swap(scratch_structure_);
  if (same && analyses_ > 0) return;
  // the body pairs J couples, (later, earlier) in island order
  std::vector<std::pair<int, int>>& pairs = scratch_pairs_;
  pairs.clear();
  for (int k = 0; k < J.num_blocks(); ++k) {
    const auto pieces = J.pieces(k);
    for (size_t p = 0; p < pieces.size(); ++p)
      for (size_t q = 0; q < p; ++q)
        pairs.emplace_back(std::max(pieces[p].body, pieces[q].body), std::min(pieces[p].body, pieces[q].body));
  }
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  // the analysis holds if it has these bodies and a block of H for each pair; pairs analysed
  // but no longer coupled cost factorization work, so a pattern that has lost a quarter of its
  // pairs is analysed anew
  std::vector<int> dofs(J.num_bodies());
  for (int b = 0; b < J.num_bodies(); ++b) dofs[b] = J.body_dofs(b);
  const bool holds = analyses_ > 0 && dofs == body_dofs_ && std::includes(pairs_.begin(), pairs_.end(), pairs.begin(), pairs.end()) &&
                     4 * pairs.size() >= 3 * pairs_.size();
  if (!holds) {
    body_dofs_ = std::move(dofs);
    pairs_ = pairs;
    H_.analyze(body_dofs_, pairs_);
    A_values_.assign(H_.values().size(), 0.0);
    ++analyses_;
  }
  locate_blocks(J);
}

void SparseNewtonSystem::locate_blocks(const BodyJacobian& J) {
  where_.clear();
  where_start_.assign(1, 0);
  for (int k = 0; k < J.num_blocks(); ++k) {
    const auto pieces = J.pieces(k);
    for (const BodyJacobian::Piece& p : pieces) where_.push_back({H_.block_offset(p.body, p.body), false});
    for (size_t p = 0; p < pieces.size(); ++p)
      for (size_t q = 0; q < p; ++q) {
        const int a = pieces[p].body, b = pieces[q].body;
        const bool swapped = H_.eliminated_after(b, a);
        where_.push_back({swapped ? H_.block_offset(b, a) : H_.block_offset(a, b), swapped});
      }
    where_start_.push_back(static_cast<int>(where_.size()));
  }
}

void SparseNewtonSystem::load_A(int body, const MatX& A_body) {
  const int nb = body_dofs_[body];
  double* D = A_values_.data() + H_.block_offset(body, body);
  for (int c = 0; c < nb; ++c)
    for (int r = 0; r < nb; ++r) D[r + c * nb] = A_body(r, c);
}

void SparseNewtonSystem::solve(const VecX& b, VecX& x) const {
  x_ = b.cast<double>();
  H_.solve(x_.data(), x_.data());
  x = x_.cast<real>();
}

bool SparseNewtonSystem::factor(const BodyJacobian& J, const std::vector<Eigen::Matrix<real, 3, 3>>& G) {
  std::vector<double>& values = H_.values();
  // the first factorization of a problem writes A + J^T G J; the next ones of the same problem
  // (Newton iterations) add J_b^T (G_b - G_b') J_b only for the blocks whose Hessian block
  // changed since (most do not: sticking and separated contacts)
  if (!loaded_ || G_loaded_.size() != G.size()) {
    std::copy(A_values_.begin(), A_values_.end(), values.begin());
    G_loaded_.assign(G.size(), Eigen::Matrix3d::Zero());
    loaded_ = true;
  }
  const real* J_values = J.values();
  Eigen::Matrix<double, 3, Eigen::Dynamic>& GJ = GJ_;
  for (int k = 0; k < J.num_blocks(); ++k) {
    const int s = J.block_size(k);
    // the block's s x s Hessian (a 1-row block's G holds its entry alone, the others are not
    // written); the difference of two floats is exact in double, so the sums stay those of the
    // blocks' own
    Eigen::Matrix3d dG = Eigen::Matrix3d::Zero();
    for (int j = 0; j < s; ++j)
      for (int i = 0; i < s; ++i) dG(i, j) = static_cast<double>(G[k](i, j)) - G_loaded_[k](i, j);
    if (dG.isZero(0)) continue;
    for (int j = 0; j < s; ++j)
      for (int i = 0; i < s; ++i) G_loaded_[k](i, j) = G[k](i, j);
    const auto pieces = J.pieces(k);
    const Where* where = where_.data() + where_start_[k];
    // M = J_a^T dG J_b (columns of piece a against those of piece b) into H's block at `value`,
    // column-major with piece a's body's DOFs as rows; only the pieces' non-zero columns
    auto add = [&](const BodyJacobian::Piece& a, const BodyJacobian::Piece& b, int value) {
      const int na = J.body_dofs(a.body), nb = J.body_dofs(b.body);
      const int ca = a.num_cols, cb = b.num_cols;
      const real* Ja = J_values + a.value;  // s x ca, column-major
      const real* Jb = J_values + b.value;
      double* M = values.data() + value;
      // a contact between free bodies (the common case), at fixed sizes
      if (s == 3 && na == 6 && nb == 6 && ca == 6 && cb == 6) {
        const Eigen::Matrix<double, 3, 6> Ja_d = Eigen::Map<const Eigen::Matrix<real, 3, 6>>(Ja).template cast<double>();
        const Eigen::Matrix<double, 3, 6> GJb = dG * Eigen::Map<const Eigen::Matrix<real, 3, 6>>(Jb).template cast<double>();
        Eigen::Map<Eigen::Matrix<double, 6, 6>>(M).noalias() += Ja_d.transpose() * GJb;
        return;
      }
      const int* cols_a = J.columns(a);
      const int* cols_b = J.columns(b);
      GJ.resize(3, cb);
      for (int c = 0; c < cb; ++c)
        for (int i = 0; i < s; ++i) {
          double sum = 0;
          for (int j = 0; j < s; ++j) sum += dG(i, j) * Jb[c * s + j];
          GJ(i, c) = sum;
        }
      for (int c = 0; c < cb; ++c) {
        double* M_c = M + static_cast<ptrdiff_t>(cols_b[c]) * na;
        for (int r = 0; r < ca; ++r) {
          double sum = 0;
          for (int i = 0; i < s; ++i) sum += Ja[r * s + i] * GJ(i, c);
          M_c[cols_a[r]] += sum;
        }
      }
    };
    for (size_t p = 0; p < pieces.size(); ++p) add(pieces[p], pieces[p], where[p].value);
    const Where* pair = where + pieces.size();
    for (size_t p = 0; p < pieces.size(); ++p)
      for (size_t q = 0; q < p; ++q, ++pair) {
        if (pair->swapped) {
          add(pieces[q], pieces[p], pair->value);
        } else {
          add(pieces[p], pieces[q], pair->value);
        }
      }
  }
  return H_.factor();
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

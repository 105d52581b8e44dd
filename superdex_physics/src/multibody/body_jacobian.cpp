// The constraint Jacobian of a rigid island by bodies (body_jacobian.h).

#include "multibody/body_jacobian.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace {

// out(0..s) += P x(cols) for a piece P (s x nc, column-major) on the body's DOFs `cols` (all
// nc = nb of them, in order, when cols is null); S = s when known at compile time
template <int S>
void add_piece_product(const real* P, int s_, int nc, const int* cols, const real* x, real* out) {
  const int s = S > 0 ? S : s_;
  real sum[3] = {0, 0, 0};
  if (cols == nullptr) {
    for (int c = 0; c < nc; ++c)
      for (int i = 0; i < s; ++i) sum[i] += P[c * s + i] * x[c];
  } else {
    for (int c = 0; c < nc; ++c)
      for (int i = 0; i < s; ++i) sum[i] += P[c * s + i] * x[cols[c]];
  }
  for (int i = 0; i < s; ++i) out[i] += sum[i];
}

// out(cols) += P^T y
template <int S>
void add_piece_transposed_product(const real* P, int s_, int nc, const int* cols, const real* y, real* out) {
  const int s = S > 0 ? S : s_;
  for (int c = 0; c < nc; ++c) {
    real sum = 0;
    for (int i = 0; i < s; ++i) sum += P[c * s + i] * y[i];
    out[cols == nullptr ? c : cols[c]] += sum;
  }
}

}  // namespace

void BodyJacobian::reset(std::span<const int> body_dofs) {
  body_start_.assign(1, 0);
  for (int nb : body_dofs) body_start_.push_back(body_start_.back() + nb);
  block_row_.clear();
  piece_start_.assign(1, 0);
  pieces_.clear();
  values_.clear();
  columns_.clear();
  rows_ = 0;
  open_ = 0;
}

void BodyJacobian::begin_block(int s) {
  block_row_.push_back(rows_);
  open_ = s;
}

real* BodyJacobian::piece(int body) {
  const int nb = body_dofs(body);
  for (size_t p = piece_start_.back(); p < pieces_.size(); ++p)
    if (pieces_[p].body == body) return values_.data() + pieces_[p].value;
  const int value = static_cast<int>(values_.size());
  pieces_.push_back({body, value});
  values_.resize(values_.size() + static_cast<size_t>(open_ * nb), real(0));
  return values_.data() + value;
}

void BodyJacobian::end_block() {
  // the open block's pieces are the last values, one after the other: each is compacted to its
  // non-zero columns, moved down behind the one before
  const int s = open_;
  const size_t first = static_cast<size_t>(piece_start_.back());
  size_t write = first < pieces_.size() ? static_cast<size_t>(pieces_[first].value) : values_.size();
  for (size_t p = first; p < pieces_.size(); ++p) {
    Piece& piece = pieces_[p];
    const int nb = body_dofs(piece.body);
    const real* P = values_.data() + piece.value;
    piece.value = static_cast<int>(write);
    piece.col_start = static_cast<int>(columns_.size());
    for (int c = 0; c < nb; ++c) {
      bool zero = true;
      for (int i = 0; i < s; ++i) zero = zero && P[c * s + i] == 0;
      if (zero) continue;
      // write <= the column's own place: a forward copy never overwrites a column not yet read
      for (int i = 0; i < s; ++i) values_[write + i] = P[c * s + i];
      write += s;
      columns_.push_back(c);
    }
    piece.num_cols = static_cast<int>(columns_.size()) - piece.col_start;
  }
  values_.resize(write);
  piece_start_.push_back(static_cast<int>(pieces_.size()));
  rows_ += open_;
  open_ = 0;
}

void BodyJacobian::multiply(const VecX& x, VecX& out) const {
  out.setZero(rows_);
  for (int k = 0; k < num_blocks(); ++k) {
    const int s = block_size(k);
    real* out_k = out.data() + block_row_[k];
    for (const Piece& p : pieces(k)) {
      const real* P = values_.data() + p.value;
      const real* x_b = x.data() + body_start_[p.body];
      const int* cols = p.num_cols == body_dofs(p.body) ? nullptr : columns(p);
      if (s == 3) {
        add_piece_product<3>(P, 3, p.num_cols, cols, x_b, out_k);
      } else {
        add_piece_product<0>(P, s, p.num_cols, cols, x_b, out_k);
      }
    }
  }
}

void BodyJacobian::multiply_transposed(const VecX& y, VecX& out) const {
  out.setZero(cols());
  for (int k = 0; k < num_blocks(); ++k) {
    const int s = block_size(k);
    const real* y_k = y.data() + block_row_[k];
    for (const Piece& p : pieces(k)) {
      const real* P = values_.data() + p.value;
      real* out_b = out.data() + body_start_[p.body];
      const int* cols = p.num_cols == body_dofs(p.body) ? nullptr : columns(p);
      if (s == 3) {
        add_piece_transposed_product<3>(P, 3, p.num_cols, cols, y_k, out_b);
      } else {
        add_piece_transposed_product<0>(P, s, p.num_cols, cols, y_k, out_b);
      }
    }
  }
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

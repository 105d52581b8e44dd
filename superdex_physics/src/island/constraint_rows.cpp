// An island solve's constraint rows (island_stages.h): each row of the island's constraints in
// J on the DOFs of the links it joins, and its spring-damper block, regularised no less than a
// small fraction of the near-rigid compliance of its row (against ill-conditioning only).

#include <algorithm>

#include "island/island_jacobian.h"
#include "island/link_jacobians.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace {

// Adds one side's part g . V of the open row (V its link's spatial velocity, J_WL v), and returns
// its compliance g^T W_L g.
real add_side(const IslandInputs& in, IslandWorkspace& w, IslandJacobian& J, const ConstraintSide& side, const Vec6& g) {
  if (side.body < 0) return 0;
  const int nb = in.s.articulations[side.body]->model.nv;
  if (nb == 0) return 0;
  const IslandWorkspace::LinkJacobian& lj = link_compliance(in.s, side.body, side.link, in.terms[side.body].A_factor, w);
  real* P = J.form() == IslandJacobian::Form::Bodies ? J.piece(w.island_position[side.body]) : nullptr;
  const int o = w.body_offset[side.body];
  for (int k = 0; k < nb; ++k) {
    const real v = g.dot(lj.J_WL.col(k));
    if (P) {
      P[k] += v;
    } else {
      J.add_column(o + k, &v);
    }
  }
  return g.dot(lj.W_L * g);
}

}  // namespace

void add_constraint_rows(const IslandInputs& in, IslandWorkspace& w, IslandJacobian& J) {
  const real near_rigid = near_rigid_factor(in.params);
  for (int k : in.island.constraints) {
    const ConstraintTerms& t = in.constraints[k];
    for (const ConstraintRow& row : t.rows) {
      J.begin_block(1);
      const real compliance = add_side(in, w, J, t.a, row.g_a) + add_side(in, w, J, t.b, row.g_b);
      J.end_block();
      ConstraintBlock blk = row.block;
      blk.R = std::max(blk.R, real(1e-3) * near_rigid * compliance);
      blk.row = J.row++;
      w.rows.blocks.push_back(blk);
    }
  }
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

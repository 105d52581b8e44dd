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
  // a rod's element: its nodes' free DOFs, the row's angular part mapped through the element's
  // turning and its linear part shared by the segment's two ends (compliance: the two ends')
  if (side.soft >= 0 && side.element >= 0) {
    const SoftStep* st = in.soft_steps[side.soft].get();
    if (st == nullptr || w.soft_offset[side.soft] < 0) return 0;
    real compliance = 0;
    for (int k = 0; k < 3; ++k) {
      Vec3 c = side.omega_map[k].transpose() * g.tail<3>();
      if (k < 2) c += g.head<3>() / 2;
      for (int a = 0; a < 3; ++a) {
        const int f = st->pattern.free_of_dof[3 * side.element_nodes[k] + a];
        if (f < 0 || c[a] == 0) continue;
        J.add_column(w.soft_offset[side.soft] + f, &c[a]);
        // (the ghost's small mass stands for the element's spin only: left out of the floor)
        if (k < 2) compliance += c[a] * c[a] / st->mass[f];
      }
    }
    return compliance;
  }
  // a node of a full soft body: its free DOFs (compliance: their lumped masses)
  if (side.soft >= 0) {
    const SoftStep* st = in.soft_steps[side.soft].get();
    if (st == nullptr || w.soft_offset[side.soft] < 0) return 0;
    real compliance = 0;
    for (int a = 0; a < 3; ++a) {
      const int f = st->pattern.free_of_dof[3 * side.node + a];
      if (f < 0 || g[a] == 0) continue;
      J.add_column(w.soft_offset[side.soft] + f, &g[a]);
      compliance += g[a] * g[a] / st->mass[f];
    }
    return compliance;
  }
  if (side.body < 0) return 0;
  const int nb = in.s.articulations[side.body]->model.nv;
  if (nb == 0) return 0;
  // joint DOFs: g's entries on the velocities of DOFs dof, dof + 1, ... (compliance: the
  // diagonal of A^-1 there, coupling between them left out of this floor)
  if (side.dof >= 0) {
    real* P = J.form() == IslandJacobian::Form::Bodies ? J.piece(w.island_position[side.body]) : nullptr;
    const int o = w.body_offset[side.body];
    real compliance = 0;
    for (int i = 0; i < 6 && side.dof + i < nb; ++i) {
      if (g[i] == 0) continue;
      if (P) {
        P[side.dof + i] += g[i];
      } else {
        J.add_column(o + side.dof + i, &g[i]);
      }
      compliance += g[i] * g[i] * in.terms[side.body].inverse_diagonal(side.dof + i);
    }
    return compliance;
  }
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

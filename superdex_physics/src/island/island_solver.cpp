// One island's solve: its convex problem assembled and solved by stages (island_stages.h), again
// with the deferred rows and contacts its solution would make act.

#include "island/island_solver.h"

#include <algorithm>
#include <cmath>

#include "island/contact_rows.h"
#include "island/deferred_contacts.h"
#include "island/island_jacobian.h"
#include "island/island_stages.h"
#include "island/link_jacobians.h"
#include "soft/soft_island_solver.h"
#include "solver/sparse_newton_system.h"
#include "solver/step_settings.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

bool island_is_sparse(const SceneData& s, const Island& island, const StepSettings& params) {
  if (!island.soft_bodies.empty()) return false;
  int dofs = 0;
  for (int b : island.bodies) dofs += s.articulations[b]->model.nv;
  return dofs > params.dense_island_max_dofs;
}

namespace {

// the solve's start: the free motion A^-1 r, or, when bodies touch, their current velocities:
// resting and pressing contacts change little from one step to the next, and the problem is
// convex, so any start converges. A solve again with deferred rows or contacts admitted starts
// from the last solve's solution (`previous`), which they mostly leave as it is.
void warm_start(const IslandInputs& in, const IslandLayout& layout, const IslandSolution* previous, IslandWorkspace& w) {
  const SceneData& s = in.s;
  if (previous != nullptr && w.soft.empty() && w.reduced.empty()) {
    for (size_t j = 0; j < in.island.bodies.size(); ++j)
      w.v_start.segment(w.body_offset[in.island.bodies[j]], previous->v[j].size()) = previous->v[j];
    return;
  }
  if (layout.num_contacts == 0) return;
  for (int b : in.island.bodies) w.v_start.segment(w.body_offset[b], s.articulations[b]->model.nv) = s.articulations[b]->state.v;
  // a reduced body: its modes' velocities, and contact nodes that keep their residual
  for (const ReducedVariables& rv : w.reduced) {
    w.v_start.segment(rv.offset, rv.A_q.size()) = s.soft_bodies[rv.soft]->state.qd;
    w.v_start.segment(rv.offset + rv.A_q.size(), rv.size() - rv.A_q.size()).setZero();
  }
}

// the convex problem's solution, dense, sparse, or with soft bodies by block elimination; every
// path leaves it in w.newton.result
const ConvexResult& solve_problem(const IslandInputs& in, bool sparse, SparseNewtonSystem* system, IslandWorkspace& w) {
  if (sparse) {
    w.A_blocks.clear();
    for (int b : in.island.bodies) w.A_blocks.push_back(&in.terms[b].A);
  }
  return !w.soft.empty() ? solve_convex_with_soft(w.A, w.r, w.rows, w.soft, w.v_start, in.params, w.newton)
         : sparse        ? solve_convex(w.A_blocks, w.r, w.J_bodies, w.rows.blocks, in.params, w.v_start, *system, w.newton)
                         : solve_convex(w.A, w.r, w.J_dense, w.rows.blocks, in.params, w.v_start, w.newton);
}

// One solve of the island, with or without the deferred joint-limit rows, with the rigid contacts
// w.contact_takes_part flags and the deferred soft contacts `admitted` flags (per island soft
// contact); `out` holds the last solve's solution when `again`.
void solve_island_once(const IslandInputs& in, bool include_deferred, const std::vector<char>& admitted, bool again, IslandWorkspace& w,
                       SparseNewtonSystem* system, IslandSolution& out) {
  const IslandLayout layout = lay_out_variables(in, include_deferred, admitted, w);
  // small islands: dense algebra; large ones: sparse, on a pattern kept from step to step
  const bool sparse = island_is_sparse(in.s, in.island, in.params);
  assemble_momentum(in, layout, sparse, w);
  IslandJacobian J(in, layout, sparse, w);
  add_joint_rows(in, w, J);
  ContactRows contact_rows(in, w, J);
  contact_rows.add_rigid();
  contact_rows.add_soft();
  add_constraint_rows(in, w, J);
  J.finish(layout.n, w.rows.J);
  warm_start(in, layout, again ? &out : nullptr, w);
  const ConvexResult& sol = solve_problem(in, sparse, system, w);
  pack_solution(in, layout, sol, w, out);
}

// Whether the island's solution `v` (per body) would make a deferred joint-limit row act.
bool violates_deferred_rows(const Island& island, const std::vector<ArticulationTerms>& terms, const std::vector<VecX>& v) {
  for (size_t j = 0; j < island.bodies.size(); ++j)
    for (const JointRow& row : terms[island.bodies[j]].joint_rows)
      if (row.deferred && (row.J.size() > 0 ? row.J.dot(v[j]) : row.sign * v[j][row.dof]) < row.block.vhat) return true;
  return false;
}

}  // namespace

void solve_island(const SceneData& s, const Island& island, const std::vector<ArticulationTerms>& terms,
                  const std::vector<Contact>& contacts, const std::vector<SoftContact>& soft_contacts,
                  const std::vector<ConstraintTerms>& constraints, const std::vector<std::unique_ptr<SoftStep>>& soft_steps, real dt, const StepSettings& params,
                  IslandWorkspace& w, SparseNewtonSystem* system, IslandSolution& out) {
  const Ticks t0 = ticks_now();
  const IslandInputs in{s, island, terms, contacts, soft_contacts, soft_steps, constraints, dt, params};
  // the links' Jacobians and compliances serve every solve of the island below
  reset_link_jacobians(s, island, w);
  select_rigid_contacts(in, w);
  std::vector<char>& admitted = w.admitted_soft_contacts;
  admitted.assign(island.soft_contacts.size(), 0);
  solve_island_once(in, false, admitted, false, w, system, out);
  out.solves = 1;
  // a deferred limit row or contact is inactive at the solution unless it says otherwise: then
  // the same problem with every limit row and the contacts the solution would close, until no
  // other would (rare: the motion kept them far from acting)
  constexpr int kLastRound = 3;  // after which every deferred contact joins
  bool all_rows = false;
  for (int round = 0;; ++round) {
    const bool rows = !all_rows && violates_deferred_rows(island, terms, out.v);
    forget_link_velocities(LinkMotion::Solution, w);
    int closing = admit_closing_rigid_contacts(in, out, w);
    closing += admit_closing_soft_contacts(in, out, w, admitted);
    if (!rows && closing == 0) break;
    all_rows = all_rows || rows;
    if (round == kLastRound) {
      std::fill(admitted.begin(), admitted.end(), 1);
      std::fill(w.contact_takes_part.begin(), w.contact_takes_part.end(), 1);
      all_rows = true;
    }
    const int iterations = out.iterations;
    solve_island_once(in, all_rows, admitted, true, w, system, out);
    out.iterations += iterations;
    ++out.solves;
    if (round == kLastRound) break;
  }
  out.ticks = ticks_now() - t0;
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

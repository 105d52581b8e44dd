#pragma once
// The stages of one solve of an island, in the order solve_island_once runs them
// (island_solver.cpp): lay out the variables, assemble the momentum terms, write J's joint and
// contact rows (island_jacobian.h, contact_rows.h), warm start, solve, pack the solution. They
// share the island's working storage (IslandWorkspace), which each stage fills for the next.

#include <algorithm>
#include <memory>
#include <vector>

#include "constraint/constraint_terms.h"
#include "island/island_solver.h"
#include "solver/step_settings.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

class IslandJacobian;  // island_jacobian.h

// What one island's solve reads (solve_island's arguments).
struct IslandInputs {
  const SceneData& s;
  const Island& island;
  const std::vector<ArticulationTerms>& terms;  // per articulation
  const std::vector<Contact>& contacts;         // the scene's contact list
  const std::vector<SoftContact>& soft_contacts;
  const std::vector<std::unique_ptr<SoftStep>>& soft_steps;  // per soft body
  const std::vector<ConstraintTerms>& constraints;  // the scene's constraint list (Island::constraints index it)
  real dt;
  const StepSettings& params;
};

// The sizes of one solve's problem; the layout itself (variable offsets, the rows that take part)
// is in the workspace.
struct IslandLayout {
  int n = 0;             // variables
  int n_rigid = 0;       // of which the articulations' DOFs and the reduced soft bodies' variables (A's dense part)
  int joint_rows = 0;    // joint rows that take part (J's first rows)
  int num_contacts = 0;  // contacts that take part, rigid and soft (three rows each)
  int constraint_rows = 0;  // rows of the island's constraints (after the contacts')
};

// v <- n copies of `value`, inline (vector::assign calls out to a general routine, a dozen
// times per island)
inline void fill_to(std::vector<int>& v, size_t n, int value) {
  v.resize(n);
  std::fill(v.begin(), v.end(), value);
}


// The variables' offsets, and the joint rows and contacts that take part (island_layout.cpp):
// the rigid contacts w.contact_takes_part flags, the soft contacts not deferred or `admitted`.
IslandLayout lay_out_variables(const IslandInputs& in, bool include_deferred, const std::vector<char>& admitted,
                               IslandWorkspace& w);
// The momentum terms: A (its dense part), r, and the free motion v_start (island_momentum.cpp).
void assemble_momentum(const IslandInputs& in, const IslandLayout& layout, bool sparse, IslandWorkspace& w);
// J's joint rows, and their constraint blocks (joint_rows.cpp).
void add_joint_rows(const IslandInputs& in, IslandWorkspace& w, IslandJacobian& J);
// J's constraint rows after the contacts', and their blocks (constraint_rows.cpp).
void add_constraint_rows(const IslandInputs& in, IslandWorkspace& w, IslandJacobian& J);
// The solution's velocities, drive efforts, soft states and contact forces into `out` (island_solution.cpp).
void pack_solution(const IslandInputs& in, const IslandLayout& layout, const ConvexResult& sol, const IslandWorkspace& w,
                   IslandSolution& out);

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

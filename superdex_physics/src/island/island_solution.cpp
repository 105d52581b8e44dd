// An island solve's result (IslandSolution) from the convex problem's solution: the bodies' next
// velocities and drive efforts, the soft bodies' next velocities (and reduced states) and the
// contact forces.

#include "island/island_stages.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

void pack_solution(const IslandInputs& in, const IslandLayout& layout, const ConvexResult& sol, const IslandWorkspace& w,
                   IslandSolution& out) {
  const SceneData& s = in.s;
  const Island& island = in.island;
  const real dt = in.dt;
  const int joint_rows = layout.joint_rows;
  out.iterations = sol.iterations;
  out.residual = sol.residual;
  out.converged = sol.converged;
  out.status = sol.status;
  out.line_search_iterations = sol.line_search_iterations;
  out.active_rows = 0;
  for (int i = 0; i < joint_rows; ++i) out.active_rows += sol.gamma[i] != 0;
  // the result vectors keep their storage from the last step (the same island, mostly)
  out.v.resize(island.bodies.size());
  out.drive_efforts.resize(island.bodies.size());
  for (size_t j = 0; j < island.bodies.size(); ++j) {
    const int b = island.bodies[j], nb = s.articulations[b]->model.nv;
    out.v[j] = sol.v.segment(w.body_offset[b], nb);
    out.drive_efforts[j].setZero(nb);
  }
  // joint drive impulses back to efforts
  for (int k = 0; k < joint_rows; ++k) {
    const auto [j, i] = w.solved_joint_rows[k];
    const JointRow& jr = in.terms[island.bodies[j]].joint_rows[i];
    if (jr.drive) out.drive_efforts[j][jr.dof] += jr.sign * sol.gamma[k] / dt;
  }
  out.soft_v.resize(island.soft_bodies.size());
  out.soft_reduced.resize(island.soft_bodies.size());
  for (size_t j = 0; j < island.soft_bodies.size(); ++j) {
    const int k = island.soft_bodies[j];
    if (w.reduced_of[k] >= 0) {
      const ReducedVariables& rv = w.reduced[w.reduced_of[k]];
      reduced_next_state(*s.soft_bodies[k], rv, sol.v.segment(rv.offset, rv.size()), s.gravity, dt, out.soft_reduced[j]);
      out.soft_v[j] = out.soft_reduced[j].v;
    } else {
      out.soft_reduced[j].q.resize(0);
      out.soft_v[j] = in.soft_steps[k]->full_velocity(sol.v.segment(w.soft_offset[k], in.soft_steps[k]->size()));
    }
  }
  out.contact_force.clear();
  out.soft_contact_force.clear();
  // deferred contacts are inactive at the solution (island_solver.cpp): no force
  const size_t rigid = w.solved_contacts.size();
  out.contact_force.assign(island.contacts.size(), Vec3::Zero());
  for (size_t k = 0; k < rigid; ++k)
    out.contact_force[w.solved_contacts[k]] = w.frames[k] * sol.gamma.segment<3>(joint_rows + 3 * k) / dt;
  out.soft_contact_force.assign(island.soft_contacts.size(), Vec3::Zero());
  for (size_t k = rigid; k < w.frames.size(); ++k)
    out.soft_contact_force[w.solved_soft_contacts[k - rigid]] = w.frames[k] * sol.gamma.segment<3>(joint_rows + 3 * k) / dt;
  // constraint rows after the contacts': each row's force along its sides' rows
  out.constraint_force_a.assign(island.constraints.size(), Vec6::Zero());
  out.constraint_force_b.assign(island.constraints.size(), Vec6::Zero());
  int row = joint_rows + 3 * layout.num_contacts;
  for (size_t k = 0; k < island.constraints.size(); ++k) {
    for (const ConstraintRow& r : in.constraints[island.constraints[k]].rows) {
      const real force = sol.gamma[row++] / dt;
      out.constraint_force_a[k] += force * r.g_a;
      out.constraint_force_b[k] += force * r.g_b;
    }
  }
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

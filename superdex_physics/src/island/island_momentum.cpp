// The momentum terms of one island solve: the block-diagonal A (dense paths; the sparse path
// takes its bodies' blocks), r, and the free (unconstrained) motion v_start.

#include "island/island_stages.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

void assemble_momentum(const IslandInputs& in, const IslandLayout& layout, bool sparse, IslandWorkspace& w) {
  const SceneData& s = in.s;
  const real dt = in.dt;
  // A as a dense matrix (the sparse path builds its own from the bodies' blocks)
  MatX& A = w.A;
  VecX &r = w.r, &v_start = w.v_start;
  if (!sparse) A.setZero(layout.n_rigid, layout.n_rigid);
  r.resize(layout.n);
  v_start.resize(layout.n);
  for (int b : in.island.bodies) {
    const int o = w.body_offset[b], nb = s.articulations[b]->model.nv;
    if (!sparse) A.block(o, o, nb, nb) = in.terms[b].A;
    r.segment(o, nb) = in.terms[b].r;
    // velocities of the free (unconstrained) motion: the start of the Newton iteration, and the
    // reference of the near-rigid target compensation
    v_start.segment(o, nb) = in.terms[b].v_free;
  }
  // a reduced body: the modal block (diagonal) and the contact nodes' residual stiffness and
  // damping h G^-1; its free motion leaves the modes to themselves and relaxes the residual
  for (const ReducedVariables& rv : w.reduced) {
    const int o = rv.offset, nq = static_cast<int>(rv.A_q.size()), k3 = rv.size() - nq;
    A.diagonal().segment(o, nq) = rv.A_q;
    r.segment(o, nq) = rv.r_q;
    v_start.segment(o, nq) = rv.r_q.cwiseQuotient(rv.A_q);
    if (k3 == 0) continue;
    A.block(o + nq, o + nq, k3, k3) = rv.h * rv.G_inv;
    r.segment(o + nq, k3).noalias() = -dt * (rv.G_inv * rv.u_old);
    v_start.segment(o + nq, k3) = -(dt / rv.h) * rv.u_old;
  }
  for (int k : in.island.soft_bodies) {
    if (w.reduced_of[k] >= 0) continue;
    const SoftStep& st = *in.soft_steps[k];
    r.segment(w.soft_offset[k], st.size()) = st.r;
    v_start.segment(w.soft_offset[k], st.size()) = st.v0;
  }
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

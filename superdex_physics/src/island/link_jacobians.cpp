// The links' world Jacobians and compliances of an island solve (link_jacobians.h).

#include "island/link_jacobians.h"

#include "island/island_stages.h"
#include "multibody/kinematics.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

void reset_link_jacobians(int links, IslandWorkspace& w) {
  w.link_jacobians_used = 0;
  fill_to(w.link_slot, links, -1);
}

IslandWorkspace::LinkJacobian& cached_link_jacobian(const SceneData& s, int body, int link, IslandWorkspace& w) {
  // the link's slot, when its body is in the island (w.link_base)
  int* slot = w.link_base[body] >= 0 ? &w.link_slot[w.link_base[body] + link] : nullptr;
  if (slot && *slot >= 0) return w.link_jacobians[*slot];
  if (w.link_jacobians_used == w.link_jacobians.size()) w.link_jacobians.emplace_back();
  if (slot) *slot = static_cast<int>(w.link_jacobians_used);
  IslandWorkspace::LinkJacobian& added = w.link_jacobians[w.link_jacobians_used++];
  added.body = body;
  added.link = link;
  added.has_W_L = false;
  const Articulation& a = *s.articulations[body];
  link_jacobian_world(a.model, a.kin, link, added.J_WL);
  return added;
}

const IslandWorkspace::LinkJacobian& link_compliance(const SceneData& s, int body, int link, const SmallLLT& A_llt,
                                                     IslandWorkspace& w) {
  IslandWorkspace::LinkJacobian& lj = cached_link_jacobian(s, body, link, w);
  if (!lj.has_W_L) {
    w.L_inv_Jt = lj.J_WL.transpose();
    A_llt.solve_lower_in_place(w.L_inv_Jt);
    lj.W_L.noalias() = w.L_inv_Jt.transpose() * w.L_inv_Jt;
    lj.has_W_L = true;
  }
  return lj;
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

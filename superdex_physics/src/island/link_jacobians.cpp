// The links' world Jacobians and compliances of an island solve (link_jacobians.h).

#include "island/link_jacobians.h"

#include "island/island_stages.h"
#include "multibody/kinematics.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

void reset_link_jacobians(const SceneData& s, const Island& island, IslandWorkspace& w) {
  fill_to(w.link_base, s.articulations.size(), -1);
  int links = 0;
  for (int b : island.bodies) w.link_base[b] = links, links += s.articulations[b]->model.num_links;
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
  added.has_V = 0;
  const Articulation& a = *s.articulations[body];
  link_jacobian_world(a.model, a.kin, link, added.J_WL);
  return added;
}

const IslandWorkspace::LinkJacobian& link_compliance(const SceneData& s, int body, int link, const TreeLDLT& A_factor,
                                                     IslandWorkspace& w) {
  IslandWorkspace::LinkJacobian& lj = cached_link_jacobian(s, body, link, w);
  if (!lj.has_W_L) {
    w.H_Jt = lj.J_WL.transpose();
    A_factor.half_solve_in_place(w.H_Jt);
    lj.W_L.noalias() = w.H_Jt.transpose() * w.H_Jt;
    lj.has_W_L = true;
  }
  return lj;
}

Vec3 link_point_velocity(const SceneData& s, int body, int link, const Vec3& p_W, LinkMotion motion, const VecX& v_body,
                         IslandWorkspace& w) {
  const Articulation& a = *s.articulations[body];
  if (a.model.nv == 0) return Vec3::Zero();
  IslandWorkspace::LinkJacobian& lj = cached_link_jacobian(s, body, link, w);
  const int k = static_cast<int>(motion);
  if (!(lj.has_V & (1u << k))) {
    lj.V[k].noalias() = lj.J_WL * v_body;
    lj.has_V |= 1u << k;
  }
  const Vec6& V = lj.V[k];
  return V.head<3>() + V.tail<3>().cross(p_W - a.kin.X_WL[link].p);
}

Vec3 contact_point_velocity_a(const SceneData& s, const Contact& c, LinkMotion motion, const VecX& v_body, IslandWorkspace& w) {
  if (c.skin_node < 0) return link_point_velocity(s, c.body_a, c.link_a, c.p_W, motion, v_body, w);
  const Articulation& a = *s.articulations[c.body_a];
  const ArticulationSkin& skin = *a.skin;
  Vec3 v = Vec3::Zero();
  for (int j = skin.first[c.skin_node]; j < skin.first[c.skin_node + 1]; ++j) {
    const SkinInfluence& f = skin.influences[j];
    const SpatialTransform& X = a.kin.X_WL[f.link];
    v += f.weight * link_point_velocity(s, c.body_a, f.link, X.R * f.p_L + X.p, motion, v_body, w);
  }
  return v;
}

void forget_link_velocities(LinkMotion motion, IslandWorkspace& w) {
  for (size_t i = 0; i < w.link_jacobians_used; ++i) w.link_jacobians[i].has_V &= ~(1u << static_cast<int>(motion));
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

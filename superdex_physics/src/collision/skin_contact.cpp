// Skin node contacts against the colliders of other actors (skin_contact.h).

#include "collision/skin_contact.h"

#include "collision/collision_geometry.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

void detect_skin_contacts(const SceneData& s, real margin, real dt, std::vector<Contact>& out) {
  for (size_t k = 0; k < s.articulations.size(); ++k) {
    const Articulation& owner = *s.articulations[k];
    if (!owner.skin) continue;
    const ArticulationSkin& skin = *owner.skin;
    // the nodes now, their bounds and how far the fastest can move within the step
    VecX x;
    skin_positions_world(skin, owner.kin.X_WL, x);
    Bounds bounds;
    real node_sweep = 0;
    for (int i = 0; i < skin.num_nodes(); ++i) {
      bounds.extend(x.segment<3>(3 * i));
      Vec3 v = Vec3::Zero();
      for (int j = skin.first[i]; j < skin.first[i + 1]; ++j) {
        const SkinInfluence& f = skin.influences[j];
        const Vec6& V = owner.kin.V_L[f.link];
        v += f.weight * (owner.kin.X_WL[f.link].R * (V.head<3>() + V.tail<3>().cross(f.p_L)));
      }
      node_sweep = std::max(node_sweep, dt * v.norm());
    }
    for (size_t b = 0; b < s.articulations.size(); ++b) {
      if (b == k) continue;  // a skin wraps its own links
      const Articulation& a = *s.articulations[b];
      for (const LinkCollider& col : a.model.colliders) {
        if (!layers_may_touch(s, skin.layer_index, col.layer)) continue;
        if (!actors_may_touch(s, owner.handle, owner.handle, a.link_handles[col.link], a.handle, true)) continue;
        const SpatialTransform X_WS = a.kin.X_WL[col.link] * col.X_LS;
        const real sweep = node_sweep + collider_sweep(a, col, dt);
        const real reach = margin + sweep;
        const ContactMaterial material = combine_materials(skin.material, col.material);
        auto add = [&](int i, const Vec3& n_W, real phi) {
          Contact c;
          c.body_a = static_cast<int>(k), c.link_a = skin.main_link[i], c.body_b = static_cast<int>(b), c.link_b = col.link;
          c.p_W = x.segment<3>(3 * i), c.n_W = n_W, c.phi = phi, c.material = material, c.skin_node = i;
          out.push_back(c);
        };
        if (const PlaneShape* half_space = std::get_if<PlaneShape>(&col.shape)) {
          const WorldPlane plane = world_plane(*half_space, X_WS);
          const Vec3 lowest = (plane.n.array() > 0).select(bounds.min, bounds.max);
          if (plane.n.dot(lowest) - plane.d >= reach) continue;
          for (int i = 0; i < skin.num_nodes(); ++i) {
            const real phi = plane.n.dot(x.segment<3>(3 * i)) - plane.d;
            if (phi < reach) add(i, plane.n, phi);
          }
          continue;
        }
        // a bounded collider's box grown by the reach: no node outside it can touch
        Bounds box = world_bounds(col.aabb_S, X_WS);
        box.min.array() -= reach;
        box.max.array() += reach;
        if (!box.overlaps(bounds)) continue;
        for (int i = 0; i < skin.num_nodes(); ++i) {
          const Vec3 p = x.segment<3>(3 * i);
          if (!(p.array() >= box.min.array()).all() || !(p.array() <= box.max.array()).all()) continue;
          Vec3 g_S;
          const real phi = shape_signed_distance(col.shape, X_WS.R.transpose() * (p - X_WS.p), &g_S);
          if (phi < reach) add(i, X_WS.R * g_S, phi);
        }
      }
    }
  }
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

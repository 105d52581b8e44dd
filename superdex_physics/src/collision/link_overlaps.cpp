// Link pairs of an articulation that interpenetrate at its default pose (link_overlaps.h): the
// model's colliders posed by forward kinematics, bounds first, then the narrow phase.

#include "superdex/physics/link_overlaps.h"

#include <algorithm>
#include <map>

#include "collision/collision_detection.h"
#include "multibody/kinematics.h"
#include "superdex/physics/error.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

std::vector<LinkOverlap> overlapping_link_pairs(const ArticulationDesc& desc, real tolerance, const std::string& source) {
  const ArticulationModel model = build_articulation_model(desc, source);
  const ArticulationState state = initial_state(model);
  ArticulationKinematics kin;
  update_kinematics(model, state, kin);
  const size_t n = model.colliders.size();
  std::vector<SpatialTransform> X_WS(n);
  std::vector<Bounds> box(n);
  for (size_t c = 0; c < n; ++c) {
    const LinkCollider& col = model.colliders[c];
    X_WS[c] = kin.X_WL[col.link] * col.X_LS;
    box[c] = world_bounds(col.aabb_S, X_WS[c]);
  }
  // deepest penetration per link pair
  std::map<std::pair<int, int>, real> depth;
  std::vector<ShapeContact> contacts;
  for (size_t i = 0; i < n; ++i)
    for (size_t j = i + 1; j < n; ++j) {
      const LinkCollider &a = model.colliders[i], &b = model.colliders[j];
      // pairs that touch: by default, or switched on by an override
      const std::pair<int, int> key(std::min(a.link, b.link), std::max(a.link, b.link));
      const auto override_it = model.contact_overrides.find(key);
      const bool touch = override_it != model.contact_overrides.end()
                             ? override_it->second
                             : link_pair_contact(model, a.link, b.link) == LinkPairContact::OnByDefault;
      if (!touch || a.link == b.link) continue;
      if (!link_moves(model, a.link) && !link_moves(model, b.link)) continue;
      if (!box[i].overlaps(box[j])) continue;
      contacts.clear();
      try {
        collide_shapes(a, X_WS[i], b, X_WS[j], 0, contacts);
      } catch (const Error&) {
        continue;  // an open mesh against another mesh: no distance to measure
      }
      real deepest = 0;
      for (const ShapeContact& c : contacts) deepest = std::max(deepest, -c.phi);
      if (deepest > tolerance) depth[key] = std::max(depth[key], deepest);
    }
  std::vector<LinkOverlap> out;
  for (const auto& [key, d] : depth) out.push_back({key.first, key.second, d});
  return out;
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

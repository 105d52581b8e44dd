// Broad phase (sweep and prune on world bounds along x), contact filters, and the loop that
// turns overlapping pairs into contacts.

#include <algorithm>
#include <array>
#include <cmath>

#include "collision/collision_detection.h"
#include "superdex/physics/engine.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

ContactMaterial combine_materials(const ContactMaterial& a, const ContactMaterial& b) {
  ContactMaterial m;
  m.friction = std::sqrt(a.friction * b.friction);
  // springs in series; a rigid side (0) leaves the other's stiffness
  if (a.stiffness > 0 && b.stiffness > 0) m.stiffness = a.stiffness * b.stiffness / (a.stiffness + b.stiffness);
  else m.stiffness = std::max(a.stiffness, b.stiffness);
  m.dissipation_time = std::max(a.dissipation_time, b.dissipation_time);
  return m;
}

Bounds world_bounds(const Bounds& local, const SpatialTransform& X) {
  // the posed centre, and the half extents through the rotation's absolute values
  const Vec3 centre = X.R * (real(0.5) * (local.min + local.max)) + X.p;
  const Vec3 half = X.R.cwiseAbs() * (real(0.5) * (local.max - local.min));
  Bounds out;
  out.min = centre - half;
  out.max = centre + half;
  return out;
}

namespace {

// Whether the actors' contact filter lets `colliding` (a link or actor, with its owner: its
// articulation, or itself) touch `collider` in that order: the rule set for the exact pair, else
// one set with IncludeNestedActors::Yes for an owner, else `fallback`.
bool direction_enabled(const SceneData& s, ActorHandle colliding, ActorHandle colliding_owner, ActorHandle collider,
                       ActorHandle collider_owner, bool fallback) {
  auto rule = [&](ActorHandle a, ActorHandle b, bool need_nested) -> int {
    auto it = s.actor_contact.find({a, b});
    if (it == s.actor_contact.end() || (need_nested && !it->second.nested)) return -1;
    return it->second.enabled ? 1 : 0;
  };
  int r = rule(colliding, collider, false);
  if (r < 0 && colliding_owner != colliding) r = rule(colliding_owner, collider, true);
  if (r < 0 && collider_owner != collider) r = rule(colliding, collider_owner, true);
  if (r < 0 && (colliding_owner != colliding || collider_owner != collider)) r = rule(colliding_owner, collider_owner, true);
  return r < 0 ? fallback : r == 1;
}

}  // namespace

bool actors_may_touch(const SceneData& s, ActorHandle a, ActorHandle a_owner, ActorHandle b, ActorHandle b_owner, bool fallback) {
  if (s.actor_contact.empty()) return fallback;
  return direction_enabled(s, a, a_owner, b, b_owner, fallback) || direction_enabled(s, b, b_owner, a, a_owner, fallback);
}

bool layers_may_touch(const SceneData& s, int a, int b) { return ((s.layer_masks[a] >> b) & 1) || ((s.layer_masks[b] >> a) & 1); }

real collider_sweep(const Articulation& a, const LinkCollider& col, real dt) {
  const Vec6& V = a.kin.V_L[col.link];
  if (std::holds_alternative<PlaneShape>(col.shape)) return dt * V.norm() * (a.model.nv > 0);
  // speed bound of the surface: origin speed plus angular speed times the farthest extent, the
  // bounds' corner farthest from the link origin (at o_S in the shape frame), axis by axis
  const Vec3 o_S = -(col.X_LS.R.transpose() * col.X_LS.p);
  const real reach = (col.aabb_S.min - o_S).cwiseAbs().cwiseMax((col.aabb_S.max - o_S).cwiseAbs()).norm();
  return dt * (V.head<3>().norm() + V.tail<3>().norm() * reach);
}

namespace {

ActorHandle link_actor(const Articulation& a, int link) { return a.link_handles[link]; }

// Whether two colliders may touch: not both immovable (welded to the world), layers, per-actor switches, and
// within one articulation the joined-links rule and its overrides.
bool pair_enabled(const SceneData& s, const Articulation& A, const LinkCollider& ca, const Articulation& B,
                  const LinkCollider& cb) {
  if (!link_moves(A.model, ca.link) && !link_moves(B.model, cb.link)) return false;
  if (!layers_may_touch(s, ca.layer, cb.layer)) return false;
  const ActorHandle la = link_actor(A, ca.link), lb = link_actor(B, cb.link);
  if (&A == &B) {
    const LinkPairContact rule = link_pair_contact(A.model, ca.link, cb.link);
    if (rule == LinkPairContact::Never) return false;
    const auto key = std::make_pair(std::min(ca.link, cb.link), std::max(ca.link, cb.link));
    auto it = A.model.contact_overrides.find(key);
    if (it != A.model.contact_overrides.end()) return it->second;
    // joined links do not touch unless the filter says so for these links
    return actors_may_touch(s, la, la, lb, lb, rule == LinkPairContact::OnByDefault);
  }
  return actors_may_touch(s, la, A.handle, lb, B.handle, true);
}

}  // namespace

ContactPairs find_contact_pairs(const SceneData& s, real margin, real dt) {
  ContactPairs out;
  find_contact_pairs(s, margin, dt, out);
  return out;
}

void find_contact_pairs(const SceneData& s, real margin, real dt, ContactPairs& out) {
  out.margin = margin;
  out.posed.clear();
  out.planes.clear();
  out.pairs.clear();
  std::vector<PosedCollider>& posed = out.posed;
  // posed colliders and their world bounds, grown by the margin
  for (size_t b = 0; b < s.articulations.size(); ++b) {
    const Articulation& a = *s.articulations[b];
    for (size_t c = 0; c < a.model.colliders.size(); ++c) {
      const LinkCollider& col = a.model.colliders[c];
      PosedCollider pc{static_cast<int>(b), static_cast<int>(c), col.link, a.kin.X_WL[col.link] * col.X_LS, {}, collider_sweep(a, col, dt)};
      if (std::holds_alternative<PlaneShape>(col.shape)) {
        out.planes.push_back(pc);
        continue;
      }
      pc.box = world_bounds(col.aabb_S, pc.X_WS);
      pc.box.min.array() -= margin + pc.sweep;
      pc.box.max.array() += margin + pc.sweep;
      posed.push_back(pc);
    }
  }
  // sweep and prune along x
  std::vector<int>& order = out.order;
  order.resize(posed.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
  std::sort(order.begin(), order.end(), [&](int i, int j) {
    if (posed[i].box.min.x() != posed[j].box.min.x()) return posed[i].box.min.x() < posed[j].box.min.x();
    return i < j;
  });
  for (size_t k = 0; k < order.size(); ++k) {
    const PosedCollider& p = posed[order[k]];
    for (size_t l = k + 1; l < order.size() && posed[order[l]].box.min.x() <= p.box.max.x(); ++l)
      if (p.box.overlaps(posed[order[l]].box)) out.pairs.emplace_back(std::min(order[k], order[l]), std::max(order[k], order[l]));
  }
  // with each plane, the colliders whose bounds reach below it (by the plane's own sweep)
  for (size_t pl = 0; pl < out.planes.size(); ++pl) {
    const PosedCollider& plane = out.planes[pl];
    const WorldPlane wp = world_plane(std::get<PlaneShape>(s.articulations[plane.body]->model.colliders[plane.collider].shape), plane.X_WS);
    for (size_t i = 0; i < posed.size(); ++i) {
      const Bounds& box = posed[i].box;
      const real lowest = wp.n.dot((box.min + box.max) / 2) - wp.n.cwiseAbs().dot((box.max - box.min) / 2) - wp.d;
      if (lowest > plane.sweep) continue;
      out.pairs.emplace_back(static_cast<int>(i), -1 - static_cast<int>(pl));
    }
  }
  // in the order of the contacts' links, so that the contact list comes out in that order; sorted
  // as keys that hold the links, which spares the comparisons the lookups
  std::vector<std::array<int, 6>>& keys = out.keys;
  keys.resize(out.pairs.size());
  for (size_t k = 0; k < keys.size(); ++k) {
    const auto [i, j] = out.pairs[k];
    const PosedCollider &a = posed[i], &b = j >= 0 ? posed[j] : out.planes[-1 - j];
    keys[k] = {a.body, a.link, b.body, b.link, i, j};
  }
  std::sort(keys.begin(), keys.end());
  for (size_t k = 0; k < keys.size(); ++k) out.pairs[k] = {keys[k][4], keys[k][5]};
}

void collide_pairs(const SceneData& s, const ContactPairs& pairs, size_t chunk, std::vector<Contact>& out) {
  // one pair's points, cleared before each pair; its capacity is kept per thread
  thread_local std::vector<ShapeContact> points;
  const size_t end = std::min(pairs.pairs.size(), (chunk + 1) * ContactPairs::kPairsPerChunk);
  for (size_t k = chunk * ContactPairs::kPairsPerChunk; k < end; ++k) {
    const auto [i, j] = pairs.pairs[k];
    const PosedCollider& pa = pairs.posed[i];
    const PosedCollider& pb = j >= 0 ? pairs.posed[j] : pairs.planes[-1 - j];
    const Articulation& A = *s.articulations[pa.body];
    const Articulation& B = *s.articulations[pb.body];
    const LinkCollider& ca = A.model.colliders[pa.collider];
    const LinkCollider& cb = B.model.colliders[pb.collider];
    if (!pair_enabled(s, A, ca, B, cb)) continue;
    const real gap = pairs.margin + pa.sweep + pb.sweep;
    // midphase: the shapes' own oriented boxes, tighter than their world bounds
    if (j >= 0 && boxes_apart(ca.aabb_S, pa.X_WS, cb.aabb_S, pb.X_WS, gap)) continue;
    points.clear();
    collide_shapes(ca, pa.X_WS, cb, pb.X_WS, gap, points);
    reduce_contacts(points, kMaxContactsPerPair);
    const ContactMaterial m = combine_materials(ca.material, cb.material);
    for (const ShapeContact& p : points) out.push_back({pa.body, ca.link, pb.body, cb.link, p.p_W, p.n_W, p.phi, m});
  }
}

std::vector<Contact> join_contacts(const std::vector<std::vector<Contact>>& chunks) {
  std::vector<Contact> contacts;
  join_contacts(chunks, contacts);
  return contacts;
}

void join_contacts(const std::vector<std::vector<Contact>>& chunks, std::vector<Contact>& contacts) {
  size_t total = 0;
  for (const auto& c : chunks) total += c.size();
  contacts.clear();
  contacts.reserve(total);
  for (const auto& c : chunks) contacts.insert(contacts.end(), c.begin(), c.end());
}

std::vector<Contact> detect_contacts(const SceneData& s, real margin, real dt) {
  const ContactPairs pairs = find_contact_pairs(s, margin, dt);
  std::vector<std::vector<Contact>> chunks(pairs.num_chunks());
  run_on_worker_threads(chunks.size(), [&](size_t c) { collide_pairs(s, pairs, c, chunks[c]); });
  return join_contacts(chunks);
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

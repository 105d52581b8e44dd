#pragma once
// Collision detection over a scene: world bounds of every collider, a sweep-and-prune broad
// phase, contact filters, and the narrow phase producing contact candidates (points with a
// normal and a signed distance) for the implicit solve.

#include <vector>

#include "scene_data.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

// A contact candidate between link `link_a` of body `body_a` and `link_b` of body `body_b`
// (bodies index SceneData::articulations). The normal points from b towards a.
struct Contact {
  int body_a = 0, link_a = 0, body_b = 0, link_b = 0;
  Vec3 p_W = Vec3::Zero();  // contact point (m), midway between the surfaces
  Vec3 n_W = Vec3::UnitZ(); // unit normal from b towards a
  real phi = 0;             // signed distance (m), negative when penetrating
  ContactMaterial material; // combined for the pair
};

// All contact candidates closer than `margin` (m) plus the distance the two shapes can close
// within `dt` at their current speeds (speculative contact), in a deterministic order.
std::vector<Contact> detect_contacts(const SceneData& scene, real margin, real dt);

// World bounds of local bounds posed by X.
Aabb world_bounds(const Aabb& local, const SpatialTransform& X);
// Whether contact between these two actors was switched off.
bool actor_pair_disabled(const SceneData& scene, ActorHandle x, ActorHandle y);
// How far a collider's surface can move within dt at its link's current velocity (m).
real collider_sweep(const Articulation& a, const LinkCollider& col, real dt);

// Contact parameters of a pair (see ContactMaterial).
ContactMaterial combine_materials(const ContactMaterial& a, const ContactMaterial& b);

// Narrow phase of one shape pair posed in the world: appends contacts (normal from b to a).
struct ContactPoint {
  Vec3 p_W, n_W;
  real phi;
};
void collide_shapes(const LinkCollider& a, const SpatialTransform& X_WA, const LinkCollider& b,
                    const SpatialTransform& X_WB, real margin, std::vector<ContactPoint>& out);

// Box-box manifold (collision_box_box.cpp); boxes centred on their frames.
void collide_box_box(const BoxShape& a, const SpatialTransform& X_WA, const BoxShape& b, const SpatialTransform& X_WB,
                     real margin, std::vector<ContactPoint>& out);

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

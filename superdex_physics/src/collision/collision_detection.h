#pragma once
// Collision detection over a scene: world bounds of every collider, a sweep-and-prune broad
// phase, contact filters, and the narrow phase producing contact candidates (points with a
// normal and a signed distance) for the implicit solve.

#include <array>
#include <limits>
#include <vector>

#include "scene/scene_data.h"
#include "shape/convex_faces.h"

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
  int skin_node = -1;       // >= 0: side a is this node of body_a's skin, moved by its links' weights
};

// A collider posed in the world for this step, with its world bounds grown by the margin and
// its sweep (planes have no bounds).
struct PosedCollider {
  int body = 0, collider = 0;  // SceneData::articulations index; index in its model's colliders
  int link = 0;                // the collider's link
  SpatialTransform X_WS;
  Bounds box;
  real sweep = 0;  // how far its surface can move within the step (m)
};

// The broad phase's result: the posed colliders and the candidate pairs (indices into `posed`;
// a negative second index -1 - k names planes[k]), ordered by the links of their contacts
// (body_a, link_a, body_b, link_b), then by their indices. The narrow phase runs on consecutive
// chunks of the pairs, which the worker threads can share; its contact list keeps that order.
struct ContactPairs {
  static constexpr size_t kPairsPerChunk = 16;
  std::vector<PosedCollider> posed, planes;
  std::vector<std::pair<int, int>> pairs;
  std::vector<int> order;  // the sweep's order of `posed` (working storage)
  std::vector<std::array<int, 6>> keys;  // the pairs' order (working storage)
  real margin = 0;  // contact margin (m)
  size_t num_chunks() const { return (pairs.size() + kPairsPerChunk - 1) / kPairsPerChunk; }
};

// Broad phase: colliders whose bounds, grown by `margin` (m) plus the distance they can move
// within `dt` at their current speeds (speculative contact), overlap; a collider is paired with
// each plane its grown bounds reach below (by the plane's own sweep). The narrow phase then skips
// the pairs whose shapes' oriented boxes stay apart by more than the margin (boxes_apart).
ContactPairs find_contact_pairs(const SceneData& scene, real margin, real dt);
// The same into `out`, whose vectors keep their storage.
void find_contact_pairs(const SceneData& scene, real margin, real dt, ContactPairs& out);
// Narrow phase of one chunk of the pairs: appends the chunk's contacts to `out`, in pair order.
void collide_pairs(const SceneData& scene, const ContactPairs& pairs, size_t chunk, std::vector<Contact>& out);
// The chunks' contacts joined in chunk order (the same list whatever the number of threads).
std::vector<Contact> join_contacts(const std::vector<std::vector<Contact>>& chunks);
void join_contacts(const std::vector<std::vector<Contact>>& chunks, std::vector<Contact>& out);
// All contact candidates (broad phase, then the narrow phase on the worker threads), in a
// deterministic order.
std::vector<Contact> detect_contacts(const SceneData& scene, real margin, real dt);

// World bounds of local bounds posed by X.
Bounds world_bounds(const Bounds& local, const SpatialTransform& X);
// Whether contact between these two actors was switched off.
// Whether the actor contact filter lets actors a and b touch (a and b links or actors, each with its
// owner: its articulation, or itself); `fallback` when no rule applies to them.
bool actors_may_touch(const SceneData& scene, ActorHandle a, ActorHandle a_owner, ActorHandle b, ActorHandle b_owner, bool fallback);
// Whether the layer filter lets colliders of layers a and b touch (in either order).
bool layers_may_touch(const SceneData& scene, int a, int b);
// How far a collider's surface can move within dt at its link's current velocity (m).
real collider_sweep(const Articulation& a, const LinkCollider& col, real dt);

// Contact parameters of a pair (see ContactMaterial).
ContactMaterial combine_materials(const ContactMaterial& a, const ContactMaterial& b);

// Narrow phase of one shape pair posed in the world: appends contacts (normal from b to a).
struct ShapeContact {
  Vec3 p_W, n_W;
  real phi;
};
void collide_shapes(const LinkCollider& a, const SpatialTransform& X_WA, const LinkCollider& b,
                    const SpatialTransform& X_WB, real margin, std::vector<ShapeContact>& out);

// At most `max_points` of a shape pair's contacts, spread over its contact patch (collision_reduce.cpp).
// More than 8 max_points, and more than kThinningThreshold, are first thinned to the deepest per
// cell of a 16^3 grid over the patch and direction of the normal (its dominant axis and sign)
// (fewer cost less to spread directly than to thin). Then the one farthest from the patch's centre, then repeatedly the one farthest from those kept
// (distance in position plus the patch's size times 1 - cos of the angle between normals), and the
// deepest; in their original order.
constexpr size_t kMaxContactsPerPair = 32;
constexpr size_t kThinningThreshold = 256;
void reduce_contacts(std::vector<ShapeContact>& points, size_t max_points);
// reduce_contacts on out[first, end).
void keep_at_most(std::vector<ShapeContact>& out, size_t first, size_t max_points);

// Contacts between two convex polyhedra (convex meshes, boxes) posed in the world
// (collision_convex.cpp): the deepest point from GJK/EPA and, where the normal is a face normal,
// the opposing face clipped against that face; at most kMaxConvexContacts (normal from b to a).
constexpr size_t kMaxConvexContacts = 4;
// The distance between two convex polyhedra posed in the world (gjk_distance.cpp), with the
// closest points on each; `overlap` when they intersect (then nothing else is set). When the
// distance is found to exceed `stop_beyond` (m), the search stops there: `beyond` is set,
// `distance` is a lower bound above stop_beyond and `normal` separates them (no closest points).
struct ConvexDistance {
  bool overlap = false;
  bool beyond = false;
  real distance = 0;  // m
  Vec3 p_a = Vec3::Zero(), p_b = Vec3::Zero();
  Vec3 normal = Vec3::UnitZ();  // unit, from b towards a
};
ConvexDistance convex_distance(const ConvexFaces& a, const SpatialTransform& X_WA, const ConvexFaces& b, const SpatialTransform& X_WB,
                               real stop_beyond = std::numeric_limits<real>::infinity());
void collide_convex_convex(const ConvexFaces& a, const SpatialTransform& X_WA, const ConvexFaces& b,
                           const SpatialTransform& X_WB, real margin, std::vector<ShapeContact>& out);

// Box-box manifold (collision_box_box.cpp); boxes centred on their frames.
void collide_box_box(const BoxShape& a, const SpatialTransform& X_WA, const BoxShape& b, const SpatialTransform& X_WB,
                     real margin, std::vector<ShapeContact>& out);

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

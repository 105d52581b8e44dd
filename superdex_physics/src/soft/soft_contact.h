#pragma once
// Contacts between soft bodies and the colliders of rigid bodies and articulation links (static
// or moving), both ways: each free surface node of a soft body against the collider's signed
// distance, and the collider's surface samples against the soft body's deformed surface
// triangles (a point on a triangle moves with its three nodes, by barycentric weights).

#include <array>
#include <vector>

#include "collision/collision_detection.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

struct SoftContact {
  int soft = 0;              // soft body index in the scene
  std::array<int, 3> nodes{-1, -1, -1};        // the soft side's nodes (-1: unused)
  std::array<real, 3> weights{1, 0, 0};         // their barycentric weights
  int body = 0, link = 0;    // the other side: articulation index and link
  Vec3 p_W = Vec3::Zero();   // contact point (m), world: the node, or the collider's sample
  Vec3 n_W = Vec3::UnitZ();  // unit normal from the collider towards the soft body
  real phi = 0;              // signed distance between the surfaces (m), negative when penetrating
  real sweep = 0;            // how far the two sides can move towards each other within the step (m)
  ContactMaterial material;  // combined for the pair
};

// All node-collider and sample-triangle pairs closer than `margin` (m) plus the distance they can close within `dt`
// at their current speeds, in a deterministic order.
std::vector<SoftContact> detect_soft_contacts(const SceneData& scene, real margin, real dt);

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

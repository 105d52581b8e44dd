#pragma once
// Contacts of articulation skins (articulation_skin.h): each skin node probes the colliders of
// the other actors (rigid bodies and other articulations' links) by their signed distance. The
// skin is colliding only: nothing probes it.

#include <vector>

#include "collision/collision_detection.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

// Appends to `out` every skin node closer than `margin` (m) plus the distance the two sides can
// close within `dt` to a collider allowed to touch it (layers, actor filter), in a deterministic
// order: side a the skinned articulation (link_a the node's link of largest weight, skin_node the
// node), side b the collider's link, the normal the collider's outward one.
void detect_skin_contacts(const SceneData& scene, real margin, real dt, std::vector<Contact>& out);

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

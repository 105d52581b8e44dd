#pragma once
// An articulation's poses apart from its state: DOF-sized poses (rotation vectors for spherical
// and free joints) from link frames and to them, and composed with DOF deltas
// (articulated_actor_api.cpp).

#include <span>
#include <vector>

#include "scene/scene_data.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

// The pose whose links best match world-from-link frames X_WL (one per link): each joint's
// motion from its parent's frame and its own, projected onto the joint's DOFs.
VecX pose_from_link_frames(const Articulation& a, std::span<const TransformRT> X_WL);

// pose (+) delta: a 3-D rotation's delta turns it in its child frame, exp(pose) exp(delta).
VecX pose_plus_delta(const ArticulationModel& m, const VecX& pose, const VecX& delta);

// World-from-link frames at `pose`, the articulation's base where it is now.
std::vector<Transform> link_frames_at(const Articulation& a, const VecX& pose);

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

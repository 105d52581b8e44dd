#pragma once
// The pose controller of an articulated actor as the scene keeps it (Articulation::
// pose_controller): the constraints it owns and the target they track, in both forms.

#include <optional>
#include <vector>

#include "superdex/physics/params/pose_controller_params.h"
#include "superdex/physics/transform.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

struct PoseController {
  std::vector<PoseConstraintInfo> info;  // link translations, link rotations, joints
  VecX target_pose;                      // DOF-sized (rotation vectors; rad, m)
  std::vector<Transform> target_links;   // world-from-link, per link
  // a target velocity (per DOF) to apply at the next step's start: the target's motion over
  // that step is then target (-) dt velocity to target
  std::optional<VecX> target_velocity;
};

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

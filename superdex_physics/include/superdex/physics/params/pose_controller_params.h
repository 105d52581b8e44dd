#pragma once
/// @file pose_controller_params.h
/// The pose controller of an articulated actor (Scene::add_pose_controller): per link, an
/// implicit spring-damper pulling the link's centre of mass to its target position
/// (link_pos_tracking), one turning the link to its target rotation (link_rot_tracking), and one
/// pulling the link's inbound joint to its target joint values (joint_tracking: revolute and
/// prismatic joints on their one DOF, spherical and free joints on their rotation; Hard joints
/// have none). Each is a scene constraint (constraint_params.h) the controller owns, solved in
/// the same convex problem as contacts. SI units; frames: W the world.

#include <vector>

#include "superdex/physics/handles.h"
#include "superdex/physics/real.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

/// One spring-damper of the controller: stiffness (N/m, or N m/rad on rotations), damping
/// (N s/m, or N m s/rad) and saturation (the per-component force cap, N or N m; negative: none;
/// never 0). Zero stiffness and damping: the entry does nothing.
struct PoseTrackingParams {
  real stiffness = 0;
  real damping = 0;
  real saturation = -1;
  bool operator==(const PoseTrackingParams&) const = default;
};

/// The controller's gains, each array indexed by link (entry i: link i, or link i's inbound
/// joint). An array may hold one entry per link, one entry (used for every link), or none (zero
/// gains everywhere).
struct PoseControllerParams {
  PoseControllerParams() = default;
  /// All three arrays with num_links default (zero-gain) entries.
  explicit PoseControllerParams(int num_links)
      : link_pos_tracking(num_links), link_rot_tracking(num_links), joint_tracking(num_links) {}
  std::vector<PoseTrackingParams> link_pos_tracking;
  std::vector<PoseTrackingParams> link_rot_tracking;
  std::vector<PoseTrackingParams> joint_tracking;
  bool operator==(const PoseControllerParams&) const = default;
};

/// What one of the controller's constraints tracks.
enum class PoseConstraintType { Joint = 0, LinkTranslation = 1, LinkRotation = 2, Invalid = 255 };

/// One of the controller's constraints: its handle, what it tracks, its link (a joint's: the
/// link the joint attaches) and that link's parent (-1 for the root).
struct PoseConstraintInfo {
  ConstraintHandle handle;
  PoseConstraintType type = PoseConstraintType::Invalid;
  int link = -1;
  int parent = -1;
  bool operator==(const PoseConstraintInfo&) const = default;
};

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

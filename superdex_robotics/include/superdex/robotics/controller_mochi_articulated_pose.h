#pragma once
/// @file controller_mochi_articulated_pose.h
/// MOCHI_ARTICULATED_POSE: the physics engine's own pose controller (physics
/// Scene::add_pose_controller, pose_controller_params.h) on a bot's articulation, aimed by a
/// target each time the script calls compute_output: world-from-root with either every link's
/// transform relative to its parent link, or the joint DOFs below the root. Its spring-dampers
/// are constraints solved inside the step, so it returns no efforts and takes no part in the
/// bot's pipeline. Its params round-trip through JSON (`.superdex_controller` files):
/// {"poseControllerParams": {"jointTracking": [{"stiffness", "damping", "saturation"}, ...],
/// "linkPosTracking": [...], "linkRotTracking": [...]}}.

#include <string>
#include <vector>

#include "superdex/physics/params/pose_controller_params.h"
#include "superdex/physics/transform.h"
#include "superdex/robotics/component.h"

namespace superdex::robotics {
inline namespace SUPERDEX_REAL_NAMESPACE {

struct ControllerMochiArticulatedPoseParams {
  physics::PoseControllerParams pose_controller_params;
  bool operator==(const ControllerMochiArticulatedPoseParams&) const = default;

  /// Reads the JSON above (absent arrays stay empty); throws superdex::Error naming `where`
  /// and the key.
  static ControllerMochiArticulatedPoseParams from_json_text(const std::string& text, const std::string& where);
  std::string to_json_text() const;
  static ControllerMochiArticulatedPoseParams load_from_file(const std::string& path);
  void save_to_file(const std::string& path) const;
};

/// What the controller observes: nothing (it is aimed by its target only).
struct ControllerMochiArticulatedPoseObsv {};

/// The pose to hold: give exactly one of local_to_parent_transforms (one per link: link i's
/// frame in its parent link's, the root's in world_from_root's) and pose_dofs (the DOFs of
/// every joint but the root's: rad, m; the root's DOFs come from world_from_root).
struct ControllerMochiArticulatedPoseTarget {
  physics::Transform world_from_root;
  std::vector<physics::Transform> local_to_parent_transforms;
  std::vector<real> pose_dofs;
};

/// The live MOCHI_ARTICULATED_POSE controller, as returned by a context's component lookup.
class ControllerMochiArticulatedPose : public Component {
 public:
  static constexpr const char* kTypeName = "MOCHI_ARTICULATED_POSE";
  virtual const ControllerMochiArticulatedPoseParams& params() const = 0;
  /// Keeps the params; once initialized, also sets the gains of the physics controller.
  virtual void set_params(const ControllerMochiArticulatedPoseParams& params) = 0;
  /// Adds the physics pose controller to the articulation (with the params set, else zero gains
  /// on every link's position and rotation); an existing one is replaced when remove_existing,
  /// else an error. Its target starts at the pose now.
  virtual void initialize(bool remove_existing) = 0;
  /// Aims the physics controller at `target` (the first aim after a reset starts at rest; later
  /// ones move over the next step). Returns nothing: the constraints act inside the step.
  virtual void compute_output(const ControllerMochiArticulatedPoseObsv& obsv, const ControllerMochiArticulatedPoseTarget& target) = 0;
};

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::robotics

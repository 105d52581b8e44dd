#pragma once
// Numerical fault detection for Scene::step (NumericalFaultPolicy in scene.h).
//
// The step computes every body's next state apart from the committed one, so the guard only has
// to look at the proposal before it is committed: an island whose solve produced a non-finite
// value or stopped unconverged is a fault. Under Raise the guard throws once it has seen every
// fault (the message lists them all), before anything is committed; under WarnAndClamp it edits
// the proposal so that a faulty body keeps its last good positions with zero velocity, and records
// the faults in SceneData::last_faults.

#include <vector>

#include "island/island_solver.h"
#include "scene/scene_data.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

class StepGuard {
 public:
  explicit StepGuard(SceneData& scene) : s_(scene) {}

  /// An island's solution: non-finite velocities or contact forces, or no convergence. Under
  /// WarnAndClamp the non-finite parts are replaced (zero velocities and forces); returns whether
  /// the solution was changed.
  bool check_island(const Island& island, IslandSolution& solution);
  /// Articulation b's next positions q and velocities v (after integration). Under WarnAndClamp
  /// non-finite ones are replaced (its last positions, zero velocities); returns whether they were.
  bool check_articulation(int b, VecX& q, VecX& v);
  /// Soft body k's next state.
  void check_soft(int k, SoftState& next);
  /// Throws superdex::Error listing the faults under Raise; records them under WarnAndClamp.
  void finish();

 private:
  void add(ActorHandle actor, const std::string& name, const std::string& quantity, const std::string& detail);
  bool clamp() const { return s_.fault_policy == NumericalFaultPolicy::WarnAndClamp; }

  SceneData& s_;
  std::vector<NumericalFault> faults_;
};

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

#pragma once
/// @file ik_solver.h
/// Inverse kinematics on a scene's articulations (SuperDex's experimental IK solver): position and
/// rotation targets on links are stiff constraints of the scene (constraint_params.h), and
/// solve() poses the articulations at the minimum of the energy of the scene's constraints,
/// 1/2 sum stiffness |deviation|^2 over their equality rows, by damped Gauss-Newton steps on the
/// joint DOFs with a backtracking line search, joint positions kept within their limits. The
/// solver is meant for a scene of its own (a kinematic twin of the simulated robot); it never
/// steps it. Units: m, rad; targets in the world frame W.

#include <map>

#include "superdex/physics/scene.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

struct IKSolverParams {
  int max_iter = 20;                             ///< Gauss-Newton iterations per solve
  VerbosityLevel verbosity = VerbosityLevel::Warning;  ///< Verbose logs each iteration's energy
  real abs_tol = real(1e-2);                     ///< stop once the energy's gradient is below (N m or N per DOF)
  real rel_tol = real(1e-8);                     ///< or once an iteration lowers the energy by less than this fraction
  real position_error_thres = real(1e-2);        ///< success: every position target within this (m)
  real rotation_error_thres = real(1e-2);        ///< and every rotation target within this (rad)
  int line_search_max_iter = 10;                 ///< halvings of a step that does not lower the energy
  double max_elapsed_time_seconds = 0;           ///< stop after this long (s); 0: no limit
  bool operator==(const IKSolverParams&) const = default;
};

class IKSolver {
 public:
  explicit IKSolver(Scene scene) : scene_(scene) {}
  Scene scene() const { return scene_; }
  void set_params(const IKSolverParams& params);
  const IKSolverParams& params() const { return params_; }
  /// Pulls the point local_position (link frame, m) of a link (or rigid) actor to
  /// target_position (world, m) with stiffness `weight` (N/m); replaces the link's previous one.
  /// The returned constraint's set_target_position moves it.
  ConstraintHandle create_position_target(ActorHandle link, const Vec3& local_position, const Vec3& target_position, real weight);
  void clear_position_target(ActorHandle link);
  /// Turns the link's frame rotated by local_rotation to the world rotation target_rotation
  /// (rotation vectors, rad) with stiffness `weight` (N m/rad); replaces the link's previous one.
  ConstraintHandle create_rotation_target(ActorHandle link, const Vec3& local_rotation, const Vec3& target_rotation, real weight);
  void clear_rotation_target(ActorHandle link);
  /// Poses the articulations (velocities zeroed) and shows the result in the debugger
  /// (Scene::update_debugger); true when every target is within its threshold. The scene's
  /// solver stats then describe the solve: its Gauss-Newton iterations, the final gradient norm
  /// as residual, Converged when the gradient fell below abs_tol or an iteration lowered the
  /// energy by no more than rel_tol of it, Stopped otherwise (iterations, time, line search).
  bool solve();

 private:
  Scene scene_;
  IKSolverParams params_;
  std::map<ActorHandle, ConstraintHandle> position_targets_, rotation_targets_;
};

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

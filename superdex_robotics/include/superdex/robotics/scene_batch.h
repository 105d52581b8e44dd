#pragma once
/// @file scene_batch.h
/// Batched stepping: many scenes built from one model (the same robot, the same props) stepped
/// in one call on the engine's worker threads (run_on_worker_threads), with the actions of every
/// scene in one row-major array and the observations written to another. No Python runs in the
/// call: actions become joint efforts or joint drive targets in C++.
///
/// Frames and units: W is the world (Z up); joint positions rad (m), velocities rad/s (m/s),
/// positions m, forces N.
///
/// One observation row (obs_size() = 2 n + 6, n = action_dofs.size()):
///   [ q (n) | v (n) | p_WE (3) | f_C_W (3) ]
/// q, v: the positions and velocities of the action DOFs; p_WE: the origin of the observed link
/// E in the world; f_C_W: the total contact force applied TO the contact actor C during the last
/// step, world frame (zero right after a reset, or when there is no contact actor).

#include <cstdint>
#include <memory>
#include <vector>

#include "superdex/physics/scene.h"

namespace superdex::robotics {
inline namespace SUPERDEX_REAL_NAMESPACE {

using physics::ActorHandle;
using physics::Scene;
using physics::real;

/// How one row of actions drives the action DOFs.
enum class BatchActionMode {
  /// a[j] is the velocity goal (rad/s) of DOF j's velocity servo: the VELOCITY_SERVO law (PI
  /// with profile acceleration and anti-windup, the seed's servo), run every physics step and
  /// applied as an external joint effort (N m).
  VelocityServo,
  /// a[j] is a joint velocity command (rad/s) tracked by an implicit joint drive: the drive's
  /// target position integrates the command (q* += a dt each physics step, starting at the
  /// pose of the reset), its target velocity is a; stiffness, damping and effort limit per DOF.
  VelocityDrive,
};

/// The model shared by every scene of a batch.
struct SceneBatchSpec {
  BatchActionMode mode = BatchActionMode::VelocityServo;
  /// DOF index (in the articulation's generalized coordinates) moved by each action column.
  std::vector<int> action_dofs;
  /// Actions are clipped to [action_low, action_high] (rad/s), per column; empty: no clipping.
  std::vector<double> action_low, action_high;
  /// VelocityServo: per column k_p (N m s/rad), k_i (N m/rad), effort_limit (N m), profile_accel (rad/s^2).
  std::vector<double> servo_k_p, servo_k_i, servo_effort_limit, servo_profile_accel;
  /// VelocityDrive: per column stiffness (N m/rad), damping (N m s/rad), max effort (N m, < 0: none).
  std::vector<double> drive_stiffness, drive_damping, drive_max_effort;
  /// Link index of the observed link E (its origin is p_WE).
  int observed_link = 0;
  /// Physics step (s) and physics steps per batch step (the control period is dt * substeps).
  double dt = 0.004;
  int substeps = 1;
};

/// One scene of a batch: the scene, its articulation and the actor whose contact force is
/// observed (0: none). All are handles; the scenes must outlive the batch's use of them.
struct SceneBatchMember {
  Scene scene{0};
  ActorHandle articulation = 0;
  ActorHandle contact_actor = 0;
};

/// Scenes of one model stepped together. Construction checks the spec against every member
/// (throws superdex::Error naming the field and the scene index), registers the contact-force
/// queries and captures each scene's state as its initial state for reset().
///
/// Not thread-safe itself: call it from one thread; it spreads the scenes over the workers.
class SceneBatch {
 public:
  SceneBatch(SceneBatchSpec spec, std::vector<SceneBatchMember> members);
  ~SceneBatch();
  SceneBatch(SceneBatch&&) noexcept;
  SceneBatch& operator=(SceneBatch&&) noexcept;

  int num_scenes() const;
  int action_size() const;
  int obs_size() const;
  const SceneBatchSpec& spec() const;

  /// Restores the initial state of the scenes `indices`, sets their action DOFs to the rows of
  /// `q0` (indices.size() x action_size(), rad or m; null: keep the initial pose), keeping the
  /// initial state's velocities, resets their servos and drive targets, and writes their
  /// observation rows into `obs_out` (num_scenes() x obs_size(); other rows untouched). Throws for
  /// an index out of range or given twice.
  void reset(const std::vector<int>& indices, const double* q0, real* obs_out);
  /// Applies `actions` (num_scenes() x action_size(), row-major) to every scene, steps each
  /// `substeps` times on the worker threads and writes every observation row into `obs_out`.
  /// A scene whose step throws (a numerical fault) makes the call rethrow that error; the other
  /// scenes may have stepped already.
  void step(const double* actions, real* obs_out);
  /// Writes every scene's observation row (contact force as of its last step).
  void observe(real* obs_out) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::robotics

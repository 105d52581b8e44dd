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
/// One observation row (obs_size() = 2 n + 6 + task columns, n = action_dofs.size()):
///   [ q (n) | v (n) | p_WE (3) | f_C_W (3) | task (0 or 3) ]
/// q, v: the positions and velocities of the action DOFs; p_WE: the origin of the observed link
/// E in the world; f_C_W: the total contact force applied TO the contact actor C during the last
/// step, world frame (zero right after a reset, or when there is no contact actor); task: the
/// task's target point (BatchTask), none without a task.

#include <array>
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

/// A task computed in C++ by each scene's own worker thread after its step: its observation
/// columns and its reward, so that no Python runs per scene. Each scene carries the task's
/// parameters (given at its reset) and t, its batch steps since that reset.
enum class BatchTaskKind {
  /// no task: the observation row ends with f_C_W, no reward
  None,
  /// follow a circle in the world's X-Z plane, pressing with force_target where the circle is
  /// inside a prop (the seed's task). Parameter: the start phase phi (rad). Target point
  /// x*(t) = center + radius (cos theta, 0, sin theta), theta = omega t dt substeps + phi, m,
  /// world (the task columns). Reward: -|(p_WE - x*)_xz| / radius - force_weight |f_z - force_target|
  /// / force_target while f_C_W is not zero (the contact actor touched something in the last step).
  CircleTracking,
  /// reach a goal point without pushing. Parameters: the goal g (m, world, 3; the task columns).
  /// Reward: -|p_WE - g| (m) - force_weight |f_C_W| (force_weight in m/N).
  GoalReach,
};

/// The task of a batch (BatchTaskKind) and its constants.
struct BatchTask {
  BatchTaskKind kind = BatchTaskKind::None;
  /// CircleTracking: circle centre (m, world), radius (m, > 0), angular speed (rad/s), force to
  /// hold (N, > 0).
  std::array<double, 3> center{0, 0, 0};
  double radius = 1;
  double omega = 0;
  double force_target = 1;
  /// Weight of the force term of the reward (CircleTracking: 1; GoalReach: m/N).
  double force_weight = 0;
};

/// Parameters per scene of a task kind (0, 1 or 3), and its observation columns (0 or 3).
int batch_task_params_size(BatchTaskKind kind);
int batch_task_obs_size(BatchTaskKind kind);

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
  /// The task whose observation columns and reward each step writes (none by default).
  BatchTask task;
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
  /// Task parameters per scene (batch_task_params_size of the spec's task).
  int params_size() const;
  const SceneBatchSpec& spec() const;

  /// Restores the initial state of the scenes `indices`, sets their action DOFs to the rows of
  /// `q0` (indices.size() x action_size(), rad or m; null: keep the initial pose), keeping the
  /// initial state's velocities, resets their servos and drive targets, sets their task
  /// parameters to the rows of `params` (indices.size() x params_size(); null: zeros) and their
  /// task time to 0, and writes their observation rows into `obs_out` (num_scenes() x
  /// obs_size(); other rows untouched). Throws for an index out of range or given twice.
  void reset(const std::vector<int>& indices, const double* q0, real* obs_out, const double* params = nullptr);
  /// Applies `actions` (num_scenes() x action_size(), row-major) to every scene, steps each
  /// `substeps` times on the worker threads and writes every observation row into `obs_out`
  /// and, with a task, every scene's reward into `reward_out` (num_scenes(); null: not written).
  /// A scene whose step throws (a numerical fault) makes the call rethrow that error; the other
  /// scenes may have stepped already.
  void step(const double* actions, real* obs_out, double* reward_out = nullptr);
  /// Writes every scene's observation row (contact force as of its last step).
  void observe(real* obs_out) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::robotics

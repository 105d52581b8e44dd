// Batched stepping of scenes of one model (scene_batch.h): actions to joint efforts or drive
// targets, the physics steps, observation rows. Each scene's work touches only that scene and
// its own row of the inputs and outputs, so the scenes run concurrently on the worker threads.

#include "superdex/robotics/scene_batch.h"

#include <algorithm>
#include <chrono>
#include <set>
#include <string>

#include "superdex/physics/engine.h"
#include "superdex/physics/error.h"
#include "batch_task.h"
#include "velocity_servo_law.h"

namespace superdex::robotics {
inline namespace SUPERDEX_REAL_NAMESPACE {

using physics::Vec3;
using physics::VecX;
using physics::JointDrive;

namespace {

// What one scene of the batch carries besides its handles.
struct SceneSlot {
  SceneBatchMember member;
  std::vector<std::uint8_t> initial_state;     // captured at construction
  std::vector<servo::VelocityServoLaw> servos;  // VelocityServo: one per action column
  std::vector<double> q_target;                 // VelocityDrive: integrated target per column (rad or m)
  bool contact_valid = false;                   // the contact query has a completed step since the reset
  std::vector<double> params;                   // the task's parameters since the reset
  long t = 0;                                   // batch steps since the reset (the task's time)
  double seconds = 0;                           // wall time of its last batch step (s)
};

void check_size(const std::vector<double>& v, size_t n, const char* field) {
  if (v.size() != n)
    throw Error(std::string("SceneBatch: spec.") + field + " has " + std::to_string(v.size()) + " entries, expected one per action DOF (" +
                std::to_string(n) + ")");
}

}  // namespace

struct SceneBatch::Impl {
  SceneBatchSpec spec;
  std::vector<SceneSlot> slots;
  std::vector<double> last_seconds;  // each slot's last step wall time (s): the order of the next
  int n = 0;  // action columns

  // the observation row of one scene, its task columns included; returns the task's reward
  double observe(const SceneSlot& slot, real* row) const {
    const Scene& scene = slot.member.scene;
    const ActorHandle art = slot.member.articulation;
    // kept per thread: a batch step observes every scene of its thread into the same vectors
    thread_local VecX q, v;
    scene.pose(art, q);
    scene.joint_velocities(art, v);
    for (int j = 0; j < n; ++j) {
      row[j] = q[spec.action_dofs[j]];
      row[n + j] = v[spec.action_dofs[j]];
    }
    const Vec3 p_WE = scene.link_transform(art, spec.observed_link).translation;
    const Vec3 f_C_W = slot.member.contact_actor != 0 && slot.contact_valid ? scene.contact_force(slot.member.contact_actor) : Vec3::Zero();
    for (int k = 0; k < 3; ++k) {
      row[2 * n + k] = p_WE[k];
      row[2 * n + 3 + k] = f_C_W[k];
    }
    return write_task_columns_and_reward(spec.task, slot.params.data(), static_cast<double>(slot.t) * spec.dt * spec.substeps, n, row);
  }

  // one physics step of one scene with its row of actions applied
  void substep(SceneSlot& slot, const double* a) {
    Scene& scene = slot.member.scene;
    const ActorHandle art = slot.member.articulation;
    const real dt = static_cast<real>(spec.dt);
    if (spec.mode == BatchActionMode::VelocityServo) {
      thread_local VecX v;
      thread_local std::vector<real> efforts;
      scene.joint_velocities(art, v);
      efforts.resize(n);
      for (int j = 0; j < n; ++j) efforts[j] = static_cast<real>(slot.servos[j].step(a[j], v[spec.action_dofs[j]], spec.dt));
      scene.set_external_forces_on_dofs(art, spec.action_dofs, efforts);
    } else {
      for (int j = 0; j < n; ++j) {
        slot.q_target[j] += a[j] * spec.dt;
        scene.set_joint_drive(art, spec.action_dofs[j],
                              JointDrive{static_cast<real>(spec.drive_stiffness[j]), static_cast<real>(spec.drive_damping[j]),
                                         static_cast<real>(slot.q_target[j]), static_cast<real>(a[j]),
                                         static_cast<real>(spec.drive_max_effort[j])});
      }
    }
    scene.step(dt);
  }

  // the clipped action row of scene k
  void clip(const double* in, double* out) const {
    for (int j = 0; j < n; ++j) {
      out[j] = in[j];
      if (!spec.action_low.empty()) out[j] = std::clamp(out[j], spec.action_low[j], spec.action_high[j]);
    }
  }
};

SceneBatch::SceneBatch(SceneBatchSpec spec, std::vector<SceneBatchMember> members) : impl_(std::make_unique<Impl>()) {
  Impl& b = *impl_;
  const size_t n = spec.action_dofs.size();
  if (members.empty()) throw Error("SceneBatch: members is empty (a batch needs at least one scene)");
  if (n == 0) throw Error("SceneBatch: spec.action_dofs is empty (a batch needs at least one action DOF)");
  if (!(spec.dt > 0)) throw Error("SceneBatch: spec.dt must be a positive number of seconds, got " + std::to_string(spec.dt));
  if (spec.substeps < 1) throw Error("SceneBatch: spec.substeps must be >= 1, got " + std::to_string(spec.substeps));
  if (!spec.action_low.empty() || !spec.action_high.empty()) {
    check_size(spec.action_low, n, "action_low");
    check_size(spec.action_high, n, "action_high");
    for (size_t j = 0; j < n; ++j)
      if (!(spec.action_low[j] <= spec.action_high[j]))
        throw Error("SceneBatch: spec.action_low[" + std::to_string(j) + "] is above spec.action_high[" + std::to_string(j) + "]");
  }
  if (spec.mode == BatchActionMode::VelocityServo) {
    check_size(spec.servo_k_p, n, "servo_k_p");
    check_size(spec.servo_k_i, n, "servo_k_i");
    check_size(spec.servo_effort_limit, n, "servo_effort_limit");
    check_size(spec.servo_profile_accel, n, "servo_profile_accel");
    for (size_t j = 0; j < n; ++j)
      if (spec.servo_effort_limit[j] < 0) throw Error("SceneBatch: spec.servo_effort_limit[" + std::to_string(j) + "] must be >= 0");
  } else {
    check_size(spec.drive_stiffness, n, "drive_stiffness");
    check_size(spec.drive_damping, n, "drive_damping");
    check_size(spec.drive_max_effort, n, "drive_max_effort");
  }
  check_batch_task(spec.task);
  if (std::set<int>(spec.action_dofs.begin(), spec.action_dofs.end()).size() != n)
    throw Error("SceneBatch: spec.action_dofs lists a DOF twice");

  int num_dofs = -1, num_links = -1;
  for (size_t k = 0; k < members.size(); ++k) {
    const SceneBatchMember& m = members[k];
    const std::string where = "SceneBatch: members[" + std::to_string(k) + "]";
    if (!physics::scene_exists(m.scene.handle())) throw Error(where + ": its scene does not exist");
    if (!m.scene.has_actor(m.articulation) || m.scene.actor_type(m.articulation) != physics::ActorType::Articulated)
      throw Error(where + ": articulation " + std::to_string(m.articulation) + " is not an articulated actor of its scene");
    if (m.contact_actor != 0 && !m.scene.has_actor(m.contact_actor))
      throw Error(where + ": contact_actor " + std::to_string(m.contact_actor) + " is not an actor of its scene");
    const int dofs = m.scene.num_dofs(m.articulation);
    const int links = static_cast<int>(m.scene.nested_link_actors(m.articulation).size());
    if (num_dofs >= 0 && (dofs != num_dofs || links != num_links))
      throw Error(where + ": its articulation has " + std::to_string(dofs) + " DOFs and " + std::to_string(links) +
                  " links, members[0]'s " + std::to_string(num_dofs) + " and " + std::to_string(num_links) + " (one model per batch)");
    num_dofs = dofs, num_links = links;
  }
  for (size_t j = 0; j < n; ++j)
    if (spec.action_dofs[j] < 0 || spec.action_dofs[j] >= num_dofs)
      throw Error("SceneBatch: spec.action_dofs[" + std::to_string(j) + "] = " + std::to_string(spec.action_dofs[j]) +
                  " is out of range (the articulation has " + std::to_string(num_dofs) + " DOFs)");
  if (spec.observed_link < 0 || spec.observed_link >= num_links)
    throw Error("SceneBatch: spec.observed_link = " + std::to_string(spec.observed_link) + " is out of range (the articulation has " +
                std::to_string(num_links) + " links)");

  b.spec = std::move(spec);
  b.n = static_cast<int>(n);
  for (SceneBatchMember& m : members) {
    SceneSlot slot;
    slot.member = m;
    if (m.contact_actor != 0) m.scene.register_query(m.contact_actor, physics::QueryType::TotalContactForce);
    m.scene.capture_state_to_bytes(slot.initial_state);
    slot.servos.resize(n);
    for (size_t j = 0; j < slot.servos.size() && b.spec.mode == BatchActionMode::VelocityServo; ++j)
      slot.servos[j].params = {b.spec.servo_k_p[j], b.spec.servo_k_i[j], b.spec.servo_effort_limit[j], b.spec.servo_profile_accel[j]};
    const VecX q = m.scene.pose(m.articulation);
    for (int dof : b.spec.action_dofs) slot.q_target.push_back(q[dof]);
    slot.params.assign(batch_task_params_size(b.spec.task.kind), 0.0);
    b.slots.push_back(std::move(slot));
  }
  b.last_seconds.resize(b.slots.size());
}

SceneBatch::~SceneBatch() = default;
SceneBatch::SceneBatch(SceneBatch&&) noexcept = default;
SceneBatch& SceneBatch::operator=(SceneBatch&&) noexcept = default;

int SceneBatch::num_scenes() const { return static_cast<int>(impl_->slots.size()); }
int SceneBatch::action_size() const { return impl_->n; }
int SceneBatch::obs_size() const { return 2 * impl_->n + 6 + batch_task_obs_size(impl_->spec.task.kind); }
int SceneBatch::params_size() const { return batch_task_params_size(impl_->spec.task.kind); }
const SceneBatchSpec& SceneBatch::spec() const { return impl_->spec; }

void SceneBatch::reset(const std::vector<int>& indices, const double* q0, real* obs_out, const double* params) {
  Impl& b = *impl_;
  std::vector<char> seen(num_scenes(), 0);
  for (int k : indices) {
    if (k < 0 || k >= num_scenes())
      throw Error("SceneBatch.reset: index " + std::to_string(k) + " is out of range (" + std::to_string(num_scenes()) + " scenes)");
    if (seen[k]++) throw Error("SceneBatch.reset: index " + std::to_string(k) + " appears twice in indices");
  }
  physics::run_on_worker_threads(indices.size(), [&](size_t i) {
    SceneSlot& slot = b.slots[indices[i]];
    Scene& scene = slot.member.scene;
    const ActorHandle art = slot.member.articulation;
    scene.restore_state_from_bytes(slot.initial_state);
    VecX q = scene.pose(art);
    if (q0 != nullptr) {
      for (int j = 0; j < b.n; ++j) q[b.spec.action_dofs[j]] = static_cast<real>(q0[i * b.n + j]);
      scene.set_pose(art, q);
    }
    for (int j = 0; j < b.n; ++j) {
      slot.servos[j].reset();
      slot.q_target[j] = q[b.spec.action_dofs[j]];
    }
    slot.contact_valid = false;
    slot.t = 0;
    const int p = params_size();
    for (int j = 0; j < p; ++j) slot.params[j] = params != nullptr ? params[i * p + j] : 0.0;
    b.observe(slot, obs_out + static_cast<size_t>(indices[i]) * obs_size());
  });
}

void SceneBatch::step(const double* actions, real* obs_out, double* reward_out) {
  Impl& b = *impl_;
  // each scene on the same thread step after step, so that its data stays in that core's cache
  // (with each scene going to whichever thread was free, 2 threads gave about 1.45x the batch
  // throughput of 1 on the seed task with the box; with home threads about 1.85x); each thread
  // runs the scenes that took longest last time first, and the threads help each other with
  // their cheapest (scenes in contact can cost many times more than free ones)
  for (size_t k = 0; k < b.slots.size(); ++k) b.last_seconds[k] = b.slots[k].seconds;
  physics::run_on_worker_threads_with_home_threads(b.last_seconds, [&](size_t k) {
    SceneSlot& slot = b.slots[k];
    const auto t0 = std::chrono::steady_clock::now();
    thread_local std::vector<double> a;
    a.resize(b.n);
    b.clip(actions + k * b.n, a.data());
    for (int s = 0; s < b.spec.substeps; ++s) b.substep(slot, a.data());
    slot.contact_valid = true;
    ++slot.t;
    const double reward = b.observe(slot, obs_out + k * obs_size());
    if (reward_out != nullptr) reward_out[k] = reward;
    slot.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  });
}

void SceneBatch::observe(real* obs_out) const {
  const Impl& b = *impl_;
  for (size_t k = 0; k < b.slots.size(); ++k) b.observe(b.slots[k], obs_out + k * obs_size());
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::robotics

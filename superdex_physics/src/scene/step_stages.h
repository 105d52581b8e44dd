#pragma once
// The stages of one scene step, in the order Scene::step_dynamics runs them (scene.cpp): each
// reads what the stages before it left in the Step and its workspace, and times itself where the
// step's statistics count its part (StepStats::time_*).

#include <memory>
#include <unordered_map>
#include <vector>

#include "core/step_ticks.h"
#include "scene/scene_data.h"
#include "scene/step_clock.h"
#include "scene/step_guard.h"
#include "scene/step_workspace.h"
#include "soft/soft_body.h"
#include "soft/soft_contact.h"
#include "solver/step_settings.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

// One step in progress: the scene, its working storage kept across steps (step_workspace.h), and
// what lives for this step only.
struct Step {
  Step(SceneData& scene, StepWorkspace& workspace, real step_dt) : s(scene), ws(workspace), dt(step_dt) {}

  SceneData& s;
  StepWorkspace& ws;
  const real dt;
  std::vector<std::unique_ptr<SoftStep>> soft_steps;  // per soft body: its part of the problem (null without free DOFs, or reduced)
  std::vector<SoftContact> soft_contacts;             // the soft bodies' contacts
  std::vector<SoftState> soft_next;                   // per soft body: the next state
  std::vector<VecX> node_forces;                      // per soft body: the next node contact forces
  Ticks collision_ticks = 0;                          // time in broad and narrow phase (step_ticks.h)
  Ticks kinematics_ticks = 0;                         // time in the articulations' dynamics terms
};

// Broad phase: the pairs of colliders that may touch (step_collision.cpp).
void find_step_contact_pairs(Step& step);
// On the worker threads: the soft bodies' problems, the articulations' terms, the narrow phase (step_items.cpp).
void prepare_step_items(Step& step);
// The contact list from the narrow phase's chunks, and the soft contacts (step_collision.cpp).
void gather_contacts(Step& step);
// The side of a constraint on `actor` (invalid: none) at `node` (soft actors), from the scene's
// current state; `index` maps the scene's articulations and soft bodies to their indices (built
// once per step), or null to search them (step_constraints.cpp).
ConstraintSide constraint_side(const SceneData& s, const ConstraintRecord& c, int which, const std::unordered_map<const void*, int>* index = nullptr);
// The pose controllers' pending target velocities applied: each target's motion over the step
// of dt (pose_controller_api.cpp).
void apply_pose_controller_velocities(SceneData& s, real dt);
// Each constraint's rows from the state at the step's start (step_constraints.cpp).
void constraint_step_terms(Step& step);
// The islands: bodies coupled by contacts and constraints (step_islands.cpp).
void build_step_islands(Step& step);
// Each large rigid island's Newton system from the scene's cache, kept by its bodies (step_islands.cpp).
void assign_sparse_systems(Step& step);
// Each island's cost estimate (contacts and DOFs), by which the solves go largest first (step_islands.cpp).
void estimate_island_costs(Step& step);
// On the worker threads: each island's solve and its bodies' next states (step_islands.cpp).
void solve_islands(Step& step);
// The next state and kinematics of island k's articulations, from its solution (next_states.cpp).
void next_island_states(Step& step, size_t k);
// Checks the islands' solutions and the articulations' next states; clamped ones are redone (next_states.cpp).
void guard_rigid_states(Step& step, StepGuard& guard);
// The soft bodies' next states (checked) and node contact forces (next_states.cpp).
void next_soft_states(Step& step, StepGuard& guard);
// The next states become the bodies' states (next_states.cpp).
void commit_next_states(Step& step);
// The step's contact results for queries, s.contacts (contact_records.cpp).
void contact_records(Step& step);
// The constraints' forces of the step, and their targets' motion over it done (step_constraints.cpp).
void constraint_records(Step& step);
// The step's statistics, s.stats, with its wall time by `clock` (step_stats.cpp).
void step_stats(Step& step, const StepClock& clock);

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

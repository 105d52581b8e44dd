#pragma once
// Private storage of the engine and its scenes. Scenes own articulations (rigid bodies are
// one-link articulations); the public API reaches them only through handles.

#include <array>
#include <map>
#include <set>
#include <memory>
#include <optional>
#include <span>
#include <atomic>
#include <shared_mutex>
#include <unordered_map>

#include <oneapi/tbb/task_arena.h>

#include "constraint/constraint_record.h"
#include "constraint/pose_controller.h"
#include "multibody/articulation_model.h"
#include "multibody/articulation_skin.h"
#include "output/debug_draw_features.h"
#include "scene/actor_records.h"
#include "shape/shape_data.h"
#include "soft/soft_body.h"
#include "superdex/physics/engine.h"
#include "superdex/physics/scene.h"
#include "solver/step_settings.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

class SparseNewtonSystem;  // sparse_newton_system.h
struct IslandWorkspace;    // island_solver.h
struct StepWorkspace;      // step_workspace.h
class SceneRecording;      // output/scene_recording.h

struct Articulation {
  ActorHandle handle = 0;
  bool is_rigid = false;   // created by create_rigid_actor
  bool is_static = false;  // welded rigid body
  std::vector<LinkRecord> links;  // per link: what it was created with
  std::vector<ArticulatedJointFrictionParams> joint_friction;  // per joint, as given
  ArticulationModel model;
  ArticulationState state;
  ArticulationKinematics kin;  // always current with `state`
  VecX drive_efforts;          // results of the last step: joint drive efforts per DOF
  ConvergenceStatus convergence_status = ConvergenceStatus::None;  // of its island's last solve
  std::vector<ActorHandle> link_handles;
  std::optional<PoseController> pose_controller;  // add_pose_controller
  std::vector<ConstraintHandle> limit_constraints;  // per limited single-DOF joint, in joint order
  std::shared_ptr<const ArticulationSkin> skin;     // ArticulatedActorParams::skin, else null
  std::vector<ActorHandle> nested_softs;            // a soft-skinned actor's soft bodies
};

// What an actor handle refers to: a whole articulation (link -1) or one of its links.
struct ActorRef {
  Articulation* articulation = nullptr;  // null for a soft actor
  int link = -1;
  SoftBody* soft = nullptr;              // a soft actor
};

// One contact of the last step, as reported to queries. Force is applied to actor_a (world).
struct ContactRecord {
  ActorHandle actor_a = 0, actor_b = 0;  // link or rigid actors
  int body_a = -1, body_b = -1;          // articulation indices at the time of the step
  int link_a = 0, link_b = 0;
  Vec3 position = Vec3::Zero();          // world (m)
  Vec3 normal = Vec3::Zero();            // unit, from b towards a
  real distance = 0;                     // signed gap before the step (m), negative when penetrating
  Vec3 force = Vec3::Zero();             // force on a (N), world
};

// A registered query of one actor.
struct QueryRecord {
  ActorHandle actor = 0;
  int type = 0;             // QueryType
  long long since_step = 0; // results are valid once a step completed after this
};

struct StepCallbackRecord {
  std::string debug_name;
  bool post = false;
  int priority = 100;
  std::shared_ptr<const StepCallback> fn;
};

// The pre- or post-step callbacks in the order they run (priority, then registration): made when first
// needed after a change, and shared with a step that runs them, so that a callback may register
// or cancel callbacks while the list it came from runs on.
using StepCallbackOrder = std::vector<std::shared_ptr<const StepCallback>>;
// An order, and the value of SceneData::callbacks_version it was built at: outdated when that
// value has changed since.
struct CachedCallbackOrder {
  std::shared_ptr<const StepCallbackOrder> order;
  std::uint64_t version = 0;
};

struct SceneData {
  SceneHandle handle = 0;
  std::string name;
  Vec3 gravity = kDefaultGravity;
  double time = 0;
  double last_time_step = 0;  // s, of the last step with a positive time step
  SolverParams solver_params = default_scene_solver_params();  // as set (Scene::set_solver_params)
  StepSettings params = step_settings_from(solver_params);      // what the solvers read
  StepStats stats;
  PerformanceStats performance;  // the last step's durations (step_stats and Scene::step)
  NumericalFaultPolicy fault_policy = NumericalFaultPolicy::Raise;
  std::vector<NumericalFault> last_faults;  // clamped by the last step (WarnAndClamp)
  std::vector<std::unique_ptr<Articulation>> articulations;  // creation order
  std::vector<std::unique_ptr<SoftBody>> soft_bodies;        // creation order
  std::unordered_map<ActorHandle, ActorRef> actors;
  long long step_count = 0;
  // contact filtering: disabled actor pairs (smaller handle first) and per-layer masks
  // the actor contact filter: rules for ordered pairs (colliding, collider), which apply to the
  // actors' links too when `nested` (collision_broad.cpp: actors_may_touch)
  struct ActorContactRule {
    bool enabled = true;
    bool nested = false;
  };
  std::map<std::pair<ActorHandle, ActorHandle>, ActorContactRule> actor_contact;
  // layer_masks[a] bit b: contact of a colliding actor of layer a with a collider of layer b; a
  // pair of actors touches when either order is enabled
  std::array<std::uint64_t, 64> layer_masks = filled_layer_masks();
  std::vector<std::string> layer_names{""};  // by index; "" is layer 0, the default
  std::vector<char> layer_registered{0};     // counted by num_contact_layers (0 for "" until used by name)
  // results of the last step and the queries that read them
  std::vector<ContactRecord> contacts;
  std::map<std::int64_t, QueryRecord> queries;
  // constraints by handle (creation order)
  std::map<ConstraintHandle, ConstraintRecord> constraints;
  std::map<CallbackHandle, StepCallbackRecord> callbacks;  // by handle: registration order
  std::array<CachedCallbackOrder, 2> callback_order;  // pre, post
  std::uint64_t callbacks_version = 0;                // counts the changes to `callbacks`
  std::map<int, SignalSource> signal_sources;  // by id (debugger frames and recordings)
  int next_signal_source = 1;
  // sparse Newton patterns of the last step's large islands, by their sorted body indices
  // (a cache: reused while an island keeps its structure)
  std::map<std::vector<int>, std::shared_ptr<SparseNewtonSystem>> sparse_systems;
  // working storage of the island solves, by island index (island_solver.h): islands keep their
  // order and shapes from step to step, so the storage fits without allocating
  std::vector<std::shared_ptr<IslandWorkspace>> island_workspaces;
  // captured states (Scene::capture_state), by handle
  std::map<StateHandle, std::vector<std::uint8_t>> states;
  bool force_single_island = false;
  // the step's working storage (created by the first step)
  std::shared_ptr<StepWorkspace> step_workspace;
  // the running HDF5 recording of this scene (Scene::start_recording), null when none
  std::shared_ptr<SceneRecording> recording;
  // debug drawing: what to draw and the buffers last drawn into (DebugDraw, debug_draw_api.cpp)
  DebugDrawState debug_draw;

  static std::array<std::uint64_t, 64> filled_layer_masks() {
    std::array<std::uint64_t, 64> m;
    m.fill(~std::uint64_t(0));
    return m;
  }
};

struct EngineData {
  std::shared_mutex mutex;  // guards the registries below
  bool initialized = false;
  int num_threads = 1;              // threads the work runs on (1: the calling thread alone)
  int requested_threads = 0;        // as initialize() was asked (-1 resolved to the cores)
  std::atomic<bool> single_threaded{false};  // set_single_threaded(): work runs on the calling thread
  std::unique_ptr<oneapi::tbb::task_arena> arena;  // null when single-threaded
  std::map<SceneHandle, std::unique_ptr<SceneData>> scenes;
  // bumped (under the unique lock) whenever `scenes` changes: scene_data()'s per-thread cache of
  // its last lookup is valid while this is unchanged
  std::atomic<std::uint64_t> scenes_version{0};
  std::unordered_map<std::int64_t, ShapeEntry> shapes;
  // the file cache (engine.h): shape data by file and bake, kept while enabled
  bool file_cache_enabled = false;
  std::map<std::string, std::shared_ptr<const ShapeData>> file_cache;
};

EngineData& engine_data();
// Adds a built articulation to the scene (its handle, link actors, initial state); links without a
// record get one from the model (the contact friction and layer of their collider).
ActorHandle add_articulation(SceneData& s, std::unique_ptr<Articulation> a);
// The scene's evolving state as bytes (scene_state.cpp), and its restoration: throws
// superdex::Error for bytes of another scene or build, changing nothing.
std::vector<std::uint8_t> state_bytes(const SceneData& s);
void restore_state_bytes(SceneData& s, std::span<const std::uint8_t> bytes);
// Makes the constraints that stand for an articulation's joint limits (constraint_api.cpp).
void add_joint_limit_constraints(SceneData& s, Articulation& a);
// Throws unless the query `type` is registered on `actor` and has a result (actor_queries.cpp).
void require_query(const SceneData& s, ActorHandle actor, QueryType type, const char* what);
// Moves a soft body's frame with the rigid motion of its nodes (soft_actor_api.cpp), as its
// RecenteringParams say.
void recenter_soft_body(SoftBody& b);
// Adds a built soft body to the scene (its pinned nodes become those its boundary conditions
// go back to).
ActorHandle add_soft_body(SceneData& s, std::unique_ptr<SoftBody> body);
// Gives a soft or rod actor the fields its params share: gravity, contact params and layer
// (actor_creation.cpp); throws naming `where` for a 65th layer.
void set_soft_actor_fields(SceneData& s, SoftBody& body, bool has_gravity, const ContactParams& contact, const std::string& layer,
                           const std::string& where);
// The index of a contact layer by name, registered on first use; throws naming `where` when the
// scene has 64 layers already.
int contact_layer_index(SceneData& s, const std::string& name, const std::string& where);
// Warns once per field when an actor is given a contact parameter this engine does not use.
void warn_unused_contact_fields(const ContactParams& p, const std::string& where);
// The data of a live shape; throws superdex::Error "<where>: ..." for an invalid or released handle.
std::shared_ptr<const ShapeData> shape_data(const ShapeHandle& shape, const std::string& where);
// The file cache's data for `key` (a path and a bake), or null; and its storage when enabled.
std::shared_ptr<const ShapeData> cached_shape(const std::string& key);
void cache_shape(const std::string& key, std::shared_ptr<const ShapeData> data);
// A new handle (one reference) to existing shape data.
ShapeHandle add_shape_reference_to(std::shared_ptr<const ShapeData> data);
// The live scene with this handle; throws superdex::Error if it does not exist.
SceneData& scene_data(SceneHandle handle);
// Recomputes kinematics after a state change.
void refresh_kinematics(Articulation& a);

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

#pragma once
// Private storage of the engine and its scenes. Scenes own articulations (rigid bodies are
// one-link articulations); the public API reaches them only through handles.

#include <map>
#include <memory>
#include <shared_mutex>
#include <unordered_map>

#include <oneapi/tbb/task_arena.h>

#include "articulation_model.h"
#include "superdex/physics/engine.h"
#include "superdex/physics/scene.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

struct Articulation {
  ActorHandle handle = 0;
  bool is_rigid = false;   // created by create_rigid_actor
  bool is_static = false;  // welded rigid body
  ShapeHandle shape = 0;   // rigid bodies: the shape they carry
  ArticulationModel model;
  ArticulationState state;
  ArticulationKinematics kin;  // always current with `state`
  std::vector<ActorHandle> link_handles;
};

// What an actor handle refers to: a whole articulation (link -1) or one of its links.
struct ActorRef {
  Articulation* articulation = nullptr;
  int link = -1;
};

struct SceneData {
  SceneHandle handle = 0;
  std::string name;
  Vec3 gravity = Vec3(0, 0, real(-9.81));
  double time = 0;
  SolverParams params;
  SolverStats stats;
  std::vector<std::unique_ptr<Articulation>> articulations;  // creation order
  std::unordered_map<ActorHandle, ActorRef> actors;
};

struct EngineData {
  std::shared_mutex mutex;  // guards the registries below
  bool initialized = false;
  int num_threads = 1;
  std::unique_ptr<oneapi::tbb::task_arena> arena;  // null when single-threaded
  std::map<SceneHandle, std::unique_ptr<SceneData>> scenes;
  std::map<ShapeHandle, ShapeGeometry> shapes;
};

EngineData& engine_data();
// The live scene with this handle; throws superdex::Error if it does not exist.
SceneData& scene_data(SceneHandle handle);
// Recomputes kinematics after a state change.
void refresh_kinematics(Articulation& a);

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

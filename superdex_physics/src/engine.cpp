// Engine lifecycle and the scene and shape registries.

#include <atomic>
#include <mutex>
#include <thread>

#include "kinematics.h"
#include "scene_data.h"
#include "superdex/physics/error.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

std::int64_t next_handle() {
  static std::atomic<std::int64_t> counter{0};
  return ++counter;
}

EngineData& engine_data() {
  static EngineData data;
  return data;
}

void initialize(int num_worker_threads) {
  if (num_worker_threads < -1) throw Error("initialize: num_worker_threads must be -1 (automatic), 0 or positive, got " + std::to_string(num_worker_threads));
  EngineData& e = engine_data();
  std::unique_lock lock(e.mutex);
  if (e.initialized) throw Error("initialize: the engine is already initialized; call shutdown() first");
  int threads = num_worker_threads;
  if (threads == -1) threads = std::max(1u, std::thread::hardware_concurrency());
  e.num_threads = std::max(1, threads);
  e.arena.reset();
  if (threads > 0) e.arena = std::make_unique<oneapi::tbb::task_arena>(threads);
  e.initialized = true;
}

void shutdown() {
  EngineData& e = engine_data();
  std::unique_lock lock(e.mutex);
  e.scenes.clear();
  e.shapes.clear();
  e.arena.reset();
  e.initialized = false;
}

bool is_initialized() {
  EngineData& e = engine_data();
  std::shared_lock lock(e.mutex);
  return e.initialized;
}

int num_worker_threads() {
  EngineData& e = engine_data();
  std::shared_lock lock(e.mutex);
  return e.num_threads;
}

namespace {
void require_initialized(const EngineData& e, const char* what) {
  if (!e.initialized) throw Error(std::string(what) + ": the engine is not initialized; call initialize() first");
}
}  // namespace

Scene create_scene(const std::string& name) {
  EngineData& e = engine_data();
  std::unique_lock lock(e.mutex);
  require_initialized(e, "create_scene");
  auto scene = std::make_unique<SceneData>();
  scene->handle = next_handle();
  scene->name = name;
  const SceneHandle h = scene->handle;
  e.scenes.emplace(h, std::move(scene));
  return Scene(h);
}

void destroy_scene(SceneHandle handle) {
  EngineData& e = engine_data();
  std::unique_lock lock(e.mutex);
  if (e.scenes.erase(handle) == 0) throw Error("destroy_scene: scene " + std::to_string(handle) + " does not exist (already destroyed?)");
}

bool scene_exists(SceneHandle handle) {
  EngineData& e = engine_data();
  std::shared_lock lock(e.mutex);
  return e.scenes.count(handle) > 0;
}

SceneData& scene_data(SceneHandle handle) {
  EngineData& e = engine_data();
  std::shared_lock lock(e.mutex);
  auto it = e.scenes.find(handle);
  if (it == e.scenes.end())
    throw Error("scene " + std::to_string(handle) + " does not exist (it was destroyed, or the engine was shut down)");
  return *it->second;
}

ShapeHandle create_shape(const ShapeGeometry& geometry) {
  validate_shape(geometry, "create_shape");
  EngineData& e = engine_data();
  std::unique_lock lock(e.mutex);
  require_initialized(e, "create_shape");
  const ShapeHandle h = next_handle();
  e.shapes.emplace(h, geometry);
  return h;
}

void release_shape(ShapeHandle shape) {
  EngineData& e = engine_data();
  std::unique_lock lock(e.mutex);
  if (e.shapes.erase(shape) == 0) throw Error("release_shape: shape " + std::to_string(shape) + " does not exist (already released?)");
}

ShapeGeometry shape_geometry(ShapeHandle shape) {
  EngineData& e = engine_data();
  std::shared_lock lock(e.mutex);
  auto it = e.shapes.find(shape);
  if (it == e.shapes.end()) throw Error("shape " + std::to_string(shape) + " does not exist (released, or the engine was shut down)");
  return it->second;
}

void refresh_kinematics(Articulation& a) { update_kinematics(a.model, a.state, a.kin); }

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

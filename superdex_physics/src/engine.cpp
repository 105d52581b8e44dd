// Engine lifecycle and the scene and shape registries.

#include <algorithm>
#include <atomic>
#include <array>
#include <numeric>
#include <mutex>
#include <thread>

#include <oneapi/tbb/parallel_for.h>

#include "kinematics.h"
#include "scene_data.h"
#include "superdex/physics/error.h"
#include "superdex/physics/recording.h"

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
  stop_recording();
  EngineData& e = engine_data();
  std::unique_lock lock(e.mutex);
  e.scenes.clear();
  ++e.scenes_version;
  e.shapes.clear();
  e.tet_meshes.clear();
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

void run_on_worker_threads(std::size_t count, const std::function<void(std::size_t)>& work) {
  // a call from inside a work item (a scene's step within a batch of scenes) runs in order on
  // its thread: the outer items already keep the threads busy
  thread_local int depth = 0;
  oneapi::tbb::task_arena* arena = nullptr;
  if (count > 1 && depth == 0) {
    EngineData& e = engine_data();
    std::shared_lock lock(e.mutex);
    arena = e.arena.get();
  }
  if (!arena || arena->max_concurrency() < 2) {
    for (std::size_t i = 0; i < count; ++i) work(i);
    return;
  }
  // greedy self-scheduling: each thread takes the next item as it becomes free, so items that
  // differ much in cost (islands, scenes), given largest first, end close together
  std::atomic<std::size_t> next{0};
  const int runners = static_cast<int>(std::min<std::size_t>(count, static_cast<std::size_t>(arena->max_concurrency())));
  arena->execute([&] {
    oneapi::tbb::parallel_for(0, runners, [&](int) {
      ++depth;
      try {
        for (std::size_t i = next.fetch_add(1); i < count; i = next.fetch_add(1)) work(i);
      } catch (...) {
        --depth;
        throw;
      }
      --depth;
    });
  });
}

void run_on_worker_threads_costliest_first(std::span<const double> costs, const std::function<void(std::size_t)>& work) {
  // the order on the stack when it is short (a scene's islands), so that a step does not allocate
  constexpr std::size_t kOnStack = 32;
  std::array<std::size_t, kOnStack> small;
  std::vector<std::size_t> large;
  if (costs.size() > kOnStack) large.resize(costs.size());
  const std::span<std::size_t> order = costs.size() > kOnStack ? std::span<std::size_t>(large) : std::span<std::size_t>(small.data(), costs.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  const auto costlier = [&](std::size_t x, std::size_t y) { return costs[x] > costs[y]; };
  if (costs.size() > kOnStack) {
    std::stable_sort(order.begin(), order.end(), costlier);
  } else {
    // stable insertion sort (std::stable_sort takes a temporary buffer from the heap)
    for (std::size_t i = 1; i < order.size(); ++i)
      for (std::size_t j = i; j > 0 && costlier(order[j], order[j - 1]); --j) std::swap(order[j], order[j - 1]);
  }
  run_on_worker_threads(order.size(), [&](std::size_t i) { work(order[i]); });
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
  ++e.scenes_version;
  return Scene(h);
}

void destroy_scene(SceneHandle handle) {
  EngineData& e = engine_data();
  std::unique_lock lock(e.mutex);
  if (e.scenes.erase(handle) == 0) throw Error("destroy_scene: scene " + std::to_string(handle) + " does not exist (already destroyed?)");
  ++e.scenes_version;
}

bool scene_exists(SceneHandle handle) {
  EngineData& e = engine_data();
  std::shared_lock lock(e.mutex);
  return e.scenes.count(handle) > 0;
}

SceneData& scene_data(SceneHandle handle) {
  EngineData& e = engine_data();
  // this thread's last lookup, valid while no scene was created or destroyed since: the calls of
  // one scene's step and of its batch row then read only the version, which every thread keeps
  // in its cache, instead of writing to the lock's cache line (two threads stepping scenes would
  // pass that line back and forth a dozen times per step)
  struct LastLookup {
    SceneHandle handle = 0;
    std::uint64_t version = 0;
    SceneData* data = nullptr;
  };
  thread_local LastLookup last;
  if (last.data && last.handle == handle && last.version == e.scenes_version.load(std::memory_order_acquire)) return *last.data;
  std::shared_lock lock(e.mutex);
  auto it = e.scenes.find(handle);
  if (it == e.scenes.end())
    throw Error("scene " + std::to_string(handle) + " does not exist (it was destroyed, or the engine was shut down)");
  last = {handle, e.scenes_version.load(std::memory_order_relaxed), it->second.get()};
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
  if (e.shapes.erase(shape) == 0 && e.tet_meshes.erase(shape) == 0) throw Error("release_shape: shape " + std::to_string(shape) + " does not exist (already released?)");
}

ShapeGeometry shape_geometry(ShapeHandle shape) {
  EngineData& e = engine_data();
  std::shared_lock lock(e.mutex);
  auto it = e.shapes.find(shape);
  if (it == e.shapes.end()) throw Error("shape " + std::to_string(shape) + " does not exist (released, or the engine was shut down)");
  return it->second;
}

ShapeHandle create_tet_mesh_shape(TetMesh mesh, const std::string& where) {
  const int n = static_cast<int>(mesh.nodes.size());
  if (mesh.tets.empty()) throw Error(where + ": the tet mesh has no tetrahedra");
  for (int i = 0; i < n; ++i)
    if (!mesh.nodes[i].allFinite()) throw Error(where + ": node " + std::to_string(i) + " has non-finite coordinates");
  for (size_t t = 0; t < mesh.tets.size(); ++t) {
    const auto& tet = mesh.tets[t];
    for (int k = 0; k < 4; ++k)
      if (tet[k] < 0 || tet[k] >= n)
        throw Error(where + ": tetrahedron " + std::to_string(t) + " refers to node " + std::to_string(tet[k]) + ", out of range (" +
                    std::to_string(n) + " nodes)");
    Mat3 D;
    D << mesh.nodes[tet[1]] - mesh.nodes[tet[0]], mesh.nodes[tet[2]] - mesh.nodes[tet[0]], mesh.nodes[tet[3]] - mesh.nodes[tet[0]];
    const real volume = D.determinant() / 6;
    const real scale = std::max({D.col(0).norm(), D.col(1).norm(), D.col(2).norm()});
    if (volume < 0) throw Error(where + ": tetrahedron " + std::to_string(t) + " is inverted (negative volume)");
    if (!(volume > real(1e-9) * scale * scale * scale)) throw Error(where + ": tetrahedron " + std::to_string(t) + " is degenerate (volume ~ 0)");
  }
  EngineData& e = engine_data();
  std::unique_lock lock(e.mutex);
  require_initialized(e, "create_tet_mesh_shape");
  const ShapeHandle h = next_handle();
  e.tet_meshes.emplace(h, std::make_shared<const TetMesh>(std::move(mesh)));
  return h;
}

std::shared_ptr<const TetMesh> tet_mesh_shape(ShapeHandle shape) {
  EngineData& e = engine_data();
  std::shared_lock lock(e.mutex);
  auto it = e.tet_meshes.find(shape);
  if (it == e.tet_meshes.end()) throw Error("shape " + std::to_string(shape) + " is not a tet mesh (create it with create_tet_mesh_shape)");
  return it->second;
}

void refresh_kinematics(Articulation& a) { update_kinematics(a.model, a.state, a.kin); }

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

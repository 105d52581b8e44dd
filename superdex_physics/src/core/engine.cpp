// Engine lifecycle and the scene and shape registries.

#include <algorithm>
#include <atomic>
#include <filesystem>
#include <sstream>
#include <mutex>
#include <thread>

#include "io/file_extension.h"
#include "multibody/kinematics.h"
#include "scene/scene_data.h"
#include "superdex/physics/mesh_io.h"
#include "superdex/physics/mesh_shape.h"
#include "superdex/physics/error.h"
#include "superdex/physics/recording.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

EngineData& engine_data() {
  // never destroyed: shape handles held by Python objects may be released while the process exits
  static EngineData* data = new EngineData();
  return *data;
}

void initialize(int num_worker_threads) {
  if (num_worker_threads < -1) throw Error("initialize: num_worker_threads must be -1 (automatic), 0 or positive, got " + std::to_string(num_worker_threads));
  EngineData& e = engine_data();
  std::unique_lock lock(e.mutex);
  if (e.initialized) throw Error("initialize: the engine has already been initialized; call shutdown() first");
  int threads = num_worker_threads;
  if (threads == -1) threads = std::max(1u, std::thread::hardware_concurrency());
  e.num_threads = std::max(1, threads);
  e.requested_threads = threads;
  e.single_threaded = false;
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

int num_threads() {
  EngineData& e = engine_data();
  std::shared_lock lock(e.mutex);
  return e.single_threaded ? 0 : e.requested_threads;
}

void set_single_threaded(bool single) { engine_data().single_threaded = single; }

bool is_single_threaded() {
  EngineData& e = engine_data();
  std::shared_lock lock(e.mutex);
  return e.single_threaded || e.requested_threads == 0;
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

namespace {

ShapeHandle register_shape(std::shared_ptr<const ShapeData> data, const char* what) {
  EngineData& e = engine_data();
  std::unique_lock lock(e.mutex);
  require_initialized(e, what);
  const std::int64_t id = next_handle();
  e.shapes.emplace(id, ShapeEntry{std::move(data), 1});
  return ShapeHandle::adopt(id);
}

// Adds `delta` references to a live shape; the shape is released when none remain.
void add_shape_references(std::int64_t id, int delta) {
  if (id == 0) return;
  EngineData& e = engine_data();
  std::unique_lock lock(e.mutex);
  auto it = e.shapes.find(id);
  if (it == e.shapes.end()) return;
  it->second.references += delta;
  if (it->second.references <= 0) e.shapes.erase(it);
}

}  // namespace

ShapeHandle::ShapeHandle(std::int64_t value) : value_(value) { add_shape_references(value_, 1); }
ShapeHandle::ShapeHandle(const ShapeHandle& other) : value_(other.value_) { add_shape_references(value_, 1); }
ShapeHandle& ShapeHandle::operator=(const ShapeHandle& other) {
  if (this != &other) set_value(other.value_);
  return *this;
}
ShapeHandle& ShapeHandle::operator=(ShapeHandle&& other) noexcept {
  if (this != &other) {
    add_shape_references(value_, -1);
    value_ = other.value_;
    other.value_ = 0;
  }
  return *this;
}
ShapeHandle::~ShapeHandle() { add_shape_references(value_, -1); }
void ShapeHandle::set_value(std::int64_t value) {
  add_shape_references(value, 1);
  add_shape_references(value_, -1);
  value_ = value;
}

ShapeHandle create_shape(const ShapeGeometry& geometry) {
  validate_shape(geometry, "create_shape");
  return register_shape(shape_from_geometry(geometry), "create_shape");
}

void release_shape(const ShapeHandle& shape) {
  EngineData& e = engine_data();
  std::unique_lock lock(e.mutex);
  e.shapes.erase(shape.value());
}

int num_shapes() {
  EngineData& e = engine_data();
  std::shared_lock lock(e.mutex);
  return static_cast<int>(e.shapes.size());
}

std::shared_ptr<const ShapeData> shape_data(const ShapeHandle& shape, const std::string& where) {
  EngineData& e = engine_data();
  std::shared_lock lock(e.mutex);
  auto it = e.shapes.find(shape.value());
  if (it == e.shapes.end())
    throw Error(where + ": shape " + std::to_string(shape.value()) +
                (shape.value() == 0 ? " is not set (an invalid ShapeHandle)" : " does not exist (released, or the engine was shut down)"));
  return it->second.data;
}

ShapeHandle add_shape_reference_to(std::shared_ptr<const ShapeData> data) { return register_shape(std::move(data), "get_reference_shape"); }

void enable_file_cache(bool enable) {
  EngineData& e = engine_data();
  std::unique_lock lock(e.mutex);
  e.file_cache_enabled = enable;
  if (!enable) e.file_cache.clear();
}

bool is_file_cache_enabled() {
  EngineData& e = engine_data();
  std::shared_lock lock(e.mutex);
  return e.file_cache_enabled;
}

void clear_file_cache() {
  EngineData& e = engine_data();
  std::unique_lock lock(e.mutex);
  e.file_cache.clear();
}

void clear_file_from_cache(const std::string& path) {
  EngineData& e = engine_data();
  std::unique_lock lock(e.mutex);
  // keys are the path, a newline, then the bake
  std::erase_if(e.file_cache, [&](const auto& kv) { return kv.first.compare(0, path.size() + 1, path + "\n") == 0; });
}

std::shared_ptr<const ShapeData> cached_shape(const std::string& key) {
  EngineData& e = engine_data();
  std::shared_lock lock(e.mutex);
  if (!e.file_cache_enabled) return nullptr;
  auto it = e.file_cache.find(key);
  return it == e.file_cache.end() ? nullptr : it->second;
}

void cache_shape(const std::string& key, std::shared_ptr<const ShapeData> data) {
  EngineData& e = engine_data();
  std::unique_lock lock(e.mutex);
  if (e.file_cache_enabled) e.file_cache[key] = std::move(data);
}

ShapeGeometry shape_geometry(const ShapeHandle& shape) {
  const auto data = shape_data(shape, "shape_geometry");
  if (!data->geometry) throw Error("shape " + std::to_string(shape.value()) + " has no geometry a rigid body can carry");
  return *data->geometry;
}

ShapeHandle create_tet_mesh_shape(TetMesh mesh, const std::string& where) {
  return register_shape(shape_from_tet_mesh(std::move(mesh), where), "create_tet_mesh_shape");
}

ShapeHandle create_model_shape(ModelData model, const std::string& where) {
  return register_shape(shape_from_model(std::move(model), where), "create_model_shape");
}

namespace {

// The file cache's key: the path, a newline, then the bake's numbers.
std::string cache_key(const std::string& path, const ShapeBake& bake) {
  std::ostringstream os;
  os.precision(17);
  os << path << '\n' << bake.scale.transpose() << ' ' << bake.rotation.coeffs().transpose() << ' ' << bake.translation.transpose();
  return os.str();
}

// The model with the bake applied (scale, then rotation, then translation).
ModelData baked(ModelData model, const ShapeBake& bake, const std::string& where) {
  if (bake.is_identity()) return model;
  check_bake(bake, where);
  model::bake_transform(model, bake.scale, bake.rotation.normalized(), bake.translation);
  return model;
}

}  // namespace

ShapeHandle load_shape_from_file(const std::string& path, const ShapeBake& bake) {
  const std::string key = cache_key(path, bake);
  if (auto cached = cached_shape(key)) return register_shape(std::move(cached), "load_shape_from_file");
  std::shared_ptr<const ShapeData> data;
  const std::string ext = lower_extension(path);
  if (ext == ".h5") {
    // tetrahedra make a tet-mesh shape (for soft actors); other .mochi.h5 files a rigid shape
    const MochiH5 file = read_mochi_h5(path);
    // a polyline (a rod's centreline, with its frame axes and tube) is kept whole as a model
    if (file.mesh && file.mesh->nodes_per_element == 2) data = shape_from_model(baked(model::load_from_file(path), bake, path), path);
    else if (std::optional<TetMesh> tets = tet_mesh_from_mochi_h5(file, path, bake)) data = shape_from_tet_mesh(std::move(*tets), path);
    else data = shape_from_geometry(shape_from_mochi_h5(file, path, bake));
  } else if (is_surface_mesh_file(path)) {
    data = shape_from_geometry(load_shape_file(path, bake));
  } else if (ext == ".json" || ext == ".off") {
    data = shape_from_model(baked(model::load_from_file(path), bake, path), path);
  } else {
    throw Error(path + ": unknown shape file extension '" + std::filesystem::path(path).extension().string() +
                "' (expected .mochi.json, .mochi.h5, .obj, .off, .stl, .ply, .dae, .gltf or .glb)");
  }
  cache_shape(key, data);
  return register_shape(std::move(data), "load_shape_from_file");
}

ShapeHandle load_shape_from_bytes(std::string_view bytes, MeshFileType type, const ShapeBake& bake) {
  const std::string where = "load_shape_from_bytes";
  ModelData model;
  try {
    model = model::load_from_bytes(bytes, type);
  } catch (const Error& e) {
    throw Error(where + ": file_data: " + e.what());
  }
  return register_shape(shape_from_model(baked(std::move(model), bake, where), where), "load_shape_from_bytes");
}

ShapeMeshes shape_meshes(const ShapeHandle& shape, const std::string& where) {
  return meshes_of(*shape_data(shape, where));
}

std::shared_ptr<const ModelData> shape_model(const ShapeHandle& shape, const std::string& where) { return shape_data(shape, where)->model; }

std::shared_ptr<const TetMesh> tet_mesh_shape(const ShapeHandle& shape) {
  const auto data = shape_data(shape, "tet_mesh_shape");
  if (!data->tet_mesh) throw Error("shape " + std::to_string(shape.value()) + " is not a tet mesh (create it with create_tet_mesh_shape)");
  return data->tet_mesh;
}

bool is_tet_mesh_shape(const ShapeHandle& shape) { return shape_data(shape, "is_tet_mesh_shape")->tet_mesh != nullptr; }

void refresh_kinematics(Articulation& a) { update_kinematics(a.model, a.state, a.kin); }

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

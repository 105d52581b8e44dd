#pragma once
/// @file engine.h
/// Engine lifecycle, scenes and shapes. All functions throw superdex::Error on misuse.
/// Thread-safety: the registries are guarded; scenes may be stepped concurrently from
/// different threads, but one scene must not be used from two threads at once.

#include <cstddef>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "superdex/physics/handles.h"
#include "superdex/physics/mochi_h5.h"
#include "superdex/physics/model.h"
#include "superdex/physics/shape_meshes.h"
#include "superdex/physics/shape.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

class Scene;

/// Threads: the registries of scenes and shapes are locked, so scenes and shapes may be created,
/// and different scenes filled and stepped, on several threads at once; one scene must not be
/// used from two threads at once. initialize() and shutdown() are not thread-safe.

/// Starts the engine. `num_worker_threads`: 0 single-threaded, -1 one per core, N > 0 threads.
/// Not thread-safe: no other thread may use the engine meanwhile.
void initialize(int num_worker_threads = 0);
/// Destroys every scene and shape and stops the engine. Safe to call when not initialized.
/// Not thread-safe: no other thread may use the engine meanwhile.
void shutdown();
bool is_initialized();
/// Worker threads in use (1 when single-threaded).
int num_worker_threads();
/// The worker threads initialize() was asked for (-1 resolved to one per core), or 0 when
/// single-threaded.
int num_threads();
/// Runs new work on the calling thread (true) or on the worker threads again (false).
void set_single_threaded(bool single);
/// Whether work runs on the calling thread: no worker threads, or set_single_threaded(true).
bool is_single_threaded();
/// Runs work(i) for every i < count on the engine's worker threads (the oneTBB arena of
/// initialize()), or in order on the calling thread when single-threaded. Returns when all are
/// done; the first exception thrown by a work item is rethrown. Work items run concurrently, so
/// each must touch its own scene. Threads take the next item as they become free, so items given
/// largest first end close together. A call made from inside a work item (a scene's step within
/// a batch of scenes) runs its items in order on that thread.
void run_on_worker_threads(std::size_t count, const std::function<void(std::size_t)>& work);
/// Runs work(k) for every k < costs.size() as run_on_worker_threads does, costliest first (by
/// costs[k], in any unit; equal costs in index order), so that the threads finish close together.
void run_on_worker_threads_costliest_first(std::span<const double> costs, const std::function<void(std::size_t)>& work);
/// Runs work(k) for every k < costs.size() as run_on_worker_threads does, but with the items split
/// into one contiguous share of indices per thread (the calling thread has the first), each
/// thread running its own share costliest first (by costs[k], in any unit; equal costs in index
/// order) and then helping with the others' from their cheapest items. An item then runs on the
/// same thread call after call (a batch of scenes, each kept in that thread's cache), while the
/// threads still finish close together.
void run_on_worker_threads_with_home_threads(std::span<const double> costs, const std::function<void(std::size_t)>& work);

Scene create_scene(const std::string& name);
/// Destroys a scene; no other thread may be stepping or using that scene.
void destroy_scene(SceneHandle scene);
bool scene_exists(SceneHandle scene);

/// Registers a shape (validated: throws superdex::Error naming the defect). The handle returned
/// holds its first reference.
ShapeHandle create_shape(const ShapeGeometry& geometry);
/// Releases a shape at once, whatever references remain (they then name nothing); no effect for
/// an invalid or already released handle. Actors made from the shape keep its data.
void release_shape(const ShapeHandle& shape);
/// The number of live (unreleased) shapes.
int num_shapes();
/// File cache: when enabled, the data of shapes loaded from files (load_shape_from_file) stays in
/// memory after their release, keyed by the path and the bake, so that loading them again is fast.
/// Disabling it empties it.
void enable_file_cache(bool enable);
bool is_file_cache_enabled();
void clear_file_cache();
/// Drops every bake of one file (the exact path given to the loader).
void clear_file_from_cache(const std::string& path);
/// The geometry of a live shape as a rigid body carries it.
ShapeGeometry shape_geometry(const ShapeHandle& shape);

/// Registers a tetrahedral mesh (for soft actors, or a rigid body bounded by its surface). Checks indices and that every tetrahedron is
/// positively oriented and not degenerate; throws superdex::Error naming `where`, the tetrahedron
/// index and the defect.
ShapeHandle create_tet_mesh_shape(TetMesh mesh, const std::string& where);
/// The tet mesh of a live tet-mesh shape; throws if `shape` is not one.
std::shared_ptr<const TetMesh> tet_mesh_shape(const ShapeHandle& shape);
/// Whether a live shape holds a tet mesh (throws if `shape` is not live).
bool is_tet_mesh_shape(const ShapeHandle& shape);

/// Registers the shape a model describes (model::validate first; errors name `where` and the
/// field): a tetrahedral mesh (soft actors; rigid ones take its boundary), a triangle mesh, a
/// box, a sphere or a plane. Polylines and distance grids alone make a shape no actor can carry.
ShapeHandle create_model_shape(ModelData model, const std::string& where = "create_model_shape");
/// A shape from a file: .mochi.json, .json and .off through model::load_from_file; .mochi.h5,
/// .obj, .stl and .ply through their readers. The bake (scale, then rotation, then translation)
/// is applied to the model before anything is computed from it. With the file cache enabled the
/// shape's data is kept, keyed by path and bake, and a second load reuses it.
ShapeHandle load_shape_from_file(const std::string& path, const ShapeBake& bake = {});
/// A shape from the bytes of a file of the given type, then baked as load_shape_from_file.
ShapeHandle load_shape_from_bytes(std::string_view data, MeshFileType type = MeshFileType::Legacy, const ShapeBake& bake = {});

/// A live shape's meshes; throws naming `where` for an invalid or released handle.
ShapeMeshes shape_meshes(const ShapeHandle& shape, const std::string& where);
/// The model a live shape was made from (shared, immutable; it stays valid after the shape's
/// release): its main mesh, visual mesh, primitive, distance grid and per-element material, in
/// the shape frame (m) with any bake applied. model::save_to_file writes it back as a file that
/// load_shape_from_file turns into the same shape. Capsules have an empty model. Throws naming
/// `where` for an invalid or released handle.
std::shared_ptr<const ModelData> shape_model(const ShapeHandle& shape, const std::string& where = "shape_model");

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

#pragma once
/// @file prefab.h
/// Loading `.mochi_prefab` / `.mochi_scene` files (FORMATS.md) into a scene: rigid and
/// articulated actors (inline link/joint fields or a `bot` file), nested prefabs with their
/// transforms, a uniform scale, contact filters and optional scene settings.
///
/// Paths that start with `./` are relative to the prefab file; other relative paths are relative
/// to the root path; absolute paths and paths containing `..` are rejected.

#include <string>
#include <vector>

#include "superdex/physics/scene.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

struct PrefabParams {
  /// Instance name: prefixes the names of the created actors ("name/actor") when not empty.
  std::string name;
  /// Uniform scale of positions and shapes (> 0). Explicit masses are kept; densities give
  /// masses of the scaled shapes.
  real scale = 1;
  /// Pose of the prefab's frame in the world.
  Transform world_from_prefab;
  /// Apply the file's `scene` settings (gravity, solver) to the scene.
  bool apply_scene_settings = false;
};

struct PrefabResult {
  std::vector<ActorHandle> actors;        ///< created actors, in file order (nested prefabs in place)
  std::vector<std::int64_t> constraints;  ///< created constraints (none are defined yet)
};

/// Adds a prefab's actors to `scene`. All or nothing: on an error, the actors created so far
/// are destroyed and superdex::Error names the file, the JSON path and the defect.
PrefabResult add_prefab_to_scene(const std::string& prefab_path, const std::string& root_path, Scene scene,
                                 const PrefabParams& params, std::vector<std::string>* warnings);

/// Loads the mesh or `.mochi.h5` shape files that links name (`LinkDesc::shape_file`),
/// relative to `base_dir`, with each link's shapeScale times `scale` baked in. Errors name
/// `source` and `links[i].shape`.
void load_link_shape_files(ArticulationDesc& desc, const std::string& base_dir, const std::string& source, real scale = 1);

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

#pragma once
/// @file prefab.h
/// Prefabs (`.mochi_prefab` / `.mochi_scene` JSON, FORMATS.md) as objects (prefab/scene_prefab.h):
/// reading and writing them, loading what they reference (nested prefab files, shape files), and
/// adding them to a scene.
///
/// Paths: "./x" is relative to the folder of the prefab file that names it (to the root path for a
/// prefab read from a string), other relative paths to the root path, absolute paths as they are.
/// Files may not name absolute paths or paths containing "..". Errors are superdex::Error naming
/// the file (when there is one), the field's path (`actors.rigid[2].mass`) and the defect.

#include <string>
#include <vector>

#include "superdex/physics/prefab/scene_prefab.h"
#include "superdex/physics/scene.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {
namespace prefab {

/// How a prefab is placed in a scene: world-from-prefab X_WP = (rotation, translation), a uniform
/// scale of positions and shapes, and a name prefixed to its actors' ("name/actor").
struct PrefabParams {
  std::string name;
  /// > 0. Scales shapes and positions; explicit masses are kept (densities give the masses of the
  /// scaled shapes). The ScenePrefab form of add_to_scene takes only 1 (its shapes are loaded).
  real scale = 1;
  Quaternion rotation = Quaternion::Identity();   ///< R_WP, non-zero
  Real3 translation = Real3::Zero();              ///< p_WoPo_W (m)
  /// Apply the top-level prefab's SceneParams (gravity, solver); nested ones are always ignored.
  bool apply_scene_settings = false;
};

/// What add_to_scene created: the top-level actors (a nested prefab's before its parent's own,
/// each prefab's rigid, then soft, then articulated actors in list order).
struct AddToSceneResult {
  std::vector<ActorHandle> actors;
  /// The created actors of one type, in the order above.
  std::vector<ActorHandle> filter(const Scene& scene, ActorType type) const;
};

/// Reads a prefab without the files it references: nested prefabs and shapes stay unloaded.
ScenePrefab shallow_load_from_file(const std::string& path, std::vector<std::string>* warnings = nullptr);
ScenePrefab shallow_load_from_json_string(const std::string& json, std::vector<std::string>* warnings = nullptr);
/// Reads a prefab with its nested prefabs and shapes.
ScenePrefab load_from_file(const std::string& prefab_path, const std::string& root_path, std::vector<std::string>* warnings = nullptr);
ScenePrefab load_from_json_string(const std::string& json, const std::string& root_path, std::vector<std::string>* warnings = nullptr);
/// (Re)loads the nested prefabs, recursively (at most 16 deep).
void load_nested_prefabs(ScenePrefab& prefab, const std::string& root_path, std::vector<std::string>* warnings = nullptr);
/// (Re)loads the shapes of the prefab and of its loaded nested prefabs, each with the scale of
/// its nesting baked in. The handles replace the params' `shape` and stay registered until
/// released (release_shape).
void load_shapes(ScenePrefab& prefab, const std::string& root_path);
/// Loads the nested prefabs and shapes not loaded yet.
void ensure_fully_loaded(ScenePrefab& prefab, const std::string& root_path, std::vector<std::string>* warnings = nullptr);

/// The prefab as JSON (its nested prefabs by reference only). Shapes given only as handles
/// (no file, no primitive) cannot be written: superdex::Error names them.
std::string save_to_json_string(const ScenePrefab& prefab);
/// Writes save_to_json_string's text to `path`, creating its folders.
void save_to_json_file(const ScenePrefab& prefab, const std::string& path);

/// Adds a fully loaded prefab's actors to `scene` (params.scale must be 1), then its contact rules
/// and, with apply_scene_settings, its scene settings. All or nothing: on an error the actors
/// created so far are destroyed.
AddToSceneResult add_to_scene(const ScenePrefab& prefab, Scene scene, const PrefabParams& params = {});
/// Loads a prefab file with the scale of `params` baked into its shapes, adds it, and releases
/// the shapes it loaded.
AddToSceneResult add_to_scene(const std::string& prefab_path, const std::string& root_path, Scene scene,
                              const PrefabParams& params = {}, std::vector<std::string>* warnings = nullptr);

/// Exporting (prefab_export.cpp): writes `<output_dir>/<export_name>/<export_name>.mochi_scene`, a
/// prefab of the actors as they are now (Scene's "creation parameters read back"), and the mesh
/// shapes they carry as `.mochi.h5` files in `<output_dir>/<export_name>/generated_assets/`, named
/// from the prefab as "./generated_assets/<file>"; primitives are written inline. The folders are
/// created. Rigid actors keep their current pose and velocity; soft actors their rest mesh at
/// their current frame; articulations their root link's current pose with the other joints at
/// the pose given at creation and no velocity. Actor names are made unique in creation order (a
/// second "box" becomes "box1"). Errors are superdex::Error naming the function and the argument
/// (empty export_name, a folder that cannot be created or written, an unknown actor).
///
/// export_scene writes every rigid, soft and articulated actor, the scene's actor contact rules
/// between them and its layer contact rules (contactFilter), and its gravity and solver settings
/// (`scene`, applied with PrefabParams::apply_scene_settings).
void export_scene(Scene scene, const std::string& export_name, const std::string& output_dir);
/// export_scene without the actors listed (an articulation with its links; a link alone cannot be
/// excluded) and without the contact rules that name them.
void export_scene_excluding(Scene scene, const std::string& export_name, const std::string& output_dir,
                            const std::vector<ActorHandle>& exclude_actors);
/// One rigid, soft or articulated actor (not a link: pass its articulation), named `export_name`;
/// no contact rules and no scene settings.
void export_actor(Scene scene, ActorHandle actor, const std::string& export_name, const std::string& output_dir);

/// A path named in a prefab as a file path: `input_path` if absolute, relative to the folder of
/// `prefab_file_path` if it starts with "./" (to the root when `prefab_file_path` is empty), else
/// relative to `root_for_relative_path`.
std::string get_prefab_full_path(const std::string& input_path, const std::string& root_for_relative_path,
                                 const std::string& prefab_file_path);

}  // namespace prefab

/// Loads the mesh or `.mochi.h5` shape files that links name (`LinkDesc::shape_file`),
/// relative to `base_dir`, with each link's shapeScale times `scale` baked in. Errors name
/// `source` and `links[i].shape`.
void load_link_shape_files(ArticulationDesc& desc, const std::string& base_dir, const std::string& source, real scale = 1);

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

#pragma once
/// @file scene_prefab.h
/// A prefab as an object (SuperDex's ScenePrefab): actors, nested prefabs, contact rules and scene
/// settings, read from and written to `.mochi_prefab` / `.mochi_scene` JSON (prefab.h), edited in
/// place and added to scenes any number of times.

#include <optional>
#include <string>
#include <vector>

#include "superdex/physics/params/solver_params.h"
#include "superdex/physics/prefab/actor_prefabs.h"
#include "superdex/physics/prefab/contact_filter.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {
namespace prefab {

/// Settings of the scene a prefab is added to; only the top-level prefab's are used, and only
/// when PrefabParams::apply_scene_settings is set.
struct SceneParams {
  std::optional<std::string> comment;
  std::string description;
  std::optional<Real3> gravity;         ///< m/s^2, world frame; replaces the scene's
  std::optional<SolverParams> solver;   ///< replaces the scene's solver params as a whole
  bool operator==(const SceneParams&) const = default;
};

struct ScenePrefab;

/// Another prefab file placed in this one: its actors are named "<name>/<actor>", its frame N is
/// placed at X_PN = (rotation, translation) and scaled by `scale` relative to this prefab's.
struct PrefabReference {
  std::optional<std::string> comment;
  std::string name;                               ///< empty: "prefab<i>" (i its index)
  std::string path;                               ///< resolved as ShapeSource::file
  real scale = 1;                                 ///< > 0; load_shapes again after changing it
  Quaternion rotation = Quaternion::Identity();   ///< R_PN
  Real3 translation = Real3::Zero();              ///< p_PoNo_P (m)
  /// The referenced prefab once loaded (load_nested_prefabs): empty until then, else one element.
  std::vector<ScenePrefab> loaded;
};

/// A complete or partial scene.
struct ScenePrefab {
  std::optional<std::string> comment;
  ActorLists actors;
  std::vector<PrefabReference> prefabs;
  std::optional<SceneParams> scene;
  std::optional<ContactFilter> contact_filter;
  /// The file it was read from (names it in errors, and is the folder of its "./" paths); empty
  /// for a prefab read from a string or built in code ("./" then means the root path).
  std::string source_file;
};

}  // namespace prefab
}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

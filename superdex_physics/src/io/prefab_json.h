#pragma once
// The JSON form of prefabs (FORMATS.md `.mochi_prefab`): reading a document into a ScenePrefab
// (prefab_json_read.cpp) and writing one (prefab_json_write.cpp), and the names both use.

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "superdex/physics/prefab/scene_prefab.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {
namespace prefab {

/// Reads a prefab document; `source` names it in errors ("<source>: actors.rigid[0].name: ...").
/// Only the JSON is checked here (types, required fields, path rules); values are checked when
/// the prefab is used. Nested prefabs and shapes are left unloaded.
ScenePrefab scene_prefab_from_json(const nlohmann::json& doc, const std::string& source, std::vector<std::string>* warnings);
/// Reads the links, joints, default pose and contact overrides of `actor` from the bot file at
/// `bot_path` (its own relative paths made absolute); errors are prefixed with `where`.
void read_bot_file(ArticulatedActorPrefab& actor, const std::string& bot_path, const std::string& where, std::vector<std::string>* warnings);
/// The document of a prefab (nested prefabs by reference).
nlohmann::json scene_prefab_to_json(const ScenePrefab& prefab);

/// A scene's solver settings as prefab JSON (prefab_json_solver.cpp): maxNewtonIterations and
/// contactMargin, then the fields that differ from default_scene_solver_params(), by group.
nlohmann::json solver_params_to_json(const SolverParams& params);
/// The reverse, from default_scene_solver_params(); errors name `file` and `path`.field.
SolverParams solver_params_from_json(const nlohmann::json& j, const std::string& file, const std::string& path);

/// The collider type a file names (collider_type_name's names), if any.
std::optional<ColliderType> collider_type_from_name(const std::string& name);

// A link of an articulation description as a prefab link: name, parent, mass properties, offset
// from its joint, collider type, contact and gravity (the caller sets its shape, render model and
// layer, which depend on where the description came from).
ArticulatedLinkPrefab link_prefab(const LinkDesc& link);
// A joint of an articulation description as a prefab joint.
ArticulatedJointPrefab joint_prefab(const JointDesc& joint);

/// "<label>: " for errors about a prefab: its file, or "ScenePrefab" for one without a file.
std::string error_prefix(const ScenePrefab& prefab);

}  // namespace prefab
}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

#pragma once
/// @file articulation_json.h
/// Reading articulation descriptions from the JSON of `.superdex_bot` files (FORMATS.md).
/// Errors name the source, the JSON path (`links[3].mass`) and what was expected; unknown
/// fields are reported as warnings.

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "superdex/physics/articulation_desc.h"
#include "superdex/physics/scene.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

/// Reads and parses a JSON file (comments allowed). Throws superdex::Error "<path>: cannot open
/// the <kind> file (does it exist?)" or "<path>: not valid JSON: ...".
nlohmann::json read_json_file(const std::string& path, const std::string& kind);

/// Parses a whole articulation (top-level `name`, `links`, `joints`, `defaultPose`,
/// `worldFromRoot`). `extra_known_fields` lists top-level, link and joint fields that
/// other layers handle (e.g. "sensors") so that they are not reported as unknown.
/// Warnings are appended to `warnings` when it is not null. Throws superdex::Error.
ArticulationDesc articulation_desc_from_json(const nlohmann::json& doc, const std::string& source,
                                             std::vector<std::string>* warnings,
                                             const std::vector<std::string>& extra_known_fields = {});

/// Parses one link object of a `.superdex_bot` file's `links` (its `sensors` and `actuators`
/// are left to the robotics layer), naming `path` in errors.
LinkDesc link_desc_from_json(const nlohmann::json& j, const std::string& source, const std::string& path,
                             std::vector<std::string>* warnings);

/// Parses one joint object of a `.superdex_bot` file's `joints`, naming `path` in errors.
JointDesc joint_desc_from_json(const nlohmann::json& j, const std::string& source, const std::string& path,
                               std::vector<std::string>* warnings);

/// Parses `{rotation: [x, y, z, w], translation: [x, y, z]}` (both optional) at `path`.
Transform transform_from_json(const nlohmann::json& j, const std::string& source, const std::string& path);

/// Parses an inline primitive shape: {"sphere": {"radius": r, "center": [..]}},
/// {"box": {"halfExtents": [..]}}, {"capsule": {"radius": r, "halfLength": l}},
/// {"plane": {"normal": [..], "distance": d}}.
ShapeGeometry shape_from_json(const nlohmann::json& j, const std::string& source, const std::string& path);

/// Pose of an inline box or capsule in the link frame, from its optional "center" and
/// "rotation" [x, y, z, w] fields (identity otherwise).
Transform shape_pose_from_json(const nlohmann::json& j, const std::string& source, const std::string& path);

/// Parses ContactParams from its JSON form (camelCase field names, all optional; unknown fields go
/// to `warnings` when given); errors name the file and the field's path.
ContactParams contact_params_from_json(const nlohmann::json& j, const std::string& source, const std::string& path,
                                       std::vector<std::string>* warnings = nullptr);

/// Parses a soft material `{type, youngsModulus, poissonRatio, density, damping (stiffness-
/// proportional Rayleigh, s), dampingAlpha (mass-proportional, 1/s)}`, all optional; unknown
/// fields are appended to `warnings`.
SoftMaterial soft_material_from_json(const nlohmann::json& j, const std::string& source, const std::string& path,
                                     std::vector<std::string>* warnings);

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

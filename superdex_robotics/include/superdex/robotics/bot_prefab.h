#pragma once
/// @file bot_prefab.h
/// A robot description: the articulation (links, joints, default pose, placement, contact
/// overrides) and the sensors and actuators declared on its links, as read from a
/// `.superdex_bot` file (FORMATS.md) or imported from URDF. Editable before create_bot.

#include <string>
#include <vector>

#include "superdex/physics/articulation_desc.h"

namespace superdex::robotics {
inline namespace SUPERDEX_REAL_NAMESPACE {

using physics::ArticulationDesc;
using physics::Transform;

/// A sensor or actuator declared on a link.
struct ComponentDecl {
  std::string type;    ///< registered type name
  std::string name;    ///< instance name, unique among the bot's components of its kind
  std::string params;  ///< inline JSON ("{...}"), a JSON file path relative to the bot file, or empty
  Transform parent_from_sensor;  ///< sensors: pose in the link frame
};

/// A sensor declared on a link, as the SuperDex API names it (one entry of BotLinkPrefab::sensors).
struct BotSensorPrefab {
  std::string type;              ///< registered sensor type, e.g. "SENSOR_CAMERA"
  std::string name;              ///< instance name
  Transform parent_from_sensor;  ///< the sensor frame in the link frame
  std::string params;            ///< inline JSON, a JSON file path relative to the bot file, or empty
  bool operator==(const BotSensorPrefab&) const = default;
};

/// An actuator declared on a link (one entry of BotLinkPrefab::actuators).
struct BotActuatorPrefab {
  std::string type;    ///< registered actuator type
  std::string name;    ///< instance name
  std::string params;  ///< inline JSON, a JSON file path relative to the bot file, or empty
  bool operator==(const BotActuatorPrefab&) const = default;
};

/// One link with the components declared on it: how a link is added to a BotPrefab in code.
struct BotLinkPrefab : physics::LinkDesc {
  std::vector<BotSensorPrefab> sensors;
  std::vector<BotActuatorPrefab> actuators;
};

struct BotPrefab {
  ArticulationDesc articulation;
  /// Per link (same length as articulation.links).
  std::vector<std::vector<ComponentDecl>> sensors, actuators;
  /// The file it was read from ("" when built in code) and its folder, for relative paths.
  std::string source, base_dir;

  const std::string& name() const { return articulation.name; }
};

/// Link `index` of `prefab` with the components declared on it (throws for a bad index).
BotLinkPrefab link_prefab(const BotPrefab& prefab, int index);
/// Appends `link`, the joint attaching it to its parent, and the components declared on it.
/// Throws superdex::Error (naming the field) for a parent index that is not an earlier link, a
/// root that is not the first link, or a component without a type.
void add_link(BotPrefab& prefab, const BotLinkPrefab& link, const physics::JointDesc& joint);

/// Reads a `.superdex_bot` file. Mesh shapes named by links are loaded (relative to the file)
/// with their shapeScale baked in. Throws superdex::Error naming the file, the JSON path and
/// what was expected; unknown fields are appended to `warnings`.
BotPrefab load_bot_prefab(const std::string& path, std::vector<std::string>* warnings);

/// Writes `prefab` as URDF XML (urdf_export.cpp): links with inertials and collision shapes
/// (boxes, spheres; a capsule as a cylinder and two spheres), joints (Hard: fixed, Revolute:
/// revolute, or continuous without limits, Prismatic: prismatic) with frames, axes, limits,
/// friction (<dynamics>) and couplings (<mimic>). The root joint is left out: the URDF's root link
/// is link 0, fixed or floating as its reader chooses. Mesh shapes are left out of the string;
/// rotor inertias (armature), which URDF cannot hold, are named in `warnings`. Throws
/// superdex::Error for a joint URDF has no type for (Spherical below the root).
std::string save_to_urdf_string(const BotPrefab& prefab, std::vector<std::string>* warnings);

/// save_to_urdf_string written to `path`, with mesh shapes as OBJ files (the triangles the engine
/// collides with) in `<stem>_meshes/` beside it.
void save_to_urdf_file(const BotPrefab& prefab, const std::string& path, std::vector<std::string>* warnings);

/// What collides for a URDF <mesh> (a .obj, .stl or .ply file; a .mochi.h5 shape is used as it is).
enum class MeshCollision {
  /// Its convex hull, as MuJoCo does: closed and convex whatever the file holds (open shells,
  /// stray or duplicate triangles), cheap to collide. Flat meshes keep their triangles.
  ConvexHull,
  /// The triangle mesh itself: concave shapes keep their cavities; a closed mesh gets a
  /// signed-distance field, an open one can only touch shapes that have one.
  Mesh,
};

/// Choices when importing a URDF.
struct UrdfImportOptions {
  /// Weld the root link to the world (a Hard root joint) instead of the default floating base
  /// (a Free root joint). Either way the root joint is named "world_joint". A URDF that
  /// attaches its root to a link named "world" keeps that joint's type.
  bool fixed_base = false;
  /// Switch off contact between links whose collision shapes already interpenetrate with every
  /// joint at zero (see physics::overlapping_link_pairs), as contact overrides named in one
  /// warning. Off: every pair of links not joined to each other collides.
  bool exclude_overlapping_links = true;
  MeshCollision mesh_collision = MeshCollision::ConvexHull;
};

/// Imports a URDF file (urdf_import.cpp). Throws superdex::Error naming the file and element.
BotPrefab load_bot_prefab_from_urdf(const std::string& path, std::vector<std::string>* warnings,
                                    const UrdfImportOptions& options = {});

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::robotics

#pragma once
/// @file mjcf_import.h
/// MJCF (MuJoCo's XML model format) import: the bodies, joints, geoms and inertias of a
/// `<mujoco>` model as bots, with MuJoCo's mass properties, so that the joint-space mass matrix
/// and bias forces equal MuJoCo's on the same file.

#include <string>
#include <vector>

#include "superdex/robotics/bot_prefab.h"

namespace superdex::robotics {
inline namespace SUPERDEX_REAL_NAMESPACE {

/// Choices when importing an MJCF file.
struct MjcfImportOptions {
  /// What a mesh geom collides as (MuJoCo itself always uses the convex hull).
  MeshCollision mesh_collision = MeshCollision::ConvexHull;
};

/// An MJCF model as bots. MuJoCo's world holds any number of kinematic trees; an articulation
/// is one tree with one root joint, so:
///  * bots[0] is the world: a root link named "world" welded at the origin that carries the
///    geoms of `<worldbody>`, with every tree that is not free (no joint on its top body: welded;
///    hinge, slide or ball joints: articulated) attached to it;
///  * each tree whose top body has a free joint is a bot of its own (after the world), with a
///    Free root joint named after that joint, placed at the body's pose.
/// The world bot is left out when it has neither geoms nor trees.
struct MjcfModel {
  std::string name;  ///< `<mujoco model>`, else the file's stem
  std::vector<BotPrefab> bots;
  physics::Vec3 gravity = physics::Vec3(0, 0, physics::real(-9.81));  ///< `<option gravity>` (m/s^2)
  physics::real timestep = physics::real(0.002);                      ///< `<option timestep>` (s)
};

/// Imports an MJCF file (mjcf/mjcf_import.cpp says what maps to what). Throws superdex::Error
/// naming the file, line and element; what is not imported is named in `warnings`.
MjcfModel load_mjcf(const std::string& path, std::vector<std::string>* warnings, const MjcfImportOptions& options = {});

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::robotics

#pragma once
// What the robot-file importers (URDF, MJCF) share: number parsing and message formatting,
// frames, the meshes that stand in for primitives the engine has no shape for, mesh scaling and
// mirroring, and the collider a mesh file becomes.

#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <vector>

#include "superdex/physics/shape.h"
#include "superdex/physics/transform.h"
#include "superdex/robotics/bot_prefab.h"

namespace superdex::robotics {
inline namespace SUPERDEX_REAL_NAMESPACE {

/// `s` in single quotes, for messages.
std::string in_quotes(const std::string& s);
/// `x` as a stream prints it (6 significant digits), for messages.
std::string format_number(double x);
/// A double-precision frame as the engine's transform.
physics::Transform to_transform(const Eigen::Isometry3d& X);

/// The whitespace-separated numbers of `text`, or nullopt with the first word that is not a
/// finite number in `bad_word`.
std::optional<std::vector<double>> parse_numbers(const std::string& text, std::string* bad_word);

/// A closed prism of `segments` sides standing in for a cylinder of `radius` (m) along z, from
/// -length/2 to +length/2, counter-clockwise seen from outside.
physics::TriangleMesh cylinder_mesh(double radius, double length, int segments = 48);

/// A closed latitude-longitude mesh of the ellipsoid with semi-axes `radii` (m) along x, y, z.
physics::TriangleMesh ellipsoid_mesh(const physics::Vec3& radii, int segments = 24);

/// Scales a mesh per axis (`s` non-zero; a negative component mirrors), with its winding reversed
/// when an odd number of axes flip, so that it still faces outward.
void scale_mesh(physics::TriangleMesh& mesh, const physics::Vec3& s);

/// The collider of a triangle mesh: its convex hull (MeshCollision::ConvexHull) or the mesh
/// itself. A flat mesh has no hull with volume: its triangles collide, and `warning` says so.
physics::ShapeGeometry mesh_collider(physics::TriangleMesh mesh, const std::string& source, MeshCollision mode,
                                     std::string* warning);

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::robotics

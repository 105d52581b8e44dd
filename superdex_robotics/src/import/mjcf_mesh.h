#pragma once
// Meshes of MJCF models: MuJoCo's binary .msh files, and the mass properties of a solid
// bounded by a triangle mesh as MuJoCo computes them for mesh geoms.

#include <Eigen/Core>
#include <string>

#include "superdex/physics/shape.h"

namespace superdex::robotics {
inline namespace SUPERDEX_REAL_NAMESPACE {

/// Reads a MuJoCo binary mesh (.msh: four int32 counts of vertices, normals, texture
/// coordinates and faces, then float32 vertices, normals and texture coordinates, then int32
/// faces). Throws superdex::Error naming the file for a truncated or inconsistent file.
physics::TriangleMesh read_msh_file(const std::string& path);

/// Mass properties of a triangle mesh as a solid of unit density, in double precision, as MuJoCo
/// computes them: the centre of mass from signed tetrahedra on the surface's area-weighted
/// centroid, then volume (m^3) and inertia about that centre from tetrahedra on it. Exact for
/// closed meshes; for open ones, MuJoCo's numbers. `absolute`: every tetrahedron counts with the
/// magnitude of its volume (MuJoCo's default "legacy" mesh inertia, which tolerates triangles
/// facing inward), else with its sign ("exact").
struct MeshMoments {
  double volume = 0;
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();  ///< about the centre, per unit density
};
MeshMoments mesh_moments(const physics::TriangleMesh& mesh, bool absolute);

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::robotics

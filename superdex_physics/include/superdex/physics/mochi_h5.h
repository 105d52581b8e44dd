#pragma once
/// @file mochi_h5.h
/// The `.mochi.h5` shape file (HDF5; groups as in FORMATS.md): read, write, and turn into a
/// ShapeGeometry. All lengths in metres, in the shape frame.
///
/// Errors (superdex::Error) name the file, the group, dataset or attribute, and the defect:
/// missing, wrong rank or shape, wrong type, NaN, grid_min >= grid_max. HDF5's own error
/// printing is silenced; no HDF5 failure escapes as anything but superdex::Error.

#include <optional>
#include <string>
#include <vector>

#include "superdex/physics/shape.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

/// `mesh/` or `visual_mesh/`: nodes and elements of k nodes each.
struct MochiMesh {
  std::vector<Vec3> coordinates;       ///< dataset `coordinates`, N x 3 (m)
  int nodes_per_element = 3;           ///< k: 3 triangles, 4 tetrahedra
  std::vector<int> connectivity;       ///< dataset `connectivity`, M x k, 0-based, row-major
  std::vector<int> constrained_nodes;  ///< optional dataset `constrained_nodes` (node indices)
  int num_elements() const { return nodes_per_element > 0 ? static_cast<int>(connectivity.size()) / nodes_per_element : 0; }
};

/// `sdf/`: a distance grid and its optional placement. A point g of the grid frame lies at
/// p = rotation * (scale .* g) + translation in the shape frame.
struct MochiSdf {
  SdfGrid grid;                     ///< dataset `grid` [nx, ny, nz]; attributes grid_min, grid_max
  std::optional<Vec3> scale;        ///< attribute `scale` (3 values, or 1 for uniform)
  std::optional<Quat> rotation;     ///< attribute `rotation`, quaternion stored [x, y, z, w]
  std::optional<Vec3> translation;  ///< attribute `translation` (m)
};

/// `material/`: attribute `type`, per-element datasets.
struct MochiMaterial {
  std::string type;                   ///< e.g. NeoHookean, StVK, Linear, Corotated
  std::vector<real> youngs_modulus;   ///< Pa, one per element (or one for all)
  std::vector<real> poisson_ratio;    ///< one per element (or one for all)
};

/// The contents of one file; absent groups are empty optionals.
struct MochiH5 {
  std::optional<MochiMesh> mesh;
  std::optional<MochiMesh> visual_mesh;
  std::optional<MochiSdf> sdf;
  std::optional<MochiMaterial> material;
  std::optional<BoxShape> box;        ///< `box/` attribute half_extents
  std::optional<SphereShape> sphere;  ///< `sphere/` attribute radius (optional center)
  std::optional<PlaneShape> plane;    ///< `plane/` attributes normal, distance
};

/// Reads and checks every group present (indices in range, finite values, sane grid).
MochiH5 read_mochi_h5(const std::string& path);

/// Writes the groups present (overwrites the file). The grid is stored C-order [nx, ny, nz].
/// Writes exactly what it is given (no checks), so tests can also produce bad files.
void write_mochi_h5(const std::string& path, const MochiH5& data);

/// Changes baked into a loaded shape: p' = transform * (scale .* p), p a mesh vertex (m).
struct ShapeBake {
  Vec3 scale = Vec3::Ones();  ///< per-axis factors, positive
  Quat rotation = Quat::Identity();
  Vec3 translation = Vec3::Zero();
  bool is_identity() const;
};

/// The shape a `.mochi.h5` file describes: a `box/`, `sphere/` or `plane/` group gives that
/// primitive; a triangle `mesh/` gives a MeshShape with the stored `sdf/` when present, else a
/// computed (cached) one when the mesh is closed. Tetrahedral meshes are an error (they become
/// soft bodies, not rigid shapes). `bake` is applied to the geometry (a box that is rotated or
/// moved becomes a mesh).
ShapeGeometry shape_from_mochi_h5(const std::string& path, const ShapeBake& bake = {});
/// The same for a file already read (`path` names it in errors).
ShapeGeometry shape_from_mochi_h5(const MochiH5& file, const std::string& path, const ShapeBake& bake = {});

/// The tet mesh of a file already read when its mesh/ holds tetrahedra (`bake` applied to the
/// nodes, which needs a positive scale); otherwise nothing.
std::optional<TetMesh> tet_mesh_from_mochi_h5(const MochiH5& file, const std::string& path, const ShapeBake& bake = {});

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

#pragma once
/// @file model.h
/// Model data: the contents of a model file (`.mochi.json`, `.mochi.h5`, or a surface mesh in
/// OBJ, OFF, PLY or STL) as plain structs, and the functions of namespace `model` that load,
/// save, check, correct and transform them. Lengths in metres, in the model's own frame.
///
/// A model holds exactly one shape: a mesh (polyline, triangle or tetrahedral), a box, a plane or
/// a sphere; a mesh may come with a visual mesh embedded in it, blend shapes, constrained nodes,
/// per-element frame axes (polylines), a precomputed signed-distance grid and a per-element
/// material. Every failure is a superdex::Error naming the file or field, e.g.
/// "mesh.connectivity[12]: node 40 out of range (8 nodes)".

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "superdex/physics/coordinate_space.h"
#include "superdex/physics/params/material_params.h"
#include "superdex/physics/types.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

struct GridSdfParams;  // params/actor_params.h

/// Coordinates per mesh node.
inline constexpr int kMeshDataSpaceDim = 3;

/// Per-node skinning: node i follows the nodes (or, for a polyline simulation mesh, the
/// elements) indices[i * weights_per_node + k] with weights weights[i * weights_per_node + k],
/// which sum to 1 for each node.
struct SkinningData {
  int weights_per_node = 0;
  std::vector<int> indices;   ///< num_nodes * weights_per_node
  std::vector<real> weights;  ///< num_nodes * weights_per_node
  bool operator==(const SkinningData&) const = default;
};

/// One blend-shape source of a skinned soft mesh: two (index, weight) pairs per mesh node.
struct BlendingData {
  std::string source_shape;   ///< name of the soft source shape (not empty)
  std::vector<int> indices;   ///< num_nodes * 2
  std::vector<real> weights;  ///< num_nodes * 2
  bool operator==(const BlendingData&) const = default;
};

/// A mesh: flat node coordinates (x0, y0, z0, x1, ...) in metres and flat element connectivity,
/// nodes_per_element indices per element (2 polyline segments, 3 triangles, 4 tetrahedra).
/// Triangles are counter-clockwise seen from outside; tetrahedra positively oriented.
struct MeshData {
  int nodes_per_element = 0;
  std::vector<real> coordinates;
  std::vector<int> connectivity;
  std::optional<SkinningData> skinning;

  int num_nodes() const { return static_cast<int>(coordinates.size() / kMeshDataSpaceDim); }
  int num_elements() const {
    return connectivity.empty() || nodes_per_element <= 0 ? 0 : static_cast<int>(connectivity.size() / nodes_per_element);
  }
  bool is_empty() const { return num_nodes() == 0; }
  bool operator==(const MeshData&) const = default;
};

/// A signed-distance grid (m, negative inside): dims[0] x dims[1] x dims[2] samples spread evenly
/// over `bounds` (the first and last samples of each axis on its faces), x fastest:
/// values[i + dims[0] * (j + dims[1] * k)]. The grid frame is placed in the model frame by
/// p = translation + rotation * (scale .* g), each part identity when absent.
struct GridSdfData {
  Int3 dims = Int3::Zero();
  std::vector<real> values;
  Aabb bounds;
  Aabb negative_value_bounds;  ///< the box of the negative (inside) region, within `bounds`
  std::optional<Real3> scale;
  std::optional<Quaternion> rotation;  ///< unit quaternion (x, y, z, w)
  std::optional<Real3> translation;
  bool operator==(const GridSdfData& o) const;
};

/// The contents of a model file; every part is optional (validate() says which combinations are
/// valid).
struct ModelData {
  std::optional<MeshData> mesh;
  std::optional<MeshData> visual_mesh;  ///< triangles skinned to `mesh`, for display
  std::optional<std::vector<BlendingData>> blending;
  std::optional<std::vector<int>> constrained_nodes;    ///< mesh node indices
  std::optional<std::vector<real>> element_frame_axes;  ///< polylines: a unit axis per element, normal to it
  std::optional<Box> box;
  std::optional<Plane> plane;
  std::optional<Sphere> sphere;
  std::optional<GridSdfData> sdf;
  std::optional<PerElementSoftMaterialData> material;
  bool operator==(const ModelData&) const = default;
};

/// Formats model::save_to_file writes.
enum class FileFormat { JSON, H5 };

/// What model::load_from_bytes parses: Legacy tells HDF5 from JSON by the HDF5 signature; the
/// others are surface meshes.
enum class MeshFileType { Legacy, PLY, OFF, STL, OBJ };

namespace model {

/// Loads a model by its file name: ending ".h5" (.mochi.h5): HDF5; ".obj", ".off", ".ply",
/// ".stl" (any case): a triangle surface mesh; anything else (.mochi.json, .json): JSON.
/// Then auto_correct() and validate().
ModelData load_from_file(const std::string& path);
/// load_from_file without auto_correct() and validate(): only what is needed to read the file is
/// checked.
ModelData load_from_file_unchecked(const std::string& path);
/// Loads a model from the bytes of a file of the given type, then auto_correct() and validate().
ModelData load_from_bytes(std::string_view data, MeshFileType type = MeshFileType::Legacy);
ModelData load_from_bytes_unchecked(std::string_view data, MeshFileType type = MeshFileType::Legacy);

/// Writes the model (creating missing directories; an existing file is replaced). JSON writes
/// the optional parts present only; H5 stores reals in the build's precision.
void save_to_file(const ModelData& data, const std::string& path, FileFormat format);
/// The model as indented JSON text (the .mochi.json format).
std::string save_to_json_string(const ModelData& data);

/// Throws superdex::Error for the first rule the model breaks, naming the field.
void validate(const ModelData& data);
/// Fixes in place what has one obvious fix: normalises skinning weights, vectors and quaternions,
/// drops empty optional parts and identity grid placements, sorts and de-duplicates constrained
/// nodes. Throws superdex::Error for what cannot be fixed (a node whose weights sum to 0).
void auto_correct(ModelData& data);

/// Applies p' = translation + rotation * (scale .* p) to every spatial part, in place. A negative
/// product of the scale factors mirrors the model and so flips the winding of its elements.
/// Frame axes transform by the inverse transpose. A sphere, a rotated box, fibre directions
/// and shape-target tensors need a uniform |scale| (else superdex::Error); the signed-distance
/// grid is kept only under a uniform |scale| (else dropped: it can be recomputed).
void bake_transform(ModelData& data, const Real3& scale = Real3::Ones(), const Quaternion& rotation = Quaternion::Identity(),
                    const Real3& translation = Real3::Zero());
void bake_transform(ModelData& data, const Real3& scale, const TransformRT& transform);

/// Converts coordinates given in `from_space` to `to_space`: axes permuted and negated (exact),
/// lengths scaled by the units ratio; the winding is flipped when the handedness changes.
void bake_coordinate_space_transform(MeshData& data, const CoordinateSpace& from_space, const CoordinateSpace& to_space);
void bake_coordinate_space_transform(ModelData& data, const CoordinateSpace& from_space, const CoordinateSpace& to_space);

/// Computes data.sdf from the closed surface of the triangle mesh, or of the tetrahedral mesh's
/// boundary, replacing any present. The voxel size follows params (GridSdfParams defaults when
/// not given).
void bake_sdf(ModelData& data);
void bake_sdf(ModelData& data, const GridSdfParams& params);

/// Reverses the orientation of every element (swaps its first two nodes); polylines unchanged.
void flip_winding_order(MeshData& data);
/// The same for mesh and visual_mesh; primitives and the grid are left alone.
void flip_winding_order(ModelData& data);

}  // namespace model

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

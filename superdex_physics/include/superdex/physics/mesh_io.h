#pragma once
/// @file mesh_io.h
/// Reading triangle meshes from OBJ, OFF, STL (ASCII and binary) and PLY (ASCII and binary) files,
/// or from their bytes in memory.
/// Coordinates are taken as they are in the file (metres, in the file's frame); polygons are
/// fan-triangulated; STL vertices shared by several facets are welded (exact duplicates).
///
/// Every reader throws superdex::Error naming the file, the line (text formats) and the defect:
/// missing file, unknown extension, malformed number, index out of range, empty mesh,
/// non-finite coordinate, a mesh of nothing but degenerate triangles. Degenerate (zero-area)
/// triangles among good ones are dropped with a warning (remove_degenerate_triangles).

#include <string>

#include "superdex/physics/shape.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

/// Reads a mesh file chosen by extension (.obj, .stl, .ply, .off, .dae, .gltf, .glb;
/// case-insensitive) and checks it with check_triangle_mesh (mesh_validation.h).
TriangleMesh read_mesh_file(const std::string& path);

/// Whether `path` names a triangle-surface file read_mesh_file reads into a rigid mesh shape (.obj,
/// .stl, .ply, .dae, .gltf, .glb; .off files are models, see model.h).
bool is_surface_mesh_file(const std::string& path);

/// COLLADA (.dae) and glTF (.gltf, .glb) through Assimp: the triangles of every mesh in the
/// file's node tree, each placed by its node's accumulated transform (so a COLLADA file's
/// `<unit meter>` and `<up_axis>` apply, as in other Assimp-based robot tools); points and lines
/// are skipped. Errors name the file and Assimp's reason.
TriangleMesh read_assimp_file(const std::string& path);

/// Wavefront OBJ: `v x y z` and `f a b c ...` records (1-based, negative = relative to the end
/// of the vertex list so far, `a/t/n` forms accepted); every other record is ignored.
TriangleMesh read_obj_file(const std::string& path);
/// STL, ASCII (`solid ... facet ... vertex x y z`) or binary (80-byte header, uint32 count,
/// 50-byte records); identical vertex positions are welded into one vertex.
TriangleMesh read_stl_file(const std::string& path);
/// PLY, `ascii`, `binary_little_endian` or `binary_big_endian`: element `vertex` with float or
/// double properties x, y, z and element `face` with a list property `vertex_indices` (or
/// `vertex_index`); other elements and properties are skipped.
TriangleMesh read_ply_file(const std::string& path);
/// Object File Format: an `OFF` header line (optional when the counts follow on the same line),
/// then `num_vertices num_faces num_edges`, the vertices `x y z`, and the faces `n i0 ... i(n-1)`
/// (0-based; extra values such as colours after the indices are ignored). `#` starts a comment.
TriangleMesh read_off_file(const std::string& path);

/// The readers above on the contents of a file held in memory; `name` stands for the file in
/// error messages.
TriangleMesh read_obj_bytes(const std::string& bytes, const std::string& name);
TriangleMesh read_stl_bytes(const std::string& bytes, const std::string& name);
TriangleMesh read_ply_bytes(const std::string& bytes, const std::string& name);
TriangleMesh read_off_bytes(const std::string& bytes, const std::string& name);

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

#pragma once
/// @file mesh_shape.h
/// Building mesh shapes: from vertex and triangle arrays, or from a shape file of any
/// supported format (.mochi.h5, .obj, .stl, .ply).

#include <optional>
#include <string>

#include "superdex/physics/mochi_h5.h"
#include "superdex/physics/sdf.h"
#include "superdex/physics/shape.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

/// A MeshShape from a triangle mesh (m, shape frame). Checks the mesh (check_triangle_mesh),
/// turns an inside-out closed mesh right side out, gives closed meshes a distance grid (`sdf`
/// when given, e.g. read from a file, else computed through the cache) and marks convex ones.
/// `source` names the mesh in messages (a file path or a function).
MeshShape make_mesh_shape(TriangleMesh mesh, const std::string& source, const SdfOptions& options = {},
                          std::shared_ptr<const SdfGrid> sdf = nullptr);

/// The convex hull of `points` (m, shape frame; see convex_hull) as a convex MeshShape, named
/// "<source> (convex hull)". Convex by construction, whatever the round-off in its faces.
MeshShape make_convex_hull_shape(const std::vector<Vec3>& points, const std::string& source);

/// Throws superdex::Error "<where>: ..." for a non-positive or non-finite scale, or a non-finite
/// transform or zero rotation quaternion.
void check_bake(const ShapeBake& bake, const std::string& where);

/// Applies `bake` to every vertex: v' = rotation * (scale .* v) + translation, after check_bake.
void bake_mesh(TriangleMesh& mesh, const ShapeBake& bake, const std::string& where);

/// Loads a shape file by extension: `.mochi.h5` (shape_from_mochi_h5), or a mesh file
/// (read_mesh_file) made into a MeshShape after baking `bake` into its vertices.
ShapeGeometry load_shape_file(const std::string& path, const ShapeBake& bake = {});

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

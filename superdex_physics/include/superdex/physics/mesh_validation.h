#pragma once
/// @file mesh_validation.h
/// Checks on triangle meshes: well-formedness (finite coordinates, indices in range, no
/// degenerate triangles), closedness (a watertight, consistently oriented surface) and
/// convexity.

#include <string>
#include <vector>

#include "superdex/physics/shape.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

/// Throws superdex::Error "<where>: <defect>" if the mesh has no vertices or triangles, a
/// non-finite coordinate, a triangle index out of range, or degenerate triangles (area below
/// 1e-12 of the squared bounding-box diagonal; the count and the first index are reported).
void check_triangle_mesh(const TriangleMesh& mesh, const std::string& where);

/// Indices of the triangles check_triangle_mesh calls degenerate (indices must be in range).
std::vector<size_t> degenerate_triangles(const TriangleMesh& mesh);

/// Drops the degenerate triangles of a mesh read from a file (exporters leave slivers and
/// triangles with a repeated vertex), with one warning "<where>: N degenerate (zero-area)
/// triangles ignored; ...". A mesh with other defects (non-finite coordinates, indices out of
/// range) or with nothing but degenerate triangles is left for check_triangle_mesh to reject.
/// Returns the number of triangles removed.
long remove_degenerate_triangles(TriangleMesh& mesh, const std::string& where);

/// The edges that keep a mesh from being a closed, consistently oriented surface.
struct EdgeReport {
  int boundary_edges = 0;     ///< edges used by exactly one triangle
  int nonmanifold_edges = 0;  ///< edges used by three or more triangles
  int misoriented_edges = 0;  ///< edges whose two triangles traverse it in the same direction
  bool closed() const { return boundary_edges == 0 && nonmanifold_edges == 0 && misoriented_edges == 0; }
  /// "N boundary edges" (and the other counts when non-zero), for messages.
  std::string describe() const;
};

/// Counts open, non-manifold and misoriented edges (indices must be in range).
EdgeReport edge_report(const TriangleMesh& mesh);

/// True when every edge is shared by exactly two triangles traversing it in opposite directions.
bool is_closed(const TriangleMesh& mesh);

/// Signed volume (m^3) enclosed by the mesh: positive when the triangles are counter-clockwise
/// seen from outside, negative when the mesh is inside out. Meaningful for closed meshes.
double signed_volume(const TriangleMesh& mesh);

/// True when the mesh is closed and every vertex lies on the inner side of every triangle's
/// plane, within `relative_tolerance` times the bounding-box diagonal. Orientation-independent
/// (an inside-out mesh is judged by its flipped planes). Cost O(triangles x vertices) for
/// convex meshes; non-convex ones usually exit early.
bool is_convex(const TriangleMesh& mesh, double relative_tolerance = 1e-6);

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

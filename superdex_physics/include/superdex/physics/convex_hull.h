#pragma once
/// @file convex_hull.h
/// Convex hulls of point sets and meshes (Qhull): the collider MuJoCo and most simulators give a
/// mesh by default. A hull is closed and convex whatever the mesh it comes from (open,
/// self-intersecting, with duplicate or stray triangles), so it always has a distance field.

#include <string>
#include <vector>

#include "superdex/physics/shape.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

/// The convex hull of `points` (m) as a closed triangle mesh, counter-clockwise seen from
/// outside. Its vertices are the hull's extreme points plus, for a hull face with more than three
/// corners, the face's centroid (faces are fanned around it, so no triangle is degenerate).
/// Points within 1e-4 of the points' extent of one another are welded into one (no sliver
/// facets) and coplanar facets are merged. Throws superdex::Error "<where>: ..." for non-finite points
/// and for points that span no volume (fewer than four, or all on one plane or line).
TriangleMesh convex_hull(const std::vector<Vec3>& points, const std::string& where);

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

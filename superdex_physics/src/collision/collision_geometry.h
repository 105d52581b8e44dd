#pragma once
// Geometric queries every shape answers, in the shape's own frame: signed distance with its
// gradient, surface sample points, and a bounding box. Contacts are built from these.

#include <vector>

#include "core/spatial.h"
#include "superdex/physics/shape.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

struct Bounds {
  Vec3 min = Vec3::Constant(std::numeric_limits<real>::infinity());
  Vec3 max = Vec3::Constant(-std::numeric_limits<real>::infinity());
  void extend(const Vec3& p) { min = min.cwiseMin(p), max = max.cwiseMax(p); }
  bool overlaps(const Bounds& o) const { return (min.array() <= o.max.array()).all() && (o.min.array() <= max.array()).all(); }
};

// Signed distance (m) from p_S to the surface, negative inside; *grad_S (unit, outward) when non-null.
real shape_signed_distance(const ShapeGeometry& shape, const Vec3& p_S, Vec3* grad_S);

// A plane shape {x_S : normal . x_S <= distance} (its normal of any length) posed by X_WS, as
// the world half-space {x : n . x <= d} with n unit: the signed distance of x is n . x - d.
struct WorldPlane {
  Vec3 n;
  real d;
};
WorldPlane world_plane(const PlaneShape& s, const SpatialTransform& X_WS);

// Points on the surface used as contact candidates against another shape's distance field:
// vertices, points along edges and, unless the mesh is convex, across faces (4 % of the longest
// side apart). Empty for planes (unbounded).
std::vector<Vec3> shape_surface_samples(const ShapeGeometry& shape);

// Bounding box in the shape frame; infinite for planes.
Bounds shape_local_aabb(const ShapeGeometry& shape);

// Whether boxes a_S and b_S (each in its shape's frame, posed by X_WA and X_WB) are more than
// `gap` (m) apart along one of their 15 separating axes (oriented_bounds.cpp). False when
// unsure (nearly parallel edges, non-finite bounds): the pair is then left to the narrow phase.
bool boxes_apart(const Bounds& a_S, const SpatialTransform& X_WA, const Bounds& b_S, const SpatialTransform& X_WB, real gap);

// The closest points cp on segment [p0, p1] and cq on segment [q0, q1].
void closest_segment_points(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1, Vec3& cp, Vec3& cq);

// Polygon `poly` clipped by the half-space n . x <= d + tol, into `out`. Points within `tol`
// outside count as inside, so that faces flush with each other keep a stable set of corners.
void clip_polygon(const std::vector<Vec3>& poly, const Vec3& n, real d, real tol, std::vector<Vec3>& out);

// Mesh implementations (mesh_geometry.cpp).
real mesh_signed_distance(const MeshShape& mesh, const Vec3& p_S, Vec3* grad_S);
std::vector<Vec3> mesh_surface_samples(const MeshShape& mesh);
Bounds mesh_local_aabb(const MeshShape& mesh);

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

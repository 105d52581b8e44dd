// Signed distance, surface samples and bounds of primitive shapes; meshes delegate to
// mesh_geometry.cpp.

#include "collision/collision_geometry.h"

#include <algorithm>

#include <cmath>

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace {

template <class... Ts>
struct Overloaded : Ts... {
  using Ts::operator()...;
};
// the deduction guide C++20 makes implicit; clang before 17 (the fuzz build) still needs it
template <class... Ts>
Overloaded(Ts...) -> Overloaded<Ts...>;

// Closest point on the capsule's segment (local z axis) to p.
Vec3 segment_closest(real half_length, const Vec3& p) {
  return Vec3(0, 0, std::clamp(p.z(), -half_length, half_length));
}

real box_distance(const Vec3& h, const Vec3& p, Vec3* grad) {
  const Vec3 q = p.cwiseAbs() - h;
  const Vec3 outside = q.cwiseMax(real(0));
  const real out_norm = outside.norm();
  if (out_norm > 0) {
    // outside: distance to the nearest point of the box
    if (grad) *grad = (outside.array() * p.array().sign()).matrix() / out_norm;
    return out_norm;
  }
  // inside: distance to the nearest face
  int axis;
  const real d = q.maxCoeff(&axis);
  if (grad) {
    *grad = Vec3::Zero();
    (*grad)[axis] = p[axis] >= 0 ? 1 : -1;
  }
  return d;
}

}  // namespace

WorldPlane world_plane(const PlaneShape& s, const SpatialTransform& X_WS) {
  const real inverse_length = 1 / s.normal.norm();
  const Vec3 n = X_WS.R * (inverse_length * s.normal);
  return {n, inverse_length * s.distance + n.dot(X_WS.p)};
}

real shape_signed_distance(const ShapeGeometry& shape, const Vec3& p, Vec3* grad) {
  return std::visit(
      Overloaded{[&](const PlaneShape& s) {
                   // the half-space in its own frame
                   const WorldPlane plane = world_plane(s, SpatialTransform{});
                   if (grad) *grad = plane.n;
                   return plane.n.dot(p) - plane.d;
                 },
                 [&](const SphereShape& s) {
                   const Vec3 d = p - s.center;
                   const real r = d.norm();
                   if (grad) *grad = r > real(1e-12) ? Vec3(d / r) : Vec3::UnitZ();
                   return r - s.radius;
                 },
                 [&](const BoxShape& s) { return box_distance(s.half_extents, p, grad); },
                 [&](const CapsuleShape& s) {
                   const Vec3 d = p - segment_closest(s.half_length, p);
                   const real r = d.norm();
                   if (grad) *grad = r > real(1e-12) ? Vec3(d / r) : Vec3::UnitX();
                   return r - s.radius;
                 },
                 [&](const MeshShape& s) { return mesh_signed_distance(s, p, grad); }},
      shape);
}

std::vector<Vec3> shape_surface_samples(const ShapeGeometry& shape) {
  return std::visit(
      Overloaded{[](const PlaneShape&) { return std::vector<Vec3>{}; },
                 [](const SphereShape& s) {
                   // poles and a ring: only used against other shapes' fields when no analytic test applies
                   std::vector<Vec3> out;
                   for (int k = 0; k < 3; ++k)
                     for (real sign : {real(-1), real(1)}) out.push_back(s.center + sign * s.radius * Vec3::Unit(k));
                   return out;
                 },
                 [](const BoxShape& s) {
                   // corners, and points along each edge so that edge-on-face contact is caught
                   std::vector<Vec3> out;
                   const Vec3& h = s.half_extents;
                   for (int i = 0; i < 8; ++i)
                     out.emplace_back((i & 1 ? 1 : -1) * h.x(), (i & 2 ? 1 : -1) * h.y(), (i & 4 ? 1 : -1) * h.z());
                   const int kEdgeSamples = 1;
                   for (int axis = 0; axis < 3; ++axis) {
                     const int a = (axis + 1) % 3, b = (axis + 2) % 3;
                     for (real sa : {real(-1), real(1)})
                       for (real sb : {real(-1), real(1)})
                         for (int k = 1; k <= kEdgeSamples; ++k) {
                           Vec3 p;
                           p[axis] = h[axis] * (-1 + real(2) * k / (kEdgeSamples + 1));
                           p[a] = sa * h[a];
                           p[b] = sb * h[b];
                           out.push_back(p);
                         }
                   }
                   return out;
                 },
                 [](const CapsuleShape& s) {
                   return std::vector<Vec3>{Vec3(0, 0, s.half_length + s.radius), Vec3(0, 0, -s.half_length - s.radius)};
                 },
                 [](const MeshShape& s) { return mesh_surface_samples(s); }},
      shape);
}

Bounds shape_local_aabb(const ShapeGeometry& shape) {
  return std::visit(Overloaded{[](const PlaneShape&) {
                                 Bounds b;
                                 b.min = Vec3::Constant(-std::numeric_limits<real>::infinity());
                                 b.max = Vec3::Constant(std::numeric_limits<real>::infinity());
                                 return b;
                               },
                               [](const SphereShape& s) {
                                 return Bounds{s.center - Vec3::Constant(s.radius), s.center + Vec3::Constant(s.radius)};
                               },
                               [](const BoxShape& s) { return Bounds{-s.half_extents, s.half_extents}; },
                               [](const CapsuleShape& s) {
                                 const Vec3 e(s.radius, s.radius, s.radius + s.half_length);
                                 return Bounds{-e, e};
                               },
                               [](const MeshShape& s) { return mesh_local_aabb(s); }},
                    shape);
}

std::pair<Vec3, Vec3> shape_bounds(const ShapeGeometry& shape) {
  const Bounds b = shape_local_aabb(shape);
  return {b.min, b.max};
}

void closest_segment_points(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1, Vec3& cp, Vec3& cq) {
  const Vec3 d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
  const real a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  real s = 0, t = 0;
  const real eps = real(1e-12);
  if (a <= eps && e <= eps) {
    s = t = 0;
  } else if (a <= eps) {
    t = std::clamp(f / e, real(0), real(1));
  } else {
    const real c = d1.dot(r);
    if (e <= eps) {
      s = std::clamp(-c / a, real(0), real(1));
    } else {
      const real b = d1.dot(d2), denom = a * e - b * b;
      s = denom > eps ? std::clamp((b * f - c * e) / denom, real(0), real(1)) : real(0);
      t = (b * s + f) / e;
      if (t < 0) t = 0, s = std::clamp(-c / a, real(0), real(1));
      else if (t > 1) t = 1, s = std::clamp((b - c) / a, real(0), real(1));
    }
  }
  cp = p0 + d1 * s;
  cq = q0 + d2 * t;
}

void clip_polygon(const std::vector<Vec3>& poly, const Vec3& n, real d, real tol, std::vector<Vec3>& out) {
  out.clear();
  for (size_t i = 0; i < poly.size(); ++i) {
    const Vec3& p = poly[i];
    const Vec3& q = poly[(i + 1) % poly.size()];
    const real dp = n.dot(p) - d - tol, dq = n.dot(q) - d - tol;
    if (dp <= 0) out.push_back(p);
    if ((dp <= 0) != (dq <= 0)) out.push_back(p + (q - p) * (dp / (dp - dq)));
  }
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

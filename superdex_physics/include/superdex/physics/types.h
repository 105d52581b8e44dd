#pragma once
/// @file types.h
/// The value types of the API, with SuperDex's names: fixed-size vectors (Real2, Real3, Real4,
/// Real6, Int2, Int3), rotations (Quaternion, stored x, y, z, w), rigid transforms (TransformRT)
/// and the simple volumes that queries and models use (Aabb, Obb, Sphere, Box, Plane).
/// Lengths are in metres, angles in radians; each volume is expressed in the frame of whatever
/// holds it (a shape, an actor's local frame or the world), which the API names.

#include <cstdint>

#include "superdex/physics/real.h"
#include "superdex/physics/transform.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

using Real2 = Eigen::Matrix<real, 2, 1>;
using Real3 = Vec3;
using Real4 = Eigen::Matrix<real, 4, 1>;
using Real6 = Vec6;
using Int2 = Eigen::Matrix<int, 2, 1>;
using Int3 = Eigen::Matrix<int, 3, 1>;
/// A rotation as a unit quaternion; coefficients indexed x, y, z, w (Eigen's storage order).
using Quaternion = Quat;
/// A rigid transform X_AB: p_A = rotation * p_B + translation.
using TransformRT = Transform;

/// An axis-aligned box [min, max] (m). Default: the point at the origin.
struct Aabb {
  Real3 min = Real3::Zero();
  Real3 max = Real3::Zero();
  Real3 center() const { return real(0.5) * (min + max); }
  Real3 size() const { return max - min; }
  bool contains(const Real3& p) const { return (p.array() >= min.array()).all() && (p.array() <= max.array()).all(); }
  bool operator==(const Aabb& o) const { return min == o.min && max == o.max; }
};

/// An oriented box: `transform` places the box frame (its centre and axes), `half_extents` (m)
/// along the box frame's axes.
struct Obb {
  TransformRT transform;
  Real3 half_extents = Real3::Zero();
  Real3 center() const { return transform.translation; }
  Real3 size() const { return 2 * half_extents; }
  bool contains(const Real3& p) const {
    const Real3 p_B = transform.inverse() * p;
    return (p_B.array().abs() <= half_extents.array()).all();
  }
  bool operator==(const Obb& o) const {
    return transform.rotation.coeffs() == o.transform.rotation.coeffs() &&
           transform.translation == o.transform.translation && half_extents == o.half_extents;
  }
};

/// A ball of `radius` (m) about `center`.
struct Sphere {
  Real3 center = Real3::Zero();
  real radius = 0;
  bool contains(const Real3& p) const { return (p - center).squaredNorm() <= radius * radius; }
  bool operator==(const Sphere& o) const { return center == o.center && radius == o.radius; }
};

/// A box of `half_extents` (m) about `center`, its axes rotated by `rotation`.
struct Box {
  Real3 center = Real3::Zero();
  Real3 half_extents = Real3::Ones();
  Quaternion rotation = Quaternion::Identity();
  bool operator==(const Box& o) const {
    return center == o.center && half_extents == o.half_extents && rotation.coeffs() == o.rotation.coeffs();
  }
};

/// The half-space {x : normal . x <= distance} (solid below the plane); `distance` in metres
/// along `normal`.
struct Plane {
  Real3 normal = Real3::UnitY();
  real distance = 0;
  bool operator==(const Plane& o) const { return normal == o.normal && distance == o.distance; }
};

/// An RGBA colour, 8 bits a channel.
struct Color {
  std::uint8_t r = 255, g = 255, b = 255, a = 255;
  bool operator==(const Color& o) const { return r == o.r && g == o.g && b == o.b && a == o.a; }
};

/// Rigid composition X_AC = X_AB * X_BC without renormalising the rotation (exact for unit
/// quaternions, and the form users compose by hand).
inline TransformRT compose(const TransformRT& X_AB, const TransformRT& X_BC) {
  return {X_AB.rotation * X_BC.rotation, X_AB.rotation * X_BC.translation + X_AB.translation};
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

#pragma once
/// @file transform.h
/// Rigid transforms. `Transform X_AB` maps coordinates in frame B to frame A:
/// p_A = X_AB * p_B = R_AB p_B + p_AB.

#include <cmath>
#include <limits>

#include "superdex/physics/real.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

/// `q` scaled to unit length, or `q` itself when it is of unit length within round-off already
/// (so that a normalized quaternion given to the engine reads back bit for bit).
inline Quat unit_quaternion(const Quat& q) {
  return std::abs(q.squaredNorm() - 1) > 8 * std::numeric_limits<real>::epsilon() ? q.normalized() : q;
}

/// A rotation (unit quaternion, stored x, y, z, w) and a translation in metres.
struct Transform {
  Quat rotation = Quat::Identity();
  Vec3 translation = Vec3::Zero();

  static Transform identity() { return {}; }

  /// Composition: (X_AB * X_BC) = X_AC.
  Transform operator*(const Transform& X_BC) const {
    return {(rotation * X_BC.rotation).normalized(), rotation * X_BC.translation + translation};
  }
  /// Maps a point of frame B into frame A.
  Vec3 operator*(const Vec3& p_B) const { return rotation * p_B + translation; }
  /// Exact equality of the stored rotation coefficients and translation.
  bool operator==(const Transform& o) const { return rotation.coeffs() == o.rotation.coeffs() && translation == o.translation; }
  /// X_BA from X_AB.
  Transform inverse() const {
    const Quat q_inv = rotation.conjugate();
    return {q_inv, -(q_inv * translation)};
  }
};

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

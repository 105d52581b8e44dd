#pragma once
// Spatial (6D) vector algebra. Ordering is linear first, angular second, for motions
// V = (v, w) and forces F = (f, n), matching the API's Jacobian rows and Pinocchio.
// A motion or force "in frame B" is expressed in B's axes and taken at B's origin.

#include "superdex/physics/real.h"
#include "superdex/physics/transform.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

inline Mat3 skew(const Vec3& a) {
  Mat3 s;
  s << 0, -a.z(), a.y(), a.z(), 0, -a.x(), -a.y(), a.x(), 0;
  return s;
}

// A rigid transform X_AB kept with its rotation matrix for repeated use in the recursions.
struct SpatialTransform {
  Mat3 R = Mat3::Identity();  // R_AB
  Vec3 p = Vec3::Zero();      // p_AB, B's origin in A

  static SpatialTransform from(const Transform& X) {
    return {X.rotation.toRotationMatrix(), X.translation};
  }
  SpatialTransform operator*(const SpatialTransform& X_BC) const {
    return {R * X_BC.R, R * X_BC.p + p};
  }
  SpatialTransform inverse() const { return {R.transpose(), -(R.transpose() * p)}; }

  // Motion in B -> motion in A.
  Vec6 apply_motion(const Vec6& V_B) const {
    Vec6 V_A;
    V_A.tail<3>() = R * V_B.tail<3>();
    V_A.head<3>() = R * V_B.head<3>() + p.cross(V_A.tail<3>());
    return V_A;
  }
  // Motion in A -> motion in B (applies the inverse transform).
  Vec6 apply_motion_inverse(const Vec6& V_A) const {
    Vec6 V_B;
    V_B.tail<3>() = R.transpose() * V_A.tail<3>();
    V_B.head<3>() = R.transpose() * (V_A.head<3>() - p.cross(V_A.tail<3>()));
    return V_B;
  }
  // Force in B -> force in A.
  Vec6 apply_force(const Vec6& F_B) const {
    Vec6 F_A;
    F_A.head<3>() = R * F_B.head<3>();
    F_A.tail<3>() = R * F_B.tail<3>() + p.cross(F_A.head<3>());
    return F_A;
  }
  // 6x6 matrix acting on motions in B, giving motions in A.
  Mat6 motion_matrix() const {
    Mat6 X = Mat6::Zero();
    X.topLeftCorner<3, 3>() = R;
    X.topRightCorner<3, 3>() = skew(p) * R;
    X.bottomRightCorner<3, 3>() = R;
    return X;
  }
  // 6x6 matrix acting on forces in B, giving forces in A (the inverse transpose of motion_matrix).
  Mat6 force_matrix() const {
    Mat6 X = Mat6::Zero();
    X.topLeftCorner<3, 3>() = R;
    X.bottomLeftCorner<3, 3>() = skew(p) * R;
    X.bottomRightCorner<3, 3>() = R;
    return X;
  }
};

// Motion cross product V x M (derivative of motion M moving with velocity V).
inline Vec6 cross_motion(const Vec6& V, const Vec6& M) {
  const auto v = V.head<3>(), w = V.tail<3>();
  Vec6 out;
  out.head<3>() = w.cross(M.head<3>()) + v.cross(M.tail<3>());
  out.tail<3>() = w.cross(M.tail<3>());
  return out;
}

// Force cross product V x* F.
inline Vec6 cross_force(const Vec6& V, const Vec6& F) {
  const auto v = V.head<3>(), w = V.tail<3>();
  Vec6 out;
  out.head<3>() = w.cross(F.head<3>());
  out.tail<3>() = w.cross(F.tail<3>()) + v.cross(F.head<3>());
  return out;
}

// Spatial inertia of a body about its frame origin, in its frame.
struct SpatialInertia {
  real mass = 0;
  Vec3 com = Vec3::Zero();             // centre of mass in the body frame
  Mat3 inertia_com = Mat3::Zero();     // rotational inertia about the COM

  // Momentum F = I V of a body moving with V (both in the body frame).
  Vec6 apply(const Vec6& V) const {
    const Vec3 h = mass * (V.head<3>() - com.cross(V.tail<3>()));
    Vec6 F;
    F.head<3>() = h;
    F.tail<3>() = inertia_com * V.tail<3>() + com.cross(h);
    return F;
  }
  Mat6 matrix() const {
    const Mat3 c = skew(com);
    Mat6 I;
    I.topLeftCorner<3, 3>() = mass * Mat3::Identity();
    I.topRightCorner<3, 3>() = -mass * c;
    I.bottomLeftCorner<3, 3>() = mass * c;
    I.bottomRightCorner<3, 3>() = inertia_com - mass * c * c;
    return I;
  }
};

// Views of 3 and 4 consecutive coordinates.
inline Eigen::Map<Vec3> map3(real* p) { return Eigen::Map<Vec3>(p); }
inline Eigen::Map<Eigen::Matrix<real, 4, 1>> map4(real* p) { return Eigen::Map<Eigen::Matrix<real, 4, 1>>(p); }

// Rotation by the rotation vector `phi` (axis * angle, rad).
inline Quat quat_exp(const Vec3& phi) {
  const real angle = phi.norm();
  if (angle < real(1e-8)) {
    Quat q(real(1), phi.x() / 2, phi.y() / 2, phi.z() / 2);
    return q.normalized();
  }
  return Quat(Eigen::AngleAxis<real>(angle, phi / angle));
}

// Rotation vector of `q`, with angle in [0, pi].
inline Vec3 quat_log(const Quat& q_in) {
  Quat q = q_in.normalized();
  if (q.w() < 0) q.coeffs() = -q.coeffs();
  const real s = q.vec().norm();
  if (s < real(1e-8)) return 2 * q.vec();
  const real angle = 2 * std::atan2(s, q.w());
  return q.vec() * (angle / s);
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

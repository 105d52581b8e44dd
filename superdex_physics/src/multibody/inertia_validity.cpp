// Physical validity of rotational inertias.

#include "superdex/physics/inertia.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cstdio>

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace {

std::string num(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", x);
  return buf;
}

}  // namespace

std::optional<std::string> inertia_defect(const Mat3& I) {
  if (!I.allFinite()) return "must be finite";
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(I.cast<double>());
  const Eigen::Vector3d l = eig.eigenvalues();  // ascending
  if (l.minCoeff() <= 0) return "must be positive definite (principal moments " + num(l[0]) + ", " + num(l[1]) + ", " + num(l[2]) + ")";
  if (l[0] + l[1] < l[2] - 1e-6 * l[2])
    return "is not physically valid: principal moments violate the triangle inequality (" + num(l[0]) + " + " + num(l[1]) +
           " < " + num(l[2]) + ")";
  return std::nullopt;
}

Mat3 nearest_physical_inertia(const Mat3& I) {
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(I.cast<double>());
  Eigen::Vector3d l = eig.eigenvalues();
  const double floor = l[2] > 0 ? 1e-6 * l[2] : 1e-9;
  for (int k = 0; k < 3; ++k) l[k] = std::max(l[k], floor);
  // raising to a floor keeps the ascending order, so l[2] is still the largest
  l[2] = std::min(l[2], l[0] + l[1]);
  const Eigen::Matrix3d V = eig.eigenvectors();
  return (V * l.asDiagonal() * V.transpose()).cast<real>();
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

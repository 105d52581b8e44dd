#pragma once
/// @file real.h
/// The scalar type of this build and the fixed-size Eigen types built on it.
///
/// The engine is compiled twice: with SUPERDEX_USE_DOUBLE defined, `real` is double,
/// otherwise float. Each build lives in its own inline namespace so that both can be
/// linked into one program without symbol clashes.

#include <Eigen/Core>
#include <Eigen/Geometry>

#ifdef SUPERDEX_USE_DOUBLE
#define SUPERDEX_REAL_NAMESPACE real_double
#else
#define SUPERDEX_REAL_NAMESPACE real_float
#endif

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

#ifdef SUPERDEX_USE_DOUBLE
using real = double;
#else
using real = float;
#endif

/// True when this build computes in double precision.
constexpr bool kUsesDoublePrecision = sizeof(real) == sizeof(double);

using Vec3 = Eigen::Matrix<real, 3, 1>;
using Vec6 = Eigen::Matrix<real, 6, 1>;
using Mat3 = Eigen::Matrix<real, 3, 3>;
using Mat6 = Eigen::Matrix<real, 6, 6>;
using Quat = Eigen::Quaternion<real>;
using VecX = Eigen::Matrix<real, Eigen::Dynamic, 1>;
using MatX = Eigen::Matrix<real, Eigen::Dynamic, Eigen::Dynamic>;
/// Row-major dynamic matrix, the layout of Jacobians handed to users.
using MatXR = Eigen::Matrix<real, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

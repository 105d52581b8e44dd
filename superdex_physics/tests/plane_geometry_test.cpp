/// @file plane_geometry_test.cpp
/// A plane shape is the half-space {x : normal . x <= distance} whatever its normal's length:
/// its signed distance in the shape frame and its world half-space (the narrow phase's and the
/// soft contacts') agree with the analytic distance to that plane, for a unit normal and for a
/// longer one.

#include <gtest/gtest.h>

#include <cmath>

#include "collision/collision_geometry.h"

namespace superdex::physics::test {
namespace {

TEST(PlaneGeometry, DistanceAndWorldHalfSpaceFollowTheShapeWhateverTheNormalLength) {
  // the plane z = 0.3 in the shape frame, written with normals of length 1 and 2.5
  const Vec3 p_S(0.4, -1.2, 0.75);
  const SpatialTransform X_WS{Quat(Eigen::AngleAxis<real>(0.6, Vec3(1, 2, -0.5).normalized())).toRotationMatrix(),
                              Vec3(0.2, -0.7, 1.1)};
  const Vec3 p_W = X_WS.R * p_S + X_WS.p;
  for (const double length : {1.0, 2.5}) {
    const PlaneShape plane{Vec3(0, 0, length), 0.3 * length};
    Vec3 grad_S;
    EXPECT_NEAR(shape_signed_distance(plane, p_S, &grad_S), 0.75 - 0.3, 1e-12) << "normal length " << length;
    EXPECT_NEAR((grad_S - Vec3::UnitZ()).norm(), 0, 1e-12);
    const WorldPlane world = world_plane(plane, X_WS);
    EXPECT_NEAR(world.n.norm(), 1, 1e-12);
    EXPECT_NEAR((world.n - X_WS.R.col(2)).norm(), 0, 1e-12);
    EXPECT_NEAR(world.n.dot(p_W) - world.d, 0.75 - 0.3, 1e-12) << "normal length " << length;
  }
}

}  // namespace
}  // namespace superdex::physics::test

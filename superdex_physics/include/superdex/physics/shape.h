#pragma once
/// @file shape.h
/// Collision and mass-property shapes. Primitive shapes are defined in the frame of the
/// body that carries them; all lengths in metres.

#include <string>
#include <variant>

#include "superdex/physics/real.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

/// Infinite half-space {x : normal . x <= distance} (solid below the plane).
struct PlaneShape {
  Vec3 normal = Vec3::UnitZ();
  real distance = 0;
};
/// Solid ball of `radius` centred at `center`.
struct SphereShape {
  Vec3 center = Vec3::Zero();
  real radius = 0;
};
/// Solid box centred at the origin with the given half extents along x, y, z.
struct BoxShape {
  Vec3 half_extents = Vec3::Zero();
};
/// Solid capsule centred at the origin, its segment along the local z axis from
/// -half_length to +half_length, swept by a ball of `radius`.
struct CapsuleShape {
  real radius = 0;
  real half_length = 0;
};

/// How a body's collision geometry is derived from its shape.
enum class ColliderType { Auto, None, Sphere, Box, Plane, Mesh, Sdf };

/// The geometry of one shape.
using ShapeGeometry = std::variant<PlaneShape, SphereShape, BoxShape, CapsuleShape>;

/// Mass properties of a solid of uniform density: mass (kg), centre of mass and
/// rotational inertia about the centre of mass (kg m^2), in the shape's frame.
struct MassProperties {
  real mass = 0;
  Vec3 center_of_mass = Vec3::Zero();
  Mat3 inertia_about_com = Mat3::Zero();
};

/// Volume in m^3; throws superdex::Error for a plane (unbounded).
real shape_volume(const ShapeGeometry& shape);
/// Mass properties of the shape filled with `density` (kg/m^3).
/// Throws superdex::Error for unbounded shapes.
MassProperties shape_mass_properties(const ShapeGeometry& shape, real density);
/// Checks the parameters (positive radii, finite values, non-zero normal); throws
/// superdex::Error naming `where` and the defect.
void validate_shape(const ShapeGeometry& shape, const std::string& where);

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

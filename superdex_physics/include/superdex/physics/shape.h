#pragma once
/// @file shape.h
/// Collision and mass-property shapes. Primitive shapes are defined in the frame of the
/// body that carries them; all lengths in metres.

#include <array>
#include <memory>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "superdex/physics/params/contact_params.h"
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

/// A triangle surface mesh: vertices (m) and triangles as vertex indices, counter-clockwise
/// seen from outside when the mesh is closed.
struct TriangleMesh {
  std::vector<Vec3> vertices;
  std::vector<std::array<int, 3>> triangles;
};

/// Signed distances (m, negative inside) sampled on a regular grid spanning
/// [grid_min, grid_max]; `values` has size[0] * size[1] * size[2] entries, x fastest
/// (index = i + size[0] * (j + size[1] * k)).
struct SdfGrid {
  Vec3 grid_min = Vec3::Zero();
  Vec3 grid_max = Vec3::Zero();
  std::array<int, 3> size{0, 0, 0};
  std::vector<real> values;
};

struct ConvexFaces;  // a convex mesh's corners and polygon faces (engine-internal)

/// A mesh shape: a triangle mesh (convex or not) with, when it is closed, a signed-distance
/// grid used for contact. Shared, immutable data.
struct MeshShape {
  std::shared_ptr<const TriangleMesh> mesh;
  std::shared_ptr<const SdfGrid> sdf;  ///< null for open meshes (they only offer surface samples)
  bool convex = false;
  std::string source;                  ///< file it came from, for messages
  std::shared_ptr<const ConvexFaces> faces;  ///< set for convex meshes: their contact is GJK/EPA and face clipping
};

/// What the contact solve uses of a surface's ContactParams. A pair combines them: friction
/// sqrt(mu_a mu_b), stiffness in series, dissipation time scale the larger.
struct ContactMaterial {
  /// Coulomb friction coefficient (>= 0).
  real friction = real(0.5);
  /// Normal stiffness in N/m; 0 means rigid (the solver's near-rigid regularisation).
  real stiffness = 0;
  /// Dissipation time scale in s (normal damping = stiffness * time scale); used with a stiffness.
  real dissipation_time = 0;
};

/// The contact solve's part of ContactParams.
ContactMaterial contact_material(const ContactParams& params);

/// A tetrahedral mesh for soft bodies: nodes (m) and tetrahedra as node indices, positively
/// oriented (det[x1 - x0, x2 - x0, x3 - x0] > 0).
struct TetMesh {
  std::vector<Vec3> nodes;
  std::vector<std::array<int, 4>> tets;
  /// Optional per-element elastic parameters (one per tetrahedron, or one for all), as read
  /// from a .mochi.h5 `material/` group: Young's modulus (Pa) and Poisson's ratio.
  std::vector<real> youngs_modulus;
  std::vector<real> poisson_ratio;
};

/// The geometry of one shape.
using ShapeGeometry = std::variant<PlaneShape, SphereShape, BoxShape, CapsuleShape, MeshShape>;

/// Mass properties of a solid of uniform density: mass (kg), centre of mass and
/// rotational inertia about the centre of mass (kg m^2), in the shape's frame.
struct MassProperties {
  real mass = 0;
  Vec3 center_of_mass = Vec3::Zero();
  Mat3 inertia_about_com = Mat3::Zero();
};

/// Bounds (min, max) of the shape in its frame (m); infinite for a plane.
std::pair<Vec3, Vec3> shape_bounds(const ShapeGeometry& shape);
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

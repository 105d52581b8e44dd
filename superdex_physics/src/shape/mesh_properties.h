#pragma once
// Volume, mass properties and validation of mesh shapes, for mass_properties.cpp.

#include <string>

#include "superdex/physics/shape.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

// Enclosed volume (m^3); throws superdex::Error naming the mesh source if it is not closed.
real mesh_volume(const MeshShape& mesh);

// Exact mass properties of the enclosed solid at `density` (kg/m^3), by the divergence theorem
// (a sum of signed tetrahedra): centre of mass and inertia about it, in the shape frame.
// Throws superdex::Error naming the mesh source if it is not closed.
MassProperties mesh_mass_properties(const MeshShape& mesh, real density);

// Checks the mesh (check_triangle_mesh) and the grid (size, values, finite, min < max);
// throws superdex::Error "<where>: ..." naming the defect.
void validate_mesh_shape(const MeshShape& mesh, const std::string& where);

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

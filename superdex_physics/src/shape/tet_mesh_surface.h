#pragma once
// The boundary surface of a tetrahedral mesh: the faces that belong to one tetrahedron only,
// counter-clockwise seen from outside (for positively oriented tetrahedra).

#include <array>
#include <string>
#include <vector>

#include "superdex/physics/shape.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

// Boundary faces as node indices of the tet mesh, in the order of their sorted node triples.
std::vector<std::array<int, 3>> tet_boundary_faces(const std::vector<std::array<int, 4>>& tets);

// The boundary as a compact triangle mesh: only the nodes on the boundary, in increasing order of
// their tet-mesh index (`surface_nodes` receives those indices when non-null).
TriangleMesh tet_boundary_mesh(const TetMesh& mesh, std::vector<int>* surface_nodes = nullptr);

// A rigid mesh shape of the boundary (closed, so with a distance grid).
MeshShape tet_mesh_boundary_shape(const TetMesh& mesh, const std::string& source);

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

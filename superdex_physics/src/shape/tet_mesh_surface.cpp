// Boundary surfaces of tetrahedral meshes (tet_mesh_surface.h).

#include "shape/tet_mesh_surface.h"

#include <algorithm>
#include <map>

#include "superdex/physics/mesh_shape.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

std::vector<std::array<int, 3>> tet_boundary_faces(const std::vector<std::array<int, 4>>& tets) {
  // each tetrahedron's faces, outward for a positively oriented tetrahedron
  static constexpr int kFaces[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
  std::map<std::array<int, 3>, std::pair<int, std::array<int, 3>>> faces;  // sorted -> (count, oriented)
  for (const auto& tet : tets)
    for (const auto& f : kFaces) {
      const std::array<int, 3> oriented{tet[f[0]], tet[f[1]], tet[f[2]]};
      std::array<int, 3> key = oriented;
      std::sort(key.begin(), key.end());
      auto& entry = faces[key];
      entry.first += 1;
      entry.second = oriented;
    }
  std::vector<std::array<int, 3>> out;
  for (const auto& [key, entry] : faces)
    if (entry.first == 1) out.push_back(entry.second);
  return out;
}

TriangleMesh tet_boundary_mesh(const TetMesh& mesh, std::vector<int>* surface_nodes) {
  const std::vector<std::array<int, 3>> faces = tet_boundary_faces(mesh.tets);
  std::vector<int> index(mesh.nodes.size(), -1);
  for (const auto& f : faces)
    for (int i : f) index[i] = 0;
  TriangleMesh out;
  std::vector<int> nodes;
  for (size_t i = 0; i < index.size(); ++i)
    if (index[i] == 0) {
      index[i] = static_cast<int>(out.vertices.size());
      out.vertices.push_back(mesh.nodes[i]);
      nodes.push_back(static_cast<int>(i));
    }
  for (const auto& f : faces) out.triangles.push_back({index[f[0]], index[f[1]], index[f[2]]});
  if (surface_nodes) *surface_nodes = std::move(nodes);
  return out;
}

MeshShape tet_mesh_boundary_shape(const TetMesh& mesh, const std::string& source) {
  return make_mesh_shape(tet_boundary_mesh(mesh), source);
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

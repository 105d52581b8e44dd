#pragma once
// Between a model's flat MeshData (model.h) and the engine's meshes: node positions as Vec3,
// elements as K node indices. No checks: callers validate the MeshData first.

#include <array>
#include <vector>

#include "superdex/physics/model.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

// The mesh's node positions (m).
inline std::vector<Vec3> mesh_nodes(const MeshData& mesh) {
  std::vector<Vec3> nodes(static_cast<size_t>(mesh.num_nodes()));
  for (size_t i = 0; i < nodes.size(); ++i) nodes[i] = Vec3(mesh.coordinates[3 * i], mesh.coordinates[3 * i + 1], mesh.coordinates[3 * i + 2]);
  return nodes;
}

// The mesh's elements, K node indices each (K = nodes_per_element).
template <size_t K>
std::vector<std::array<int, K>> mesh_elements(const MeshData& mesh) {
  std::vector<std::array<int, K>> out(mesh.connectivity.size() / K);
  for (size_t e = 0; e < out.size(); ++e)
    for (size_t k = 0; k < K; ++k) out[e][k] = mesh.connectivity[K * e + k];
  return out;
}

// MeshData of nodes and K-node elements.
template <size_t K>
MeshData mesh_data(const std::vector<Vec3>& nodes, const std::vector<std::array<int, K>>& elements) {
  MeshData m;
  m.nodes_per_element = static_cast<int>(K);
  m.coordinates.reserve(3 * nodes.size());
  for (const Vec3& p : nodes) m.coordinates.insert(m.coordinates.end(), {p.x(), p.y(), p.z()});
  m.connectivity.reserve(K * elements.size());
  for (const auto& e : elements) m.connectivity.insert(m.connectivity.end(), e.begin(), e.end());
  return m;
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

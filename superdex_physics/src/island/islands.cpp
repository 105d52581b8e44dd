// Union-find over bodies linked by contacts and constraints.

#include "island/islands.h"

#include <numeric>

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

std::vector<Island> build_islands(const std::vector<int>& num_dofs, const std::vector<Contact>& contacts,
                                  const std::vector<int>& soft_free_dofs, const std::vector<SoftContact>& soft_contacts,
                                  const std::vector<std::array<int, 2>>& constraints) {
  std::vector<Island> islands;
  IslandScratch scratch;
  build_islands(num_dofs, contacts, soft_free_dofs, soft_contacts, constraints, islands, scratch);
  return islands;
}

void build_islands(const std::vector<int>& num_dofs, const std::vector<Contact>& contacts, const std::vector<int>& soft_free_dofs,
                   const std::vector<SoftContact>& soft_contacts, const std::vector<std::array<int, 2>>& constraints,
                   std::vector<Island>& islands, IslandScratch& scratch) {
  // nodes: articulations, then soft bodies
  const int na = static_cast<int>(num_dofs.size());
  const int n = na + static_cast<int>(soft_free_dofs.size());
  std::vector<int>& dofs = scratch.dofs;
  dofs.assign(num_dofs.begin(), num_dofs.end());
  dofs.insert(dofs.end(), soft_free_dofs.begin(), soft_free_dofs.end());
  std::vector<int>& parent = scratch.parent;
  parent.resize(n);
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  auto join = [&](int a, int b) {
    if (dofs[a] == 0 || dofs[b] == 0) return;
    const int ra = find(a), rb = find(b);
    if (ra != rb) parent[std::max(ra, rb)] = std::min(ra, rb);
  };
  for (const Contact& c : contacts) join(c.body_a, c.body_b);
  for (const SoftContact& c : soft_contacts) join(na + c.soft, c.body);
  for (const auto& [a, b] : constraints)
    if (a >= 0 && b >= 0) join(a, b);
  // islands ordered by their smallest node, so the result is deterministic; the islands' lists
  // keep their storage from the last call
  std::vector<int>& index_of_root = scratch.index_of_root;
  index_of_root.assign(n, -1);
  size_t count = 0;
  auto island_of = [&](int root) -> Island& {
    if (index_of_root[root] < 0) {
      index_of_root[root] = static_cast<int>(count++);
      if (islands.size() < count) islands.emplace_back();
      Island& fresh = islands[count - 1];
      fresh.bodies.clear();
      fresh.contacts.clear();
      fresh.soft_bodies.clear();
      fresh.soft_contacts.clear();
      fresh.constraints.clear();
    }
    return islands[index_of_root[root]];
  };
  for (int b = 0; b < n; ++b) {
    if (dofs[b] == 0) continue;
    Island& island = island_of(find(b));
    if (b < na) island.bodies.push_back(b);
    else island.soft_bodies.push_back(b - na);
  }
  islands.resize(count);
  for (size_t k = 0; k < contacts.size(); ++k) {
    const Contact& c = contacts[k];
    const int body = dofs[c.body_a] > 0 ? c.body_a : c.body_b;
    if (dofs[body] == 0) continue;
    islands[index_of_root[find(body)]].contacts.push_back(static_cast<int>(k));
  }
  for (size_t k = 0; k < soft_contacts.size(); ++k) {
    const int node = na + soft_contacts[k].soft;
    if (dofs[node] == 0) continue;
    islands[index_of_root[find(node)]].soft_contacts.push_back(static_cast<int>(k));
  }
  for (size_t k = 0; k < constraints.size(); ++k) {
    const auto [a, b] = constraints[k];
    const int body = a >= 0 && dofs[a] > 0 ? a : b;
    if (body < 0 || dofs[body] == 0) continue;
    islands[index_of_root[find(body)]].constraints.push_back(static_cast<int>(k));
  }
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

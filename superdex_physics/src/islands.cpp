// Union-find over bodies linked by contacts.

#include "islands.h"

#include <map>
#include <numeric>

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

std::vector<Island> build_islands(const std::vector<int>& num_dofs, const std::vector<Contact>& contacts,
                                  const std::vector<int>& soft_free_dofs, const std::vector<SoftContact>& soft_contacts) {
  // nodes: articulations, then soft bodies
  const int na = static_cast<int>(num_dofs.size());
  const int n = na + static_cast<int>(soft_free_dofs.size());
  std::vector<int> dofs = num_dofs;
  dofs.insert(dofs.end(), soft_free_dofs.begin(), soft_free_dofs.end());
  std::vector<int> parent(n);
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
  // islands ordered by their smallest node, so the result is deterministic
  std::map<int, int> index_of_root;
  std::vector<Island> islands;
  for (int b = 0; b < n; ++b) {
    if (dofs[b] == 0) continue;
    auto [it, inserted] = index_of_root.emplace(find(b), static_cast<int>(islands.size()));
    if (inserted) islands.emplace_back();
    if (b < na) islands[it->second].bodies.push_back(b);
    else islands[it->second].soft_bodies.push_back(b - na);
  }
  for (size_t k = 0; k < contacts.size(); ++k) {
    const Contact& c = contacts[k];
    const int body = dofs[c.body_a] > 0 ? c.body_a : c.body_b;
    if (dofs[body] == 0) continue;
    islands[index_of_root.at(find(body))].contacts.push_back(static_cast<int>(k));
  }
  for (size_t k = 0; k < soft_contacts.size(); ++k) {
    const int node = na + soft_contacts[k].soft;
    if (dofs[node] == 0) continue;
    islands[index_of_root.at(find(node))].soft_contacts.push_back(static_cast<int>(k));
  }
  return islands;
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

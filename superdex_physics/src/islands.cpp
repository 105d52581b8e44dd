// Union-find over bodies linked by contacts.

#include "islands.h"

#include <map>
#include <numeric>

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

std::vector<Island> build_islands(const std::vector<int>& num_dofs, const std::vector<Contact>& contacts) {
  const int n = static_cast<int>(num_dofs.size());
  std::vector<int> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  for (const Contact& c : contacts)
    if (num_dofs[c.body_a] > 0 && num_dofs[c.body_b] > 0) {
      const int ra = find(c.body_a), rb = find(c.body_b);
      if (ra != rb) parent[std::max(ra, rb)] = std::min(ra, rb);
    }
  // islands ordered by their smallest body, so the result is deterministic
  std::map<int, int> index_of_root;
  std::vector<Island> islands;
  for (int b = 0; b < n; ++b) {
    if (num_dofs[b] == 0) continue;
    const int root = find(b);
    auto [it, inserted] = index_of_root.emplace(root, static_cast<int>(islands.size()));
    if (inserted) islands.emplace_back();
    islands[it->second].bodies.push_back(b);
  }
  for (size_t k = 0; k < contacts.size(); ++k) {
    const Contact& c = contacts[k];
    const int body = num_dofs[c.body_a] > 0 ? c.body_a : c.body_b;
    if (num_dofs[body] == 0) continue;
    islands[index_of_root.at(find(body))].contacts.push_back(static_cast<int>(k));
  }
  return islands;
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

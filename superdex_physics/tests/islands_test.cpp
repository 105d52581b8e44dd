/// @file islands_test.cpp
/// Islands: the bodies with DOFs that contacts and constraints connect, against an independent
/// reference (breadth-first search over the graph of contacts and constraints), for random scenes; and the same islands when
/// the output storage is reused from a call on a different scene (as a scene's step workspace
/// reuses it from step to step).

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <queue>
#include <random>

#include "island/islands.h"

namespace superdex::physics {
namespace {

// Nodes: articulations 0..na-1, then soft bodies. Islands as sorted node lists, ordered by their
// smallest node; contacts listed by island in ascending order.
struct Reference {
  std::vector<std::vector<int>> nodes, contacts, soft_contacts, constraints;
};

Reference reference_islands(const std::vector<int>& dofs_a, const std::vector<Contact>& contacts, const std::vector<int>& dofs_s,
                            const std::vector<SoftContact>& soft_contacts, const std::vector<std::array<int, 2>>& constraints) {
  const int na = static_cast<int>(dofs_a.size()), n = na + static_cast<int>(dofs_s.size());
  auto dofs = [&](int node) { return node < na ? dofs_a[node] : dofs_s[node - na]; };
  std::vector<std::vector<int>> adjacent(n);
  auto link = [&](int a, int b) {
    if (dofs(a) > 0 && dofs(b) > 0) adjacent[a].push_back(b), adjacent[b].push_back(a);
  };
  for (const Contact& c : contacts) link(c.body_a, c.body_b);
  for (const SoftContact& c : soft_contacts) link(na + c.soft, c.body);
  // a constraint with the world (-1) links nothing
  for (const auto& [a, b] : constraints)
    if (a >= 0 && b >= 0) link(a, b);
  Reference ref;
  std::vector<int> island_of(n, -1);
  for (int start = 0; start < n; ++start) {
    if (dofs(start) == 0 || island_of[start] >= 0) continue;
    const int id = static_cast<int>(ref.nodes.size());
    ref.nodes.emplace_back();
    std::queue<int> open;
    open.push(start);
    island_of[start] = id;
    while (!open.empty()) {
      const int x = open.front();
      open.pop();
      ref.nodes[id].push_back(x);
      for (int y : adjacent[x])
        if (island_of[y] < 0) island_of[y] = id, open.push(y);
    }
    std::sort(ref.nodes[id].begin(), ref.nodes[id].end());
  }
  ref.contacts.resize(ref.nodes.size());
  ref.soft_contacts.resize(ref.nodes.size());
  ref.constraints.resize(ref.nodes.size());
  for (size_t k = 0; k < contacts.size(); ++k) {
    const int body = dofs(contacts[k].body_a) > 0 ? contacts[k].body_a : contacts[k].body_b;
    if (dofs(body) > 0) ref.contacts[island_of[body]].push_back(static_cast<int>(k));
  }
  for (size_t k = 0; k < soft_contacts.size(); ++k) {
    const int node = na + soft_contacts[k].soft;
    if (dofs(node) > 0) ref.soft_contacts[island_of[node]].push_back(static_cast<int>(k));
  }
  for (size_t k = 0; k < constraints.size(); ++k) {
    // in the island of a side with DOFs; none when neither has any
    for (int body : constraints[k]) {
      if (body >= 0 && dofs(body) > 0) {
        ref.constraints[island_of[body]].push_back(static_cast<int>(k));
        break;
      }
    }
  }
  return ref;
}

void expect_matches(const std::vector<Island>& islands, const Reference& ref, int na, int trial) {
  ASSERT_EQ(islands.size(), ref.nodes.size()) << "trial " << trial;
  for (size_t k = 0; k < islands.size(); ++k) {
    std::vector<int> nodes = islands[k].bodies;
    for (int s : islands[k].soft_bodies) nodes.push_back(na + s);
    EXPECT_EQ(nodes, ref.nodes[k]) << "trial " << trial << ", island " << k;
    EXPECT_EQ(islands[k].contacts, ref.contacts[k]) << "trial " << trial << ", island " << k;
    EXPECT_EQ(islands[k].soft_contacts, ref.soft_contacts[k]) << "trial " << trial << ", island " << k;
    EXPECT_EQ(islands[k].constraints, ref.constraints[k]) << "trial " << trial << ", island " << k;
  }
}

TEST(Islands, MatchConnectedComponentsAndReuseStorageAcrossScenes) {
  std::mt19937 rng(5);
  auto uniform = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
  std::vector<Island> reused;  // kept across the trials, as the step workspace keeps it
  IslandScratch scratch;
  for (int trial = 0; trial < 300; ++trial) {
    const int na = uniform(1, 12), ns = uniform(0, 3);
    std::vector<int> dofs_a(na), dofs_s(ns);
    for (int& d : dofs_a) d = uniform(0, 3) == 0 ? 0 : uniform(1, 7);  // some static bodies
    for (int& d : dofs_s) d = uniform(0, 4) == 0 ? 0 : 3 * uniform(1, 50);
    std::vector<Contact> contacts(uniform(0, 2 * na));
    for (Contact& c : contacts) c.body_a = uniform(0, na - 1), c.body_b = uniform(0, na - 1);
    std::vector<SoftContact> soft_contacts(ns > 0 ? uniform(0, 6) : 0);
    for (SoftContact& c : soft_contacts) c.soft = uniform(0, ns - 1), c.body = uniform(0, na - 1);
    // constraints between bodies, or between a body and the world (-1)
    std::vector<std::array<int, 2>> constraints(uniform(0, na));
    for (auto& c : constraints) c = {uniform(-1, na - 1), uniform(-1, na - 1)};
    const Reference ref = reference_islands(dofs_a, contacts, dofs_s, soft_contacts, constraints);
    expect_matches(build_islands(dofs_a, contacts, dofs_s, soft_contacts, constraints), ref, na, trial);
    build_islands(dofs_a, contacts, dofs_s, soft_contacts, constraints, reused, scratch);
    expect_matches(reused, ref, na, trial);
  }
}

}  // namespace
}  // namespace superdex::physics

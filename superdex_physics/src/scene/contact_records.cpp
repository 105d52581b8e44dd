// The step's contact results (s.contacts), ordered by their links (body_a, link_a, body_b,
// link_b): first the soft contacts (side a is the soft body, body index -1 - soft index), then the
// rigid ones in the contact list's order, which the broad phase made that order.

#include <algorithm>
#include <tuple>

#include "scene/step_stages.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

void contact_records(Step& step) {
  SceneData& s = step.s;
  StepWorkspace& ws = step.ws;
  const std::vector<Island>& islands = ws.islands;
  const std::vector<Contact>& contacts = ws.contacts;
  const std::vector<SoftContact>& soft_contacts = step.soft_contacts;
  const std::vector<IslandSolution>& solutions = ws.solutions;
  std::vector<SoftContactRecordKey>& soft_keys = ws.soft_record_keys;
  std::vector<std::pair<int, int>>& place = ws.record_places;
  soft_keys.clear();
  place.assign(contacts.size(), {-1, -1});
  for (size_t k = 0; k < islands.size(); ++k) {
    for (size_t j = 0; j < islands[k].contacts.size(); ++j) place[islands[k].contacts[j]] = {static_cast<int>(k), static_cast<int>(j)};
    for (size_t j = 0; j < islands[k].soft_contacts.size(); ++j) {
      const SoftContact& c = soft_contacts[islands[k].soft_contacts[j]];
      soft_keys.push_back({{-1 - c.soft, c.nodes[0], c.body, c.link}, static_cast<int>(k), static_cast<int>(j)});
    }
  }
  std::sort(soft_keys.begin(), soft_keys.end(), [](const SoftContactRecordKey& x, const SoftContactRecordKey& y) {
    return std::tie(x.links, x.island, x.index) < std::tie(y.links, y.island, y.index);
  });
  s.contacts.clear();
  s.contacts.reserve(soft_keys.size() + contacts.size());
  for (const SoftContactRecordKey& key : soft_keys) {
    const SoftContact& c = soft_contacts[islands[key.island].soft_contacts[key.index]];
    s.contacts.push_back({s.soft_bodies[c.soft]->handle, s.articulations[c.body]->link_handles[c.link], -1 - c.soft, c.body, c.nodes[0],
                          c.link, c.p_W, c.n_W, c.phi, solutions[key.island].soft_contact_force[key.index]});
  }
  for (size_t i = 0; i < contacts.size(); ++i) {
    const auto [k, j] = place[i];
    if (k < 0) continue;
    const Contact& c = contacts[i];
    s.contacts.push_back({s.articulations[c.body_a]->link_handles[c.link_a], s.articulations[c.body_b]->link_handles[c.link_b], c.body_a,
                          c.body_b, c.link_a, c.link_b, c.p_W, c.n_W, c.phi, solutions[k].contact_force[j]});
  }
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

// The layout of one island solve's problem: which variables (articulation DOFs, reduced soft
// bodies' modes and contact nodes, full soft bodies' free DOFs) and which rows take part, and where.

#include <algorithm>

#include "island/deferred_contacts.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

IslandLayout lay_out_variables(const IslandInputs& in, bool include_deferred, const std::vector<char>& admitted,
                               IslandWorkspace& w) {
  const SceneData& s = in.s;
  const Island& island = in.island;
  const std::vector<std::unique_ptr<SoftStep>>& soft_steps = in.soft_steps;
  // variable offsets: the articulations' DOFs, then each soft body's free DOFs
  std::vector<int>& offset = w.body_offset;
  std::vector<int>& soft_offset = w.soft_offset;
  fill_to(offset, s.articulations.size(), -1);
  fill_to(soft_offset, soft_steps.size(), -1);
  fill_to(w.island_position, s.articulations.size(), -1);
  int n = 0;
  for (size_t j = 0; j < island.bodies.size(); ++j) {
    const int b = island.bodies[j];
    offset[b] = n, n += s.articulations[b]->model.nv;
    w.island_position[b] = static_cast<int>(j);
  }
  // the rigid contacts that take part (positions in island.contacts)
  std::vector<int>& solved_rigid = w.solved_contacts;
  solved_rigid.clear();
  for (size_t j = 0; j < island.contacts.size(); ++j)
    if (w.contact_takes_part[j]) solved_rigid.push_back(static_cast<int>(j));
  // the soft contacts that take part (positions in island.soft_contacts)
  std::vector<int>& solved_soft = w.solved_soft_contacts;
  solved_soft.clear();
  for (size_t j = 0; j < island.soft_contacts.size(); ++j)
    if (admitted[j] || !soft_contact_deferred(in.soft_contacts[island.soft_contacts[j]])) solved_soft.push_back(static_cast<int>(j));
  // reduced soft bodies: dense variables after the articulations' DOFs, with the residual
  // velocities of the free nodes of the contacts that take part
  std::vector<ReducedVariables>& reduced = w.reduced;
  std::vector<int>& reduced_of = w.reduced_of;
  reduced.resize(0);
  fill_to(reduced_of, soft_steps.size(), -1);
  for (int k : island.soft_bodies) {
    const SoftBody& body = *s.soft_bodies[k];
    if (!body.reduced) continue;
    std::vector<int> nodes;
    for (int j : solved_soft) {
      const SoftContact& c = in.soft_contacts[island.soft_contacts[j]];
      if (c.soft != k) continue;
      for (int v = 0; v < 3; ++v)
        if (c.nodes[v] >= 0 && c.weights[v] != 0 && body.reduced->free_of_dof[3 * c.nodes[v]] >= 0) nodes.push_back(c.nodes[v]);
    }
    std::sort(nodes.begin(), nodes.end());
    nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
    reduced_of[k] = static_cast<int>(reduced.size());
    reduced.emplace_back();
    reduced_variables(body, k, s.gravity, in.dt, std::move(nodes), reduced.back());
    reduced.back().offset = soft_offset[k] = n;
    n += reduced.back().size();
  }
  const int n_rigid = n;
  std::vector<SoftStep*>& soft = w.soft;
  soft.clear();
  for (int k : island.soft_bodies) {
    if (reduced_of[k] >= 0) continue;
    soft.push_back(soft_steps[k].get());
    soft_offset[k] = n;
    n += soft.back()->size();
  }

  // the joint rows that take part, in row order: deferred limit rows only when `include_deferred`
  std::vector<IslandWorkspace::JointRowRef>& solved_rows = w.solved_joint_rows;
  solved_rows.clear();
  for (size_t j = 0; j < island.bodies.size(); ++j) {
    const std::vector<JointRow>& body_rows = in.terms[island.bodies[j]].joint_rows;
    for (size_t i = 0; i < body_rows.size(); ++i)
      if (!body_rows[i].deferred || include_deferred) solved_rows.push_back({static_cast<int>(j), static_cast<int>(i)});
  }
  IslandLayout layout;
  layout.n = n;
  layout.n_rigid = n_rigid;
  layout.joint_rows = static_cast<int>(solved_rows.size());
  layout.num_contacts = static_cast<int>(solved_rigid.size() + solved_soft.size());
  for (int k : island.constraints) layout.constraint_rows += static_cast<int>(in.constraints[k].rows.size());
  return layout;
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

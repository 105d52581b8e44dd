// The step's islands: built from the contacts, given their Newton systems and cost estimates, and
// solved on the worker threads, each one implicit solve.

#include <algorithm>
#include <functional>
#include <map>

#include "island/island_solver.h"
#include "scene/step_stages.h"
#include "solver/sparse_newton_system.h"
#include "superdex/physics/engine.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

void build_step_islands(Step& step) {
  SceneData& s = step.s;
  StepWorkspace& ws = step.ws;
  const size_t n = s.articulations.size();
  std::vector<int>& num_dofs = ws.num_dofs;
  num_dofs.resize(n);
  for (size_t i = 0; i < n; ++i) num_dofs[i] = s.articulations[i]->model.nv;
  build_islands(num_dofs, ws.contacts, ws.soft_free, step.soft_contacts, ws.constraint_bodies, ws.islands, ws.island_scratch);
  // Scene::set_force_single_island: every island's bodies and contacts in the first
  if (s.force_single_island && ws.islands.size() > 1) {
    Island& all = ws.islands[0];
    for (size_t k = 1; k < ws.islands.size(); ++k) {
      const Island& o = ws.islands[k];
      all.bodies.insert(all.bodies.end(), o.bodies.begin(), o.bodies.end());
      all.contacts.insert(all.contacts.end(), o.contacts.begin(), o.contacts.end());
      all.soft_bodies.insert(all.soft_bodies.end(), o.soft_bodies.begin(), o.soft_bodies.end());
      all.soft_contacts.insert(all.soft_contacts.end(), o.soft_contacts.begin(), o.soft_contacts.end());
      all.constraints.insert(all.constraints.end(), o.constraints.begin(), o.constraints.end());
    }
    for (auto* list : {&all.bodies, &all.contacts, &all.soft_bodies, &all.soft_contacts, &all.constraints}) std::sort(list->begin(), list->end());
    ws.islands.resize(1);
  }
}

void assign_sparse_systems(Step& step) {
  SceneData& s = step.s;
  const std::vector<Island>& islands = step.ws.islands;
  // kept for islands that still exist, by their bodies; the map is complete before the parallel
  // solves
  std::map<std::vector<int>, std::shared_ptr<SparseNewtonSystem>> sparse_systems;
  std::vector<SparseNewtonSystem*>& sparse_cache = step.ws.sparse_cache;
  sparse_cache.assign(islands.size(), nullptr);
  for (size_t k = 0; k < islands.size(); ++k) {
    if (!island_is_sparse(s, islands[k], s.params)) continue;
    auto previous = s.sparse_systems.find(islands[k].bodies);
    auto& slot = sparse_systems[islands[k].bodies];
    if (previous != s.sparse_systems.end()) slot = std::move(previous->second);
    if (!slot) slot = std::make_shared<SparseNewtonSystem>();
    sparse_cache[k] = slot.get();
  }
  s.sparse_systems = std::move(sparse_systems);
}

void estimate_island_costs(Step& step) {
  const StepWorkspace& ws = step.ws;
  const std::vector<Island>& islands = ws.islands;
  std::vector<double>& island_size = step.ws.island_size;
  island_size.resize(islands.size());
  for (size_t k = 0; k < islands.size(); ++k) {
    island_size[k] = static_cast<double>(islands[k].contacts.size() + islands[k].soft_contacts.size());
    for (int b : islands[k].bodies) island_size[k] += ws.num_dofs[b];
    for (int b : islands[k].soft_bodies) island_size[k] += ws.soft_free[b];
  }
}

void solve_islands(Step& step) {
  SceneData& s = step.s;
  StepWorkspace& ws = step.ws;
  const size_t n = s.articulations.size();
  const std::vector<Island>& islands = ws.islands;
  if (s.island_workspaces.size() < islands.size()) s.island_workspaces.resize(islands.size());
  for (size_t k = 0; k < islands.size(); ++k)
    if (!s.island_workspaces[k]) s.island_workspaces[k] = std::make_shared<IslandWorkspace>();
  ws.solutions.resize(islands.size());
  // the next states (next_island_states), committed once every island is checked
  ws.q_next.resize(n);
  ws.v_next.resize(n);
  ws.efforts_next.resize(n);
  ws.kin_next.resize(n);
  const auto solve = [&](size_t k) {
    solve_island(s, islands[k], ws.terms, ws.contacts, step.soft_contacts, ws.constraint_terms, step.soft_steps, step.dt, s.params, *s.island_workspaces[k],
                 ws.sparse_cache[k], ws.solutions[k]);
    next_island_states(step, k);
  };
  run_on_worker_threads_costliest_first(ws.island_size, std::cref(solve));
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

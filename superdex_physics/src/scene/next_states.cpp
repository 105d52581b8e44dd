// The bodies' next states: proposed by the island solves, checked by the step's guard (a fault
// raises before anything is committed, or is clamped: step_guard.h), then committed.

#include <utility>

#include "multibody/kinematics.h"
#include "scene/step_stages.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace {

// the kinematics of articulation b's next state
void next_kinematics(Step& step, size_t b) {
  const Articulation& a = *step.s.articulations[b];
  update_kinematics(a.model, step.ws.q_next[b], step.ws.v_next[b], a.state.X_W_base, step.ws.kin_next[b]);
}

}  // namespace

void next_island_states(Step& step, size_t k) {
  StepWorkspace& ws = step.ws;
  const Island& island = ws.islands[k];
  for (size_t j = 0; j < island.bodies.size(); ++j) {
    const int b = island.bodies[j];
    ws.v_next[b] = ws.solutions[k].v[j];
    ws.efforts_next[b] = ws.solutions[k].drive_efforts[j];
    ws.q_next[b] = step.s.articulations[b]->state.q;
    integrate_positions(step.s.articulations[b]->model, ws.q_next[b], ws.v_next[b], step.dt);
    next_kinematics(step, b);
  }
}

void guard_rigid_states(Step& step, StepGuard& guard) {
  StepWorkspace& ws = step.ws;
  for (size_t k = 0; k < ws.islands.size(); ++k)
    if (guard.check_island(ws.islands[k], ws.solutions[k])) next_island_states(step, k);  // clamped
  for (size_t b = 0; b < step.s.articulations.size(); ++b)
    if (ws.num_dofs[b] > 0 && guard.check_articulation(static_cast<int>(b), ws.q_next[b], ws.v_next[b])) next_kinematics(step, b);  // clamped
}

void next_soft_states(Step& step, StepGuard& guard) {
  SceneData& s = step.s;
  const std::vector<Island>& islands = step.ws.islands;
  std::vector<IslandSolution>& solutions = step.ws.solutions;
  std::vector<SoftState>& soft_next = step.soft_next;
  std::vector<VecX>& node_forces = step.node_forces;
  soft_next.resize(s.soft_bodies.size());
  node_forces.resize(s.soft_bodies.size());
  for (size_t k = 0; k < s.soft_bodies.size(); ++k) {
    soft_next[k] = s.soft_bodies[k]->state;
    node_forces[k] = VecX::Zero(soft_next[k].x.size());
  }
  for (size_t i = 0; i < islands.size(); ++i) {
    for (size_t j = 0; j < islands[i].soft_bodies.size(); ++j) {
      const int k = islands[i].soft_bodies[j];
      if (s.soft_bodies[k]->reduced) {
        // the solve's positions and reduced state; a clamped island keeps the last ones, at rest
        if (solutions[i].soft_reduced[j].q.size() > 0) soft_next[k] = std::move(solutions[i].soft_reduced[j]);
        else soft_next[k].v.setZero(), soft_next[k].qd.setZero();
      } else {
        soft_next[k].v = solutions[i].soft_v[j];
        soft_next[k].x += step.dt * soft_next[k].v;
      }
      guard.check_soft(k, soft_next[k]);
    }
    for (size_t j = 0; j < islands[i].soft_contacts.size(); ++j) {
      const SoftContact& c = step.soft_contacts[islands[i].soft_contacts[j]];
      for (int v = 0; v < 3; ++v)
        if (c.nodes[v] >= 0) node_forces[c.soft].segment<3>(3 * c.nodes[v]) += c.weights[v] * solutions[i].soft_contact_force[j];
    }
  }
}

void commit_next_states(Step& step) {
  SceneData& s = step.s;
  StepWorkspace& ws = step.ws;
  for (size_t b = 0; b < s.articulations.size(); ++b) {
    if (ws.num_dofs[b] == 0) continue;
    Articulation& a = *s.articulations[b];
    // swapped: the old state's storage serves the next step's
    a.drive_efforts.swap(ws.efforts_next[b]);
    a.state.q.swap(ws.q_next[b]);
    a.state.v.swap(ws.v_next[b]);
    std::swap(a.kin, ws.kin_next[b]);
  }
  for (size_t k = 0; k < s.soft_bodies.size(); ++k) {
    s.soft_bodies[k]->state = std::move(step.soft_next[k]);
    s.soft_bodies[k]->node_contact_forces = std::move(step.node_forces[k]);
    recenter_soft_body(*s.soft_bodies[k]);
  }
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

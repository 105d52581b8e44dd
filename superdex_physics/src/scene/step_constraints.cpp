// The step's constraints: their rows from the state at the step's start, and afterwards their
// forces and the end of their targets' motion over the step.

#include <unordered_map>

#include "constraint/constraint_terms.h"
#include "soft/rod_model.h"
#include "scene/step_stages.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace {

// The index of a body in `list` (articulations or soft bodies), from the map when given.
template <class T>
int index_in(const std::vector<std::unique_ptr<T>>& list, const T* body, const std::unordered_map<const void*, int>* index) {
  if (index) return index->at(body);
  for (size_t i = 0; i < list.size(); ++i)
    if (list[i].get() == body) return static_cast<int>(i);
  return -1;
}

}  // namespace

ConstraintSide constraint_side(const SceneData& s, const ConstraintRecord& c, int which, const std::unordered_map<const void*, int>* index) {
  ConstraintSide side;
  const ActorHandle actor = which == 0 ? c.actor_a : c.actor_b;
  if (!actor.is_valid()) return side;
  const ActorRef& r = s.actors.at(actor);
  if (r.soft && c.element >= 0 && which == 1) {
    // a rod's element: its frame and the map of its nodes' velocities to its turning
    const SoftBody& b = *r.soft;
    side.soft = index_in(s.soft_bodies, r.soft, index);
    side.element = c.element;
    side.element_nodes = b.model.rod->elements[c.element].nodes;
    const Mat3 R = rod_element_frame(*b.model.rod, c.element, b.state.x, &side.omega_map);
    side.X_WL = {Quat(R).normalized(), (b.state.x.segment<3>(3 * side.element_nodes[0]) + b.state.x.segment<3>(3 * side.element_nodes[1])) / 2};
    side.com_W = side.X_WL.translation;
    return side;
  }
  if (r.soft) {
    side.soft = index_in(s.soft_bodies, r.soft, index);
    side.node = which == 0 ? c.node_a : c.node_b;
    side.node_W = r.soft->state.x.segment<3>(3 * side.node);
    return side;
  }
  const Articulation& a = *r.articulation;
  side.body = index_in(s.articulations, &a, index);
  // a joint target's side: the joint's child link, and the joint's value now
  side.link = c.joint >= 0 ? c.joint : r.link < 0 ? 0 : r.link;
  if (c.joint >= 0) {
    const JointModel& j = a.model.joints[c.joint];
    side.dof = c.dof;
    if (j.nv == 1) {
      side.q_dof = a.state.q[j.q_offset];
    } else {
      // the rotation's quaternion (x, y, z, w): a spherical joint's coordinates, a free joint's last four
      const int q = j.q_offset + (j.type == JointType::Free ? 3 : 0);
      side.R_joint = Quat(a.state.q[q + 3], a.state.q[q], a.state.q[q + 1], a.state.q[q + 2]).normalized();
    }
  }
  const SpatialTransform& X = a.kin.X_WL[side.link];
  side.X_WL = {Quat(X.R).normalized(), X.p};
  side.com_W = X.R * a.model.inertia[side.link].com + X.p;
  return side;
}

void constraint_step_terms(Step& step) {
  SceneData& s = step.s;
  StepWorkspace& ws = step.ws;
  apply_pose_controller_velocities(s, step.dt);
  ws.constraint_terms.resize(s.constraints.size());
  ws.constraint_bodies.resize(s.constraints.size());
  if (s.constraints.empty()) return;
  // the bodies' indices, made at the first constraint that needs them
  std::unordered_map<const void*, int> index;
  const auto make_index = [&] {
    if (!index.empty()) return;
    for (size_t i = 0; i < s.articulations.size(); ++i) index[s.articulations[i].get()] = static_cast<int>(i);
    for (size_t i = 0; i < s.soft_bodies.size(); ++i) index[s.soft_bodies[i].get()] = static_cast<int>(i);
  };
  // the islands' nodes: articulations, then soft bodies
  const int na = static_cast<int>(s.articulations.size());
  const auto island_node = [na](const ConstraintSide& side) { return side.soft >= 0 ? na + side.soft : side.body; };
  size_t k = 0;
  for (const auto& [handle, c] : s.constraints) {
    ConstraintTerms& t = ws.constraint_terms[k];
    // a joint's limit: its articulation's own limit rows act (articulation_step.cpp), nothing here
    if (c.type == ConstraintType::ArticulatedSingleDofRange) {
      t.rows.clear();
      ws.constraint_bodies[k++] = {-1, -1};
      continue;
    }
    make_index();
    t.a = constraint_side(s, c, 0, &index);
    t.b = constraint_side(s, c, 1, &index);
    constraint_terms(c, step.dt, t);
    ws.constraint_bodies[k] = {island_node(t.a), island_node(t.b)};
    ++k;
  }
}

void constraint_records(Step& step) {
  SceneData& s = step.s;
  StepWorkspace& ws = step.ws;
  // each constraint's place among its island's
  std::vector<std::pair<int, int>> place(s.constraints.size(), {-1, -1});
  for (size_t k = 0; k < ws.islands.size(); ++k)
    for (size_t j = 0; j < ws.islands[k].constraints.size(); ++j) place[ws.islands[k].constraints[j]] = {static_cast<int>(k), static_cast<int>(j)};
  size_t i = 0;
  for (auto& [handle, c] : s.constraints) {
    const ConstraintTerms& t = ws.constraint_terms[i];
    const auto [k, j] = place[i++];
    // a joint's limit reports no force (its rows are the articulation's)
    if (c.type == ConstraintType::ArticulatedSingleDofRange) continue;
    const Vec6 F_a = k >= 0 ? ws.solutions[k].constraint_force_a[j] : Vec6::Zero();
    const Vec6 F_b = k >= 0 ? ws.solutions[k].constraint_force_b[j] : Vec6::Zero();
    c.force.clear();
    side_generalized_force(t.a, F_a, constraint_dof_indices(c, 0), c.force);
    if (c.actor_b.is_valid()) side_generalized_force(t.b, F_b, constraint_dof_indices(c, 1), c.force);
    c.force_step = s.step_count;
    // the target's motion over this step is done: the next step's damping follows only its next
    settle_constraint_targets(c);
  }
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

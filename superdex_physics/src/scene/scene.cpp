// Scene settings, actor creation and destruction, and the step pipeline.

#include <algorithm>
#include <set>
#include <cmath>

#include "output/debug_link.h"
#include "output/recording_internal.h"
#include "soft/soft_body.h"
#include "scene/step_stages.h"
#include "multibody/kinematics.h"
#include "scene/scene_data.h"
#include "superdex/physics/error.h"
#include "superdex/physics/scene.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

std::string Scene::name() const { return scene_data(handle_).name; }

void Scene::set_gravity(const Vec3& g_W) {
  if (!g_W.allFinite()) throw Error("set_gravity: gravity must be finite");
  scene_data(handle_).gravity = g_W;
}
Vec3 Scene::gravity() const { return scene_data(handle_).gravity; }
double Scene::total_simulation_time() const { return scene_data(handle_).time; }

void Scene::set_numerical_fault_policy(NumericalFaultPolicy policy) { scene_data(handle_).fault_policy = policy; }
NumericalFaultPolicy Scene::numerical_fault_policy() const { return scene_data(handle_).fault_policy; }
std::vector<NumericalFault> Scene::last_numerical_faults() const { return scene_data(handle_).last_faults; }

void Scene::set_solver_params(const SolverParams& p) {
  if (p.max_newton_iterations < 1) throw Error("set_solver_params: max_newton_iterations must be >= 1");
  if (p.max_line_search_iterations < 1) throw Error("set_solver_params: max_line_search_iterations must be >= 1");
  if (!(p.absolute_tolerance >= 0) || !(p.relative_tolerance >= 0)) throw Error("set_solver_params: tolerances must be >= 0");
  if (!(p.near_rigid_beta > 0)) throw Error("set_solver_params: near_rigid_beta must be > 0");
  if (!(p.friction_sigma > 0)) throw Error("set_solver_params: friction_sigma must be > 0");
  if (!(p.contact_margin >= 0) || !std::isfinite(p.contact_margin)) throw Error("set_solver_params: contact_margin must be >= 0");
  if (p.drift_correction_iterations < 0) throw Error("set_solver_params: drift_correction_iterations must be >= 0");
  if (!(p.soft_hessian_reuse_strain >= 0) || !std::isfinite(p.soft_hessian_reuse_strain))
    throw Error("set_solver_params: soft_hessian_reuse_strain must be finite and >= 0");
  if (p.dense_island_max_dofs < 0) throw Error("set_solver_params: dense_island_max_dofs must be >= 0");
  scene_data(handle_).params = p;
}
SolverParams Scene::solver_params() const { return scene_data(handle_).params; }
SolverStats Scene::solver_stats() const { return scene_data(handle_).stats; }

namespace {

ActorHandle add_articulation(SceneData& s, std::unique_ptr<Articulation> a) {
  a->handle = next_handle();
  a->state = initial_state(a->model);
  refresh_kinematics(*a);
  for (int i = 0; i < a->model.num_links; ++i) {
    const ActorHandle link = a->is_rigid ? a->handle : ActorHandle(next_handle());
    a->link_handles.push_back(link);
    if (!a->is_rigid) s.actors[link] = {a.get(), i};
  }
  s.actors[a->handle] = {a.get(), -1};
  const ActorHandle h = a->handle;
  s.articulations.push_back(std::move(a));
  return h;
}

}  // namespace

ActorHandle Scene::create_rigid_actor(const std::string& name, const ShapeHandle& shape, bool is_static, const Transform& X_WL,
                                      std::optional<real> density, std::optional<real> mass, const ContactMaterial& contact,
                                      int layer, ColliderType collider_type) {
  SceneData& s = scene_data(handle_);
  const std::string source = "create_rigid_actor('" + name + "')";
  std::shared_ptr<const ShapeData> data = shape_data(shape, source + ": shape");
  if (!data->geometry) throw Error(source + ": shape: it has no geometry a rigid body can carry");
  const ShapeGeometry& geometry = *data->geometry;
  if (!is_static && std::holds_alternative<PlaneShape>(geometry))
    throw Error(source + ": shape: a plane is unbounded and can only be static (pass is_static=True)");
  if (mass && density) throw Error(source + ": give mass or density, not both");
  ArticulationDesc desc;
  desc.name = name;
  desc.world_from_root = X_WL;
  LinkDesc link;
  link.name = name;
  link.shape = geometry;
  link.contact = contact;
  link.layer = layer;
  if (collider_type == ColliderType::None) link.collider_type = "None";
  if (is_static) {
    // welded bodies never move: their inertia only needs to be valid
    link.mass = 1;
    link.moment_of_inertia = std::array<real, 6>{1, 0, 0, 1, 0, 1};
  } else {
    link.mass = mass;
    link.density = density;
  }
  JointDesc joint;
  joint.name = name + "_root";
  joint.type = is_static ? JointType::Hard : JointType::Free;
  desc.links = {link};
  desc.joints = {joint};
  auto a = std::make_unique<Articulation>();
  a->is_rigid = true;
  a->is_static = is_static;
  a->shape = std::move(data);
  a->model = build_articulation_model(desc, source);
  return add_articulation(s, std::move(a));
}

ActorHandle Scene::create_articulated_actor(const ArticulationDesc& desc, const std::string& source) {
  SceneData& s = scene_data(handle_);
  auto a = std::make_unique<Articulation>();
  a->model = build_articulation_model(desc, source);
  return add_articulation(s, std::move(a));
}

ActorHandle Scene::create_soft_actor(const std::string& name, const ShapeHandle& tet_mesh, const SoftMaterial& material,
                                     const Transform& X_WL, const std::vector<int>& fixed_nodes) {
  SceneData& s = scene_data(handle_);
  if (!X_WL.translation.allFinite() || !X_WL.rotation.coeffs().allFinite() || X_WL.rotation.norm() < real(1e-6))
    throw Error("create_soft_actor('" + name + "'): world_from_local must be finite with a non-zero quaternion");
  Transform X = X_WL;
  X.rotation.normalize();
  auto body = build_soft_body(name, tet_mesh_shape(tet_mesh), material, X, fixed_nodes, "create_soft_actor('" + name + "')");
  body->handle = next_handle();
  const ActorHandle h = body->handle;
  s.actors[h] = ActorRef{nullptr, -1, body.get()};
  s.soft_bodies.push_back(std::move(body));
  return h;
}

namespace {

// The soft actor behind a handle; throws naming the API call `what` otherwise.
SoftBody& soft_actor(const SceneData& s, ActorHandle h, const char* what) {
  auto it = s.actors.find(h);
  if (it == s.actors.end() || !it->second.soft)
    throw Error(std::string(what) + ": actor " + std::to_string(h) + " is not a soft actor of scene '" + s.name + "'");
  return *it->second.soft;
}

}  // namespace

std::vector<Vec3> Scene::node_positions(ActorHandle h) const {
  const VecX& x = soft_actor(scene_data(handle_), h, "get_node_positions_world").state.x;
  std::vector<Vec3> out(x.size() / 3);
  for (size_t i = 0; i < out.size(); ++i) out[i] = x.segment<3>(3 * i);
  return out;
}

real Scene::elastic_energy(ActorHandle h) const {
  const SoftBody& b = soft_actor(scene_data(handle_), h, "get_elastic_energy");
  return soft_elastic_energy(b, b.state.x);
}

namespace {

void check_nodes(const SoftBody& b, const std::vector<int>& nodes, const char* what) {
  const int n = static_cast<int>(b.model.pinned.size());
  for (size_t k = 0; k < nodes.size(); ++k)
    if (nodes[k] < 0 || nodes[k] >= n)
      throw Error(std::string(what) + ": node_indices[" + std::to_string(k) + "] = " + std::to_string(nodes[k]) +
                  " is out of range (" + std::to_string(n) + " nodes)");
}

// A reduced body's modes hold for its pinned nodes at rest: they cannot change.
void refuse_reduced(const SoftBody& b, const char* what) {
  if (b.reduced)
    throw Error(std::string(what) + ": soft actor '" + b.model.name +
                "' is reduced (material.reducedModes): its modes are those of its pinned nodes held at rest, which cannot change");
}

}  // namespace

void Scene::set_boundary_nodes(ActorHandle h, const std::vector<int>& nodes, const std::vector<Vec3>& positions_W) {
  const char* what = "add_boundary_condition_nodes_world";
  SoftBody& b = soft_actor(scene_data(handle_), h, what);
  check_nodes(b, nodes, what);
  refuse_reduced(b, what);
  if (positions_W.size() != nodes.size())
    throw Error(std::string(what) + ": " + std::to_string(nodes.size()) + " node indices but " + std::to_string(positions_W.size()) +
                " positions");
  for (size_t k = 0; k < positions_W.size(); ++k)
    if (!positions_W[k].allFinite()) throw Error(std::string(what) + ": positions[" + std::to_string(k) + "] is not finite");
  for (size_t k = 0; k < nodes.size(); ++k) {
    if (!b.model.pinned[nodes[k]]) b.pattern.reset();  // the free DOFs change
    b.model.pinned[nodes[k]] = 1;
    b.model.pin_target.segment<3>(3 * nodes[k]) = positions_W[k];
  }
}

void Scene::release_boundary_nodes(ActorHandle h, const std::vector<int>& nodes) {
  const char* what = "remove_boundary_condition_nodes";
  SoftBody& b = soft_actor(scene_data(handle_), h, what);
  check_nodes(b, nodes, what);
  refuse_reduced(b, what);
  for (int i : nodes) {
    if (b.model.pinned[i]) b.pattern.reset();
    b.model.pinned[i] = 0;
  }
}

std::vector<int> Scene::boundary_nodes(ActorHandle h) const {
  const SoftBody& b = soft_actor(scene_data(handle_), h, "get_boundary_condition_nodes");
  std::vector<int> nodes;
  for (size_t i = 0; i < b.model.pinned.size(); ++i)
    if (b.model.pinned[i]) nodes.push_back(static_cast<int>(i));
  return nodes;
}

void Scene::destroy_actor(ActorHandle actor) {
  SceneData& s = scene_data(handle_);
  auto it = s.actors.find(actor);
  if (it == s.actors.end()) throw Error("destroy_actor: actor " + std::to_string(actor) + " does not exist in scene '" + s.name + "'");
  if (SoftBody* soft = it->second.soft) {
    s.actors.erase(it);
    std::erase_if(s.queries, [&](const auto& q) { return q.second.actor == actor; });
    // contact records refer to soft bodies by -1 - index: drop this one's and renumber the rest
    const int index = static_cast<int>(std::find_if(s.soft_bodies.begin(), s.soft_bodies.end(),
                                                    [&](const auto& p) { return p.get() == soft; }) - s.soft_bodies.begin());
    std::erase_if(s.contacts, [&](const ContactRecord& c) { return c.body_a == -1 - index; });
    for (ContactRecord& c : s.contacts)
      if (c.body_a < -1 - index) ++c.body_a;
    s.soft_bodies.erase(s.soft_bodies.begin() + index);
    return;
  }
  if (it->second.link >= 0 && !it->second.articulation->is_rigid)
    throw Error("destroy_actor: actor " + std::to_string(actor) + " is a link of articulation " +
                std::to_string(it->second.articulation->handle) + "; destroy the articulation instead");
  Articulation* a = it->second.articulation;
  std::set<ActorHandle> gone(a->link_handles.begin(), a->link_handles.end());
  gone.insert(a->handle);
  for (ActorHandle h : gone) s.actors.erase(h);
  std::erase_if(s.queries, [&](const auto& q) { return gone.count(q.second.actor) > 0; });
  std::erase_if(s.disabled_actor_pairs, [&](const auto& p) { return gone.count(p.first) || gone.count(p.second); });
  // contact records refer to bodies by index: drop this body's and renumber the rest
  const int index = static_cast<int>(std::find_if(s.articulations.begin(), s.articulations.end(),
                                                  [&](const auto& p) { return p.get() == a; }) - s.articulations.begin());
  std::erase_if(s.contacts, [&](const ContactRecord& c) { return c.body_a == index || c.body_b == index; });
  for (ContactRecord& c : s.contacts) {
    if (c.body_a > index) --c.body_a;
    if (c.body_b > index) --c.body_b;
  }
  s.articulations.erase(s.articulations.begin() + index);
}

bool Scene::has_actor(ActorHandle actor) const { return scene_data(handle_).actors.count(actor) > 0; }

std::vector<ActorHandle> Scene::actors() const {
  std::vector<ActorHandle> out;
  for (const auto& a : scene_data(handle_).articulations) out.push_back(a->handle);
  for (const auto& b : scene_data(handle_).soft_bodies) out.push_back(b->handle);
  return out;
}

void Scene::register_pre_step_callback(const std::string& name, StepCallback fn, int priority) {
  if (!fn) throw Error("register_pre_step_callback('" + name + "'): no function given");
  SceneData& s = scene_data(handle_);
  s.callbacks[name] = {false, priority, std::make_shared<const StepCallback>(std::move(fn))};
  ++s.callbacks_version;
}

void Scene::register_post_step_callback(const std::string& name, StepCallback fn, int priority) {
  if (!fn) throw Error("register_post_step_callback('" + name + "'): no function given");
  SceneData& s = scene_data(handle_);
  s.callbacks[name] = {true, priority, std::make_shared<const StepCallback>(std::move(fn))};
  ++s.callbacks_version;
}

void Scene::cancel_callback(const std::string& name) {
  SceneData& s = scene_data(handle_);
  if (s.callbacks.erase(name) == 0) throw Error("cancel_callback: no callback named '" + name + "'");
  ++s.callbacks_version;
}

int Scene::add_signal_source(SignalSource source) {
  if (!source) throw Error("add_signal_source: no function given");
  SceneData& s = scene_data(handle_);
  const int id = s.next_signal_source++;
  s.signal_sources[id] = std::move(source);
  return id;
}

void Scene::remove_signal_source(int id) { scene_data(handle_).signal_sources.erase(id); }

namespace {

// Runs the pre- or post-step callbacks by priority, then name: those registered when the
// step began, also when a callback registers or cancels callbacks.
void run_callbacks(Scene& scene, SceneData& s, bool post, real dt) {
  CachedCallbackOrder& cached = s.callback_order[post];
  if (!cached.order || cached.version != s.callbacks_version) {
    std::vector<std::pair<int, const StepCallbackRecord*>> by_priority;  // the map is ordered by name
    for (const auto& [name, cb] : s.callbacks)
      if (cb.post == post) by_priority.push_back({cb.priority, &cb});
    std::stable_sort(by_priority.begin(), by_priority.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    auto made = std::make_shared<StepCallbackOrder>();
    for (const auto& [priority, cb] : by_priority) made->push_back(cb->fn);
    cached = {std::move(made), s.callbacks_version};
  }
  // taken out of the scene while it runs, by a move (no reference counting, which threads
  // stepping their own scenes would contend for when the counts share a cache line), so that it
  // outlives a change a callback makes; put back afterwards, also after an exception, unless a
  // step within a callback cached a newer one (a change meanwhile leaves it outdated by its version)
  struct PutBack {
    CachedCallbackOrder& slot;
    CachedCallbackOrder running;
    ~PutBack() {
      if (!slot.order) slot = std::move(running);
    }
  } put_back{cached, std::move(cached)};
  for (const auto& fn : *put_back.running.order) (*fn)(scene, dt);
}

}  // namespace

void Scene::step(real dt) {
  if (!std::isfinite(dt) || dt <= 0) throw Error("step: dt must be a positive finite number of seconds, got " + std::to_string(dt));
  debug_before_step(*this);
  run_callbacks(*this, scene_data(handle_), false, dt);
  step_dynamics(dt);
  run_callbacks(*this, scene_data(handle_), true, dt);
  record_step(scene_data(handle_));
  debug_after_step(*this, scene_data(handle_));
}

void Scene::step_dynamics(real dt) {
  SceneData& s = scene_data(handle_);
  // the step's wall time, its parts counted by the stages in time-stamp ticks (step_ticks.h)
  const StepClock clock = StepClock::start();
  if (!s.step_workspace) s.step_workspace = std::make_shared<StepWorkspace>();
  Step step(s, *s.step_workspace, dt);
  // 1. broad phase; then, together on the worker threads, the soft bodies' parts of the problem,
  // the dynamics terms of every body and the narrow phase; then the contact lists
  find_step_contact_pairs(step);
  prepare_step_items(step);
  gather_contacts(step);
  // 2. islands, each one implicit solve, the costliest first
  build_step_islands(step);
  assign_sparse_systems(step);
  estimate_island_costs(step);
  solve_islands(step);
  // 3. next states; a fault (non-finite, unconverged) raises before anything is committed, or
  // is clamped (step_guard.h)
  StepGuard guard(s);
  guard_rigid_states(step, guard);
  next_soft_states(step, guard);
  guard.finish();
  commit_next_states(step);
  // 4. contact results for queries, the scene's time, statistics
  contact_records(step);
  s.time += dt;
  s.step_count += 1;
  step_stats(step, clock);
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

// Scene settings, actor creation and destruction, and the step pipeline.

#include <algorithm>
#include <set>
#include <chrono>
#include <functional>
#include <tuple>
#include <cmath>

#include "island/island_solver.h"
#include "solver/sparse_newton_system.h"
#include "output/debug_link.h"
#include "output/recording_internal.h"
#include "soft/soft_contact.h"
#include "soft/soft_body.h"
#include "scene/step_guard.h"
#include "scene/step_workspace.h"
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
    const ActorHandle link = a->is_rigid ? a->handle : next_handle();
    a->link_handles.push_back(link);
    if (!a->is_rigid) s.actors[link] = {a.get(), i};
  }
  s.actors[a->handle] = {a.get(), -1};
  const ActorHandle h = a->handle;
  s.articulations.push_back(std::move(a));
  return h;
}

}  // namespace

ActorHandle Scene::create_rigid_actor(const std::string& name, ShapeHandle shape, bool is_static, const Transform& X_WL,
                                      std::optional<real> density, std::optional<real> mass, const ContactMaterial& contact,
                                      int layer, ColliderType collider_type) {
  SceneData& s = scene_data(handle_);
  const ShapeGeometry geometry = shape_geometry(shape);
  const std::string source = "create_rigid_actor('" + name + "')";
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
  a->shape = shape;
  a->model = build_articulation_model(desc, source);
  return add_articulation(s, std::move(a));
}

ActorHandle Scene::create_articulated_actor(const ArticulationDesc& desc, const std::string& source) {
  SceneData& s = scene_data(handle_);
  auto a = std::make_unique<Articulation>();
  a->model = build_articulation_model(desc, source);
  return add_articulation(s, std::move(a));
}

ActorHandle Scene::create_soft_actor(const std::string& name, ShapeHandle tet_mesh, const SoftMaterial& material,
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

// The step's contact results (s.contacts), ordered by their links (body_a, link_a, body_b,
// link_b): first the soft contacts (side a is the soft body, body index -1 - soft index), then the
// rigid ones in the contact list's order, which the broad phase made that order.
void contact_records(SceneData& s, const std::vector<Island>& islands, const std::vector<Contact>& contacts,
                     const std::vector<SoftContact>& soft_contacts, const std::vector<IslandSolution>& solutions,
                     StepWorkspace& ws) {
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
  // the step's wall time and its parts in time-stamp ticks (step_ticks.h); by steady_clock too
  // until the ticks' rate is calibrated
  const double calibrated_tick_seconds = calibrated_seconds_per_tick();
  const auto t0 = calibrated_tick_seconds > 0 ? std::chrono::steady_clock::time_point{} : std::chrono::steady_clock::now();
  const Ticks k0 = ticks_now();
  const size_t n = s.articulations.size();
  const auto parallel = run_on_worker_threads;

  if (!s.step_workspace) s.step_workspace = std::make_shared<StepWorkspace>();
  StepWorkspace& ws = *s.step_workspace;

  // 1. broad phase; then, together on the worker threads, the soft bodies' parts of the problem
  // (the costliest items, first), the dynamics terms of every body and the narrow phase
  ContactPairs& pairs = ws.pairs;
  find_contact_pairs(s, s.params.contact_margin, dt, pairs);
  Ticks collision_ticks = ticks_now() - k0;
  const size_t num_soft = s.soft_bodies.size();
  std::vector<std::unique_ptr<SoftStep>> soft_steps(num_soft);
  std::vector<int>& soft_free = ws.soft_free;
  soft_free.assign(num_soft, 0);
  for (size_t k = 0; k < num_soft; ++k)
    for (char pinned : s.soft_bodies[k]->model.pinned) soft_free[k] += pinned ? 0 : 3;
  std::vector<ArticulationTerms>& terms = ws.terms;
  terms.resize(n);
  std::vector<std::vector<Contact>>& chunk_contacts = ws.chunk_contacts;
  chunk_contacts.resize(pairs.num_chunks());
  for (auto& chunk : chunk_contacts) chunk.clear();
  // the articulations by groups of a few (each costs about a microsecond: one item each would
  // pass the threads' shared item counter back and forth as often)
  constexpr size_t kBodiesPerItem = 8;
  const size_t body_items = (n + kBodiesPerItem - 1) / kBodiesPerItem;
  // each item's time (the soft bodies' are not reported)
  std::vector<Ticks>& item_ticks = ws.item_ticks;
  item_ticks.assign(num_soft + body_items + pairs.num_chunks(), 0);
  const auto prepare = [&](size_t i) {
    if (i < num_soft) {
      if (soft_free[i] > 0 && !s.soft_bodies[i]->reduced) soft_steps[i] = std::make_unique<SoftStep>(*s.soft_bodies[i], s.gravity, dt, s.params.soft_hessian_reuse_strain);
      return;
    }
    const Ticks t = ticks_now();
    if (i < num_soft + body_items) {
      const size_t first = (i - num_soft) * kBodiesPerItem;
      for (size_t b = first; b < std::min(n, first + kBodiesPerItem); ++b)
        articulation_terms(*s.articulations[b], s.gravity, dt, s.params, terms[b]);
    } else {
      const size_t c = i - num_soft - body_items;
      collide_pairs(s, pairs, c, chunk_contacts[c]);
    }
    item_ticks[i] = ticks_now() - t;
  };
  // by reference: a std::function holds a reference without allocating (the lambda is too large)
  parallel(item_ticks.size(), std::cref(prepare));
  // 2. the contact list, and soft contacts
  const Ticks k2 = ticks_now();
  std::vector<Contact>& contacts = ws.contacts;
  join_contacts(chunk_contacts, contacts);
  const std::vector<SoftContact> soft_contacts = detect_soft_contacts(s, s.params.contact_margin, dt);
  collision_ticks += ticks_now() - k2;
  Ticks kinematics_ticks = 0;
  for (size_t i = num_soft; i < item_ticks.size(); ++i) (i < num_soft + body_items ? kinematics_ticks : collision_ticks) += item_ticks[i];
  // 3. islands, each one implicit solve; a non-finite result throws before anything is committed
  std::vector<int>& num_dofs = ws.num_dofs;
  num_dofs.resize(n);
  for (size_t i = 0; i < n; ++i) num_dofs[i] = s.articulations[i]->model.nv;
  std::vector<Island>& islands = ws.islands;
  build_islands(num_dofs, contacts, soft_free, soft_contacts, islands, ws.island_scratch);
  // each large rigid island gets its slot of the sparse pattern cache (kept for islands that
  // still exist, by their bodies); the map is complete before the parallel solves
  std::map<std::vector<int>, std::shared_ptr<SparseNewtonSystem>> sparse_systems;
  std::vector<SparseNewtonSystem*>& sparse_cache = ws.sparse_cache;
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
  // an island's size (contacts and DOFs) estimates its cost: largest first
  std::vector<double>& island_size = ws.island_size;
  island_size.resize(islands.size());
  for (size_t k = 0; k < islands.size(); ++k) {
    island_size[k] = static_cast<double>(islands[k].contacts.size() + islands[k].soft_contacts.size());
    for (int b : islands[k].bodies) island_size[k] += num_dofs[b];
    for (int b : islands[k].soft_bodies) island_size[k] += soft_free[b];
  }
  if (s.island_workspaces.size() < islands.size()) s.island_workspaces.resize(islands.size());
  for (size_t k = 0; k < islands.size(); ++k)
    if (!s.island_workspaces[k]) s.island_workspaces[k] = std::make_shared<IslandWorkspace>();
  std::vector<IslandSolution>& solutions = ws.solutions;
  solutions.resize(islands.size());
  std::vector<VecX>&q_next = ws.q_next, &v_next = ws.v_next, &efforts_next = ws.efforts_next;
  std::vector<ArticulationKinematics>& kin_next = ws.kin_next;
  q_next.resize(n);
  v_next.resize(n);
  efforts_next.resize(n);
  kin_next.resize(n);
  const auto next_kinematics = [&](size_t b) {
    const Articulation& a = *s.articulations[b];
    update_kinematics(a.model, q_next[b], v_next[b], a.state.X_W_base, kin_next[b]);
  };
  // the next states of island k's bodies and their kinematics (committed below, once every
  // island is checked)
  auto next_states = [&](size_t k) {
    for (size_t j = 0; j < islands[k].bodies.size(); ++j) {
      const int b = islands[k].bodies[j];
      v_next[b] = solutions[k].v[j];
      efforts_next[b] = solutions[k].drive_efforts[j];
      q_next[b] = s.articulations[b]->state.q;
      integrate_positions(s.articulations[b]->model, q_next[b], v_next[b], dt);
      next_kinematics(b);
    }
  };
  const auto solve = [&](size_t k) {
    solve_island(s, islands[k], terms, contacts, soft_contacts, soft_steps, dt, s.params, *s.island_workspaces[k], sparse_cache[k],
                 solutions[k]);
    next_states(k);
  };
  run_on_worker_threads_costliest_first(island_size, std::cref(solve));

  // 4. next states; a fault (non-finite, unconverged) raises before anything is committed, or
  // is clamped (step_guard.h)
  StepGuard guard(s);
  for (size_t k = 0; k < islands.size(); ++k)
    if (guard.check_island(islands[k], solutions[k])) next_states(k);  // clamped
  for (size_t b = 0; b < n; ++b)
    if (num_dofs[b] > 0 && guard.check_articulation(static_cast<int>(b), q_next[b], v_next[b])) next_kinematics(b);  // clamped
  // soft bodies: next positions and node contact forces
  std::vector<SoftState> soft_next(s.soft_bodies.size());
  std::vector<VecX> node_forces(s.soft_bodies.size());
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
        soft_next[k].x += dt * soft_next[k].v;
      }
      guard.check_soft(k, soft_next[k]);
    }
    for (size_t j = 0; j < islands[i].soft_contacts.size(); ++j) {
      const SoftContact& c = soft_contacts[islands[i].soft_contacts[j]];
      for (int v = 0; v < 3; ++v)
        if (c.nodes[v] >= 0) node_forces[c.soft].segment<3>(3 * c.nodes[v]) += c.weights[v] * solutions[i].soft_contact_force[j];
    }
  }
  guard.finish();
  for (size_t b = 0; b < n; ++b) {
    if (num_dofs[b] == 0) continue;
    Articulation& a = *s.articulations[b];
    // swapped: the old state's storage serves the next step's
    a.drive_efforts.swap(efforts_next[b]);
    a.state.q.swap(q_next[b]);
    a.state.v.swap(v_next[b]);
    std::swap(a.kin, kin_next[b]);
  }

  for (size_t k = 0; k < s.soft_bodies.size(); ++k) {
    s.soft_bodies[k]->state = std::move(soft_next[k]);
    s.soft_bodies[k]->node_contact_forces = std::move(node_forces[k]);
  }

  // 5. contact results for queries
  contact_records(s, islands, contacts, soft_contacts, solutions, ws);
  SolverStats stats;
  stats.num_islands = static_cast<int>(islands.size());
  stats.num_contacts = static_cast<int>(contacts.size());
  Ticks solve_ticks = 0;
  for (const auto& st : soft_steps)
    if (st) {
      stats.soft_element_hessians += st->element_hessians();
      stats.soft_factorizations += st->factorizations();
    }
  for (const IslandSolution& sol : solutions) {
    stats.newton_iterations = std::max(stats.newton_iterations, sol.iterations);
    stats.total_newton_iterations += sol.iterations;
    stats.residual = std::max(stats.residual, sol.residual);
    stats.converged = stats.converged && sol.converged;
    stats.num_constraints += sol.active_rows;
    solve_ticks += sol.ticks;
  }
  s.time += dt;
  s.step_count += 1;
  const Ticks total_ticks = ticks_now() - k0;
  double tick_seconds = calibrated_tick_seconds;
  if (tick_seconds > 0) {
    stats.time_total = tick_seconds * static_cast<double>(total_ticks);
  } else {
    stats.time_total = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    tick_seconds = seconds_per_tick(stats.time_total, total_ticks);
  }
  stats.time_kinematics = tick_seconds * static_cast<double>(kinematics_ticks);
  stats.time_collision = tick_seconds * static_cast<double>(collision_ticks);
  stats.time_solve = tick_seconds * static_cast<double>(solve_ticks);
  s.stats = stats;
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

// Scene settings, actor creation and destruction, and the step pipeline.

#include <algorithm>
#include <set>
#include <cmath>

#include "output/debug_link.h"
#include "output/recording_internal.h"
#include "output/scene_recording.h"
#include "soft/material_from_params.h"
#include "soft/soft_body.h"
#include "scene/step_stages.h"
#include "multibody/kinematics.h"
#include "scene/scene_data.h"
#include "scene/step_clock.h"
#include "superdex/physics/error.h"
#include "superdex/physics/scene.h"
#include "solver/step_settings.h"

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
  SceneData& s = scene_data(handle_);
  validate(p, "set_solver_params: params");
  s.solver_params = p;
  s.params = step_settings_from(p);
}
SolverParams Scene::solver_params() const { return scene_data(handle_).solver_params; }

SolverStats Scene::solver_stats() const {
  const StepStats& st = scene_data(handle_).stats;
  SolverStats out;
  out.max_non_linear_iters = st.newton_iterations;
  out.residual_norm = st.residual;
  out.max_line_search_iters = st.line_search_iterations;
  out.convergence_status = st.status;
  out.total_non_linear_iters = st.total_newton_iterations;
  out.num_islands = st.num_islands;
  out.num_constraints = st.num_constraints;
  out.num_contacts = st.num_contacts;
  out.soft_element_hessians = st.soft_element_hessians;
  out.soft_factorizations = st.soft_factorizations;
  out.num_island_solves = st.island_solves;
  return out;
}

PerformanceStats Scene::performance_stats() const {
  const SceneData& s = scene_data(handle_);
  PerformanceStats out = s.performance;
  out.kinematics_duration_sec = s.stats.time_kinematics;
  out.collision_duration_sec = s.stats.time_collision;
  out.island_solve_duration_sec = s.stats.time_solve;
  return out;
}

ActorHandle add_articulation(SceneData& s, std::unique_ptr<Articulation> a) {
  a->handle = next_handle();
  a->state = initial_state(a->model);
  refresh_kinematics(*a);
  // links created from a description rather than params: their contact friction and layer
  for (int i = static_cast<int>(a->links.size()); i < a->model.num_links; ++i) {
    LinkRecord r;
    r.contact = a->model.desc.links[i].contact;
    const int layer = a->model.desc.links[i].layer;
    r.layer = layer < static_cast<int>(s.layer_names.size()) ? s.layer_names[layer] : "";
    r.density = a->model.desc.links[i].density.value_or(0);
    a->links.push_back(std::move(r));
  }
  for (int i = static_cast<int>(a->joint_friction.size()); i < a->model.num_links; ++i) {
    ArticulatedJointFrictionParams f;
    f.coulomb = a->model.desc.joints[i].coulomb_friction;
    f.viscous = a->model.desc.joints[i].viscous_friction;
    a->joint_friction.push_back(f);
  }
  for (int i = 0; i < a->model.num_links; ++i) {
    const ActorHandle link = a->is_rigid ? a->handle : ActorHandle(next_handle());
    a->link_handles.push_back(link);
    if (!a->is_rigid) s.actors[link] = {a.get(), i};
  }
  s.actors[a->handle] = {a.get(), -1};
  if (!a->is_rigid) add_joint_limit_constraints(s, *a);
  const ActorHandle h = a->handle;
  s.articulations.push_back(std::move(a));
  return h;
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
  const std::string where = "create_soft_actor('" + name + "')";
  auto shape = shape_data(tet_mesh, where + ": shape");
  if (!shape->tet_mesh) throw Error(where + ": shape is not a tetrahedral mesh");
  const std::shared_ptr<const TetMesh> shape_mesh = shape->tet_mesh;
  auto body = build_soft_body(name, shape->tet_mesh, material, X, fixed_nodes, where);
  body->X_WL = X;
  body->shape = std::move(shape);
  body->contact_params.coulomb_friction_coefficient = body->model.contact.friction;
  body->contact_params.contact_stiffness = body->model.contact.stiffness;
  body->contact_params.dissipation_time_scale = body->model.contact.dissipation_time;
  // what the material getters (and soft_actor_params) report
  body->material_params = soft_material_params_from(material, *shape_mesh);
  return add_soft_body(s, std::move(body));
}

ActorHandle add_soft_body(SceneData& s, std::unique_ptr<SoftBody> body) {
  // what boundary conditions go back to: the nodes pinned at creation
  body->base_pinned = body->model.pinned;
  body->base_pin_target = body->model.pin_target;
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
  require_query(scene_data(handle_), h, QueryType::ElasticEnergy, "get_elastic_energy");
  return soft_elastic_energy(b, b.state.x);
}

void Scene::destroy_actor(ActorHandle actor) {
  SceneData& s = scene_data(handle_);
  auto it = s.actors.find(actor);
  if (it == s.actors.end()) throw Error("destroy_actor: actor " + std::to_string(actor) + " does not exist in scene '" + s.name + "'");
  if (SoftBody* soft = it->second.soft) {
    if (soft->skeleton.is_valid() && s.actors.count(soft->skeleton))
      throw Error("destroy_actor: actor " + std::to_string(actor) + " is a soft body of soft-skinned actor " + std::to_string(soft->skeleton) +
                  "; destroy that actor instead");
    s.actors.erase(it);
    std::erase_if(s.queries, [&](const auto& q) { return q.second.actor == actor; });
    std::erase_if(s.constraints, [&](const auto& c) { return c.second.actor_a == actor || c.second.actor_b == actor; });
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
  // a soft-skinned actor's soft bodies go first (their ties to the links with them)
  for (ActorHandle soft : a->nested_softs)
    if (auto found = s.actors.find(soft); found != s.actors.end()) {
      found->second.soft->skeleton = ActorHandle();
      destroy_actor(soft);
    }
  std::set<ActorHandle> gone(a->link_handles.begin(), a->link_handles.end());
  gone.insert(a->handle);
  for (ActorHandle h : gone) s.actors.erase(h);
  std::erase_if(s.queries, [&](const auto& q) { return gone.count(q.second.actor) > 0; });
  std::erase_if(s.actor_contact, [&](const auto& p) { return gone.count(p.first.first) || gone.count(p.first.second); });
  // constraints on the actor or its links go with it
  std::erase_if(s.constraints, [&](const auto& c) { return gone.count(c.second.actor_a) || gone.count(c.second.actor_b); });
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

namespace {

CallbackHandle add_callback(SceneData& s, const std::string& debug_name, StepCallback fn, int priority, bool post) {
  if (!fn) throw Error(std::string(post ? "register_post_step_callback" : "register_pre_step_callback") + "('" + debug_name + "'): no function given");
  const CallbackHandle h = next_handle();
  s.callbacks[h] = {debug_name, post, priority, std::make_shared<const StepCallback>(std::move(fn))};
  ++s.callbacks_version;
  return h;
}

}  // namespace

CallbackHandle Scene::register_pre_step_callback(const std::string& debug_name, StepCallback fn, int priority) {
  return add_callback(scene_data(handle_), debug_name, std::move(fn), priority, false);
}

CallbackHandle Scene::register_post_step_callback(const std::string& debug_name, StepCallback fn, int priority) {
  return add_callback(scene_data(handle_), debug_name, std::move(fn), priority, true);
}

void Scene::cancel_callback(CallbackHandle handle) {
  SceneData& s = scene_data(handle_);
  if (s.callbacks.erase(handle) > 0) ++s.callbacks_version;
}

std::size_t Scene::num_step_callbacks() const { return scene_data(handle_).callbacks.size(); }

int Scene::add_signal_source(SignalSource source) {
  if (!source) throw Error("add_signal_source: no function given");
  SceneData& s = scene_data(handle_);
  const int id = s.next_signal_source++;
  s.signal_sources[id] = std::move(source);
  return id;
}

void Scene::remove_signal_source(int id) { scene_data(handle_).signal_sources.erase(id); }

namespace {

// Runs the pre- or post-step callbacks by priority, then registration: those registered when the
// step began, also when a callback registers or cancels callbacks.
void run_callbacks(Scene& scene, SceneData& s, bool post, double dt) {
  CachedCallbackOrder& cached = s.callback_order[post];
  if (!cached.order || cached.version != s.callbacks_version) {
    std::vector<std::pair<int, const StepCallbackRecord*>> by_priority;  // the map is ordered by registration
    for (const auto& [handle, cb] : s.callbacks)
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
  const StepInfo info{scene, dt};
  for (const auto& fn : *put_back.running.order) (*fn)(info);
}

}  // namespace

namespace {

// A BDF2 step (bdf2_step.h): `be_step` (the implicit step) over 2/3 dt from the extrapolated
// state when the last steps allow it, else over dt (backward Euler); the scene's time moves by dt.
template <class BackwardEulerStep>
void step_bdf2(SceneData& s, double dt, BackwardEulerStep&& be_step) {
  if (!s.step_workspace) s.step_workspace = std::make_shared<StepWorkspace>();
  Bdf2History& history = s.step_workspace->bdf2;
  Bdf2History& start = s.step_workspace->bdf2_start;
  bdf2_capture(s, start);
  const double t0 = s.time;
  if (bdf2_can_extrapolate(s, history, dt)) {
    bdf2_extrapolate(s, history);
    try {
      be_step(static_cast<real>(2 * dt / 3));
    } catch (...) {
      bdf2_restore(s, start);
      history.valid = false;
      throw;
    }
    s.time = t0 + dt;
  } else {
    be_step(static_cast<real>(dt));
  }
  bdf2_advance(s, dt, start, history);
}

}  // namespace

void Scene::step(double dt) {
  if (!std::isfinite(dt) || dt < 0) throw Error("step: time_step_sec must be a finite number of seconds >= 0, got " + std::to_string(dt));
  // the step's wall time and its parts (PerformanceStats), in time-stamp ticks
  const StepClock clock = StepClock::start();
  debug_before_step(*this);
  run_callbacks(*this, scene_data(handle_), false, dt);
  const Ticks after_pre = ticks_now();
  if (dt > 0) {
    SceneData& s = scene_data(handle_);
    if (s.solver_params.integration_method == IntegrationMethod::BDF2) {
      step_bdf2(s, dt, [this](real h) { step_dynamics(h); });
    } else {
      step_dynamics(static_cast<real>(dt));
    }
    s.last_time_step = dt;
  } else {
    // a zero step changes no state: queries registered before it become readable
    SceneData& s = scene_data(handle_);
    s.stats = StepStats{};
    s.step_count += 1;
  }
  const Ticks after_solve = ticks_now();
  run_callbacks(*this, scene_data(handle_), true, dt);
  const Ticks after_post = ticks_now();
  record_step(scene_data(handle_));
  if (const auto recording = scene_data(handle_).recording) recording->record_frame(*this, dt);
  debug_after_step(*this, scene_data(handle_));
  double tick_seconds = 0;
  PerformanceStats& perf = scene_data(handle_).performance;
  perf.total_step_duration_sec = clock.seconds(tick_seconds);
  perf.pre_step_callbacks_duration_sec = tick_seconds * static_cast<double>(after_pre - clock.k0);
  perf.solve_step_duration_sec = tick_seconds * static_cast<double>(after_solve - after_pre);
  perf.post_step_callbacks_duration_sec = tick_seconds * static_cast<double>(after_post - after_solve);
  perf.recording_step_duration_sec = std::max(0.0, perf.total_step_duration_sec - tick_seconds * static_cast<double>(after_post - clock.k0));
}

double Scene::last_time_step() const { return scene_data(handle_).last_time_step; }

void Scene::update_debugger() {
  const SceneData& s = scene_data(handle_);
  record_current_frame(s);
  debug_update(s);
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
  constraint_step_terms(step);
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
  constraint_records(step);
  s.time += dt;
  s.step_count += 1;
  step_stats(step, clock);
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

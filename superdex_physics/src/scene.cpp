// Scene settings, actor creation and destruction, and the step pipeline.

#include <chrono>
#include <cmath>
#include <oneapi/tbb/parallel_for.h>

#include "articulation_step.h"
#include "kinematics.h"
#include "scene_data.h"
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

void Scene::set_solver_params(const SolverParams& p) {
  if (p.max_newton_iterations < 1) throw Error("set_solver_params: max_newton_iterations must be >= 1");
  if (p.max_line_search_iterations < 1) throw Error("set_solver_params: max_line_search_iterations must be >= 1");
  if (!(p.absolute_tolerance >= 0) || !(p.relative_tolerance >= 0)) throw Error("set_solver_params: tolerances must be >= 0");
  if (!(p.near_rigid_beta > 0)) throw Error("set_solver_params: near_rigid_beta must be > 0");
  if (!(p.friction_sigma > 0)) throw Error("set_solver_params: friction_sigma must be > 0");
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
                                      std::optional<real> density, std::optional<real> mass) {
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

void Scene::destroy_actor(ActorHandle actor) {
  SceneData& s = scene_data(handle_);
  auto it = s.actors.find(actor);
  if (it == s.actors.end()) throw Error("destroy_actor: actor " + std::to_string(actor) + " does not exist in scene '" + s.name + "'");
  if (it->second.link >= 0 && !it->second.articulation->is_rigid)
    throw Error("destroy_actor: actor " + std::to_string(actor) + " is a link of articulation " +
                std::to_string(it->second.articulation->handle) + "; destroy the articulation instead");
  Articulation* a = it->second.articulation;
  for (ActorHandle link : a->link_handles) s.actors.erase(link);
  s.actors.erase(a->handle);
  std::erase_if(s.articulations, [&](const auto& p) { return p.get() == a; });
}

bool Scene::has_actor(ActorHandle actor) const { return scene_data(handle_).actors.count(actor) > 0; }

std::vector<ActorHandle> Scene::actors() const {
  std::vector<ActorHandle> out;
  for (const auto& a : scene_data(handle_).articulations) out.push_back(a->handle);
  return out;
}

void Scene::step(real dt) {
  SceneData& s = scene_data(handle_);
  if (!std::isfinite(dt) || dt <= 0) throw Error("step: dt must be a positive finite number of seconds, got " + std::to_string(dt));
  const auto t0 = std::chrono::steady_clock::now();
  const size_t n = s.articulations.size();
  std::vector<ArticulationStepResult> results(n);
  auto work = [&](size_t i) { results[i] = step_articulation(*s.articulations[i], s.gravity, dt, s.params); };
  EngineData& e = engine_data();
  if (e.arena && n > 1) {
    e.arena->execute([&] { oneapi::tbb::parallel_for(size_t(0), n, work); });
  } else {
    for (size_t i = 0; i < n; ++i) work(i);
  }
  // a non-finite result leaves every actor in its last good state
  for (size_t i = 0; i < n; ++i) {
    const Articulation& a = *s.articulations[i];
    if (!results[i].v.allFinite() || !results[i].q.allFinite())
      throw Error("step: actor '" + a.model.name + "' (handle " + std::to_string(a.handle) + "): " +
                  (results[i].v.allFinite() ? "positions" : "velocities") +
                  " became non-finite; the scene keeps its last good state (check forces, masses and dt)");
  }
  SolverStats stats;
  for (size_t i = 0; i < n; ++i) {
    Articulation& a = *s.articulations[i];
    ArticulationStepResult& r = results[i];
    a.state.q = std::move(r.q);
    a.state.v = std::move(r.v);
    refresh_kinematics(a);
    if (a.model.nv == 0) continue;
    stats.num_islands += 1;
    stats.newton_iterations = std::max(stats.newton_iterations, r.iterations);
    stats.total_newton_iterations += r.iterations;
    stats.residual = std::max(stats.residual, r.residual);
    stats.converged = stats.converged && r.converged;
    stats.num_constraints += r.active_rows;
    stats.time_kinematics += r.time_dynamics;
    stats.time_solve += r.time_solve;
  }
  s.time += dt;
  stats.time_total = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  s.stats = stats;
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

// The Scene class: settings, stepping, actor creation and lookup, solver parameters and stats.

#include <nanobind/stl/optional.h>
#include <nanobind/stl/string.h>

#include <nlohmann/json.hpp>

#include "bind_common.h"
#include "superdex/physics/articulation_json.h"
#include "superdex/physics/engine.h"

namespace superdex::python {

namespace {

std::optional<real> optional_positive(nb::handle obj, const std::string& arg) {
  if (obj.is_none()) return std::nullopt;
  double x;
  if (!nb::try_cast(obj, x)) throw Error(arg + ": expected a number or None");
  if (!std::isfinite(x) || x <= 0) throw Error(arg + ": must be a positive finite number, got " + std::to_string(x));
  return static_cast<real>(x);
}


// A Python callable kept by C++: dropped with the GIL held, since step() runs without it.
struct PythonCallable {
  nb::object fn;
  ~PythonCallable() {
    nb::gil_scoped_acquire gil;
    fn.reset();
  }
};

// A Python callable as a step callback: copies share one holder (no Python reference counting
// without the GIL); a Python exception propagates out of step() as itself, traceback included.
StepCallback python_step_callback(nb::callable fn) {
  auto holder = std::make_shared<PythonCallable>(PythonCallable{std::move(fn)});
  return [holder](Scene& scene, real dt) {
    nb::gil_scoped_acquire gil;
    holder->fn(scene, dt);
  };
}

nb::callable callable_of(nb::handle fn, const std::string& arg) {
  if (!PyCallable_Check(fn.ptr())) throw Error(arg + ": expected a callable fn(scene, dt), got " + nb::inst_name(fn).c_str());
  return nb::borrow<nb::callable>(fn);
}

// The faults that the last step clamped (NumericalFaultPolicy.WARN_AND_CLAMP), as RuntimeWarnings.
void warn_numerical_faults(const Scene& s) {
  for (const NumericalFault& f : s.last_numerical_faults())
    if (PyErr_WarnEx(PyExc_RuntimeWarning, f.message.c_str(), 1) != 0) throw nb::python_error();
}

void emit_warnings(const std::vector<std::string>& warnings) {
  for (const std::string& w : warnings) PyErr_WarnEx(PyExc_UserWarning, w.c_str(), 1);
}

}  // namespace

ActorHandle actor_handle_of(nb::handle obj, const std::string& arg) {
  if (nb::isinstance<Actor>(obj)) return nb::cast<Actor&>(obj).handle;
  ActorHandle h;
  if (!nb::try_cast(obj, h)) throw Error(arg + ": expected an Actor or an actor handle");
  return h;
}

// A Python object made of dicts, lists, strings, numbers, booleans and None, as JSON.
// Non-finite floats are kept so that the reader can name the field that holds them.
nlohmann::json to_json(nb::handle obj, const std::string& path) {
  if (obj.is_none()) return nullptr;
  if (nb::isinstance<nb::bool_>(obj)) return nb::cast<bool>(obj);
  if (nb::isinstance<nb::int_>(obj)) return nb::cast<long long>(obj);
  if (nb::isinstance<nb::float_>(obj)) return nb::cast<double>(obj);
  if (nb::isinstance<nb::str>(obj)) return nb::cast<std::string>(obj);
  if (nb::isinstance<nb::dict>(obj)) {
    nlohmann::json out = nlohmann::json::object();
    for (auto [k, v] : nb::cast<nb::dict>(obj)) {
      if (!nb::isinstance<nb::str>(k)) throw Error(path + ": dict keys must be strings");
      const std::string key = nb::cast<std::string>(k);
      out[key] = to_json(v, path + "." + key);
    }
    return out;
  }
  if (nb::isinstance<nb::list>(obj) || nb::isinstance<nb::tuple>(obj) || nb::hasattr(obj, "tolist")) {
    nb::object seq = nb::hasattr(obj, "tolist") ? obj.attr("tolist")() : nb::borrow(obj);
    if (!nb::isinstance<nb::list>(seq) && !nb::isinstance<nb::tuple>(seq)) return to_json(seq, path);
    nlohmann::json out = nlohmann::json::array();
    size_t i = 0;
    for (nb::handle item : seq) out.push_back(to_json(item, path + "[" + std::to_string(i++) + "]"));
    return out;
  }
  if (nb::hasattr(obj, "__float__")) return nb::cast<double>(obj.attr("__float__")());
  throw Error(path + ": cannot be read as JSON (got " + std::string(nb::inst_name(obj).c_str()) + ")");
}

void export_scene(nb::module_& m) {
  nb::class_<SceneState>(m, "SceneState", "A captured scene state (see Scene.capture_state).")
      .def("to_bytes", [](const SceneState& st) { return nb::bytes(reinterpret_cast<const char*>(st.bytes.data()), st.bytes.size()); });

  nb::class_<SolverParams>(m, "SolverParams", "Parameters of the implicit solve.")
      .def(nb::init<>())
      .def_rw("max_newton_iterations", &SolverParams::max_newton_iterations)
      .def_rw("absolute_tolerance", &SolverParams::absolute_tolerance)
      .def_rw("relative_tolerance", &SolverParams::relative_tolerance)
      .def_rw("max_line_search_iterations", &SolverParams::max_line_search_iterations)
      .def_rw("near_rigid_beta", &SolverParams::near_rigid_beta)
      .def_rw("friction_sigma", &SolverParams::friction_sigma)
      .def_rw("contact_margin", &SolverParams::contact_margin)
      .def_rw("drift_correction_iterations", &SolverParams::drift_correction_iterations)
      .def_rw("defer_inactive_joint_limits", &SolverParams::defer_inactive_joint_limits)
      .def_rw("soft_hessian_reuse_strain", &SolverParams::soft_hessian_reuse_strain)
      .def_rw("dense_island_max_dofs", &SolverParams::dense_island_max_dofs);

  nb::class_<SolverStats>(m, "SolverStats", "What the last step did.")
      .def_ro("newton_iterations", &SolverStats::newton_iterations)
      .def_ro("total_newton_iterations", &SolverStats::total_newton_iterations)
      .def_ro("residual", &SolverStats::residual)
      .def_ro("converged", &SolverStats::converged)
      .def_ro("num_islands", &SolverStats::num_islands)
      .def_ro("num_constraints", &SolverStats::num_constraints)
      .def_ro("num_contacts", &SolverStats::num_contacts)
      .def_ro("soft_element_hessians", &SolverStats::soft_element_hessians)
      .def_ro("soft_factorizations", &SolverStats::soft_factorizations)
      .def_ro("time_kinematics", &SolverStats::time_kinematics)
      .def_ro("time_collision", &SolverStats::time_collision)
      .def_ro("time_solve", &SolverStats::time_solve)
      .def_ro("time_total", &SolverStats::time_total);

  nb::class_<Scene>(m, "Scene", "A set of actors stepped together. Not thread-safe: use one scene from one thread at a time.")
      .def("get_name", &Scene::name)
      .def("get_handle", &Scene::handle)
      .def("set_gravity", [](Scene& s, nb::handle g) { s.set_gravity(read_vec3(g, "set_gravity: gravity")); }, "gravity"_a,
           "Gravity in m/s^2, world frame (Z up).")
      .def("get_gravity", [](const Scene& s) { return s.gravity(); })
      .def("step", [](Scene& s, nb::handle dt) {
             double x;
             if (!nb::try_cast(dt, x)) throw Error(std::string("step: dt: expected a number of seconds, got ") + nb::inst_name(dt).c_str());
             {
               nb::gil_scoped_release release;
               s.step(static_cast<real>(x));
             }
             warn_numerical_faults(s);
           }, "dt"_a,
           "Advances the scene by dt seconds (releases the GIL while the physics runs).\n\n"
           "Raises superdex.physics.Error for a dt that is not a positive finite number and, under the\n"
           "default NumericalFaultPolicy.RAISE, for a numerical fault (the scene then keeps its last good\n"
           "state). An exception raised by a Python callback or component propagates as itself, with its\n"
           "traceback. Thread safety: different scenes may be stepped from different Python threads at\n"
           "the same time; one scene must not be used from two threads at once.")
      .def("get_total_simulation_time", &Scene::total_simulation_time)
      .def("get_solver_params", &Scene::solver_params)
      .def("set_solver_params", [](Scene& s, nb::handle params) {
             s.set_solver_params(object_of<SolverParams>(params, "set_solver_params: params", "a superdex.physics.SolverParams"));
           }, "params"_a.none())
      .def("get_solver_stats", &Scene::solver_stats)
      .def("set_numerical_fault_policy", [](Scene& s, nb::handle policy) {
             NumericalFaultPolicy p;
             if (!nb::try_cast(policy, p))
               throw Error(std::string("set_numerical_fault_policy: policy: expected a superdex.physics.NumericalFaultPolicy, got ") +
                           nb::inst_name(policy).c_str());
             s.set_numerical_fault_policy(p);
           }, "policy"_a,
           "NumericalFaultPolicy.RAISE (default): a step whose result is not finite or does not converge raises\n"
           "superdex.physics.Error naming the actor and quantity, and the scene keeps its last good state.\n"
           "NumericalFaultPolicy.WARN_AND_CLAMP: the step goes on, the faulty island's bodies keep their last\n"
           "good positions with zero velocity, and each fault is a RuntimeWarning (get_last_numerical_faults()).\n"
           "Not thread-safe: call it while no thread steps this scene.")
      .def("get_numerical_fault_policy", &Scene::numerical_fault_policy)
      .def("get_last_numerical_faults", &Scene::last_numerical_faults,
           "The faults the last step clamped under WARN_AND_CLAMP (empty after a clean step).")
      .def("create_rigid_actor",
           [](Scene& s, const std::string& name, nb::handle shape, bool is_static, nb::handle world_from_local,
              ColliderType collider_type, nb::handle density, nb::handle mass, int layer, nb::handle contact) {
             const std::string where = "create_rigid_actor('" + name + "')";
             const ShapeHandle h = shape_handle_of(shape, where + ": shape");
             const Transform X = read_transform(world_from_local, where + ": world_from_local");
             ContactMaterial material;
             if (!contact.is_none()) material = contact_material_from_json(to_json(contact, "contact"), where, "contact");
             if (layer < 0 || layer > 63) throw Error(where + ": layer must be between 0 and 63, got " + std::to_string(layer));
             const ActorHandle a = s.create_rigid_actor(name, h, is_static, X, optional_positive(density, where + ": density"),
                                                        optional_positive(mass, where + ": mass"), material, layer, collider_type);
             return Actor{s, a};
           },
           "name"_a, "shape"_a, "is_static"_a = false, "world_from_local"_a.none() = nb::none(),
           "collider_type"_a = ColliderType::Auto, "density"_a.none() = nb::none(), "mass"_a.none() = nb::none(), "layer"_a = 0,
           "contact"_a.none() = nb::none(),
           "A rigid body: static, or dynamic (mass from `mass` kg, else `density` kg/m^3, default 1000).")
      .def("create_articulated_actor",
           [](Scene& s, const std::string& name, nb::handle links, nb::handle joints, nb::handle world_from_root,
              nb::handle default_pose, nb::handle contact_overrides) {
             const std::string source = "create_articulated_actor('" + name + "')";
             nlohmann::json doc;
             doc["name"] = name;
             doc["links"] = to_json(links, "links");
             doc["joints"] = to_json(joints, "joints");
             if (!default_pose.is_none()) doc["defaultPose"] = to_json(default_pose, "defaultPose");
             if (!contact_overrides.is_none()) doc["contactOverrides"] = to_json(contact_overrides, "contactOverrides");
             std::vector<std::string> warnings;
             ArticulationDesc desc = articulation_desc_from_json(doc, source, &warnings);
             desc.world_from_root = read_transform(world_from_root, source + ": world_from_root");
             emit_warnings(warnings);
             return Actor{s, s.create_articulated_actor(desc, source)};
           },
           "name"_a, "links"_a, "joints"_a, "world_from_root"_a.none() = nb::none(), "default_pose"_a.none() = nb::none(),
           "contact_overrides"_a.none() = nb::none(),
           "An articulation from lists of link and joint dicts with the .superdex_bot fields (FORMATS.md);\n"
           "contact_overrides: [{linkA, linkB, enable}] as in bot files.")
      .def("create_soft_actor",
           [](Scene& s, const std::string& name, nb::handle shape, nb::handle material, nb::handle world_from_local,
              nb::handle density, nb::handle fixed_nodes) {
             const std::string where = "create_soft_actor('" + name + "')";
             SoftMaterial mat;
             if (!material.is_none()) {
               std::vector<std::string> warnings;
               mat = soft_material_from_json(to_json(material, "material"), where, "material", &warnings);
               emit_warnings(warnings);
             }
             if (!density.is_none()) mat.density = *optional_positive(density, where + ": density");
             std::vector<int> fixed;
             if (!fixed_nodes.is_none()) {
               const VecX f = read_vector(fixed_nodes, where + ": fixed_nodes");
               for (Eigen::Index i = 0; i < f.size(); ++i) fixed.push_back(static_cast<int>(f[i]));
             }
             return Actor{s, s.create_soft_actor(name, shape_handle_of(shape, where + ": shape"), mat,
                                                 read_transform(world_from_local, where + ": world_from_local"), fixed)};
           },
           "name"_a, "shape"_a, "material"_a.none() = nb::none(), "world_from_local"_a.none() = nb::none(),
           "density"_a.none() = nb::none(), "fixed_nodes"_a.none() = nb::none(),
           "A soft body from a tet-mesh shape; material {type, youngsModulus, poissonRatio, density, damping\n"
           "(stiffness-proportional Rayleigh, s), dampingAlpha (mass-proportional, 1/s)}; fixed_nodes are pinned.")
      .def("get_actor", [](Scene& s, nb::handle handle) {
             const ActorHandle h = actor_handle_of(handle, "get_actor: handle");
             if (!s.has_actor(h)) throw Error("get_actor: actor " + std::to_string(h) + " does not exist in scene '" + s.name() + "'");
             return Actor{s, h};
           }, "handle"_a)
      .def("destroy_actor", [](Scene& s, nb::handle actor) { s.destroy_actor(actor_handle_of(actor, "destroy_actor")); }, "actor"_a)
      .def("for_each_actor", [](Scene& s, nb::callable fn) {
             for (ActorHandle h : s.actors())
               if (s.has_actor(h)) fn(Actor{s, h});
           }, "fn"_a, "Calls fn(actor) for every rigid and articulated actor, in creation order.")
      .def("get_actors", [](Scene& s) {
             std::vector<Actor> out;
             for (ActorHandle h : s.actors()) out.push_back(Actor{s, h});
             return out;
           })
      .def("enable_actor_contact_symmetric", [](Scene& s, nb::handle a, nb::handle b, bool enable) {
             s.enable_actor_contact(actor_handle_of(a, "enable_actor_contact_symmetric: a"),
                                    actor_handle_of(b, "enable_actor_contact_symmetric: b"), enable);
           }, "a"_a, "b"_a, "enable"_a, "Enables or disables contact between two actors (both ways).")
      .def("enable_layer_contact_symmetric", &Scene::enable_layer_contact, "layer_a"_a, "layer_b"_a, "enable"_a,
           "Enables or disables contact between two collision layers (0..63, both ways).")
      .def("register_pre_step_callback", [](Scene& s, const std::string& name, nb::handle fn, int priority) {
             s.register_pre_step_callback(name, python_step_callback(callable_of(fn, "register_pre_step_callback('" + name + "'): fn")), priority);
           }, "name"_a, "fn"_a.none(), "priority"_a = 100,
           "Calls fn(scene, dt) at the start of every step, lower priority first. Exceptions propagate to step().")
      .def("register_post_step_callback", [](Scene& s, const std::string& name, nb::handle fn, int priority) {
             s.register_post_step_callback(name, python_step_callback(callable_of(fn, "register_post_step_callback('" + name + "'): fn")), priority);
           }, "name"_a, "fn"_a.none(), "priority"_a = 100, "Calls fn(scene, dt) at the end of every step.")
      .def("cancel_callback", &Scene::cancel_callback, "name"_a)
      .def("capture_state", [](const Scene& s) { return SceneState{s.capture_state()}; },
           "The evolving state; restore_state() replays bitwise identically.")
      .def("restore_state", [](Scene& s, nb::handle state) {
             s.restore_state(object_of<SceneState>(state, "restore_state: state", "a SceneState from capture_state()").bytes);
           }, "state"_a.none())
      .def("capture_state_to_bytes", [](const Scene& s) {
             const std::vector<std::uint8_t> b = s.capture_state();
             return nb::bytes(reinterpret_cast<const char*>(b.data()), b.size());
           })
      .def("restore_state_from_bytes", [](Scene& s, nb::bytes b) {
             const auto* p = static_cast<const std::uint8_t*>(b.data());
             s.restore_state(std::vector<std::uint8_t>(p, p + b.size()));
           }, "data"_a)
      .def("__eq__", [](const Scene& a, const Scene& b) { return a.handle() == b.handle(); })
      .def("__hash__", [](const Scene& a) { return a.handle(); })
      .def("__repr__", [](const Scene& s) { return "Scene(" + std::to_string(s.handle()) + ")"; });
}

}  // namespace superdex::python

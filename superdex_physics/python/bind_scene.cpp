// The Scene class: gravity, solver params and stats, stepping and step callbacks, actor creation
// from params (or their fields as keywords), lookup and destruction, captured states, contact
// filters, and the numerical fault policy.

#include <nanobind/stl/optional.h>
#include <nanobind/stl/string.h>

#include "bind_common.h"
#include "bind_container.h"
#include "struct_binder.h"
#include "superdex/physics/engine.h"

namespace superdex::python {

namespace {

// A Python callable kept by C++: dropped with the GIL held, since step() runs without it.
struct PythonCallable {
  nb::object fn;
  ~PythonCallable() {
    if (!Py_IsInitialized()) {
      fn.release();  // the interpreter is gone: leave its object alone
      return;
    }
    nb::gil_scoped_acquire gil;
    fn.reset();
  }
};

// A Python callable as a step callback: fn(info) with a StepInfo of its own; a Python exception
// propagates out of step() as itself, traceback included.
StepCallback python_step_callback(nb::handle fn, const std::string& what) {
  if (!PyCallable_Check(fn.ptr())) throw Error(what + ": callback must be callable as callback(info: StepInfo), got " + nb::inst_name(fn).c_str());
  auto holder = std::make_shared<PythonCallable>(PythonCallable{nb::borrow(fn)});
  return [holder](const StepInfo& info) {
    nb::gil_scoped_acquire gil;
    holder->fn(StepInfo(info));
  };
}

// The faults that the last step clamped (NumericalFaultPolicy.WARN_AND_CLAMP), as RuntimeWarnings.
void warn_numerical_faults(const Scene& s) {
  for (const NumericalFault& f : s.last_numerical_faults())
    if (PyErr_WarnEx(PyExc_RuntimeWarning, f.message.c_str(), 1) != 0) throw nb::python_error();
}

// Params built from keyword arguments (the create_*_actor keyword forms).
template <class Params>
Params params_from_kwargs(nb::handle params_type, nb::kwargs kwargs) {
  return nb::cast<Params>(params_type(**kwargs));
}

// Bytes from bytes, bytearray, a DynamicArrayUint8 or an array of uint8.
std::vector<std::uint8_t> read_bytes(nb::handle data, const char* what) {
  if (nb::isinstance<std::vector<std::uint8_t>>(data)) return nb::cast<std::vector<std::uint8_t>&>(data);
  if (PyBytes_Check(data.ptr())) {
    const auto* p = reinterpret_cast<const std::uint8_t*>(PyBytes_AS_STRING(data.ptr()));
    return std::vector<std::uint8_t>(p, p + PyBytes_GET_SIZE(data.ptr()));
  }
  if (PyByteArray_Check(data.ptr())) {
    const auto* p = reinterpret_cast<const std::uint8_t*>(PyByteArray_AS_STRING(data.ptr()));
    return std::vector<std::uint8_t>(p, p + PyByteArray_GET_SIZE(data.ptr()));
  }
  nb::ndarray<const std::uint8_t, nb::ndim<1>, nb::c_contig> a;
  if (nb::try_cast(data, a, true)) return std::vector<std::uint8_t>(a.data(), a.data() + a.shape(0));
  throw Error(std::string(what) + ": data: expected bytes, a bytearray, a DynamicArrayUint8 or a uint8 array, got " + nb::inst_name(data).c_str());
}

// The handle of an actor argument that must exist in the scene; errors name the argument.
ActorHandle existing_actor(const Scene& s, nb::handle obj, const std::string& arg) {
  const ActorHandle h = actor_handle_of(obj, arg);
  if (!s.has_actor(h)) throw Error(arg + ": actor " + std::to_string(h) + " does not exist in scene '" + s.name() + "'");
  return h;
}

nb::object actor_or_none(const Scene& s, ActorHandle h) {
  if (!h.is_valid() || !s.has_actor(h)) return nb::none();
  return nb::cast(Actor{s, h});
}

}  // namespace

ActorHandle actor_handle_of(nb::handle obj, const std::string& arg) {
  if (nb::isinstance<Actor>(obj)) return nb::cast<Actor&>(obj).handle;
  ActorHandle h;
  if (nb::try_cast(obj, h)) return h;
  throw Error(arg + ": expected an Actor or an ActorHandle, got " + std::string(nb::inst_name(obj).c_str()));
}

void export_scene(nb::module_& m) {
  nb::class_<Scene> scene(m, "Scene", "A set of actors stepped together. Not thread-safe: use one scene from one thread at a time.");
  add_recording_methods(scene);
  add_constraint_methods(scene);
  nb::class_<StepInfo>(m, "StepInfo", "What a step callback receives.")
      .def_ro("scene", &StepInfo::scene)
      .def_ro("time_step_sec", &StepInfo::time_step_sec, "s");
  nb::class_<NumericalFault>(m, "NumericalFault", "A numerical fault that the last step clamped.")
      .def_ro("actor", &NumericalFault::actor, "the rigid, articulated or soft actor")
      .def_ro("quantity", &NumericalFault::quantity, "\"positions\", \"velocities\", \"contact forces\", \"node positions\", ... or \"convergence\"")
      .def_ro("message", &NumericalFault::message)
      .def("__repr__", [](const NumericalFault& f) { return "NumericalFault(" + f.message + ")"; });

  scene.attr("DEFAULT_CALLBACK_PRIORITY") = Scene::kDefaultCallbackPriority;
  scene.def("get_handle", &Scene::handle)
      .def("get_name", &Scene::name)
      .def("get_gravity", &Scene::gravity, "m/s^2, world frame.")
      .def("set_gravity", &Scene::set_gravity, "gravity"_a, "m/s^2, world frame (default (0, -9.8, 0)).")
      .def("get_solver_params", &Scene::solver_params)
      .def("set_solver_params", &Scene::set_solver_params, "params"_a,
           "Validated: superdex.physics.Error names a field out of range or a choice this engine does not have.")
      .def("step", [](Scene& s, double time_step_sec) {
             {
               nb::gil_scoped_release release;
               s.step(time_step_sec);
             }
             warn_numerical_faults(s);
           }, "time_step_sec"_a,
           "Advances the scene by time_step_sec seconds (>= 0; 0 runs the callbacks and updates queries without moving\n"
           "anything), releasing the GIL while the physics runs. Raises superdex.physics.Error for a negative or\n"
           "non-finite time step and, under the default NumericalFaultPolicy.RAISE, for a numerical fault (the scene\n"
           "then keeps its last good state). An exception raised by a Python callback or component propagates as itself.")
      .def("update_debugger", [](Scene& s) {
             nb::gil_scoped_release release;
             s.update_debugger();
           },
           "Shows the scene's current state in the debugger without stepping it: a frame to the connected pages and\n"
           "to a running recording (only when it differs from the scene's last frame). For scenes a script poses or\n"
           "solves rather than steps, such as a checkpoint that worker scenes restore from.")
      .def("get_last_time_step", &Scene::last_time_step, "s: the last positive time step.")
      .def("get_total_simulation_time", &Scene::total_simulation_time, "s")
      .def("get_solver_stats", &Scene::solver_stats)
      .def("get_performance_stats", &Scene::performance_stats)
      .def("set_force_single_island", &Scene::set_force_single_island, "force_single_island"_a)
      .def("get_force_single_island", &Scene::force_single_island)
      .def("set_numerical_fault_policy", &Scene::set_numerical_fault_policy, "policy"_a,
           "NumericalFaultPolicy.RAISE (default): a step whose result is not finite or whose solve diverges raises\n"
           "superdex.physics.Error naming the actor and quantity, and the scene keeps its last good state.\n"
           "NumericalFaultPolicy.WARN_AND_CLAMP: the step goes on, the faulty island's bodies keep their last good\n"
           "positions with zero velocity, and each fault is a RuntimeWarning (get_last_numerical_faults()).")
      .def("get_numerical_fault_policy", &Scene::numerical_fault_policy)
      .def("get_last_numerical_faults", [](const Scene& s) { return to_list(s.last_numerical_faults()); },
           "The faults the last step clamped under WARN_AND_CLAMP (empty after a clean step).")
      // captured states
      .def("capture_state", &Scene::capture_state, "A handle to a copy of the scene's evolving state.")
      .def("restore_state", &Scene::restore_state, "handle"_a, "release_immediately"_a,
           "Restores a captured state (bitwise: the same steps follow); releases it when release_immediately.")
      .def("release_state", &Scene::release_state, "handle"_a)
      .def("release_all_states", &Scene::release_all_states)
      .def("is_equal_state", &Scene::is_equal_state, "state_a"_a, "state_b"_a)
      .def("capture_state_to_bytes", [](const Scene& s, nb::handle out) {
             std::vector<std::uint8_t> bytes;
             s.capture_state_to_bytes(bytes);
             if (nb::isinstance<std::vector<std::uint8_t>>(out)) {
               auto& v = nb::cast<std::vector<std::uint8_t>&>(out);
               v.insert(v.end(), bytes.begin(), bytes.end());
             } else if (PyByteArray_Check(out.ptr())) {
               nb::borrow<nb::object>(out).attr("extend")(nb::bytes(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
             } else {
               throw Error("capture_state_to_bytes: out_data: expected a DynamicArrayUint8 or a bytearray, got " +
                           std::string(nb::inst_name(out).c_str()));
             }
           }, "out_data"_a, "Appends the state's bytes to out_data (same build and scene only).")
      .def("restore_state_from_bytes", [](Scene& s, nb::handle data) {
             const std::vector<std::uint8_t> bytes = read_bytes(data, "restore_state_from_bytes");
             s.restore_state_from_bytes(bytes);
           }, "data"_a)
      .def("capture_state_to_file", &Scene::capture_state_to_file, "file_path"_a, "A JSON snapshot for inspection.")
      // actors
      .def("create_rigid_actor", [](Scene& s, const RigidActorParams& p) { return Actor{s, s.create_rigid_actor(p)}; }, "params"_a)
      .def("create_rigid_actor", [](Scene& s, nb::kwargs kwargs) {
             nb::object params = nb::module_::import_("superdex.physics").attr("RigidActorParams")(**kwargs);
             return Actor{s, s.create_rigid_actor(nb::cast<const RigidActorParams&>(params))};
           }, "A rigid actor from RigidActorParams, or from its fields as keywords.")
      .def("create_soft_actor", [](Scene& s, const SoftActorParams& p) { return Actor{s, s.create_soft_actor(p)}; }, "params"_a)
      .def("create_soft_actor", [](Scene& s, nb::kwargs kwargs) {
             nb::object params = nb::module_::import_("superdex.physics").attr("SoftActorParams")(**kwargs);
             return Actor{s, s.create_soft_actor(nb::cast<const SoftActorParams&>(params))};
           }, "A soft actor from SoftActorParams, or from its fields as keywords.")
      .def("create_articulated_actor", [](Scene& s, const ArticulatedActorParams& p) { return Actor{s, s.create_articulated_actor(p)}; },
           "params"_a)
      .def("create_articulated_actor", [](Scene& s, nb::kwargs kwargs) {
             nb::object params = nb::module_::import_("superdex.physics").attr("ArticulatedActorParams")(**kwargs);
             return Actor{s, s.create_articulated_actor(nb::cast<const ArticulatedActorParams&>(params))};
           }, "An articulated actor from ArticulatedActorParams, or from its fields as keywords.")
      .def("create_soft_skinned_actor", [](Scene& s, const SoftSkinnedActorParams& p) { return Actor{s, s.create_soft_skinned_actor(p)}; },
           "params"_a)
      .def("create_soft_skinned_actor", [](Scene& s, nb::kwargs kwargs) {
             nb::object params = nb::module_::import_("superdex.physics").attr("SoftSkinnedActorParams")(**kwargs);
             return Actor{s, s.create_soft_skinned_actor(nb::cast<const SoftSkinnedActorParams&>(params))};
           }, "A soft-skinned actor (an articulated actor with soft bodies tied to its links) from SoftSkinnedActorParams, or from its "
              "fields as keywords.")
      .def("destroy_actor", [](Scene& s, nb::handle actor) {
             if (actor.is_none()) return;
             // an Actor knows its scene: one of another live scene is a mistake, not a destroyed actor
             if (nb::isinstance<Actor>(actor)) {
               const Actor& a = nb::cast<const Actor&>(actor);
               if (a.scene.handle() != s.handle() && physics::scene_exists(a.scene.handle()))
                 throw Error("destroy_actor: actor: actor " + std::to_string(a.handle) + " belongs to scene '" + a.scene.name() + "', not '" +
                             s.name() + "'");
             }
             const ActorHandle h = actor_handle_of(actor, "destroy_actor: actor");
             if (!s.has_actor(h)) return;
             if (s.is_nested_link_actor(h))
               throw Error("destroy_actor: actor " + std::to_string(h) + " is a link of an articulated actor; destroy the articulated actor");
             s.destroy_actor(h);
           }, "actor"_a.none(), "Destroys an actor (an articulation with its links); no effect for None or a destroyed actor.")
      .def("get_actor", [](const Scene& s, ActorHandle h) { return actor_or_none(s, h); }, "actor"_a, "The actor with this handle, or None.")
      .def("get_num_actors", [](const Scene& s) { return s.all_actors().size(); }, "Every actor, links included.")
      .def("for_each_actor", [](const Scene& s, nb::callable fn) {
             for (ActorHandle h : s.all_actors())
               if (s.has_actor(h)) fn(Actor{s, h});
           }, "callback"_a, "Calls callback(actor) for every actor, links included, in creation order.")
      // contact filters
      .def("enable_layer_contact_asymmetric", &Scene::enable_layer_contact_asymmetric, "layer_a"_a, "layer_b"_a, "enable"_a,
           "Contact of colliding actors of layer_a with colliders of layer_b (enabled by default).")
      .def("enable_layer_contact_symmetric", &Scene::enable_layer_contact_symmetric, "layer_a"_a, "layer_b"_a, "enable"_a)
      .def("is_layer_contact_enabled", &Scene::is_layer_contact_enabled, "layer_a"_a, "layer_b"_a)
      .def("get_num_contact_layers", &Scene::num_contact_layers)
      .def("enumerate_contact_layer_names", [](const Scene& s, nb::callable fn) {
             for (const std::string& name : s.contact_layer_names()) fn(name);
           }, "callback"_a)
      .def("enable_actor_contact_asymmetric", [](Scene& s, nb::handle colliding, nb::handle collider, bool enable, IncludeNestedActors nested) {
             // in argument order, so that an error names the first bad one
             const ActorHandle a = existing_actor(s, colliding, "enable_actor_contact_asymmetric: colliding");
             const ActorHandle b = existing_actor(s, collider, "enable_actor_contact_asymmetric: collider");
             s.enable_actor_contact_asymmetric(a, b, enable, nested);
           }, "colliding"_a, "collider"_a, "enable"_a, "include_nested_actors"_a)
      .def("enable_actor_contact_symmetric", [](Scene& s, nb::handle a, nb::handle b, bool enable, IncludeNestedActors nested) {
             const ActorHandle ha = existing_actor(s, a, "enable_actor_contact_symmetric: actor_a");
             const ActorHandle hb = existing_actor(s, b, "enable_actor_contact_symmetric: actor_b");
             s.enable_actor_contact_symmetric(ha, hb, enable, nested);
           }, "actor_a"_a, "actor_b"_a, "enable"_a, "include_nested_actors"_a)
      // callbacks
      .def("register_pre_step_callback", [](Scene& s, const std::string& debug_name, nb::handle callback, int priority) {
             return s.register_pre_step_callback(debug_name, python_step_callback(callback, "register_pre_step_callback('" + debug_name + "')"),
                                                 priority);
           }, "debug_name"_a, "callback"_a.none(), "priority"_a = Scene::kDefaultCallbackPriority,
           "Calls callback(info) at the start of every step, lower priority first. Exceptions propagate to step().")
      .def("register_post_step_callback", [](Scene& s, const std::string& debug_name, nb::handle callback, int priority) {
             return s.register_post_step_callback(debug_name, python_step_callback(callback, "register_post_step_callback('" + debug_name + "')"),
                                                  priority);
           }, "debug_name"_a, "callback"_a.none(), "priority"_a = Scene::kDefaultCallbackPriority, "Calls callback(info) at the end of every step.")
      .def("cancel_callback", &Scene::cancel_callback, "handle"_a, "No effect for an invalid or cancelled handle.")
      .def("get_debug_draw", &Scene::debug_draw, "The scene's debug drawing (DebugDraw): off until DebugDraw.enable(True).")
      .def("__eq__", [](const Scene& a, const Scene& b) { return a.handle() == b.handle(); }, nb::is_operator())
      .def("__ne__", [](const Scene& a, const Scene& b) { return a.handle() != b.handle(); }, nb::is_operator())
      .def("__hash__", [](const Scene& a) { return std::hash<std::int64_t>()(a.handle().value); })
      .def("__repr__", [](const Scene& s) { return "Scene(" + std::to_string(s.handle().value) + ")"; });

  nb::enum_<NumericalFaultPolicy>(m, "NumericalFaultPolicy",
                                  "What scene.step does when a body's next state is not finite or its solve diverges.")
      .value("RAISE", NumericalFaultPolicy::Raise,
             "raise superdex.physics.Error naming the actor and quantity; the scene keeps its last good state (default)")
      .value("WARN_AND_CLAMP", NumericalFaultPolicy::WarnAndClamp,
             "warn (RuntimeWarning) and keep going: a faulty island's bodies keep their last good positions with zero velocity");
}

}  // namespace superdex::python

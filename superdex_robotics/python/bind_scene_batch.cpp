// superdex.robotics.SceneBatch: batched stepping of scenes of one model (scene_batch.h). The
// arrays are checked and their buffers taken with the GIL held; reset and step then run without
// it, spread over the engine's worker threads.

#include <nanobind/stl/array.h>
#include <nanobind/stl/string.h>

#include "bind_common.h"
#include "superdex/robotics/scene_batch.h"

namespace superdex::python {

using robotics::BatchActionMode;
using robotics::BatchTask;
using robotics::BatchTaskKind;
using robotics::SceneBatch;
using robotics::SceneBatchMember;
using robotics::SceneBatchSpec;

namespace {

std::string shape_text(const std::vector<size_t>& shape) {
  std::string text = "(";
  for (size_t i = 0; i < shape.size(); ++i) text += (i ? ", " : "") + std::to_string(shape[i]);
  return text + (shape.size() == 1 ? ",)" : ")");
}

// The buffer of a C-contiguous numpy array of dtype T and the given shape (1 or 2 dimensions);
// raises superdex.physics.Error naming `arg` otherwise.
template <typename T>
T* array_buffer(nb::handle obj, const std::string& arg, const std::vector<size_t>& shape, bool writable) {
  const std::string dtype = std::is_same_v<std::remove_const_t<T>, double> ? "float64" : "float32";
  const std::string expect = std::string(writable ? "a writable" : "a") + ", C-contiguous numpy array of dtype " + dtype + " and shape " +
                             shape_text(shape);
  if (writable && nb::hasattr(obj, "flags") && !nb::cast<bool>(obj.attr("flags").attr("writeable")))
    throw Error(arg + ": expected " + expect + ", got a read-only array");
  nb::ndarray<> a;
  if (!nb::try_cast(obj, a, false)) throw Error(arg + ": expected " + expect + ", got " + nb::inst_name(obj).c_str());
  bool same_shape = a.ndim() == shape.size();
  // C order: the last axis has stride 1, each other the product of the extents after it
  bool contiguous = true;
  int64_t stride = 1;
  for (size_t d = a.ndim(); d-- > 0;) {
    same_shape = same_shape && a.shape(d) == shape[d];
    contiguous = contiguous && (a.shape(d) <= 1 || a.stride(d) == stride);
    stride *= static_cast<int64_t>(a.shape(d));
  }
  if (a.dtype() != nb::dtype<std::remove_const_t<T>>() || !same_shape || !contiguous) {
    std::string got = "ndim " + std::to_string(a.ndim());
    if (a.ndim() == shape.size()) {
      std::vector<size_t> have(a.ndim());
      for (size_t d = 0; d < a.ndim(); ++d) have[d] = a.shape(d);
      got = "shape " + shape_text(have);
    }
    if (a.dtype() != nb::dtype<std::remove_const_t<T>>()) got += " with another dtype";
    else if (!contiguous) got += ", not contiguous";
    throw Error(arg + ": expected " + expect + ", got " + got);
  }
  return static_cast<T*>(a.data());
}

// The spec's per-column lists as Python lists. No std::vector caster is included here (the physics
// bindings bind vectors of their element types as DynamicArrays, std::vector<double> only in the
// double build), so the fields are read from any sequence or array of numbers and given back as
// lists of Python numbers, in both builds alike.
template <class T>
nb::list to_py_list(const std::vector<T>& values) {
  nb::list l;
  for (const T& x : values) l.append(nb::cast(x));
  return l;
}

template <class T>
std::vector<T> from_py_sequence(nb::handle obj, const std::string& field) {
  if (!nb::hasattr(obj, "__iter__") || nb::isinstance<nb::str>(obj))
    throw Error("SceneBatchSpec." + field + ": expected a sequence of numbers, got " + nb::inst_name(obj).c_str());
  std::vector<T> out;
  size_t i = 0;
  for (nb::handle item : nb::iter(obj)) {
    T x;
    if constexpr (std::is_integral_v<T>) {
      if (!nb::try_cast(nb::module_::import_("operator").attr("index")(item), x))
        throw Error("SceneBatchSpec." + field + "[" + std::to_string(i) + "]: expected an integer, got " + nb::inst_name(item).c_str());
    } else if (!nb::try_cast(nb::float_(item), x)) {
      throw Error("SceneBatchSpec." + field + "[" + std::to_string(i) + "]: expected a number, got " + nb::inst_name(item).c_str());
    }
    out.push_back(x);
    ++i;
  }
  return out;
}

template <class T>
void def_list_field(nb::class_<SceneBatchSpec>& c, const char* name, std::vector<T> SceneBatchSpec::*field, const char* doc) {
  const std::string field_name = name;
  c.def_prop_rw(name, [field](const SceneBatchSpec& s) { return to_py_list(s.*field); },
                [field, field_name](SceneBatchSpec& s, nb::handle v) { s.*field = from_py_sequence<T>(v, field_name); }, doc);
}

}  // namespace

void export_scene_batch(nb::module_& m) {
  nb::enum_<BatchActionMode>(m, "BatchActionMode", "How a SceneBatch's actions drive its action DOFs (scene_batch.h).")
      .value("VELOCITY_SERVO", BatchActionMode::VelocityServo, "velocity goals (rad/s) of VELOCITY_SERVO PI servos, applied as efforts")
      .value("VELOCITY_DRIVE", BatchActionMode::VelocityDrive, "joint velocity commands (rad/s) tracked by implicit joint drives");

  nb::enum_<BatchTaskKind>(m, "BatchTaskKind", "The C++ task of a SceneBatch (scene_batch.h).")
      .value("NONE", BatchTaskKind::None, "no task columns, no reward")
      .value("CIRCLE_TRACKING", BatchTaskKind::CircleTracking,
             "follow a circle in the world's X-Z plane with force regulation (the seed's task); param: start phase (rad)")
      .value("GOAL_REACH", BatchTaskKind::GoalReach, "reach a goal point without pushing; params: the goal (m, world, 3)");

  nb::class_<BatchTask>(m, "BatchTask",
                        "A SceneBatch's task, computed in C++ per scene after its step: 3 observation columns (the target\n"
                        "point, m, world) and a reward (scene_batch.h gives the formulas).")
      .def(nb::init<>())
      .def_rw("kind", &BatchTask::kind)
      .def_rw("center", &BatchTask::center, "CIRCLE_TRACKING: circle centre (m, world)")
      .def_rw("radius", &BatchTask::radius, "CIRCLE_TRACKING: circle radius (m)")
      .def_rw("omega", &BatchTask::omega, "CIRCLE_TRACKING: angular speed along the circle (rad/s)")
      .def_rw("force_target", &BatchTask::force_target, "CIRCLE_TRACKING: force to hold on the prop (N)")
      .def_rw("force_weight", &BatchTask::force_weight, "weight of the reward's force term (GOAL_REACH: m/N)");

  nb::class_<SceneBatchSpec> spec(m, "SceneBatchSpec", "The model shared by every scene of a SceneBatch (units: rad, rad/s, N m, s).");
  spec.def(nb::init<>()).def_rw("mode", &SceneBatchSpec::mode);
  def_list_field(spec, "action_dofs", &SceneBatchSpec::action_dofs, "DOF index moved by each action column");
  def_list_field(spec, "action_low", &SceneBatchSpec::action_low, "per column lower clip (rad/s); empty: no clipping");
  def_list_field(spec, "action_high", &SceneBatchSpec::action_high, "");
  def_list_field(spec, "servo_k_p", &SceneBatchSpec::servo_k_p, "VELOCITY_SERVO: N m s/rad per column");
  def_list_field(spec, "servo_k_i", &SceneBatchSpec::servo_k_i, "VELOCITY_SERVO: N m/rad per column");
  def_list_field(spec, "servo_effort_limit", &SceneBatchSpec::servo_effort_limit, "VELOCITY_SERVO: N m per column");
  def_list_field(spec, "servo_profile_accel", &SceneBatchSpec::servo_profile_accel, "VELOCITY_SERVO: rad/s^2 per column (0: no ramp)");
  def_list_field(spec, "drive_stiffness", &SceneBatchSpec::drive_stiffness, "VELOCITY_DRIVE: N m/rad per column");
  def_list_field(spec, "drive_damping", &SceneBatchSpec::drive_damping, "VELOCITY_DRIVE: N m s/rad per column");
  def_list_field(spec, "drive_max_effort", &SceneBatchSpec::drive_max_effort, "VELOCITY_DRIVE: N m per column (< 0: unbounded)");
  spec.def_rw("observed_link", &SceneBatchSpec::observed_link, "link index E whose origin p_WE is observed")
      .def_rw("dt", &SceneBatchSpec::dt, "physics step (s)")
      .def_rw("substeps", &SceneBatchSpec::substeps, "physics steps per batch step")
      .def_rw("task", &SceneBatchSpec::task, "the task whose observation columns and reward each step writes (BatchTask)");

  nb::class_<SceneBatch>(m, "SceneBatch",
                         "Scenes of one model stepped in one call on the engine's worker threads. Observation rows are\n"
                         "[q (n) | v (n) | p_WE (3, m, world) | f_C_W (3, N, world: contact force on the contact actor)].")
      .def("__init__",
           [](SceneBatch* self, const SceneBatchSpec& spec, nb::sequence scenes, nb::sequence articulations, nb::sequence contact_actors) {
             const size_t count = nb::len(scenes);
             if (nb::len(articulations) != count || nb::len(contact_actors) != count)
               throw Error("SceneBatch: scenes, articulations and contact_actors must have the same length (" + std::to_string(count) + ", " +
                           std::to_string(nb::len(articulations)) + ", " + std::to_string(nb::len(contact_actors)) + ")");
             std::vector<SceneBatchMember> members(count);
             for (size_t k = 0; k < count; ++k) {
               const std::string index = "[" + std::to_string(k) + "]";
               Scene* scene = nullptr;
               if (!nb::try_cast(scenes[k], scene) || scene == nullptr) throw Error("SceneBatch: scenes" + index + " is not a Scene");
               members[k].scene = *scene;
               members[k].articulation = actor_handle_of(articulations[k], "SceneBatch: articulations" + index);
               nb::object c = contact_actors[k];
               members[k].contact_actor = c.is_none() ? ActorHandle() : actor_handle_of(c, "SceneBatch: contact_actors" + index);
             }
             new (self) SceneBatch(spec, std::move(members));
           },
           "spec"_a, "scenes"_a, "articulations"_a, "contact_actors"_a,
           "Checks the spec against every scene, registers the contact queries and captures each scene's initial state.")
      .def_prop_ro("num_scenes", &SceneBatch::num_scenes)
      .def_prop_ro("action_size", &SceneBatch::action_size)
      .def_prop_ro("obs_size", &SceneBatch::obs_size)
      .def_prop_ro("params_size", &SceneBatch::params_size, "task parameters per scene")
      .def(
          "reset",
          [](SceneBatch& b, nb::handle indices_arg, nb::handle q0, nb::handle obs_out, nb::handle params) {
            const std::vector<int> indices = read_indices(indices_arg, "SceneBatch.reset: indices");
            const size_t rows = indices.size(), n = b.action_size(), p = b.params_size();
            const double* q = q0.is_none() ? nullptr : array_buffer<const double>(q0, "SceneBatch.reset: q0", {rows, n}, false);
            real* obs = array_buffer<real>(obs_out, "SceneBatch.reset: obs_out", {size_t(b.num_scenes()), size_t(b.obs_size())}, true);
            const double* par = params.is_none() ? nullptr : array_buffer<const double>(params, "SceneBatch.reset: params", {rows, p}, false);
            nb::gil_scoped_release release;
            b.reset(indices, q, obs, par);
          },
          "indices"_a, "q0"_a.none(), "obs_out"_a, "params"_a.none() = nb::none(),
          "Restores the initial state of scenes `indices`, sets their action DOFs to the rows of q0 (float64,\n"
          "len(indices) x action_size; None: initial pose), resets servos and drives, sets their task parameters\n"
          "to the rows of params (float64, len(indices) x params_size; None: zeros) and their task time to 0,\n"
          "writes their rows of obs_out.")
      .def(
          "step",
          [](SceneBatch& b, nb::handle actions, nb::handle obs_out, nb::handle reward_out) {
            const size_t scenes = b.num_scenes();
            const double* a = array_buffer<const double>(actions, "SceneBatch.step: actions", {scenes, size_t(b.action_size())}, false);
            real* obs = array_buffer<real>(obs_out, "SceneBatch.step: obs_out", {scenes, size_t(b.obs_size())}, true);
            double* reward = reward_out.is_none() ? nullptr : array_buffer<double>(reward_out, "SceneBatch.step: reward_out", {scenes}, true);
            nb::gil_scoped_release release;
            b.step(a, obs, reward);
          },
          "actions"_a, "obs_out"_a, "reward_out"_a.none() = nb::none(),
          "Applies actions (float64, num_scenes x action_size) and steps every scene `substeps` times on the\n"
          "worker threads (GIL released); writes every row of obs_out (build dtype, num_scenes x obs_size) and,\n"
          "given reward_out (float64, num_scenes), every scene's task reward.")
      .def(
          "observe",
          [](SceneBatch& b, nb::handle obs_out) {
            real* obs = array_buffer<real>(obs_out, "SceneBatch.observe: obs_out", {size_t(b.num_scenes()), size_t(b.obs_size())}, true);
            b.observe(obs);
          },
          "obs_out"_a, "Writes every scene's observation row.");
}

}  // namespace superdex::python

// superdex.physics.experimental's inverse kinematics: IKSolverParams, the IKSolver on a scene of
// its own, and create_ik_solver / destroy_ik_solver / is_valid_ik_solver.

#include <memory>

#include "bind_common.h"
#include "bind_container.h"
#include "struct_binder.h"
#include "superdex/physics/engine.h"
#include "superdex/physics/ik_solver.h"

namespace superdex::python {

namespace {

using physics::IKSolver;
using physics::IKSolverParams;

// An IK solver as Python holds it: empty once destroyed.
struct PyIKSolver {
  std::shared_ptr<IKSolver> impl;
  IKSolver& get(const char* what) const {
    if (!impl) throw Error(std::string(what) + ": the IK solver was destroyed");
    if (!physics::scene_exists(impl->scene().handle())) throw Error(std::string(what) + ": the IK solver's scene was destroyed");
    return *impl;
  }
};

}  // namespace

void export_ik_solver(nb::module_& e) {
  StructBinder<IKSolverParams>(e, "IKSolverParams",
                               "Inverse kinematics: Gauss-Newton iterations (max_iter), stopping tolerances on the energy's\n"
                               "gradient (abs_tol) and relative decrease (rel_tol), and the errors a successful solve is within\n"
                               "(position_error_thres, m; rotation_error_thres, rad).")
      .field("max_iter", &IKSolverParams::max_iter)
      .field("verbosity", &IKSolverParams::verbosity)
      .field("abs_tol", &IKSolverParams::abs_tol)
      .field("rel_tol", &IKSolverParams::rel_tol)
      .field("position_error_thres", &IKSolverParams::position_error_thres)
      .field("rotation_error_thres", &IKSolverParams::rotation_error_thres)
      .field("line_search_max_iter", &IKSolverParams::line_search_max_iter)
      .field("max_elapsed_time_seconds", &IKSolverParams::max_elapsed_time_seconds)
      .done();

  nb::class_<PyIKSolver>(e, "IKSolver",
                         "Poses the articulations of its scene at the minimum of the energy of the scene's constraints: its\n"
                         "position and rotation targets (stiff constraints on links) and any other equality constraint.")
      .def("set_solver_params", [](PyIKSolver& s, const IKSolverParams& p) { s.get("set_solver_params").set_params(p); }, "params"_a)
      .def("get_solver_params", [](const PyIKSolver& s) { return s.get("get_solver_params").params(); })
      .def("create_position_target", [](PyIKSolver& s, ActorHandle actor, const Real3& local_position, const Real3& target_position, real weight) {
             IKSolver& ik = s.get("create_position_target");
             return Constraint{ik.scene(), ik.create_position_target(actor, local_position, target_position, weight)};
           }, "actor"_a, "local_position"_a, "target_position"_a, "weight"_a,
           "The point local_position (m, link frame) of a link actor to target_position (m, world), with stiffness weight\n"
           "(N/m); the returned constraint's set_target_position moves it.")
      .def("clear_position_target", [](PyIKSolver& s, ActorHandle actor) { s.get("clear_position_target").clear_position_target(actor); },
           "actor"_a)
      .def("create_rotation_target", [](PyIKSolver& s, ActorHandle actor, const Real3& local_rotation, const Real3& target_rotation, real weight) {
             IKSolver& ik = s.get("create_rotation_target");
             return Constraint{ik.scene(), ik.create_rotation_target(actor, local_rotation, target_rotation, weight)};
           }, "actor"_a, "local_rotation"_a, "target_rotation"_a, "weight"_a,
           "The link frame rotated by local_rotation to the world rotation target_rotation (rotation vectors, rad), with\n"
           "stiffness weight (N m/rad).")
      .def("clear_rotation_target", [](PyIKSolver& s, ActorHandle actor) { s.get("clear_rotation_target").clear_rotation_target(actor); },
           "actor"_a)
      .def("solve_ik", [](PyIKSolver& s) { return s.get("solve_ik").solve(); },
           "Poses the articulations (velocities zeroed); True when every target is within its threshold.")
      .def("get_scene", [](const PyIKSolver& s) { return s.get("get_scene").scene(); });

  e.def("create_ik_solver", [](const Scene& scene) {
         if (!physics::scene_exists(scene.handle())) throw Error("create_ik_solver: the scene was destroyed");
         return PyIKSolver{std::make_shared<IKSolver>(scene)};
       }, "scene"_a, "An IK solver on a scene of its own (it never steps it); destroy_ik_solver destroys that scene.");
  e.def("destroy_ik_solver", [](PyIKSolver& s) {
         if (!s.impl) return;
         if (physics::scene_exists(s.impl->scene().handle())) physics::destroy_scene(s.impl->scene().handle());
         s.impl.reset();
       }, "solver"_a, "Destroys the solver and its scene; no effect when destroyed already.");
  e.def("is_valid_ik_solver", [](const PyIKSolver& s) { return s.impl && physics::scene_exists(s.impl->scene().handle()); }, "solver"_a);
}

}  // namespace superdex::python

// The native module: one per scalar type (_superdex_float, _superdex_double), loaded by
// the `superdex.physics` package according to SUPERDEX_PRECISION. Types are registered before the
// functions whose defaults or signatures name them.

#include "bind_actor.h"

NB_MODULE(SUPERDEX_MODULE_NAME, m) {
  using namespace superdex::python;
  m.doc() = "SuperDex native engine";
  export_error(m);
  export_values(m);
  export_containers(m);
  export_handles(m);
  export_enums(m);
  export_solver_params(m);
  export_recording_params(m);
  export_material_params(m);
  export_actor_params(m);
  export_constants(m);
  export_context(m);
  export_debug_draw(m);
  export_constraints(m);
  export_pose_controller(m);
  export_scene(m);
  export_actor(m);
  export_experimental(m);
  export_debug_server(m);
  export_robotics(m);
  export_meshes(m);
  export_model(m);
  export_physics_prefab(m);
}

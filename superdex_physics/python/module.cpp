// The native module: one per scalar type (_superdex_float, _superdex_double), loaded by
// the `superdex.physics` package according to SUPERDEX_PRECISION.

#include "bind_common.h"

NB_MODULE(SUPERDEX_MODULE_NAME, m) {
  m.doc() = "SuperDex native engine";
  superdex::python::export_types(m);
  superdex::python::export_values(m);
  superdex::python::export_containers(m);
  superdex::python::export_engine(m);
  superdex::python::export_debug_server(m);
  superdex::python::export_scene(m);
  superdex::python::export_actor(m);
  superdex::python::export_robotics(m);
  superdex::python::export_meshes(m);
  superdex::python::export_prefab_loader(m);
}

// superdex.physics.experimental: per-element soft materials (SuperDex's experimental functions
// that this engine implements).

#include "bind_common.h"

namespace superdex::python {

void export_experimental(nb::module_& m) {
  nb::module_ e = m.def_submodule("experimental", "Functions whose form may still change.");
  e.def("set_soft_material_params_field", [](Actor& actor, const SoftMaterialParams& params, int element_index) {
          actor.scene.set_soft_material_params_field(actor.handle, params, element_index);
        }, "actor"_a, "params"_a, "element_index"_a,
        "The material of one tetrahedron of a soft actor (its index in get_mesh()): elastic model, moduli and density\n"
        "(the node masses follow). Validated as set_soft_material_params; set_soft_material_params resets every element.");
  e.def("get_soft_material_params_field", [](const Actor& actor, int element_index) {
          return actor.scene.soft_material_params_field(actor.handle, element_index);
        }, "actor"_a, "element_index"_a, "The material of one tetrahedron of a soft actor.");
}

}  // namespace superdex::python

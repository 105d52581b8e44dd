// The native side of superdex.physics.prefab: loading .mochi_prefab files into a scene.

#include <nanobind/stl/string.h>

#include "bind_common.h"
#include "superdex/physics/prefab.h"

namespace superdex::python {

void export_prefab_loader(nb::module_& m) {
  m.def("_add_prefab_to_scene",
        [](const std::string& prefab_path, const std::string& root_path, Scene& scene, const std::string& name, double scale,
           nb::handle world_from_prefab, bool apply_scene_settings) {
          PrefabParams params;
          params.name = name;
          params.scale = static_cast<real>(scale);
          params.world_from_prefab = read_transform(world_from_prefab, "PrefabParams: rotation/translation");
          params.apply_scene_settings = apply_scene_settings;
          std::vector<std::string> warnings;
          PrefabResult r = add_prefab_to_scene(prefab_path, root_path, scene, params, &warnings);
          for (const std::string& w : warnings) PyErr_WarnEx(PyExc_UserWarning, w.c_str(), 1);
          // Python lists: the constraint ids (std::vector<std::int64_t>) have no DynamicArray type
          return nb::make_tuple(to_list(r.actors), to_list(r.constraints));
        },
        "prefab_path"_a, "root_path"_a, "scene"_a, "name"_a, "scale"_a, "world_from_prefab"_a.none(), "apply_scene_settings"_a);
}

}  // namespace superdex::python

// Scene recordings to HDF5: RecordingParams and Scene.start_recording / stop_recording /
// is_recording (docs/recording_format.md, "Scene recordings").

#include <nanobind/stl/string.h>

#include "bind_common.h"
#include "bind_container.h"
#include "struct_binder.h"

namespace superdex::python {

void export_recording_params(nb::module_& m) {
  StructBinder<RecordingParams>(m, "RecordingParams",
                                "What a scene recording writes: per actor when first seen (meshes, DOF map, mass matrix), and per step.")
      .field("record_actor_meshes", &RecordingParams::record_actor_meshes, "the actor's meshes in its own frame")
      .field("record_actor_local_to_global_map", &RecordingParams::record_actor_local_to_global_map,
             "the actor's DOF indices in the scene's DOF vector")
      .field("record_actor_mass_matrix", &RecordingParams::record_actor_mass_matrix,
             "an articulated or rigid actor's joint-space mass matrix, a soft actor's node masses")
      .field("record_target_state", &RecordingParams::record_target_state, "joint and link drive targets and gains, every step")
      .field("record_dynamic_actor_state", &RecordingParams::record_dynamic_actor_state,
             "poses, velocities, joint coordinates and soft node displacements of dynamic actors, every step")
      .field("record_static_actor_state", &RecordingParams::record_static_actor_state, "the same for static actors")
      .field("record_contact_points", &RecordingParams::record_contact_points, "the step's contact points, normals and forces")
      .field("record_node_contact_forces", &RecordingParams::record_node_contact_forces,
             "the contact force on every node of each soft actor (N, world)")
      .field("record_sdf_distances", &RecordingParams::record_sdf_distances, "the signed gap at each contact point before the step (m)")
      .done()
      .def_static("all", &RecordingParams::all, "enabled"_a = true, "Every part on (enabled=True) or off.");
}

void add_recording_methods(nb::class_<Scene>& scene) {
  scene.def("start_recording", &Scene::start_recording, "file_path"_a, "params"_a,
            "Records this scene to an HDF5 file (created or replaced): its actors, then a frame after every step with what "
            "`params` selects. Stops a recording already running. Raises Error naming the file when it cannot be created.")
      .def("stop_recording", &Scene::stop_recording, "Closes the recording's file; no effect when none runs.")
      .def("is_recording", &Scene::is_recording);
}

}  // namespace superdex::python

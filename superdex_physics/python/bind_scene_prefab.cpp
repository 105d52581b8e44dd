// superdex.physics.prefab: the prefab object model (ScenePrefab and the actor prefabs, subclasses
// of the actor params), reading and writing prefab JSON, loading what prefabs reference, and
// add_to_scene. Values are checked when a prefab is used, each error naming the field.

#include <nanobind/stl/filesystem.h>
#include <nanobind/stl/optional.h>
#include <nanobind/stl/string.h>

#include "bind_common.h"
#include "bind_container.h"
#include "struct_binder.h"
#include "superdex/physics/prefab.h"

namespace superdex::python {

namespace fs = std::filesystem;
using namespace physics::prefab;

namespace {

// What add_to_scene made, as Actor objects.
struct PyAddToSceneResult {
  std::vector<Actor> actors;
  std::vector<Actor> filter(ActorType type) const {
    std::vector<Actor> out;
    for (const Actor& a : actors)
      if (a.scene.has_actor(a.handle) && a.scene.actor_type(a.handle) == type) out.push_back(a);
    return out;
  }
};

PyAddToSceneResult as_python(const AddToSceneResult& r, const Scene& scene) {
  PyAddToSceneResult out;
  for (ActorHandle h : r.actors) out.actors.push_back(Actor{scene, h});
  return out;
}

// Runs `load` with a warnings list, then raises each warning as a Python UserWarning.
template <class F>
auto with_warnings(F load) {
  std::vector<std::string> warnings;
  auto result = load(&warnings);
  for (const std::string& w : warnings) PyErr_WarnEx(PyExc_UserWarning, w.c_str(), 1);
  return result;
}

// SuperDex's flat shape fields over ShapeSource: shape_file, <scale_name>, shape_rotation,
// shape_translation.
template <class T, class Base>
void add_shape_source(StructBinder<T, Base>& b, const char* scale_name) {
  b.property("shape_file", [](const T& t) { return t.shape_source.file; }, [](T& t, const std::string& v) { t.shape_source.file = v; },
             "Model file: './x' from the prefab file's folder, 'x' from the root path, or absolute")
      .property(scale_name, [](const T& t) { return Real3(t.shape_source.scale); }, [](T& t, const Real3& v) { t.shape_source.scale = v; },
                "Per-axis scale baked into the shape (non-zero)")
      .property("shape_rotation", [](const T& t) { return Quaternion(t.shape_source.rotation); },
                [](T& t, const Quaternion& v) { t.shape_source.rotation = v; }, "Rotation baked into the shape, [x, y, z, w]")
      .property("shape_translation", [](const T& t) { return Real3(t.shape_source.translation); },
                [](T& t, const Real3& v) { t.shape_source.translation = v; }, "m, baked into the shape");
}

template <class T, class Base>
void add_render_model(StructBinder<T, Base>& b) {
  b.property("render_model_file", [](const T& t) { return t.render_model.file; }, [](T& t, const std::string& v) { t.render_model.file = v; },
             "A model shown in place of the shape (a .glb for the debugger); not simulated")
      .property("render_model_scale", [](const T& t) { return Real3(t.render_model.scale); }, [](T& t, const Real3& v) { t.render_model.scale = v; })
      .property("render_model_rotation", [](const T& t) { return Quaternion(t.render_model.rotation); },
                [](T& t, const Quaternion& v) { t.render_model.rotation = v; })
      .property("render_model_translation", [](const T& t) { return Real3(t.render_model.translation); },
                [](T& t, const Real3& v) { t.render_model.translation = v; }, "m");
}

void export_actor_prefabs(nb::module_& p) {
  StructBinder<RigidActorPrefab, RigidActorParams> rigid(
      p, "RigidActorPrefab", "A rigid actor of a prefab: placed by rotation/translation in the prefab frame, shaped by shape_file.");
  rigid.field("comment", &RigidActorPrefab::comment);
  add_shape_source(rigid, "scale");
  rigid.field("rotation", &RigidActorPrefab::rotation, "Prefab-from-local rotation, [x, y, z, w]")
      .field("translation", &RigidActorPrefab::translation, "m, prefab frame");
  add_render_model(rigid);
  rigid.done(false);
  bind_dynamic_array<RigidActorPrefab>(p, "DynamicArrayRigidActorPrefab");

  StructBinder<SoftActorPrefab, SoftActorParams> soft(
      p, "SoftActorPrefab", "A soft actor of a prefab: placed and shaped as RigidActorPrefab (positive scale only).");
  soft.field("comment", &SoftActorPrefab::comment);
  add_shape_source(soft, "scale");
  soft.field("collider_type", &SoftActorPrefab::collider_type, "[Experimental] only AUTO (the surface mesh)")
      .field("sdf", &SoftActorPrefab::sdf, "[Experimental] unused")
      .field("flow_file", &SoftActorPrefab::flow_file, "[Experimental] not supported yet")
      .field("flow", &SoftActorPrefab::flow, "[Experimental] not supported yet")
      .field("use_recentering", &SoftActorPrefab::use_recentering)
      .field("rotation", &SoftActorPrefab::rotation, "Prefab-from-local rotation, [x, y, z, w]")
      .field("translation", &SoftActorPrefab::translation, "m, prefab frame");
  add_render_model(soft);
  soft.field("fixed_nodes", &SoftActorPrefab::fixed_nodes, "Pinned node indices (this engine's addition)")
      .field("fixed_region", &SoftActorPrefab::fixed_region, "Nodes inside this box (m, actor frame, before scaling) are pinned")
      .field("reduced_modes", &SoftActorPrefab::reduced_modes, "Vibration modes of a reduced model; 0: the full model")
      .done(false);
  bind_dynamic_array<SoftActorPrefab>(p, "DynamicArraySoftActorPrefab");

  StructBinder<ArticulatedJointPrefab, ArticulatedJointParams>(p, "ArticulatedJointPrefab", "A joint of an articulated prefab.").done();
  bind_dynamic_array<ArticulatedJointPrefab>(p, "DynamicArrayArticulatedJointPrefab");
  StructBinder<ArticulatedLinkPrefab, ArticulatedLinkParams> link(p, "ArticulatedLinkPrefab",
                                                                  "A link of an articulated prefab, shaped by shape_file (empty: no shape).");
  add_shape_source(link, "shape_scale");
  add_render_model(link);
  link.done();
  bind_dynamic_array<ArticulatedLinkPrefab>(p, "DynamicArrayArticulatedLinkPrefab");

  StructBinder<ArticulatedActorPrefab>(p, "ArticulatedActorPrefab", "An articulated actor of a prefab.")
      .field("comment", &ArticulatedActorPrefab::comment)
      .field("name", &ArticulatedActorPrefab::name)
      .field("scale", &ArticulatedActorPrefab::scale, "Uniform (> 0): multiplies link shapes and joint offsets")
      .field("rotation", &ArticulatedActorPrefab::rotation, "Prefab-from-root rotation, [x, y, z, w]")
      .field("translation", &ArticulatedActorPrefab::translation, "m, prefab frame")
      .field("cycles", &ArticulatedActorPrefab::cycles)
      .field("joints", &ArticulatedActorPrefab::joints)
      .field("links", &ArticulatedActorPrefab::links)
      .field("joint_velocities", &ArticulatedActorPrefab::joint_velocities, "m/s or rad/s, one per DOF")
      .field("default_pose", &ArticulatedActorPrefab::default_pose, "Initial joint positions (bot-DOF order, root excluded)")
      .field("bot_file", &ArticulatedActorPrefab::bot_file, "The .superdex_bot file the links and joints come from; saved in their place")
      .done();
  bind_dynamic_array<ArticulatedActorPrefab>(p, "DynamicArrayArticulatedActorPrefab");

  StructBinder<ActorLists>(p, "ActorLists", "The actors of a prefab, by type.")
      .field("comment", &ActorLists::comment)
      .field("articulated", &ActorLists::articulated)
      .field("rigid", &ActorLists::rigid)
      .field("soft", &ActorLists::soft)
      .done(false);
}

void export_prefab_model(nb::module_& p) {
  StructBinder<SceneParams>(p, "SceneParams", "Scene settings of a top-level prefab, applied with PrefabParams.apply_scene_settings.")
      .field("comment", &SceneParams::comment)
      .field("description", &SceneParams::description)
      .field("gravity", &SceneParams::gravity, "m/s^2, world frame")
      .field("solver", &SceneParams::solver, "Replaces the scene's solver params as a whole")
      .done();
  StructBinder<PrefabReference>(p, "PrefabReference", "Another prefab file nested in this one.")
      .field("comment", &PrefabReference::comment)
      .field("name", &PrefabReference::name, "Its actors are named '<name>/<actor>'")
      .field("path", &PrefabReference::path)
      .field("scale", &PrefabReference::scale, "Uniform (> 0), relative to the parent's")
      .field("rotation", &PrefabReference::rotation, "In the parent's frame, [x, y, z, w]")
      .field("translation", &PrefabReference::translation, "m, parent's frame")
      .done(false);
  bind_dynamic_array<PrefabReference>(p, "DynamicArrayPrefabReference");
  StructBinder<ActorContactEntry>(p, "ActorContactEntry", "Contact between two named actors of the prefab.")
      .field("enable", &ActorContactEntry::enable)
      .field("actors", &ActorContactEntry::actors, "Exactly 2 names; asymmetric: the first collides with the second")
      .field("include_nested_actors", &ActorContactEntry::include_nested_actors)
      .done();
  bind_dynamic_array<ActorContactEntry>(p, "DynamicArrayActorContactEntry");
  StructBinder<LayerContactEntry>(p, "LayerContactEntry", "Contact between two contact layers.")
      .field("enable", &LayerContactEntry::enable)
      .field("layers", &LayerContactEntry::layers, "Exactly 2 layer names")
      .done();
  bind_dynamic_array<LayerContactEntry>(p, "DynamicArrayLayerContactEntry");
  StructBinder<ContactFilter>(p, "ContactFilter", "Contact rules applied once the prefab's actors exist (layers, then actors).")
      .field("comment", &ContactFilter::comment)
      .field("actor_contact_asymmetric", &ContactFilter::actor_contact_asymmetric)
      .field("actor_contact_symmetric", &ContactFilter::actor_contact_symmetric)
      .field("layer_contact_asymmetric", &ContactFilter::layer_contact_asymmetric)
      .field("layer_contact_symmetric", &ContactFilter::layer_contact_symmetric)
      .done();
  StructBinder<ScenePrefab>(p, "ScenePrefab", "A complete or partial scene: actors, nested prefabs, contact rules, scene settings.")
      .field("comment", &ScenePrefab::comment)
      .field("actors", &ScenePrefab::actors)
      .field("prefabs", &ScenePrefab::prefabs)
      .field("scene", &ScenePrefab::scene)
      .field("contact_filter", &ScenePrefab::contact_filter)
      .done(false);
  StructBinder<PrefabParams>(p, "PrefabParams", "How add_to_scene places a prefab in the world.")
      .field("name", &PrefabParams::name, "Prefixes the actors' names: 'name/actor'")
      .field("scale", &PrefabParams::scale, "Uniform (> 0); only the file form of add_to_scene takes another than 1")
      .field("rotation", &PrefabParams::rotation, "World-from-prefab rotation, [x, y, z, w]")
      .field("translation", &PrefabParams::translation, "m, world frame")
      .field("apply_scene_settings", &PrefabParams::apply_scene_settings)
      .done(false);
}

// The handles of exclude_actors: a sequence of ActorHandle or Actor objects.
std::vector<ActorHandle> actor_handles(nb::handle items, const char* what) {
  if (items.is_none()) return {};
  if (!nb::hasattr(items, "__iter__"))
    throw Error(std::string(what) + ": exclude_actors: expected a list of ActorHandle or Actor, got " + nb::inst_name(items).c_str());
  std::vector<ActorHandle> out;
  for (nb::handle item : items)
    out.push_back(actor_handle_of(item, std::string(what) + ": exclude_actors[" + std::to_string(out.size()) + "]"));
  return out;
}

const Scene& require_scene(const Scene* scene, const char* what) {
  if (!scene) throw Error(std::string(what) + ": scene: expected a Scene, got None");
  return *scene;
}

void export_functions(nb::module_& p) {
  p.def("export_scene", [](const Scene* scene, const std::string& export_name, const fs::path& output_dir) {
        physics::prefab::export_scene(require_scene(scene, "export_scene"), export_name, output_dir.string());
      }, "scene"_a.none(), "export_name"_a, "output_dir"_a,
      "Writes the scene's rigid, soft and articulated actors as <output_dir>/<export_name>/<export_name>.mochi_scene, mesh "
      "shapes as .mochi.h5 files in generated_assets/ beside it ('./generated_assets/<file>'; primitives inline), with the "
      "scene's contact rules and its gravity and solver settings. Names are made unique ('box', 'box1'). Joint positions "
      "(beyond the root link's pose) and velocities of articulations are not exported. Folders are created.");
  p.def("export_scene_excluding", [](const Scene* scene, const std::string& export_name, const fs::path& output_dir, nb::handle exclude_actors) {
        const Scene& s = require_scene(scene, "export_scene_excluding");
        physics::prefab::export_scene_excluding(s, export_name, output_dir.string(), actor_handles(exclude_actors, "export_scene_excluding"));
      }, "scene"_a.none(), "export_name"_a, "output_dir"_a, "exclude_actors"_a.none(),
      "export_scene without the actors listed (an articulation with its links) and the contact rules that name them.");
  p.def("export_actor", [](const Actor* actor, const std::string& export_name, const fs::path& output_dir) {
        if (!actor) throw Error("export_actor: actor: expected an Actor, got None");
        physics::prefab::export_actor(actor->scene, actor->handle, export_name, output_dir.string());
      }, "actor"_a.none(), "export_name"_a, "output_dir"_a,
      "Writes one rigid, soft or articulated actor (not a link: pass its articulation) as "
      "<output_dir>/<export_name>/<export_name>.mochi_scene, named export_name, its meshes in generated_assets/.");
}

}  // namespace

void export_physics_prefab(nb::module_& m) {
  bind_dynamic_array<Actor>(m, "DynamicArrayActor");
  nb::module_ p = m.def_submodule("prefab", "Prefabs: sets of actors read from and written to .mochi_prefab / .mochi_scene files.");
  export_actor_prefabs(p);
  export_prefab_model(p);
  export_functions(p);
  nb::class_<PyAddToSceneResult>(p, "AddToSceneResult", "The actors add_to_scene created (a nested prefab's before its parent's own).")
      .def(nb::init<>())
      .def_rw("actors", &PyAddToSceneResult::actors)
      .def("filter", &PyAddToSceneResult::filter, "type"_a, "The created actors of one type, in creation order.");

  p.def("load_from_file", [](const fs::path& prefab_path, const fs::path& root_path) {
        return with_warnings([&](auto* w) { return load_from_file(prefab_path.string(), root_path.string(), w); });
      }, "prefab_path"_a, "root_path"_a, "Reads a prefab file with its nested prefabs and shapes.");
  p.def("load_from_json_string", [](const std::string& json, const fs::path& root_path) {
        return with_warnings([&](auto* w) { return load_from_json_string(json, root_path.string(), w); });
      }, "json"_a, "root_path"_a, "Reads a prefab from JSON text with its nested prefabs and shapes ('./' paths from root_path).");
  p.def("shallow_load_from_file", [](const fs::path& path) {
        return with_warnings([&](auto* w) { return shallow_load_from_file(path.string(), w); });
      }, "path"_a, "Reads a prefab file alone: nested prefabs and shapes stay unloaded.");
  p.def("shallow_load_from_json_string", [](const std::string& json) {
        return with_warnings([&](auto* w) { return shallow_load_from_json_string(json, w); });
      }, "json"_a, "Reads a prefab from JSON text alone.");
  p.def("load_nested_prefabs", [](ScenePrefab& prefab, const fs::path& root_path) {
        with_warnings([&](auto* w) { return load_nested_prefabs(prefab, root_path.string(), w), 0; });
      }, "prefab"_a, "root_path"_a, "(Re)loads the nested prefabs, recursively.");
  p.def("load_shapes", [](ScenePrefab& prefab, const fs::path& root_path) { load_shapes(prefab, root_path.string()); }, "prefab"_a, "root_path"_a,
        "(Re)loads the shapes of the prefab and of its loaded nested prefabs.");
  p.def("ensure_fully_loaded", [](ScenePrefab& prefab, const fs::path& root_path) {
        with_warnings([&](auto* w) { return ensure_fully_loaded(prefab, root_path.string(), w), 0; });
      }, "prefab"_a, "root_path"_a, "Loads the nested prefabs and shapes not loaded yet.");
  p.def("save_to_json_string", &save_to_json_string, "prefab"_a, "The prefab as JSON (nested prefabs by reference).");
  p.def("save_to_json_file", [](const ScenePrefab& prefab, const fs::path& path) { save_to_json_file(prefab, path.string()); }, "prefab"_a,
        "path"_a, "Writes the prefab as JSON, creating the folders.");
  p.def("add_to_scene", [](const ScenePrefab& prefab, Scene& scene, const PrefabParams& params) {
        return as_python(add_to_scene(prefab, scene, params), scene);
      }, "prefab"_a, "scene"_a, "params"_a = PrefabParams(),
      "Adds a fully loaded prefab (params.scale 1). All or nothing: on an Error no actor of it remains.");
  p.def("add_to_scene", [](const fs::path& prefab_path, const fs::path& root_path, Scene& scene, const PrefabParams& params) {
        return as_python(with_warnings([&](auto* w) { return add_to_scene(prefab_path.string(), root_path.string(), scene, params, w); }), scene);
      }, "prefab_path"_a, "root_path"_a, "scene"_a, "params"_a = PrefabParams(),
      "Loads a prefab file (params.scale baked into its shapes) and adds it. All or nothing.");
  p.def("get_prefab_full_path", [](const std::string& input_path, const std::string& root_for_relative_path, const std::string& prefab_file_path) {
        return get_prefab_full_path(input_path, root_for_relative_path, prefab_file_path);
      }, "input_path"_a, "root_for_relative_path"_a, "prefab_file_path"_a,
      "Absolute paths unchanged; './x' from the folder of prefab_file_path; other relative paths from the root.");
}

}  // namespace superdex::python

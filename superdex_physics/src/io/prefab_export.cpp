// Exporting scenes and actors as prefabs (prefab.h export_scene, export_scene_excluding,
// export_actor): each actor's creation parameters read back from the scene (scene.h "Creation
// parameters read back") become a ScenePrefab, written with save_to_json_file to
// <output_dir>/<name>/<name>.mochi_scene; mesh shapes go to .mochi.h5 files in generated_assets/
// beside it (model::save_to_file), named from the prefab as "./generated_assets/<file>".
// Primitives (box, sphere, capsule, plane) are written inline.

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <map>
#include <set>

#include "io/prefab_json.h"
#include "superdex/physics/engine.h"
#include "superdex/physics/error.h"
#include "superdex/physics/model.h"
#include "superdex/physics/prefab.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {
namespace prefab {

namespace fs = std::filesystem;

namespace {

constexpr const char* kAssetsFolder = "generated_assets";

// A file name from an actor or link name: letters, digits, '-' and '_' kept, the rest '_'.
std::string file_stem(const std::string& name) {
  std::string out;
  for (char c : name) out += std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' ? c : '_';
  return out.empty() ? "shape" : out;
}

// Whether a shape is written inline (the primitives) rather than to a file (meshes).
bool is_primitive(const ShapeGeometry& g) { return !std::holds_alternative<MeshShape>(g); }

// A primitive with a per-axis scale applied (as the articulation model applies shapeScale: spheres
// by x, capsules' radius by x and length by z).
ShapeGeometry scaled(ShapeGeometry g, const Vec3& s) {
  if (auto* x = std::get_if<SphereShape>(&g)) x->radius *= s.x(), x->center = x->center.cwiseProduct(s);
  if (auto* x = std::get_if<BoxShape>(&g)) x->half_extents = x->half_extents.cwiseProduct(s);
  if (auto* x = std::get_if<CapsuleShape>(&g)) x->radius *= s.x(), x->half_length *= s.z();
  return g;
}

ModelData triangle_model(const TriangleMesh& mesh) {
  MeshData m;
  m.nodes_per_element = 3;
  for (const Vec3& v : mesh.vertices) m.coordinates.insert(m.coordinates.end(), {v.x(), v.y(), v.z()});
  for (const auto& t : mesh.triangles) m.connectivity.insert(m.connectivity.end(), t.begin(), t.end());
  ModelData model;
  model.mesh = std::move(m);
  return model;
}

struct Exporter {
  Exporter(Scene s, const char* w, fs::path f) : scene(s), what(w), folder(std::move(f)) {}
  Scene scene;
  std::string what;     // the calling function, for errors
  fs::path folder;      // <output_dir>/<export_name>
  ScenePrefab prefab;
  std::set<std::string> names, files;
  std::map<ActorHandle, std::string> exported;  // actor -> its name in the prefab
  std::string name_override;  // export_actor: the name of the one actor

  // "box", then "box1", "box2", ... for later actors of the same name
  std::string unique_name(const std::string& name) {
    if (!name_override.empty()) return name_override;
    std::string n = name;
    for (int k = 1; names.count(n); ++k) n = name + std::to_string(k);
    names.insert(n);
    return n;
  }

  // Writes a model to generated_assets/<stem>.mochi.h5 (a new name per file) and returns the
  // prefab's path to it.
  std::string write_model(const ModelData& model, const std::string& stem) {
    std::string file = file_stem(stem) + ".mochi.h5";
    for (int k = 1; files.count(file); ++k) file = file_stem(stem) + "_" + std::to_string(k) + ".mochi.h5";
    files.insert(file);
    const fs::path path = folder / kAssetsFolder / file;
    try {
      model::save_to_file(model, path.string(), FileFormat::H5);
    } catch (const Error& e) {
      throw Error(what + ": output_dir: cannot write '" + path.string() + "': " + e.what());
    }
    return std::string("./") + kAssetsFolder + "/" + file;
  }

  // The shape of a rigid or soft actor: inline primitive, or its model in a file.
  ShapeSource shape_source(const ShapeHandle& shape, const std::string& stem) {
    ShapeSource s;
    if (!shape.is_valid()) return s;
    const ShapeGeometry g = shape_geometry(shape);
    if (is_primitive(g)) {
      s.primitive = g;
      return s;
    }
    s.file = write_model(*shape_model(shape), stem);
    return s;
  }

  // A rigid or soft actor's prefab from its creation params: a unique name, its shape as a
  // source, the params' pose moved to the prefab's placement.
  template <class Prefab, class Params>
  Prefab actor_prefab(ActorHandle h, const Params& p, const char* fallback_name) {
    Prefab a;
    static_cast<Params&>(a) = p;
    a.name = unique_name(p.name.empty() ? fallback_name : p.name);
    a.shape_source = shape_source(p.shape, a.name);
    a.shape = ShapeHandle();
    a.rotation = p.world_from_local.rotation;
    a.translation = p.world_from_local.translation;
    a.world_from_local = TransformRT();
    exported[h] = a.name;
    return a;
  }

  void add_rigid(ActorHandle h) {
    // the shape reference read back is dropped with the params
    prefab.actors.rigid.push_back(actor_prefab<RigidActorPrefab>(h, scene.rigid_actor_params(h), "rigid"));
  }

  void add_soft(ActorHandle h) {
    SoftActorPrefab a = actor_prefab<SoftActorPrefab>(h, scene.soft_actor_params(h), "soft");
    a.use_recentering = scene.recentering_params(h).use_recentering;
    a.fixed_nodes = scene.soft_fixed_nodes(h);
    a.reduced_modes = scene.soft_reduced_modes(h);
    prefab.actors.soft.push_back(std::move(a));
  }

  // A link's shape: a primitive inline (scaled, posed in the link frame), a mesh in a file (its
  // scale and pose baked in when loaded).
  ShapeSource link_shape(const LinkDesc& l, const std::string& stem) {
    ShapeSource s;
    if (!l.shape) return s;
    if (is_primitive(*l.shape)) {
      ShapeGeometry g = scaled(*l.shape, l.shape_scale);
      Transform X_LS = l.link_from_shape;
      // a sphere carries its place as its centre (files have no pose for spheres)
      if (auto* sphere = std::get_if<SphereShape>(&g)) {
        sphere->center = X_LS * Vec3(sphere->center);
        X_LS = Transform{};
      }
      s.primitive = g;
      s.rotation = X_LS.rotation;
      s.translation = X_LS.translation;
      return s;
    }
    s.file = write_model(triangle_model(*std::get<MeshShape>(*l.shape).mesh), stem);
    s.scale = l.shape_scale;
    s.rotation = l.link_from_shape.rotation;
    s.translation = l.link_from_shape.translation;
    return s;
  }

  void add_articulated(ActorHandle h) {
    const ArticulationDesc d = scene.articulation_desc(h);
    const std::vector<ActorHandle> link_actors = scene.nested_link_actors(h);
    ArticulatedActorPrefab a;
    a.name = unique_name(d.name.empty() ? "articulation" : d.name);
    a.rotation = d.world_from_root.rotation;
    a.translation = d.world_from_root.translation;
    for (size_t i = 0; i < d.links.size(); ++i) {
      const LinkDesc& l = d.links[i];
      ArticulatedLinkPrefab p = link_prefab(l);
      p.shape_source = link_shape(l, a.name + "_" + (l.name.empty() ? "link" + std::to_string(i) : l.name));
      p.layer = scene.contact_layer(link_actors[i]);
      a.links.push_back(std::move(p));
      a.joints.push_back(joint_prefab(d.joints[i]));
    }
    a.default_pose = d.default_pose;
    a.contact_overrides = d.contact_overrides;
    exported[h] = a.name;
    prefab.actors.articulated.push_back(std::move(a));
  }

  // The scene's contact rules between exported actors and between named layers.
  void add_contact_filter() {
    ContactFilter f;
    const std::vector<std::string> layers = scene.contact_layer_names();
    auto push = [](auto& list, auto entry) {
      if (!list) list.emplace();
      list->push_back(std::move(entry));
    };
    // layers: the pairs whose contact is off one way or both (every pair starts enabled)
    for (size_t i = 0; i < layers.size(); ++i)
      for (size_t k = i; k < layers.size(); ++k) {
        const std::string &a = layers[i], &b = layers[k];
        if (a.empty() || b.empty()) continue;  // the default layer cannot be named in rules
        const bool ab = scene.is_layer_contact_enabled(a, b), ba = scene.is_layer_contact_enabled(b, a);
        if (!ab && !ba) push(f.layer_contact_symmetric, LayerContactEntry{false, {a, b}});
        else if (!ab) push(f.layer_contact_asymmetric, LayerContactEntry{false, {a, b}});
        else if (!ba) push(f.layer_contact_asymmetric, LayerContactEntry{false, {b, a}});
      }
    const std::vector<ActorContactRule> rules = scene.actor_contact_rules();
    auto rule_of = [&](ActorHandle colliding, ActorHandle collider) -> const ActorContactRule* {
      for (const ActorContactRule& r : rules)
        if (r.colliding == colliding && r.collider == collider) return &r;
      return nullptr;
    };
    for (const ActorContactRule& r : rules) {
      auto a = exported.find(r.colliding), b = exported.find(r.collider);
      if (a == exported.end() || b == exported.end()) continue;  // an excluded actor or a link
      const ActorContactEntry entry{r.enable, {a->second, b->second}, r.nested == IncludeNestedActors::Yes};
      const ActorContactRule* back = rule_of(r.collider, r.colliding);
      if (back && back->enable == r.enable && back->nested == r.nested) {
        // both ways alike: one symmetric entry, written for the first of the pair
        if (r.colliding.value <= r.collider.value) push(f.actor_contact_symmetric, entry);
      } else {
        push(f.actor_contact_asymmetric, entry);
      }
    }
    if (f.actor_contact_asymmetric || f.actor_contact_symmetric || f.layer_contact_asymmetric || f.layer_contact_symmetric)
      prefab.contact_filter = std::move(f);
  }

  void add_actor(ActorHandle h) {
    switch (scene.actor_type(h)) {
      case ActorType::Rigid: add_rigid(h); break;
      case ActorType::Soft: add_soft(h); break;
      case ActorType::Articulated: add_articulated(h); break;
      default: break;
    }
  }

  // Creates the folders and writes the prefab file.
  void write(const std::string& export_name) {
    const fs::path file = folder / (export_name + ".mochi_scene");
    try {
      save_to_json_file(prefab, file.string());
    } catch (const Error& e) {
      throw Error(what + ": output_dir: " + e.what());
    }
  }
};

// Checks the arguments and creates <output_dir>/<export_name>/generated_assets.
fs::path export_folder(const char* what, const std::string& export_name, const std::string& output_dir) {
  if (export_name.empty()) throw Error(std::string(what) + ": export_name: must not be empty");
  if (export_name == "." || export_name == ".." || export_name.find_first_of("/\\") != std::string::npos)
    throw Error(std::string(what) + ": export_name: must be a plain name (no '/', '\\\\', '.' or '..'), got '" + export_name + "'");
  if (output_dir.empty()) throw Error(std::string(what) + ": output_dir: must name a folder (\".\" for the current one)");
  const fs::path folder = fs::path(output_dir) / export_name;
  std::error_code ec;
  fs::create_directories(folder / kAssetsFolder, ec);
  if (ec || !fs::is_directory(folder / kAssetsFolder))
    throw Error(std::string(what) + ": output_dir: cannot create the folder '" + (folder / kAssetsFolder).string() + "'" +
                (ec ? ": " + ec.message() : std::string()));
  return folder;
}

void export_excluding(const char* what, Scene scene, const std::string& export_name, const std::string& output_dir,
                      const std::vector<ActorHandle>& exclude_actors) {
  std::set<ActorHandle> excluded;
  for (size_t i = 0; i < exclude_actors.size(); ++i) {
    const ActorHandle h = exclude_actors[i];
    const std::string where = std::string(what) + ": exclude_actors[" + std::to_string(i) + "]";
    if (!scene.has_actor(h)) throw Error(where + ": actor " + std::to_string(h) + " does not exist in scene '" + scene.name() + "'");
    if (scene.is_nested_link_actor(h))
      throw Error(where + ": actor " + std::to_string(h) + " ('" + scene.actor_name(h) +
                  "') is a link: links are exported with their articulation; exclude the articulation (" +
                  std::to_string(scene.articulated_actor_of_link(h)) + ") instead");
    excluded.insert(h);
  }
  Exporter x{scene, what, export_folder(what, export_name, output_dir)};
  std::vector<ActorHandle> actors = scene.actors();
  // creation order (ids grow with it) across kinds, so that the first of two "box" keeps its name
  std::sort(actors.begin(), actors.end(), [](ActorHandle a, ActorHandle b) { return a.value < b.value; });
  for (ActorHandle h : actors)
    if (!excluded.count(h)) x.add_actor(h);
  x.add_contact_filter();
  SceneParams settings;
  settings.description = scene.name();
  settings.gravity = scene.gravity();
  settings.solver = scene.solver_params();
  x.prefab.scene = settings;
  x.write(export_name);
}

}  // namespace

void export_scene(Scene scene, const std::string& export_name, const std::string& output_dir) {
  export_excluding("export_scene", scene, export_name, output_dir, {});
}

void export_scene_excluding(Scene scene, const std::string& export_name, const std::string& output_dir,
                            const std::vector<ActorHandle>& exclude_actors) {
  export_excluding("export_scene_excluding", scene, export_name, output_dir, exclude_actors);
}

void export_actor(Scene scene, ActorHandle actor, const std::string& export_name, const std::string& output_dir) {
  const char* what = "export_actor";
  if (!scene.has_actor(actor)) throw Error(std::string(what) + ": actor: actor " + std::to_string(actor) + " does not exist in scene '" + scene.name() + "'");
  if (scene.is_nested_link_actor(actor))
    throw Error(std::string(what) + ": actor: actor " + std::to_string(actor) + " ('" + scene.actor_name(actor) +
                "') is a link of an articulation: pass the articulation (Actor.get_articulated_actor()) to export it whole");
  Exporter x{scene, what, export_folder(what, export_name, output_dir)};
  x.name_override = export_name;  // the export's name is the actor's name
  x.add_actor(actor);
  x.write(export_name);
}

}  // namespace prefab
}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

// Adding a prefab to a scene (prefab.h add_to_scene): nested prefabs first (depth first), then the
// prefab's rigid, soft and articulated actors, then its contact rules; scene settings last. All
// or nothing: an error destroys the actors made so far and leaves the scene's settings alone.

#include <cmath>
#include <filesystem>

#include "io/prefab_json.h"
#include "io/prefab_shapes.h"
#include "multibody/joint_from_params.h"
#include "soft/material_from_params.h"
#include "superdex/physics/engine.h"
#include "superdex/physics/error.h"
#include "superdex/physics/prefab.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {
namespace prefab {

namespace {

// Where a prefab goes: its name prefix, its uniform scale and X_WP.
struct Placement {
  std::string name;
  real scale = 1;
  Transform X_WP;

  std::string prefixed(const std::string& n) const { return name.empty() ? n : name + "/" + n; }
  // X_WL of an entry placed at X_PL (the translation scaled with the prefab)
  Transform place(const Quaternion& R_PL, const Real3& p_PL) const {
    Transform X_PL{R_PL.normalized(), p_PL * scale};
    return X_WP * X_PL;
  }
};

void check_rotation(const Quaternion& q, const std::string& where) {
  if (!q.coeffs().allFinite() || !(q.norm() > real(1e-6))) throw Error(where + ".rotation: must be a finite, non-zero quaternion");
}

void check_positive(const std::optional<real>& value, const std::string& where, const char* field) {
  if (value && !(std::isfinite(*value) && *value > 0))
    throw Error(where + "." + field + ": must be a positive finite number, got " + nlohmann::json(*value).dump());
}

const ShapeHandle& loaded_shape(const ShapeHandle& h, const std::string& where) {
  if (!h.is_valid()) throw Error(where + ".shape: not loaded (call prefab.ensure_fully_loaded or prefab.load_shapes first)");
  return h;
}

// The actors made, named relative to the prefab being added ("box", "nested/box").
struct Made {
  std::vector<std::pair<std::string, ActorHandle>> actors;
};

struct Instantiator {
  Scene scene;
  AddToSceneResult result;

  ActorHandle keep(ActorHandle h, Made& made, const std::string& relative_name) {
    result.actors.push_back(h);
    made.actors.emplace_back(relative_name, h);
    return h;
  }

  void add_rigid(const RigidActorPrefab& a, const Placement& at, const std::string& where, Made& made) {
    check_rotation(a.rotation, where);
    check_positive(a.mass, where, "mass");
    check_positive(a.density, where, "density");
    RigidActorParams params = a;
    params.name = at.prefixed(a.name);
    params.shape = loaded_shape(a.shape, where);
    params.world_from_local = at.place(a.rotation, a.translation);
    try {
      keep(scene.create_rigid_actor(params), made, a.name);
    } catch (const Error& e) {
      throw Error(where + ": " + e.what());
    }
  }

  void add_soft(const SoftActorPrefab& a, const Placement& at, const std::string& where, Made& made) {
    check_rotation(a.rotation, where);
    if (!a.flow_file.empty() || a.flow.is_valid()) throw Error(where + ".flow_file: deep flow shapes are not supported yet");
    if (a.collider_type != ColliderType::Auto) throw Error(where + ".collider_type: soft actors collide by their surface mesh (AUTO) only");
    if (!a.has_gravity || !a.has_inertia || !a.has_stress)
      throw Error(where + (a.has_gravity ? a.has_inertia ? ".has_stress" : ".has_inertia" : ".has_gravity") +
                  ": soft prefabs are simulated with gravity, inertia and stress (keep it True)");
    const std::shared_ptr<const TetMesh> mesh = tet_mesh_shape(loaded_shape(a.shape, where));
    std::vector<int> fixed;
    for (size_t k = 0; k < a.fixed_nodes.size(); ++k) {
      if (a.fixed_nodes[k] < 0 || a.fixed_nodes[k] >= static_cast<int>(mesh->nodes.size()))
        throw Error(where + ".fixed_nodes[" + std::to_string(k) + "]: node " + std::to_string(a.fixed_nodes[k]) +
                    " is out of range (the mesh has " + std::to_string(mesh->nodes.size()) + " nodes)");
      fixed.push_back(a.fixed_nodes[k]);
    }
    if (a.fixed_region) {
      // the region scales with the shape (whose nodes carry the prefab's scale)
      const real s = at.scale;
      for (size_t k = 0; k < mesh->nodes.size(); ++k)
        if ((mesh->nodes[k].array() >= a.fixed_region->min.array() * s).all() && (mesh->nodes[k].array() <= a.fixed_region->max.array() * s).all())
          fixed.push_back(static_cast<int>(k));
    }
    SoftMaterial material = soft_material_from_params(a.material, *mesh);
    material.reduced_modes = a.reduced_modes;
    try {
      validate(static_cast<const SoftActorParams&>(a), "params");
      const ActorHandle h = scene.create_soft_actor(at.prefixed(a.name), a.shape, material, at.place(a.rotation, a.translation), fixed);
      keep(h, made, a.name);
      if (!(a.contact == ContactParams{})) scene.set_contact_params(h, a.contact);
      if (!a.layer.empty()) scene.set_contact_layer(h, a.layer);
      if (!a.use_recentering) scene.set_recentering_params(h, RecenteringParams{false});
    } catch (const Error& e) {
      throw Error(where + ": " + e.what());
    }
  }

  void add_articulated(const ArticulatedActorPrefab& a, const ScenePrefab& p, const Placement& at, const std::string& where, Made& made) {
    check_rotation(a.rotation, where);
    if (!a.cycles.empty()) throw Error(where + ".cycles: cycle joints are not supported by prefabs yet");
    if (a.joints.size() != a.links.size())
      throw Error(where + ".joints: expected one joint per link (" + std::to_string(a.links.size()) + "), got " + std::to_string(a.joints.size()));
    const real s = at.scale * a.scale;  // lengths of the links and joints
    ArticulationDesc desc;
    desc.name = at.prefixed(a.name.empty() ? "articulation" : a.name);
    desc.world_from_root = at.place(a.rotation, a.translation);
    desc.default_pose = a.default_pose;
    desc.contact_overrides = a.contact_overrides;
    std::vector<std::pair<int, std::string>> named_layers;
    for (size_t i = 0; i < a.links.size(); ++i) {
      const ArticulatedLinkPrefab& l = a.links[i];
      const std::string lw = where + ".links[" + std::to_string(i) + "]";
      LinkDesc d;
      d.name = l.name.empty() ? "link_" + std::to_string(i) : l.name;
      d.parent_link = l.parent_link;
      d.mass = l.mass;
      d.density = l.density;
      if (l.center_of_mass) d.center_of_mass = *l.center_of_mass * s;
      if (l.moment_of_inertia) d.moment_of_inertia = std::array<real, 6>{(*l.moment_of_inertia)[0], (*l.moment_of_inertia)[1], (*l.moment_of_inertia)[2],
                                                                         (*l.moment_of_inertia)[3], (*l.moment_of_inertia)[4], (*l.moment_of_inertia)[5]};
      if (l.shape.is_valid()) d.shape = shape_geometry(l.shape);
      else if (!l.shape_source.file.empty() || l.shape_source.primitive) loaded_shape(l.shape, lw);
      // a primitive's pose is kept; a file's is baked into it
      if (l.shape_source.primitive && l.shape_source.file.empty())
        d.link_from_shape = Transform{l.shape_source.rotation.normalized(), l.shape_source.translation * s};
      d.collider_type = collider_type_name(l.collider_type);
      d.contact = l.contact;
      d.has_gravity = l.has_gravity;
      d.joint_from_link = l.parent_joint_from_link.translation * s;
      if (!l.layer.empty() && l.layer.find_first_not_of("0123456789") == std::string::npos && l.layer.size() <= 2) d.layer = std::stoi(l.layer);
      else if (!l.layer.empty()) named_layers.emplace_back(static_cast<int>(i), l.layer);
      // a render model (debugger only) whose path can be resolved without the root
      const std::filesystem::path model(l.render_model.file);
      if (model.is_absolute() || (l.render_model.file.rfind("./", 0) == 0 && !p.source_file.empty())) {
        d.render_model = get_prefab_full_path(l.render_model.file, "", p.source_file);
        d.render_model_scale = l.render_model.scale * s;
      }
      desc.links.push_back(std::move(d));
      JointDesc jd = joint_desc_from_params(a.joints[i], static_cast<int>(i));
      jd.parent_link_from_joint.translation *= s;
      desc.joints.push_back(jd);
    }
    const ActorHandle h = keep(scene.create_articulated_actor(desc, where), made, a.name);
    try {
      const std::vector<ActorHandle> links = scene.nested_link_actors(h);
      for (const auto& [index, layer] : named_layers) scene.set_contact_layer(links.at(index), layer);
      if (a.joint_velocities) {
        const int nv = scene.num_dofs(h);
        if (static_cast<int>(a.joint_velocities->size()) != nv)
          throw Error("joint_velocities: expected one value per DOF (" + std::to_string(nv) + "), got " + std::to_string(a.joint_velocities->size()));
        scene.set_joint_velocities(h, Eigen::Map<const VecX>(a.joint_velocities->data(), nv));
      }
    } catch (const Error& e) {
      throw Error(where + (std::string(e.what()).rfind("joint_velocities", 0) == 0 ? "." : ": ") + e.what());
    }
  }

  // The handles of the actors named `name` in `made`: the actor itself, or with include_nested
  // an articulation and its links (the scene's rule covers them), and a nested prefab's actors.
  std::vector<ActorHandle> named(const Made& made, const std::string& name, const std::string& where) const {
    std::vector<ActorHandle> out;
    for (const auto& [n, h] : made.actors)
      if (n == name || n.rfind(name + "/", 0) == 0) out.push_back(h);
    if (out.empty()) throw Error(where + ": no actor named '" + name + "' in this prefab");
    return out;
  }

  // One contact rule: between two layers (LayerContactEntry) or two named actors (ActorContactEntry).
  void apply_entry(const LayerContactEntry& e, bool symmetric, const std::string& where, const Made&) {
    if (e.layers.size() != 2) throw Error(where + ".layers: expected 2 layer names, got " + std::to_string(e.layers.size()));
    try {
      if (symmetric) scene.enable_layer_contact_symmetric(e.layers[0], e.layers[1], e.enable);
      else scene.enable_layer_contact_asymmetric(e.layers[0], e.layers[1], e.enable);
    } catch (const Error& err) {
      throw Error(where + ": " + err.what());
    }
  }
  void apply_entry(const ActorContactEntry& e, bool symmetric, const std::string& where, const Made& made) {
    if (e.actors.size() != 2) throw Error(where + ".actors: expected 2 actor names, got " + std::to_string(e.actors.size()));
    const IncludeNestedActors nested = e.include_nested_actors ? IncludeNestedActors::Yes : IncludeNestedActors::No;
    for (ActorHandle a : named(made, e.actors[0], where))
      for (ActorHandle b : named(made, e.actors[1], where)) {
        if (symmetric) scene.enable_actor_contact_symmetric(a, b, e.enable, nested);
        else scene.enable_actor_contact_asymmetric(a, b, e.enable, nested);
      }
  }

  void apply_filter(const ContactFilter& f, const std::string& at, const Made& made) {
    auto apply = [&](const auto& entries, const char* key, bool symmetric) {
      if (!entries) return;
      for (size_t i = 0; i < entries->size(); ++i)
        apply_entry((*entries)[i], symmetric, at + "contact_filter." + key + "[" + std::to_string(i) + "]", made);
    };
    apply(f.layer_contact_asymmetric, "layer_contact_asymmetric", false);
    apply(f.layer_contact_symmetric, "layer_contact_symmetric", true);
    apply(f.actor_contact_asymmetric, "actor_contact_asymmetric", false);
    apply(f.actor_contact_symmetric, "actor_contact_symmetric", true);
  }

  Made add(const ScenePrefab& p, const Placement& at) {
    const std::string prefix = error_prefix(p);
    Made made;
    for (size_t i = 0; i < p.prefabs.size(); ++i) {
      const PrefabReference& ref = p.prefabs[i];
      const std::string where = prefix + "prefabs[" + std::to_string(i) + "]";
      if (ref.loaded.empty()) throw Error(where + ": not loaded (call prefab.ensure_fully_loaded or prefab.load_nested_prefabs first)");
      if (!(ref.scale > 0) || !std::isfinite(ref.scale)) throw Error(where + ".scale: must be positive");
      check_rotation(ref.rotation, where);
      const std::string name = ref.name.empty() ? "prefab" + std::to_string(i) : ref.name;
      Placement nested{at.prefixed(name), at.scale * ref.scale, at.place(ref.rotation, ref.translation)};
      for (auto& [n, h] : add(ref.loaded[0], nested).actors) made.actors.emplace_back(name + "/" + n, h);
    }
    for (size_t i = 0; i < p.actors.rigid.size(); ++i) add_rigid(p.actors.rigid[i], at, prefix + "actors.rigid[" + std::to_string(i) + "]", made);
    for (size_t i = 0; i < p.actors.soft.size(); ++i) add_soft(p.actors.soft[i], at, prefix + "actors.soft[" + std::to_string(i) + "]", made);
    for (size_t i = 0; i < p.actors.articulated.size(); ++i)
      add_articulated(p.actors.articulated[i], p, at, prefix + "actors.articulated[" + std::to_string(i) + "]", made);
    if (p.contact_filter) apply_filter(*p.contact_filter, prefix, made);
    return made;
  }

  void apply_scene_settings(const ScenePrefab& p) {
    if (!p.scene) return;
    const std::string where = error_prefix(p) + "scene";
    if (p.scene->gravity) {
      if (!p.scene->gravity->allFinite()) throw Error(where + ".gravity: must be finite");
    }
    if (p.scene->solver) {
      try {
        scene.set_solver_params(*p.scene->solver);
      } catch (const Error& e) {
        throw Error(where + ".solver: " + e.what());
      }
    }
    if (p.scene->gravity) scene.set_gravity(*p.scene->gravity);
  }
};

AddToSceneResult instantiate(const ScenePrefab& prefab, Scene scene, const PrefabParams& params, real scale) {
  check_rotation(params.rotation, "add_to_scene: params");
  if (!params.translation.allFinite()) throw Error("add_to_scene: params.translation: must be finite");
  Instantiator in{scene, {}};
  const SolverParams solver_before = scene.solver_params();
  try {
    in.add(prefab, Placement{params.name, scale, Transform{params.rotation.normalized(), params.translation}});
    if (params.apply_scene_settings) in.apply_scene_settings(prefab);
  } catch (...) {
    for (ActorHandle h : in.result.actors)
      if (scene.has_actor(h)) scene.destroy_actor(h);
    scene.set_solver_params(solver_before);
    throw;
  }
  return in.result;
}

}  // namespace

std::vector<ActorHandle> AddToSceneResult::filter(const Scene& scene, ActorType type) const {
  std::vector<ActorHandle> out;
  for (ActorHandle h : actors)
    if (scene.has_actor(h) && scene.actor_type(h) == type) out.push_back(h);
  return out;
}

AddToSceneResult add_to_scene(const ScenePrefab& prefab, Scene scene, const PrefabParams& params) {
  if (params.scale != 1)
    throw Error("add_to_scene: params.scale: a loaded prefab is added at scale 1 (its shapes are loaded); add the file with a scale instead");
  return instantiate(prefab, scene, params, 1);
}

AddToSceneResult add_to_scene(const std::string& prefab_path, const std::string& root_path, Scene scene, const PrefabParams& params,
                              std::vector<std::string>* warnings) {
  if (!(params.scale > 0) || !std::isfinite(params.scale)) throw Error("add_to_scene: params.scale: scale must be a positive number");
  ScenePrefab prefab = shallow_load_from_file(prefab_path, warnings);
  load_nested_prefabs(prefab, root_path, warnings);
  // The actors keep their own geometry (a rigid actor a copy, a soft actor the shared tet mesh),
  // so the shapes made for them are released, added or not: kept, they piled up in the shape
  // registry with every load (a duck's whole tet mesh per load; found by memory_cycles_test).
  const std::vector<ShapeHandle> shapes = load_scaled_shapes(prefab, root_path, params.scale);
  auto release = [&] {
    for (const ShapeHandle& h : shapes) release_shape(h);
  };
  try {
    AddToSceneResult r = instantiate(prefab, scene, params, params.scale);
    release();
    return r;
  } catch (...) {
    release();
    throw;
  }
}

}  // namespace prefab
}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

// Loading `.mochi_prefab` / `.mochi_scene` files into a scene (prefab.h).

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "superdex/physics/articulation_json.h"
#include "superdex/physics/engine.h"
#include "superdex/physics/error.h"
#include "superdex/physics/file_path.h"
#include "superdex/physics/mesh_shape.h"
#include "superdex/physics/prefab.h"
#include "solver/step_settings.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

[[noreturn]] void fail(const std::string& file, const std::string& path, const std::string& what) {
  throw Error(file + ": " + path + ": " + what);
}

// A path named in a prefab: "./x" relative to the prefab's folder, "x" relative to the root.
fs::path resolve(const std::string& name, const fs::path& prefab_dir, const fs::path& root, const std::string& file,
                 const std::string& path) {
  const fs::path p(name);
  if (name.empty()) fail(file, path, "the path is empty");
  if (p.is_absolute()) fail(file, path, "absolute paths are not allowed ('" + name + "'): use ./ (prefab folder) or a path under the root");
  for (const auto& part : p)
    if (part == "..") fail(file, path, "paths containing '..' are not allowed ('" + name + "')");
  return (name.rfind("./", 0) == 0 ? prefab_dir / p : root / p).lexically_normal();
}

// The placement of an entry: worldFromLocal, or rotation/translation fields.
Transform local_pose(const json& e, const std::string& file, const std::string& path) {
  if (e.contains("worldFromLocal")) return transform_from_json(e.at("worldFromLocal"), file, path + ".worldFromLocal");
  json t = json::object();
  if (e.contains("rotation")) t["rotation"] = e.at("rotation");
  if (e.contains("translation")) t["translation"] = e.at("translation");
  return transform_from_json(t, file, path);
}

ShapeGeometry scaled_primitive(ShapeGeometry g, real s) {
  if (auto* x = std::get_if<SphereShape>(&g)) x->radius *= s, x->center *= s;
  if (auto* x = std::get_if<BoxShape>(&g)) x->half_extents *= s;
  if (auto* x = std::get_if<CapsuleShape>(&g)) x->radius *= s, x->half_length *= s;
  if (auto* x = std::get_if<PlaneShape>(&g)) x->distance *= s;
  return g;
}

struct Loader {
  Scene scene;
  const fs::path root;
  std::vector<std::string>* warnings;
  PrefabResult result;
  std::vector<ShapeHandle> shapes;  // made for the actors; released when the load ends
  int depth = 0;

  std::optional<real> opt_number(const json& e, const char* key, const std::string& file, const std::string& path) {
    if (!e.contains(key) || e.at(key).is_null()) return std::nullopt;
    if (!e.at(key).is_number()) fail(file, path + "." + key, "expected a number");
    return e.at(key).get<real>();
  }
  // e[key] when present: a boolean, an integer or a string; fails naming the field otherwise
  bool opt_bool(const json& e, const char* key, bool fallback, const std::string& file, const std::string& path) {
    if (!e.contains(key)) return fallback;
    if (!e.at(key).is_boolean()) fail(file, path + "." + key, "expected a boolean, got " + e.at(key).dump());
    return e.at(key).get<bool>();
  }
  int opt_int(const json& e, const char* key, int fallback, const std::string& file, const std::string& path) {
    if (!e.contains(key)) return fallback;
    const json& v = e.at(key);
    if (!v.is_number_integer() || v.get<std::int64_t>() < -(1 << 30) || v.get<std::int64_t>() > (1 << 30))
      fail(file, path + "." + key, "expected an integer, got " + v.dump());
    return v.get<int>();
  }
  Vec3 vec3(const json& v, const std::string& file, const std::string& path) {
    if (!v.is_array() || v.size() != 3) fail(file, path, "expected 3 numbers, got " + v.dump());
    Vec3 x;
    for (int k = 0; k < 3; ++k) {
      if (!v[k].is_number()) fail(file, path + "[" + std::to_string(k) + "]", "expected a number, got " + v[k].dump());
      x[k] = v[k].get<real>();
    }
    if (!x.allFinite()) fail(file, path, "must be finite");
    return x;
  }

  void load(const fs::path& file_path, const PrefabParams& params) {
    const std::string file = file_path.string();
    if (++depth > 16) fail(file, "prefabs", "prefabs nest more than 16 deep (a prefab includes itself?)");
    const json doc = read_json_file(file, "prefab");
    if (!doc.is_object()) fail(file, "(top level)", "expected an object");
    if (doc.contains("actors") && !doc.at("actors").is_object())
      fail(file, "actors", "expected an object with lists rigid, soft and articulated, got " + doc.at("actors").dump());
    const fs::path dir = file_path.parent_path();
    const real s = params.scale;
    // world-from-local of an entry: the prefab's pose, then the scaled local placement
    auto place = [&](Transform X) {
      X.translation *= s;
      return params.world_from_prefab * X;
    };
    auto prefixed = [&](const std::string& n) { return params.name.empty() ? n : params.name + "/" + n; };

    if (params.apply_scene_settings && doc.contains("scene")) {
      const json& sc = doc.at("scene");
      if (sc.contains("gravity")) {
        scene.set_gravity(vec3(sc.at("gravity"), file, "scene.gravity"));
      }
      if (sc.contains("solver")) {
        SolverParams p = scene.solver_params();
        const json& so = sc.at("solver");
        p.non_linear_solver.max_iter = opt_int(so, "maxNewtonIterations", p.non_linear_solver.max_iter, file, "scene.solver");
        p.implicit_step.contact_margin = opt_number(so, "contactMargin", file, "scene.solver").value_or(p.implicit_step.contact_margin);
        try {
          scene.set_solver_params(p);
        } catch (const Error& err) {
          fail(file, "scene.solver", err.what());
        }
      }
    }

    const json actors = doc.value("actors", json::object());
    for (const char* kind : {"rigid", "soft", "articulated"})
      if (actors.contains(kind) && !actors.at(kind).is_array()) fail(file, std::string("actors.") + kind, "expected an array");
    if (actors.contains("rigid"))
      for (size_t i = 0; i < actors.at("rigid").size(); ++i) add_rigid(actors.at("rigid")[i], file, dir, "actors.rigid[" + std::to_string(i) + "]", place, prefixed, s);
    if (actors.contains("soft"))
      for (size_t i = 0; i < actors.at("soft").size(); ++i) add_soft(actors.at("soft")[i], file, dir, "actors.soft[" + std::to_string(i) + "]", place, prefixed, s);
    if (actors.contains("articulated"))
      for (size_t i = 0; i < actors.at("articulated").size(); ++i)
        add_articulated(actors.at("articulated")[i], file, dir, "actors.articulated[" + std::to_string(i) + "]", place, prefixed, s);

    if (doc.contains("prefabs")) {
      const json& list = doc.at("prefabs");
      if (!list.is_array()) fail(file, "prefabs", "expected an array");
      for (size_t i = 0; i < list.size(); ++i) {
        const std::string path = "prefabs[" + std::to_string(i) + "]";
        const json& e = list[i];
        if (!e.is_object() || !e.contains("path") || !e.at("path").is_string()) fail(file, path + ".path", "required: the nested prefab's file");
        PrefabParams nested;
        if (e.contains("name") && !e.at("name").is_string()) fail(file, path + ".name", "expected a string, got " + e.at("name").dump());
        nested.name = prefixed(e.value("name", std::string("prefab") + std::to_string(i)));
        const real ns = opt_number(e, "scale", file, path).value_or(1);
        if (!(ns > 0)) fail(file, path + ".scale", "must be positive");
        nested.scale = s * ns;
        nested.world_from_prefab = place(local_pose(e, file, path));
        const fs::path nested_path = resolve(e.at("path").get<std::string>(), dir, root, file, path + ".path");
        if (!is_existing_file(nested_path)) fail(file, path + ".path", "prefab file '" + nested_path.string() + "' does not exist");
        load(nested_path, nested);
      }
    }

    if (doc.contains("contactFilter")) apply_filter(doc.at("contactFilter"), file, prefixed);
    if (doc.contains("constraints") && !doc.at("constraints").empty())
      fail(file, "constraints", "constraints are not supported yet");
    --depth;
  }

  template <class Place, class Prefix>
  void add_rigid(const json& e, const std::string& file, const fs::path& dir, const std::string& path, Place place, Prefix prefixed, real s) {
    if (!e.is_object()) fail(file, path, "expected an object");
    if (!e.contains("name") || !e.at("name").is_string()) fail(file, path + ".name", "required: a string");
    if (!e.contains("shape")) fail(file, path + ".shape", "required: a shape file or an inline primitive");
    ShapeGeometry geometry;
    const json& sh = e.at("shape");
    if (sh.is_string()) {
      const fs::path p = resolve(sh.get<std::string>(), dir, root, file, path + ".shape");
      if (!is_existing_file(p)) fail(file, path + ".shape", "shape file '" + p.string() + "' does not exist");
      ShapeBake bake;
      bake.scale = Vec3::Constant(s);
      try {
        geometry = load_shape_file(p.string(), bake);
      } catch (const Error& err) {
        fail(file, path + ".shape", err.what());
      }
    } else {
      geometry = scaled_primitive(shape_from_json(sh, file, path + ".shape"), s);
    }
    RigidActorParams params;
    params.is_static = opt_bool(e, "isStatic", false, file, path);
    if (e.contains("contact")) params.contact = contact_params_from_json(e.at("contact"), file, path + ".contact");
    ColliderType collider = ColliderType::Auto;
    if (e.contains("colliderType")) {
      static const std::vector<std::string> kNames = {"Auto", "None", "Sphere", "Box", "Plane", "Mesh", "Sdf"};
      const json& c = e.at("colliderType");
      if (!c.is_string() || std::find(kNames.begin(), kNames.end(), c.get<std::string>()) == kNames.end())
        fail(file, path + ".colliderType", "unknown collider type " + c.dump() + " (expected Auto, None, Sphere, Box, Plane, Mesh or Sdf)");
      if (c == "None") collider = ColliderType::None;
    }
    if (e.contains("layer")) {
      if (!e.at("layer").is_string()) fail(file, path + ".layer", "expected a contact layer name (a string), got " + e.at("layer").dump());
      params.layer = e.at("layer").get<std::string>();
    }
    const Transform X_WL = place(local_pose(e, file, path));
    const std::optional<real> density = opt_number(e, "density", file, path), mass = opt_number(e, "mass", file, path);
    for (const auto& [key, value] : {std::pair{"mass", mass}, std::pair{"density", density}})
      if (value && !(std::isfinite(*value) && *value > 0))
        fail(file, path + "." + key, "must be a positive finite number, got " + json(*value).dump());
    validate_shape(geometry, file + ": " + path + ".shape");
    params.name = prefixed(e.at("name").get<std::string>());
    params.shape = create_shape(geometry);
    params.world_from_local = X_WL;
    params.density = density;
    params.mass = mass;
    params.collider_type = collider;
    try {
      result.actors.push_back(scene.create_rigid_actor(params));
    } catch (const Error& err) {
      fail(file, path, err.what());
    }
  }

  // A soft actor: a tetrahedral .mochi.h5 shape, a material, and pinned nodes (fixedNodes indices
  // and/or the nodes inside fixedRegion, an AABB {min, max} in the actor's frame, scaled with it).
  template <class Place, class Prefix>
  void add_soft(const json& e, const std::string& file, const fs::path& dir, const std::string& path, Place place, Prefix prefixed, real s) {
    if (!e.is_object()) fail(file, path, "expected an object");
    if (!e.contains("name") || !e.at("name").is_string()) fail(file, path + ".name", "required: a string");
    if (!e.contains("shape") || !e.at("shape").is_string()) fail(file, path + ".shape", "required: a .mochi.h5 file with a tetrahedral mesh/");
    const fs::path p = resolve(e.at("shape").get<std::string>(), dir, root, file, path + ".shape");
    if (!is_existing_file(p)) fail(file, path + ".shape", "shape file '" + p.string() + "' does not exist");
    ShapeBake bake;
    bake.scale = Vec3::Constant(s);
    std::optional<TetMesh> mesh;
    try {
      mesh = read_tet_mesh_file(p.string(), bake);
    } catch (const Error& err) {
      fail(file, path + ".shape", err.what());
    }
    if (!mesh) fail(file, path + ".shape", "'" + p.string() + "' has no tetrahedral mesh/ (connectivity M x 4)");
    SoftMaterial material;
    if (e.contains("material")) material = soft_material_from_json(e.at("material"), file, path + ".material", warnings);
    if (auto d = opt_number(e, "density", file, path)) material.density = *d;
    std::vector<int> fixed;
    if (e.contains("fixedNodes")) {
      const json& list = e.at("fixedNodes");
      if (!list.is_array()) fail(file, path + ".fixedNodes", "expected an array of node indices");
      for (size_t k = 0; k < list.size(); ++k) {
        const std::string field = path + ".fixedNodes[" + std::to_string(k) + "]";
        if (!list[k].is_number_integer()) fail(file, field, "expected an integer, got " + list[k].dump());
        if (list[k].get<std::int64_t>() < 0 || list[k].get<std::int64_t>() >= static_cast<std::int64_t>(mesh->nodes.size()))
          fail(file, field, "node " + list[k].dump() + " is out of range (the mesh has " + std::to_string(mesh->nodes.size()) + " nodes)");
        fixed.push_back(list[k].get<int>());
      }
    }
    if (e.contains("fixedRegion")) {
      const json& r = e.at("fixedRegion");
      auto corner = [&](const char* key) {
        if (!r.is_object() || !r.contains(key)) fail(file, path + ".fixedRegion." + key, "required: 3 numbers (m, actor frame)");
        return vec3(r.at(key), file, path + ".fixedRegion." + key) * s;
      };
      const Vec3 lo = corner("min"), hi = corner("max");
      if ((lo.array() > hi.array()).any()) fail(file, path + ".fixedRegion", "min must not exceed max in any axis");
      for (size_t k = 0; k < mesh->nodes.size(); ++k)
        if ((mesh->nodes[k].array() >= lo.array()).all() && (mesh->nodes[k].array() <= hi.array()).all()) fixed.push_back(static_cast<int>(k));
    }
    const std::string source = file + ": " + path;
    const Transform X_WL = place(local_pose(e, file, path));
    try {
      const ShapeHandle shape = create_tet_mesh_shape(std::move(*mesh), source + ".shape");
      shapes.push_back(shape);
      result.actors.push_back(scene.create_soft_actor(prefixed(e.at("name").get<std::string>()), shape, material, X_WL, fixed));
    } catch (const Error& err) {
      const std::string msg = err.what();
      throw Error(msg.rfind(file, 0) == 0 ? msg : source + ": " + msg);
    }
  }

  template <class Place, class Prefix>
  void add_articulated(const json& e, const std::string& file, const fs::path& dir, const std::string& path, Place place, Prefix prefixed, real s) {
    if (!e.is_object()) fail(file, path, "expected an object");
    ArticulationDesc desc;
    std::string source = file + ": " + path;
    fs::path base = dir;
    if (e.contains("bot")) {
      if (!e.at("bot").is_string()) fail(file, path + ".bot", "expected a path to a .superdex_bot file");
      const fs::path p = resolve(e.at("bot").get<std::string>(), dir, root, file, path + ".bot");
      json bot;
      try {
        bot = read_json_file(p.string(), "bot");
      } catch (const Error& err) {
        fail(file, path + ".bot", err.what());
      }
      desc = articulation_desc_from_json(bot, p.string(), warnings, {"sensors", "actuators"});
      source = p.string();
      base = p.parent_path();
    } else {
      json inline_desc = e;
      desc = articulation_desc_from_json(inline_desc, source, warnings, {"bot", "worldFromLocal", "rotation", "translation", "isStatic"});
    }
    if (e.contains("name") && e.at("name").is_string()) desc.name = e.at("name").get<std::string>();
    desc.name = prefixed(desc.name.empty() ? "articulation" : desc.name);
    load_link_shape_files(desc, base.string(), source, s);
    if (s != 1)
      for (auto& j : desc.joints) j.parent_link_from_joint.translation *= s;
    desc.world_from_root = place(local_pose(e, file, path)) * desc.world_from_root;
    result.actors.push_back(scene.create_articulated_actor(desc, source));
  }

  template <class Prefix>
  void apply_filter(const json& f, const std::string& file, Prefix prefixed) {
    auto handle_of = [&](const std::string& name, const std::string& path) {
      for (ActorHandle h : result.actors)
        if (scene.actor_name(h) == prefixed(name)) return h;
      fail(file, path, "no actor named '" + name + "' in this prefab");
    };
    if (!f.is_object()) fail(file, "contactFilter", "expected an object {disabledPairs, disabledLayers}");
    for (const char* key : {"disabledPairs", "disabledLayers"})
      if (f.contains(key) && !f.at(key).is_array()) fail(file, std::string("contactFilter.") + key, "expected an array of pairs");
    if (f.contains("disabledPairs"))
      for (size_t i = 0; i < f.at("disabledPairs").size(); ++i) {
        const json& p = f.at("disabledPairs")[i];
        const std::string path = "contactFilter.disabledPairs[" + std::to_string(i) + "]";
        if (!p.is_array() || p.size() != 2 || !p[0].is_string() || !p[1].is_string()) fail(file, path, "expected two actor names");
        scene.enable_actor_contact_symmetric(handle_of(p[0], path), handle_of(p[1], path), false, IncludeNestedActors::Yes);
      }
    if (f.contains("disabledLayers"))
      for (size_t i = 0; i < f.at("disabledLayers").size(); ++i) {
        const json& p = f.at("disabledLayers")[i];
        const std::string path = "contactFilter.disabledLayers[" + std::to_string(i) + "]";
        if (!p.is_array() || p.size() != 2 || !p[0].is_string() || !p[1].is_string()) fail(file, path, "expected two layer names");
        try {
          scene.enable_layer_contact_symmetric(p[0].get<std::string>(), p[1].get<std::string>(), false);
        } catch (const Error& err) {
          fail(file, path, err.what());
        }
      }
  }
};

}  // namespace

void load_link_shape_files(ArticulationDesc& desc, const std::string& base_dir, const std::string& source, real scale) {
  for (size_t i = 0; i < desc.links.size(); ++i) {
    LinkDesc& link = desc.links[i];
    const std::string path = "links[" + std::to_string(i) + "].shape";
    if (link.shape && scale != 1) link.shape = scaled_primitive(*link.shape, scale), link.link_from_shape.translation *= scale;
    if (link.center_of_mass && scale != 1) *link.center_of_mass *= scale;
    // the render model (.glb, for the debugger), relative to the file
    if (!link.render_model.empty()) {
      fs::path model_path(link.render_model);
      if (model_path.is_relative()) model_path = fs::path(base_dir) / model_path;
      const std::string field = "links[" + std::to_string(i) + "].renderModel";
      if (!is_existing_file(model_path)) fail(source, field, "render model '" + model_path.string() + "' does not exist");
      if (model_path.extension() != ".glb") fail(source, field, "render models are binary glTF (.glb) files, got '" + model_path.string() + "'");
      link.render_model = model_path.lexically_normal().string();
      if (scale != 1) link.render_model_scale *= scale;
    }
    if (link.shape_file.empty()) continue;
    fs::path shape_path(link.shape_file);
    if (shape_path.is_relative()) shape_path = fs::path(base_dir) / shape_path;
    if (!is_existing_file(shape_path)) fail(source, path, "shape file '" + shape_path.string() + "' does not exist");
    ShapeBake bake;
    bake.scale = link.shape_scale * scale;
    try {
      link.shape = load_shape_file(shape_path.string(), bake);
    } catch (const Error& e) {
      fail(source, path, e.what());
    }
    link.shape_scale = Vec3::Ones();
  }
}

PrefabResult add_prefab_to_scene(const std::string& prefab_path, const std::string& root_path, Scene scene,
                                 const PrefabParams& params, std::vector<std::string>* warnings) {
  if (!(params.scale > 0) || !std::isfinite(params.scale)) throw Error("add_to_scene: scale must be a positive number");
  Loader loader{scene, fs::path(root_path), warnings, {}, {}};
  // The actors keep their own geometry (a rigid actor a copy, a soft actor the shared tet mesh),
  // so the engine-wide shapes made for them are released, loaded or not: kept, they piled up in
  // the shape registry with every load (a duck's whole tet mesh per load; found by
  // memory_cycles_test, issue 9).
  auto release_shapes = [&] {
    for (ShapeHandle h : loader.shapes) release_shape(h);
  };
  try {
    try {
      loader.load(fs::path(prefab_path), params);
    } catch (const nlohmann::json::exception& e) {
      // a value of the wrong JSON type that no check above caught
      throw Error(prefab_path + ": unexpected JSON value: " + e.what());
    }
  } catch (...) {
    // all or nothing
    for (ActorHandle h : loader.result.actors)
      if (scene.has_actor(h)) scene.destroy_actor(h);
    release_shapes();
    throw;
  }
  release_shapes();
  return loader.result;
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

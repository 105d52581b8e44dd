// Reading a prefab document into a ScenePrefab (prefab_json.h). Each actor kind has its reader;
// articulated entries go through the `.superdex_bot` reader (inline, or the file `bot` names).

#include <cmath>
#include <cstdint>
#include <filesystem>

#include "io/prefab_json.h"
#include "superdex/physics/articulation_json.h"
#include "superdex/physics/error.h"
#include "superdex/physics/params/solver_params.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {
namespace prefab {

namespace fs = std::filesystem;
using json = nlohmann::json;

std::optional<ColliderType> collider_type_from_name(const std::string& name) {
  for (ColliderType t : {ColliderType::None, ColliderType::Auto, ColliderType::Sphere, ColliderType::Box, ColliderType::Mesh,
                         ColliderType::Plane, ColliderType::Sdf})
    if (name == collider_type_name(t)) return t;
  return std::nullopt;
}

std::string error_prefix(const ScenePrefab& prefab) { return (prefab.source_file.empty() ? "ScenePrefab" : prefab.source_file) + ": "; }

ArticulatedLinkPrefab link_prefab(const LinkDesc& l) {
  ArticulatedLinkPrefab p;
  p.name = l.name;
  p.parent_link = l.parent_link;
  p.mass = l.mass;
  p.density = l.density;
  p.center_of_mass = l.center_of_mass;
  if (l.moment_of_inertia) p.moment_of_inertia = Real6(Eigen::Map<const Real6>(l.moment_of_inertia->data()));
  p.parent_joint_from_link.translation = l.joint_from_link;
  p.collider_type = collider_type_from_name(l.collider_type).value_or(ColliderType::Auto);
  p.contact = l.contact;
  p.has_gravity = l.has_gravity;
  return p;
}

ArticulatedJointPrefab joint_prefab(const JointDesc& j) {
  ArticulatedJointPrefab p;
  p.name = j.name;
  p.type = j.type;
  p.axis = j.axis;
  p.parent_link_from_joint = j.parent_link_from_joint;
  p.min_limit = j.min_limit;
  p.max_limit = j.max_limit;
  p.friction.coulomb = j.coulomb_friction;
  p.friction.viscous = j.viscous_friction;
  if (j.armature != 0) p.inertia = j.armature;
  p.limit_stiffness = j.limit_stiffness;
  p.limit_damping = j.limit_damping;
  return p;
}

namespace {

// Reads the fields of one entry; errors name the source, the entry's path and the field.
struct Entry {
  const json& e;
  const std::string& file;
  std::string path;

  [[noreturn]] void fail(const std::string& field, const std::string& what) const {
    throw Error(file + ": " + (field.empty() ? path : path.empty() ? field : path + "." + field) + ": " + what);
  }
  bool has(const char* key) const { return e.contains(key) && !e.at(key).is_null(); }
  std::optional<real> number(const char* key) const {
    if (!has(key)) return std::nullopt;
    if (!e.at(key).is_number()) fail(key, "expected a number, got " + e.at(key).dump());
    return e.at(key).get<real>();
  }
  bool boolean(const char* key, bool fallback) const {
    if (!has(key)) return fallback;
    if (!e.at(key).is_boolean()) fail(key, "expected a boolean, got " + e.at(key).dump());
    return e.at(key).get<bool>();
  }
  std::optional<std::string> string(const char* key) const {
    if (!has(key)) return std::nullopt;
    if (!e.at(key).is_string()) fail(key, "expected a string, got " + e.at(key).dump());
    return e.at(key).get<std::string>();
  }
  template <int N>
  std::optional<Eigen::Matrix<real, N, 1>> vec(const char* key) const {
    if (!has(key)) return std::nullopt;
    const json& v = e.at(key);
    if (!v.is_array() || v.size() != N) fail(key, "expected " + std::to_string(N) + " numbers, got " + v.dump());
    Eigen::Matrix<real, N, 1> x;
    for (int k = 0; k < N; ++k) {
      if (!v[k].is_number()) fail(std::string(key) + "[" + std::to_string(k) + "]", "expected a number, got " + v[k].dump());
      x[k] = v[k].get<real>();
    }
    if (!x.allFinite()) fail(key, "must be finite");
    return x;
  }
  // a path written in the file: "./x" (the prefab's folder) or "x" (the root)
  std::string file_path(const char* key) const {
    const std::string name = *string(key);
    const fs::path p(name);
    if (name.empty()) fail(key, "the path is empty");
    if (p.is_absolute()) fail(key, "absolute paths are not allowed ('" + name + "'): use ./ (prefab folder) or a path under the root");
    for (const auto& part : p)
      if (part == "..") fail(key, "paths containing '..' are not allowed ('" + name + "')");
    return name;
  }
  // the placement X_PL: worldFromLocal, or rotation/translation fields
  Transform pose() const {
    if (has("worldFromLocal")) return transform_from_json(e.at("worldFromLocal"), file, path + ".worldFromLocal");
    json t = json::object();
    for (const char* key : {"rotation", "translation"})
      if (has(key)) t[key] = e.at(key);
    return transform_from_json(t, file, path);
  }
  Quaternion quaternion(const char* key) const {
    if (!has(key)) return Quaternion::Identity();
    const Real4 q = *vec<4>(key);
    if (q.norm() < real(1e-6)) fail(key, "must be a non-zero quaternion [x, y, z, w]");
    return Quaternion(q[3], q[0], q[1], q[2]).normalized();
  }
  ColliderType collider(const char* key) const {
    if (!has(key)) return ColliderType::Auto;
    const json& c = e.at(key);
    const std::optional<ColliderType> t = c.is_string() ? collider_type_from_name(c.get<std::string>()) : std::nullopt;
    if (!t) fail(key, "unknown collider type " + c.dump() + " (expected Auto, None, Sphere, Box, Plane, Mesh or Sdf)");
    return *t;
  }
  std::optional<std::string> comment() const { return string("comment"); }
  const json& list(const char* key) const {
    if (!e.at(key).is_array()) fail(key, "expected an array");
    return e.at(key);
  }
};

std::string indexed(const std::string& list, size_t i) { return list + "[" + std::to_string(i) + "]"; }

void read_render_model(const Entry& r, RenderModel& m) {
  if (r.has("renderModel")) m.file = r.file_path("renderModel");
  if (auto v = r.vec<3>("renderModelScale")) m.scale = *v;
  m.rotation = r.quaternion("renderModelRotation");
  if (auto v = r.vec<3>("renderModelTranslation")) m.translation = *v;
}

// `shape`: a file path or an inline primitive; then scale, shapeRotation, shapeTranslation
void read_shape(const Entry& r, ShapeSource& s, bool primitives_allowed) {
  if (!r.has("shape")) r.fail("shape", primitives_allowed ? "required: a shape file or an inline primitive" : "required: a .mochi.h5 file with a tetrahedral mesh/");
  const json& sh = r.e.at("shape");
  if (sh.is_string()) {
    s.file = r.file_path("shape");
  } else if (primitives_allowed) {
    s.primitive = shape_from_json(sh, r.file, r.path + ".shape");
    const Transform X_LS = shape_pose_from_json(sh, r.file, r.path + ".shape");
    s.rotation = X_LS.rotation;
    s.translation = X_LS.translation;
  } else {
    r.fail("shape", "required: a .mochi.h5 file with a tetrahedral mesh/");
  }
  if (auto v = r.vec<3>("scale")) s.scale = *v;
  if (r.has("shapeRotation")) s.rotation = r.quaternion("shapeRotation");
  if (auto v = r.vec<3>("shapeTranslation")) s.translation = *v;
}

// What rigid and soft entries share: a name, a comment, the shape, the placement X_PL, the contact
// layer and parameters, gravity and a render model.
template <class Prefab>
Prefab read_placed_actor(const Entry& r, bool primitives_allowed) {
  if (!r.e.is_object()) r.fail("", "expected an object");
  Prefab a;
  if (!r.has("name") || !r.e.at("name").is_string()) r.fail("name", "required: a string");
  a.name = *r.string("name");
  a.comment = r.comment();
  read_shape(r, a.shape_source, primitives_allowed);
  if (r.has("contact")) a.contact = contact_params_from_json(r.e.at("contact"), r.file, r.path + ".contact");
  if (r.has("layer") && !r.e.at("layer").is_string())
    r.fail("layer", "expected a contact layer name (a string), got " + r.e.at("layer").dump());
  a.layer = r.string("layer").value_or("");
  const Transform X_PL = r.pose();
  a.rotation = X_PL.rotation;
  a.translation = X_PL.translation;
  a.has_gravity = r.boolean("hasGravity", true);
  read_render_model(r, a.render_model);
  return a;
}

RigidActorPrefab read_rigid(const Entry& r) {
  RigidActorPrefab a = read_placed_actor<RigidActorPrefab>(r, true);
  a.is_static = r.boolean("isStatic", false);
  a.collider_type = r.collider("colliderType");
  a.density = r.number("density");
  a.mass = r.number("mass");
  a.center_of_mass = r.vec<3>("centerOfMass");
  a.moment_of_inertia = r.vec<6>("momentOfInertia");
  a.linear_velocity = r.vec<3>("linearVelocity");
  a.angular_velocity = r.vec<3>("angularVelocity");
  return a;
}

// `material` {type, youngsModulus, poissonRatio, density, damping, dampingAlpha, reducedModes}
void read_soft_material(const Entry& r, SoftActorPrefab& a) {
  if (!r.has("material")) return;
  const std::string path = r.path + ".material";
  const SoftMaterial m = soft_material_from_json(r.e.at("material"), r.file, path, nullptr);
  SoftMaterialParams& p = a.material;
  real *E = nullptr, *nu = nullptr;
  if (m.type == "NeoHookean" || m.type == "StableNeoHookean") {
    p.type = SoftMaterialType::NeoHookean, E = &p.neo_hookean.youngs_modulus, nu = &p.neo_hookean.poisson_ratio;
  } else if (m.type == "StVK" || m.type == "StVenantKirchhoff") {
    p.type = SoftMaterialType::StVenantKirchhoff, E = &p.st_venant_kirchhoff.youngs_modulus, nu = &p.st_venant_kirchhoff.poisson_ratio;
  } else if (m.type == "Linear" || m.type == "LinearElastic") {
    p.type = SoftMaterialType::LinearElastic, E = &p.linear_elastic.youngs_modulus, nu = &p.linear_elastic.poisson_ratio;
  } else {
    throw Error(r.file + ": " + path + ".type: unknown material type '" + m.type + "' (expected NeoHookean, StVK or Linear)");
  }
  if (m.youngs_modulus) *E = *m.youngs_modulus;
  if (m.poisson_ratio) *nu = *m.poisson_ratio;
  p.density = m.density;
  p.mass_damping_coefficient = m.damping_alpha;
  p.stiffness_damping_coefficient = m.damping_beta;
  a.reduced_modes = m.reduced_modes;
}

SoftActorPrefab read_soft(const Entry& r) {
  SoftActorPrefab a = read_placed_actor<SoftActorPrefab>(r, false);
  read_soft_material(r, a);
  if (auto d = r.number("density")) a.material.density = *d;
  a.use_recentering = r.boolean("useRecentering", true);
  if (r.has("fixedNodes")) {
    const json& list = r.e.at("fixedNodes");
    if (!list.is_array()) r.fail("fixedNodes", "expected an array of node indices");
    for (size_t k = 0; k < list.size(); ++k) {
      if (!list[k].is_number_integer() || list[k].get<std::int64_t>() < 0 || list[k].get<std::int64_t>() > (1 << 30))
        r.fail(indexed("fixedNodes", k), "expected a node index (an integer >= 0), got " + list[k].dump());
      a.fixed_nodes.push_back(list[k].get<int>());
    }
  }
  if (r.has("fixedRegion")) {
    const Entry region{r.e.at("fixedRegion"), r.file, r.path + ".fixedRegion"};
    Aabb box;
    for (auto [key, corner] : {std::pair{"min", &box.min}, std::pair{"max", &box.max}}) {
      if (!region.e.is_object() || !region.has(key)) region.fail(key, "required: 3 numbers (m, actor frame)");
      *corner = *region.vec<3>(key);
    }
    if ((box.min.array() > box.max.array()).any()) region.fail("", "min must not exceed max in any axis");
    a.fixed_region = box;
  }
  return a;
}

// The link and joint fields of a bot document as prefab links and joints. Files named by a bot
// file are relative to its folder: they become absolute here.
void take_articulation(ArticulationDesc desc, const fs::path& bot_dir, ArticulatedActorPrefab& a) {
  auto located = [&](const std::string& file) {
    return file.empty() || bot_dir.empty() || fs::path(file).is_absolute() ? file : (bot_dir / file).lexically_normal().string();
  };
  for (const LinkDesc& l : desc.links) {
    ArticulatedLinkPrefab p = link_prefab(l);
    p.shape_source.file = located(l.shape_file);
    p.shape_source.primitive = l.shape;
    p.shape_source.scale = l.shape_scale;
    p.shape_source.rotation = l.link_from_shape.rotation;
    p.shape_source.translation = l.link_from_shape.translation;
    p.render_model.file = located(l.render_model);
    p.render_model.scale = l.render_model_scale;
    p.layer = l.layer == 0 ? "" : std::to_string(l.layer);
    a.links.push_back(std::move(p));
  }
  for (size_t i = 0; i < desc.joints.size(); ++i) {
    ArticulatedJointPrefab p = joint_prefab(desc.joints[i]);
    // the file's worldFromRoot places the root joint in the root frame R
    if (i == 0) p.parent_link_from_joint = desc.world_from_root * p.parent_link_from_joint;
    a.joints.push_back(p);
  }
  a.default_pose = std::move(desc.default_pose);
  a.contact_overrides = std::move(desc.contact_overrides);
}

ArticulatedActorPrefab read_articulated(const Entry& r, std::vector<std::string>* warnings) {
  if (!r.e.is_object()) r.fail("", "expected an object");
  ArticulatedActorPrefab a;
  a.comment = r.comment();
  const std::vector<std::string> entry_fields = {"bot", "worldFromLocal", "rotation", "translation", "isStatic", "scale", "comment", "jointVelocities"};
  if (r.has("bot")) {
    // read with the nested prefabs (read_bot_file): a file the prefab references
    if (!r.e.at("bot").is_string()) r.fail("bot", "expected a path to a .superdex_bot file");
    a.bot_file = r.file_path("bot");
  } else {
    // links written inline may name their contact layer (bot files number them): the names are
    // set aside for the bot reader and given to the links after it
    json entry = r.e;
    std::vector<std::pair<size_t, std::string>> named_layers;
    if (entry.contains("links") && entry.at("links").is_array())
      for (size_t i = 0; i < entry.at("links").size(); ++i) {
        json& l = entry.at("links")[i];
        if (l.is_object() && l.contains("layer") && l.at("layer").is_string()) {
          const std::string name = l.at("layer").get<std::string>();
          if (name.empty()) Entry{l, r.file, indexed(r.path + ".links", i)}.fail("layer", "expected a layer number or a non-empty name");
          named_layers.emplace_back(i, name);
          l.erase("layer");
        }
      }
    ArticulationDesc desc = articulation_desc_from_json(entry, r.file + ": " + r.path, warnings, entry_fields);
    for (size_t i = 0; i < desc.links.size(); ++i)
      if (!desc.links[i].shape_file.empty()) Entry{r.e.at("links")[i], r.file, indexed(r.path + ".links", i)}.file_path("shape");
    a.name = desc.name;
    take_articulation(std::move(desc), {}, a);
    for (const auto& [i, name] : named_layers) a.links[i].layer = name;
  }
  if (auto n = r.string("name")) a.name = *n;
  const Transform X_PR = r.pose();
  a.rotation = X_PR.rotation;
  a.translation = X_PR.translation;
  if (auto s = r.number("scale")) a.scale = *s;
  if (r.has("jointVelocities")) {
    const json& v = r.list("jointVelocities");
    a.joint_velocities.emplace();
    for (size_t k = 0; k < v.size(); ++k) {
      if (!v[k].is_number()) r.fail(indexed("jointVelocities", k), "expected a number, got " + v[k].dump());
      a.joint_velocities->push_back(v[k].get<real>());
    }
  }
  return a;
}

PrefabReference read_reference(const Entry& r) {
  if (!r.e.is_object() || !r.has("path") || !r.e.at("path").is_string()) r.fail("path", "required: the nested prefab's file");
  PrefabReference ref;
  ref.comment = r.comment();
  ref.path = r.file_path("path");
  ref.name = r.string("name").value_or("");
  ref.scale = r.number("scale").value_or(1);
  if (!(ref.scale > 0) || !std::isfinite(ref.scale)) r.fail("scale", "must be positive");
  const Transform X_PN = r.pose();
  ref.rotation = X_PN.rotation;
  ref.translation = X_PN.translation;
  return ref;
}

// one list of contact entries: `names_key` holds the two actor or layer names
template <class E>
std::vector<E> read_entries(const Entry& f, const char* key, const char* names_key) {
  std::vector<E> out;
  const json& list = f.list(key);
  for (size_t i = 0; i < list.size(); ++i) {
    const Entry r{list[i], f.file, f.path + "." + indexed(key, i)};
    if (!r.e.is_object()) r.fail("", "expected an object {enable, " + std::string(names_key) + "}");
    E entry;
    entry.enable = r.boolean("enable", true);
    const json& names = r.has(names_key) ? r.e.at(names_key) : json();
    if (!names.is_array() || names.size() != 2 || !names[0].is_string() || !names[1].is_string())
      r.fail(names_key, "expected two names, got " + names.dump());
    if constexpr (requires { entry.actors; }) {
      entry.actors = {names[0], names[1]};
      entry.include_nested_actors = r.boolean("includeNestedActors", true);
    } else {
      entry.layers = {names[0], names[1]};
    }
    out.push_back(std::move(entry));
  }
  return out;
}

ContactFilter read_contact_filter(const Entry& f) {
  if (!f.e.is_object()) f.fail("", "expected an object");
  ContactFilter c;
  c.comment = f.comment();
  if (f.has("actorContactAsymmetric")) c.actor_contact_asymmetric = read_entries<ActorContactEntry>(f, "actorContactAsymmetric", "actors");
  if (f.has("actorContactSymmetric")) c.actor_contact_symmetric = read_entries<ActorContactEntry>(f, "actorContactSymmetric", "actors");
  if (f.has("layerContactAsymmetric")) c.layer_contact_asymmetric = read_entries<LayerContactEntry>(f, "layerContactAsymmetric", "layers");
  if (f.has("layerContactSymmetric")) c.layer_contact_symmetric = read_entries<LayerContactEntry>(f, "layerContactSymmetric", "layers");
  // the short form: pairs whose contact is disabled both ways
  for (auto [key, is_actor] : {std::pair{"disabledPairs", true}, std::pair{"disabledLayers", false}}) {
    if (!f.has(key)) continue;
    const json& list = f.list(key);
    for (size_t i = 0; i < list.size(); ++i) {
      const json& p = list[i];
      if (!p.is_array() || p.size() != 2 || !p[0].is_string() || !p[1].is_string())
        f.fail(indexed(key, i), is_actor ? "expected two actor names" : "expected two layer names");
      if (is_actor) {
        if (!c.actor_contact_symmetric) c.actor_contact_symmetric.emplace();
        c.actor_contact_symmetric->push_back({false, {p[0], p[1]}, true});
      } else {
        if (!c.layer_contact_symmetric) c.layer_contact_symmetric.emplace();
        c.layer_contact_symmetric->push_back({false, {p[0], p[1]}});
      }
    }
  }
  return c;
}

SceneParams read_scene(const Entry& s) {
  if (!s.e.is_object()) s.fail("", "expected an object {gravity, solver, description}");
  SceneParams p;
  p.comment = s.comment();
  p.description = s.string("description").value_or("");
  if (s.has("gravity")) {
    const json& g = s.e.at("gravity");
    if (!g.is_array() || g.size() != 3) s.fail("gravity", "expected 3 numbers, got " + g.dump());
    p.gravity = s.vec<3>("gravity");
  }
  if (s.has("solver")) p.solver = solver_params_from_json(s.e.at("solver"), s.file, s.path + ".solver");
  return p;
}

}  // namespace

void read_bot_file(ArticulatedActorPrefab& actor, const std::string& bot_path, const std::string& where, std::vector<std::string>* warnings) {
  json bot;
  try {
    bot = read_json_file(bot_path, "bot");
  } catch (const Error& err) {
    throw Error(where + ": " + err.what());
  }
  ArticulationDesc desc = articulation_desc_from_json(bot, bot_path, warnings, {"sensors", "actuators"});
  if (actor.name.empty()) actor.name = desc.name;
  ArticulatedActorPrefab read;
  take_articulation(std::move(desc), fs::absolute(bot_path).parent_path(), read);
  actor.links = std::move(read.links);
  actor.joints = std::move(read.joints);
  actor.default_pose = std::move(read.default_pose);
  actor.contact_overrides = std::move(read.contact_overrides);
}

ScenePrefab scene_prefab_from_json(const json& doc, const std::string& source, std::vector<std::string>* warnings) {
  const Entry top{doc, source, ""};
  if (!doc.is_object()) top.fail("(top level)", "expected an object");
  ScenePrefab prefab;
  prefab.comment = top.comment();
  if (top.has("actors")) {
    const Entry actors{doc.at("actors"), source, "actors"};
    if (!actors.e.is_object())
      top.fail("actors", "expected an object with lists rigid, soft and articulated, got " + actors.e.dump());
    prefab.actors.comment = actors.comment();
    for (const char* kind : {"rigid", "soft", "articulated"})
      if (actors.has(kind)) actors.list(kind);
    if (actors.has("rigid"))
      for (size_t i = 0; i < actors.e.at("rigid").size(); ++i)
        prefab.actors.rigid.push_back(read_rigid({actors.e.at("rigid")[i], source, indexed("actors.rigid", i)}));
    if (actors.has("soft"))
      for (size_t i = 0; i < actors.e.at("soft").size(); ++i)
        prefab.actors.soft.push_back(read_soft({actors.e.at("soft")[i], source, indexed("actors.soft", i)}));
    if (actors.has("articulated"))
      for (size_t i = 0; i < actors.e.at("articulated").size(); ++i)
        prefab.actors.articulated.push_back(
            read_articulated({actors.e.at("articulated")[i], source, indexed("actors.articulated", i)}, warnings));
    if (actors.has("softSkinned") && !actors.e.at("softSkinned").empty())
      actors.fail("softSkinned", "soft skinned actors are not supported yet");
  }
  if (top.has("prefabs")) {
    const json& list = top.list("prefabs");
    for (size_t i = 0; i < list.size(); ++i) prefab.prefabs.push_back(read_reference({list[i], source, indexed("prefabs", i)}));
  }
  if (top.has("contactFilter")) prefab.contact_filter = read_contact_filter({doc.at("contactFilter"), source, "contactFilter"});
  if (top.has("scene")) prefab.scene = read_scene({doc.at("scene"), source, "scene"});
  for (const char* key : {"constraints", "controllers"})
    if (top.has(key) && !doc.at(key).empty()) top.fail(key, std::string(key) + " are not supported yet");
  return prefab;
}

}  // namespace prefab
}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

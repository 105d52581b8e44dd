// Mod-bots: a `.superdex_bot` file holding a `base` bot and the `modifications` that build on it
// (AttachLink: one more link on a named link; AttachBot: a whole bot file on a named link, its
// root joint replaced by the modification's joint). The result is one flat BotPrefab.

#include <filesystem>
#include <nlohmann/json.hpp>
#include <set>

#include "bot_files.h"
#include "superdex/physics/articulation_json.h"
#include "superdex/physics/error.h"
#include "superdex/physics/prefab.h"
#include "superdex/robotics/context.h"

namespace superdex::robotics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace fs = std::filesystem;
using json = nlohmann::json;
using physics::JointDesc;
using physics::JointType;
using physics::real;

namespace {

struct ModContext {
  const std::string& source;  // the mod-bot file
  std::vector<std::string>* warnings;
  [[noreturn]] void fail(const std::string& path, const std::string& what) const { throw Error(source + ": " + path + ": " + what); }
  void warn(const std::string& path, const std::string& what) const {
    if (warnings) warnings->push_back(source + ": " + path + ": " + what);
  }
};

const json& field(const ModContext& c, const json& obj, const char* key, const std::string& path) {
  if (!obj.contains(key) || obj.at(key).is_null()) c.fail(path + "." + key, "required");
  return obj.at(key);
}

std::string string_of(const ModContext& c, const json& obj, const char* key, const std::string& path) {
  const json& v = field(c, obj, key, path);
  if (!v.is_string()) c.fail(path + "." + key, "expected a string");
  return v.get<std::string>();
}

// The index of the link named `name`, or an error naming the modification's field.
int link_named(const ModContext& c, const BotPrefab& bot, const std::string& name, const std::string& path) {
  const auto& links = bot.articulation.links;
  for (size_t i = 0; i < links.size(); ++i)
    if (links[i].name == name) return static_cast<int>(i);
  c.fail(path, "no link named '" + name + "' in the bot built so far (" + std::to_string(links.size()) + " links)");
}

// DOFs of the bot after its root joint, in link order: the length of its default pose.
int pose_size(const BotPrefab& bot) {
  int n = 0;
  for (size_t i = 1; i < bot.articulation.joints.size(); ++i) n += physics::joint_num_dofs(bot.articulation.joints[i].type);
  return n;
}

// The default pose, zeros where the file gave none.
std::vector<real> full_pose(const BotPrefab& bot) {
  std::vector<real> pose = bot.articulation.default_pose;
  if (pose.empty()) pose.assign(static_cast<size_t>(pose_size(bot)), 0);
  return pose;
}

// Component params naming a file stay valid once the component belongs to a bot read elsewhere.
void absolutize_params(std::vector<std::vector<ComponentDecl>>& lists, const std::string& base_dir) {
  for (auto& list : lists)
    for (ComponentDecl& d : list) d.params = params_relative_to(d.params, base_dir);
}

// Adds `link` (with its components) below `parent` through `joint`, keeping names unique.
void attach_one(const ModContext& c, BotPrefab& bot, BotLinkPrefab link, const JointDesc& joint, int parent, const std::string& path) {
  for (const auto& l : bot.articulation.links)
    if (l.name == link.name) c.fail(path, "link name '" + link.name + "' is already used in the bot");
  for (const auto& j : bot.articulation.joints)
    if (!joint.name.empty() && j.name == joint.name) c.fail(path, "joint name '" + joint.name + "' is already used in the bot");
  link.parent_link = parent;
  add_link(bot, link, joint);
}

void apply_attach_link(const ModContext& c, BotPrefab& bot, const json& mod, const std::string& path, std::set<std::string>& sensor_names,
                       std::set<std::string>& actuator_names) {
  const int parent = link_named(c, bot, string_of(c, mod, "parentLinkName", path), path + ".parentLinkName");
  const JointDesc joint = physics::joint_desc_from_json(field(c, mod, "joint", path), c.source, path + ".joint", c.warnings);
  if (joint.type == JointType::Free) c.fail(path + ".joint.type", "an attached link hangs from its parent: Free is not allowed");
  const json& link_json = field(c, mod, "link", path);
  // the link's shape file, relative to the mod-bot file like every path in it
  physics::ArticulationDesc one;
  one.links.push_back(physics::link_desc_from_json(link_json, c.source, path + ".link", c.warnings));
  physics::load_link_shape_files(one, fs::absolute(fs::path(c.source)).parent_path().string(), c.source);
  BotLinkPrefab link;
  static_cast<physics::LinkDesc&>(link) = one.links[0];
  if (link.name.empty()) link.name = mod.contains("name") && mod.at("name").is_string() ? mod.at("name").get<std::string>() : "";
  if (link.name.empty()) c.fail(path + ".link.name", "required: the attached link's name");
  for (const ComponentDecl& d : read_link_components(link_json, "sensors", c.source, path + ".link", sensor_names, c.warnings))
    link.sensors.push_back({d.type, d.name, d.parent_from_sensor, d.params});
  for (const ComponentDecl& d : read_link_components(link_json, "actuators", c.source, path + ".link", actuator_names, c.warnings))
    link.actuators.push_back({d.type, d.name, d.params});
  std::vector<real> pose = full_pose(bot);
  attach_one(c, bot, std::move(link), joint, parent, path);
  pose.insert(pose.end(), static_cast<size_t>(physics::joint_num_dofs(joint.type)), real(0));
  bot.articulation.default_pose = std::move(pose);
}

void apply_attach_bot(const ModContext& c, BotPrefab& bot, const json& mod, const std::string& path, std::vector<std::string>& chain) {
  const int parent = link_named(c, bot, string_of(c, mod, "parentLinkName", path), path + ".parentLinkName");
  const JointDesc joint = physics::joint_desc_from_json(field(c, mod, "joint", path), c.source, path + ".joint", c.warnings);
  if (joint.type == JointType::Free) c.fail(path + ".joint.type", "an attached bot hangs from its parent link: Free is not allowed");
  const std::string file = resolve_bot_reference(string_of(c, mod, "path", path), c.source, path + ".path");
  BotPrefab child = load_bot_file(file, c.warnings, chain);
  absolutize_params(child.sensors, child.base_dir);
  absolutize_params(child.actuators, child.base_dir);
  std::vector<real> pose = full_pose(bot);
  const std::vector<real> child_pose = full_pose(child);
  const int offset = static_cast<int>(bot.articulation.links.size());
  // the child's root hangs from `parent` by the modification's joint; its other links keep their tree
  for (size_t k = 0; k < child.articulation.links.size(); ++k) {
    BotLinkPrefab link = link_prefab(child, static_cast<int>(k));
    const int to = k == 0 ? parent : link.parent_link + offset;
    JointDesc j = k == 0 ? joint : child.articulation.joints[k];
    if (k == 0 && j.name.empty()) j.name = child.articulation.joints[0].name;
    attach_one(c, bot, std::move(link), j, to, path + " (link '" + child.articulation.links[k].name + "' of " + file + ")");
  }
  pose.insert(pose.end(), static_cast<size_t>(physics::joint_num_dofs(joint.type)), real(0));
  pose.insert(pose.end(), child_pose.begin(), child_pose.end());
  bot.articulation.default_pose = std::move(pose);
  auto& a = bot.articulation;
  a.couplings.insert(a.couplings.end(), child.articulation.couplings.begin(), child.articulation.couplings.end());
  a.fixed_tendons.insert(a.fixed_tendons.end(), child.articulation.fixed_tendons.begin(), child.articulation.fixed_tendons.end());
  a.contact_overrides.insert(a.contact_overrides.end(), child.articulation.contact_overrides.begin(), child.articulation.contact_overrides.end());
  // the child's transmissions name its joints by index: now `offset` further on
  for (physics::LinearTransmission t : child.articulation.linear_transmissions) {
    for (int& j : t.joint_indices) j += offset;
    a.linear_transmissions.push_back(std::move(t));
  }
}

}  // namespace

BotPrefab build_mod_bot(const json& doc, const std::string& path, std::vector<std::string>* warnings, std::vector<std::string>& chain) {
  const ModContext c{path, warnings};
  if (!doc.at("base").is_string()) c.fail("base", "expected the path of the bot to build on");
  for (const char* key : {"links", "joints"})
    if (doc.contains(key)) c.fail(key, "a mod-bot (one with a base) takes its links and joints from the base and its modifications");
  BotPrefab bot = load_bot_file(resolve_bot_reference(doc.at("base").get<std::string>(), path, "base"), warnings, chain);
  absolutize_params(bot.sensors, bot.base_dir);
  absolutize_params(bot.actuators, bot.base_dir);
  bot.source = path;
  bot.base_dir = fs::absolute(fs::path(path)).parent_path().string();
  if (doc.contains("name")) {
    if (!doc.at("name").is_string() || doc.at("name").get<std::string>().empty()) c.fail("name", "expected a non-empty string");
    bot.articulation.name = doc.at("name").get<std::string>();
  }
  std::set<std::string> sensor_names, actuator_names;
  for (const auto& list : bot.sensors)
    for (const ComponentDecl& d : list) sensor_names.insert(d.name);
  for (const auto& list : bot.actuators)
    for (const ComponentDecl& d : list) actuator_names.insert(d.name);
  const json mods = doc.contains("modifications") ? doc.at("modifications") : json::array();
  if (!mods.is_array()) c.fail("modifications", "expected an array of modifications");
  for (size_t i = 0; i < mods.size(); ++i) {
    const std::string at = "modifications[" + std::to_string(i) + "]";
    if (!mods[i].is_object() || mods[i].size() != 1)
      c.fail(at, "expected an object with one key naming the modification: AttachLink or AttachBot");
    const std::string kind = mods[i].begin().key();
    const json& mod = mods[i].begin().value();
    const std::string mpath = at + "." + kind;
    if (!mod.is_object()) c.fail(mpath, "expected an object");
    if (mod.contains("enabled")) {
      if (!mod.at("enabled").is_boolean()) c.fail(mpath + ".enabled", "expected true or false");
      if (!mod.at("enabled").get<bool>()) continue;
    }
    if (kind == "AttachLink") {
      for (auto it = mod.begin(); it != mod.end(); ++it)
        if (it.key() != "enabled" && it.key() != "joint" && it.key() != "link" && it.key() != "name" && it.key() != "parentLinkName")
          c.warn(mpath + "." + it.key(), "unknown field, ignored");
      apply_attach_link(c, bot, mod, mpath, sensor_names, actuator_names);
    } else if (kind == "AttachBot") {
      for (auto it = mod.begin(); it != mod.end(); ++it)
        if (it.key() != "enabled" && it.key() != "joint" && it.key() != "path" && it.key() != "name" && it.key() != "parentLinkName")
          c.warn(mpath + "." + it.key(), "unknown field, ignored");
      apply_attach_bot(c, bot, mod, mpath, chain);
    } else {
      c.fail(at, "unknown modification '" + kind + "' (this version builds AttachLink and AttachBot)");
    }
  }
  for (auto it = doc.begin(); it != doc.end(); ++it)
    if (it.key() != "base" && it.key() != "modifications" && it.key() != "name") c.warn(it.key(), "unknown field, ignored");
  // component names stay unique across the parts
  std::set<std::string> seen;
  for (size_t i = 0; i < bot.sensors.size(); ++i)
    for (const ComponentDecl& d : bot.sensors[i])
      if (!seen.insert("s:" + d.name).second) c.fail("modifications", "sensor name '" + d.name + "' appears twice in the built bot");
  for (size_t i = 0; i < bot.actuators.size(); ++i)
    for (const ComponentDecl& d : bot.actuators[i])
      if (!seen.insert("a:" + d.name).second) c.fail("modifications", "actuator name '" + d.name + "' appears twice in the built bot");
  return bot;
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::robotics

// Reading `.superdex_bot` files: the articulation fields (shared with the physics JSON reader),
// the sensors and actuators declared on links, and mesh shapes named by links. Mod-bots (a base
// bot plus modifications) are built in bot_mods.cpp.

#include <algorithm>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "bot_files.h"
#include "superdex/physics/articulation_json.h"
#include "superdex/physics/error.h"
#include "superdex/physics/prefab.h"
#include "superdex/robotics/bot_prefab.h"

namespace superdex::robotics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

[[noreturn]] void fail(const std::string& source, const std::string& path, const std::string& what) {
  throw Error(source + ": " + path + ": " + what);
}

std::string string_field(const json& j, const char* key, const std::string& source, const std::string& path, bool required) {
  if (!j.contains(key) || j.at(key).is_null()) {
    if (required) fail(source, path + "." + key, "required");
    return "";
  }
  if (!j.at(key).is_string()) fail(source, path + "." + key, "expected a string");
  return j.at(key).get<std::string>();
}

// A flat bot file: links and joints.
BotPrefab load_flat_bot(const json& doc, const std::string& path, std::vector<std::string>* warnings) {
  BotPrefab prefab;
  prefab.source = path;
  prefab.base_dir = fs::absolute(fs::path(path)).parent_path().string();
  prefab.articulation = physics::articulation_desc_from_json(doc, path, warnings);
  if (prefab.articulation.name.empty()) fail(path, "name", "required: the bot's name");
  const json& links = doc.at("links");
  std::set<std::string> sensor_names, actuator_names;
  for (size_t i = 0; i < links.size(); ++i) {
    const std::string link_path = "links[" + std::to_string(i) + "]";
    prefab.sensors.push_back(read_link_components(links[i], "sensors", path, link_path, sensor_names, warnings));
    prefab.actuators.push_back(read_link_components(links[i], "actuators", path, link_path, actuator_names, warnings));
  }
  // mesh or .mochi.h5 shapes, relative to the bot file, with each link's shapeScale baked in
  physics::load_link_shape_files(prefab.articulation, prefab.base_dir, path);
  return prefab;
}

}  // namespace

std::vector<ComponentDecl> read_link_components(const json& link, const char* key, const std::string& source,
                                                const std::string& link_path, std::set<std::string>& names,
                                                std::vector<std::string>* warnings) {
  std::vector<ComponentDecl> out;
  if (!link.is_object() || !link.contains(key) || link.at(key).is_null()) return out;
  const json& list = link.at(key);
  const std::string list_path = link_path + "." + key;
  if (!list.is_array()) fail(source, list_path, "expected an array of objects");
  for (size_t k = 0; k < list.size(); ++k) {
    const std::string path = list_path + "[" + std::to_string(k) + "]";
    const json& c = list[k];
    if (!c.is_object()) fail(source, path, "expected an object with type, name and params");
    ComponentDecl d;
    d.type = string_field(c, "type", source, path, true);
    if (d.type.empty()) fail(source, path + ".type", "must not be empty");
    d.name = string_field(c, "name", source, path, true);
    if (d.name.empty()) fail(source, path + ".name", "must not be empty");
    if (!names.insert(d.name).second) fail(source, path + ".name", "duplicate name '" + d.name + "'");
    if (c.contains("params") && !c.at("params").is_null()) {
      // a string as the format says, or (for convenience) an inline object
      if (c.at("params").is_string()) d.params = c.at("params").get<std::string>();
      else if (c.at("params").is_object()) d.params = c.at("params").dump();
      else fail(source, path + ".params", "expected a string (inline JSON, a JSON file path, or empty)");
    }
    if (c.contains("parentFromSensor")) d.parent_from_sensor = physics::transform_from_json(c.at("parentFromSensor"), source, path + ".parentFromSensor");
    for (auto it = c.begin(); it != c.end(); ++it)
      if (warnings && it.key() != "type" && it.key() != "name" && it.key() != "params" && it.key() != "parentFromSensor")
        warnings->push_back(source + ": " + path + "." + it.key() + ": unknown field, ignored");
    out.push_back(std::move(d));
  }
  return out;
}

BotPrefab load_bot_file(const std::string& path, std::vector<std::string>* warnings, std::vector<std::string>& chain) {
  const std::string key = fs::absolute(fs::path(path)).lexically_normal().string();
  if (std::find(chain.begin(), chain.end(), key) != chain.end()) {
    std::string cycle;
    for (const std::string& f : chain) cycle += f + " -> ";
    throw Error(path + ": the bot includes itself (" + cycle + key + ")");
  }
  const json doc = physics::read_json_file(path, "bot");
  chain.push_back(key);
  BotPrefab prefab = doc.is_object() && doc.contains("base") ? build_mod_bot(doc, path, warnings, chain) : load_flat_bot(doc, path, warnings);
  chain.pop_back();
  return prefab;
}

BotPrefab load_bot_prefab(const std::string& path, std::vector<std::string>* warnings) {
  std::vector<std::string> chain;
  return load_bot_file(path, warnings, chain);
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::robotics

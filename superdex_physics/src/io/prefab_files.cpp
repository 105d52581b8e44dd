// Prefab files (prefab.h): resolving the paths they name, reading them shallowly or with what they
// reference (nested prefabs and bot files here, shapes in prefab_shapes.cpp), and writing them.

#include <filesystem>
#include <fstream>

#include "io/prefab_json.h"
#include "io/prefab_shapes.h"
#include "superdex/physics/articulation_json.h"
#include "superdex/physics/error.h"
#include "superdex/physics/file_path.h"
#include "superdex/physics/prefab.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {
namespace prefab {

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

// a prefab nested deeper than this includes itself, directly or not
constexpr int kMaxNesting = 16;

// the document of `text`, or `source`: not valid JSON / a wrong JSON type no check caught
template <class Read>
ScenePrefab read_document(const std::string& source, Read read) {
  try {
    return read();
  } catch (const json::exception& e) {
    throw Error(source + ": unexpected JSON value: " + e.what());
  }
}

void load_nested(ScenePrefab& p, const std::string& root, std::vector<std::string>* warnings, int depth, bool only_missing) {
  const std::string at = error_prefix(p);
  for (size_t i = 0; i < p.actors.articulated.size(); ++i) {
    ArticulatedActorPrefab& a = p.actors.articulated[i];
    if (a.bot_file.empty() || (only_missing && !a.links.empty())) continue;
    read_bot_file(a, get_prefab_full_path(a.bot_file, root, p.source_file), at + "actors.articulated[" + std::to_string(i) + "].bot", warnings);
  }
  for (size_t i = 0; i < p.prefabs.size(); ++i) {
    PrefabReference& ref = p.prefabs[i];
    const std::string where = at + "prefabs[" + std::to_string(i) + "].path";
    if (!only_missing || ref.loaded.empty()) {
      if (depth >= kMaxNesting) throw Error(at + "prefabs: prefabs nest more than 16 deep (a prefab includes itself?)");
      const std::string path = get_prefab_full_path(ref.path, root, p.source_file);
      if (!is_existing_file(path)) throw Error(where + ": prefab file '" + path + "' does not exist");
      ref.loaded = {shallow_load_from_file(path, warnings)};
    }
    load_nested(ref.loaded[0], root, warnings, depth + 1, only_missing);
  }
}

}  // namespace

std::string get_prefab_full_path(const std::string& input_path, const std::string& root_for_relative_path, const std::string& prefab_file_path) {
  const fs::path p(input_path);
  if (p.is_absolute()) return input_path;
  if (input_path.rfind("./", 0) == 0) {
    const fs::path base = prefab_file_path.empty() ? fs::path(root_for_relative_path) : fs::path(prefab_file_path).parent_path();
    return (base / p).lexically_normal().string();
  }
  return (fs::path(root_for_relative_path) / p).lexically_normal().string();
}

ScenePrefab shallow_load_from_file(const std::string& path, std::vector<std::string>* warnings) {
  ScenePrefab p = read_document(path, [&] { return scene_prefab_from_json(read_json_file(path, "prefab"), path, warnings); });
  p.source_file = path;
  return p;
}

ScenePrefab shallow_load_from_json_string(const std::string& text, std::vector<std::string>* warnings) {
  const std::string source = "JSON string";
  return read_document(source, [&] {
    json doc;
    try {
      doc = json::parse(text, nullptr, true, true);
    } catch (const json::parse_error& e) {
      throw Error(source + ": not valid JSON: " + e.what());
    }
    return scene_prefab_from_json(doc, source, warnings);
  });
}

void load_nested_prefabs(ScenePrefab& prefab, const std::string& root_path, std::vector<std::string>* warnings) {
  read_document(error_prefix(prefab), [&] { return load_nested(prefab, root_path, warnings, 0, false), ScenePrefab(); });
}

void ensure_fully_loaded(ScenePrefab& prefab, const std::string& root_path, std::vector<std::string>* warnings) {
  read_document(error_prefix(prefab), [&] { return load_nested(prefab, root_path, warnings, 0, true), ScenePrefab(); });
  load_missing_shapes(prefab, root_path);
}

ScenePrefab load_from_file(const std::string& prefab_path, const std::string& root_path, std::vector<std::string>* warnings) {
  ScenePrefab p = shallow_load_from_file(prefab_path, warnings);
  load_nested_prefabs(p, root_path, warnings);
  load_shapes(p, root_path);
  return p;
}

ScenePrefab load_from_json_string(const std::string& json_text, const std::string& root_path, std::vector<std::string>* warnings) {
  ScenePrefab p = shallow_load_from_json_string(json_text, warnings);
  load_nested_prefabs(p, root_path, warnings);
  load_shapes(p, root_path);
  return p;
}

std::string save_to_json_string(const ScenePrefab& prefab) { return scene_prefab_to_json(prefab).dump(2); }

void save_to_json_file(const ScenePrefab& prefab, const std::string& path) {
  const std::string text = save_to_json_string(prefab);
  const fs::path p(path);
  std::error_code ec;
  if (p.has_parent_path()) fs::create_directories(p.parent_path(), ec);
  std::ofstream out(p);
  if (!out || !(out << text << "\n")) throw Error("save_to_json_file: cannot write '" + path + "'");
}

}  // namespace prefab
}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

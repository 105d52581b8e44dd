// How bot files name other bot files: "//" below the asset root (the folder of the nearest
// `.superdex_root` marker), "@tag/" through a marker's tag table, or relative to the file.

#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>

#include "bot_files.h"
#include "superdex/physics/error.h"
#include "superdex/physics/file_path.h"

namespace superdex::robotics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace fs = std::filesystem;

namespace {

constexpr const char* kRootMarker = ".superdex_root";

// The folder of `file` and its ancestors, nearest first.
std::vector<fs::path> folders_above(const std::string& file) {
  std::vector<fs::path> out;
  for (fs::path d = fs::absolute(fs::path(file)).parent_path();; d = d.parent_path()) {
    out.push_back(d);
    if (d == d.parent_path()) break;
  }
  return out;
}

}  // namespace

std::string resolve_bot_reference(const std::string& reference, const std::string& referencing_file, const std::string& where) {
  auto fail = [&](const std::string& what) -> void { throw Error(referencing_file + ": " + where + ": " + what); };
  if (reference.empty()) fail("expected a bot file path, got an empty string");
  fs::path resolved;
  if (reference.rfind("//", 0) == 0) {
    for (const fs::path& d : folders_above(referencing_file))
      if (is_existing_file(d / kRootMarker)) {
        resolved = d / reference.substr(2);
        break;
      }
    if (resolved.empty())
      fail("'" + reference + "' is relative to the asset root, but no " + kRootMarker + " marker is in '" +
           fs::absolute(fs::path(referencing_file)).parent_path().string() + "' or above");
  } else if (reference[0] == '@') {
    const std::string tag = reference.substr(0, reference.find('/'));
    const std::string rest = tag.size() < reference.size() ? reference.substr(tag.size() + 1) : "";
    for (const fs::path& d : folders_above(referencing_file)) {
      const fs::path marker = d / kRootMarker;
      if (!is_existing_file(marker)) continue;
      // an empty marker only marks the root; tags map to folders relative to the marker's
      std::ifstream in(marker);
      const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
      if (text.find_first_not_of(" \t\r\n") == std::string::npos) continue;
      nlohmann::json table;
      try {
        table = nlohmann::json::parse(text, nullptr, true, true);
      } catch (const nlohmann::json::exception& e) {
        throw Error(marker.string() + ": not valid JSON: " + e.what());
      }
      if (!table.is_object()) throw Error(marker.string() + ": expected a JSON object {\"@tag\": \"folder\"}");
      if (!table.contains(tag)) continue;
      if (!table.at(tag).is_string()) throw Error(marker.string() + ": " + tag + ": expected a folder path string");
      fs::path folder(table.at(tag).get<std::string>());
      if (folder.is_relative()) folder = d / folder;
      resolved = folder / rest;
      break;
    }
    if (resolved.empty()) fail("asset tag " + tag + " is defined by no " + kRootMarker + " marker above the file");
  } else {
    resolved = fs::path(reference);
    if (resolved.is_relative()) resolved = fs::absolute(fs::path(referencing_file)).parent_path() / resolved;
  }
  resolved = resolved.lexically_normal();
  if (!is_existing_file(resolved)) fail("'" + reference + "' resolves to '" + resolved.string() + "', which does not exist");
  return resolved.string();
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::robotics

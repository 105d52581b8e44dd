#pragma once
// Internal to the bot loader: how `.superdex_bot` files name other files, and mod-bots (a `base`
// bot plus `modifications`) built into one flat BotPrefab.

#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include "superdex/robotics/bot_prefab.h"

namespace superdex::robotics {
inline namespace SUPERDEX_REAL_NAMESPACE {

/// The file that `reference` names from the bot file `referencing_file`:
///   "//rest"     rest below the folder of the nearest `.superdex_root` marker above the file;
///   "@tag/rest"  rest below the folder the nearest marker defining "@tag" maps it to (a marker
///                is JSON {"@tag": "folder"}, folders relative to the marker's);
///   absolute     as is;  anything else  relative to the referencing file's folder.
/// Throws superdex::Error naming `where` when it cannot be resolved or names no file.
std::string resolve_bot_reference(const std::string& reference, const std::string& referencing_file, const std::string& where);

/// Reads a bot file, flat or a mod-bot, following `base` and AttachBot paths; `chain` holds the
/// files being read above this one (a file that includes itself is an error).
BotPrefab load_bot_file(const std::string& path, std::vector<std::string>* warnings, std::vector<std::string>& chain);

/// Builds the mod-bot `doc` read from `path` (`base`, `modifications`, optional `name`).
BotPrefab build_mod_bot(const nlohmann::json& doc, const std::string& path, std::vector<std::string>* warnings,
                        std::vector<std::string>& chain);

/// The sensors (key "sensors") or actuators of one link object of a bot file; names must be unique
/// among the bot's components of that kind (`names` collects them).
std::vector<ComponentDecl> read_link_components(const nlohmann::json& link, const char* key, const std::string& source,
                                                const std::string& link_path, std::set<std::string>& names,
                                                std::vector<std::string>* warnings);

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::robotics

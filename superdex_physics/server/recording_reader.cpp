// Reading and checking a recording for replay (recording_reader.h).

#include "recording_reader.h"

#include <fstream>
#include <set>
#include <nlohmann/json.hpp>

#include "superdex/physics/error.h"

namespace superdex::physics::debug {

namespace {

using json = nlohmann::json;

// the newest format version this reader understands
constexpr int kRecordingVersion = 1;

// Checks the fields of one parsed line; `fail` throws with the line's context.
class LineChecker {
 public:
  LineChecker(const std::string& path, std::size_t line_no) : path_(path), line_no_(line_no) {}

  [[noreturn]] void fail(const std::string& field, const std::string& what) const {
    throw Error("debug server: '" + path_ + "': line " + std::to_string(line_no_) + ": " + (field.empty() ? "" : field + ": ") + what);
  }
  static std::string shown(const json& v) {
    std::string s = v.dump(-1, ' ', false, json::error_handler_t::replace);
    return s.size() > 40 ? s.substr(0, 40) + "..." : s;
  }
  const json& required(const json& j, const std::string& type, const char* key) const {
    if (!j.contains(key)) fail(type + "." + key, "required");
    return j.at(key);
  }
  long long integer(const json& j, const std::string& type, const char* key) const {
    const json& v = required(j, type, key);
    if (!v.is_number_integer()) fail(type + "." + key, "expected an integer, got " + shown(v));
    return v.get<long long>();
  }
  void number(const json& j, const std::string& type, const char* key) const {
    const json& v = required(j, type, key);
    if (!v.is_number()) fail(type + "." + key, "expected a number, got " + shown(v));
  }
  void numbers(const json& v, const std::string& field, std::size_t count) const {
    if (!v.is_array() || (count && v.size() != count))
      fail(field, (count ? "expected " + std::to_string(count) + " numbers" : std::string("expected an array of numbers")) + ", got " + shown(v));
    for (const json& x : v)
      if (!x.is_number()) fail(field, "expected numbers, got " + shown(x));
  }
  void optional_kind(const json& j, const std::string& type, const char* key, json::value_t kind, const char* what) const {
    if (j.contains(key) && j.at(key).type() != kind) fail(type + "." + key, std::string("expected ") + what + ", got " + shown(j.at(key)));
  }

 private:
  const std::string& path_;
  std::size_t line_no_;
};

}  // namespace

RecordingLines read_recording(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error("debug server: cannot read the recording '" + path + "'");
  RecordingLines out;
  std::set<long long> scenes;
  std::size_t line_no = 0;
  for (std::string line; std::getline(in, line);) {
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    const LineChecker check(path, line_no);
    const json j = json::parse(line, nullptr, /*allow_exceptions=*/false);
    const bool first = out.lines.empty();
    if (first && (!j.is_object() || j.value("type", json()) != "header" || j.value("format", json()) != "superdex-recording"))
      check.fail("", "not a SuperDex recording (its first line is not a recording header {\"type\": \"header\", \"format\": \"superdex-recording\", ...})");
    if (j.is_discarded()) check.fail("", "not valid JSON");
    if (!j.is_object()) check.fail("", "expected a JSON object, got " + LineChecker::shown(j));
    if (!j.contains("type")) check.fail("type", "required");
    if (!j.at("type").is_string()) check.fail("type", "expected a string, got " + LineChecker::shown(j.at("type")));
    const std::string type = j.at("type").get<std::string>();
    if (type == "header") {
      if (!first) check.fail("", "a second header");
      const long long version = check.integer(j, type, "version");
      if (version < 1 || version > kRecordingVersion)
        check.fail("header.version", "recording format version " + std::to_string(version) + " is not supported (this reader reads version " +
                                         std::to_string(kRecordingVersion) + ")");
    } else if (type == "scene") {
      scenes.insert(check.integer(j, type, "scene"));
    } else if (type == "actor" || type == "destroy" || type == "signals" || type == "frame") {
      const long long scene = check.integer(j, type, "scene");
      if (!scenes.count(scene)) check.fail(type + ".scene", "scene " + std::to_string(scene) + " was not described by an earlier scene line");
      if (type == "actor" || type == "destroy") check.integer(j, type, "handle");
      if (type == "frame") {
        check.number(j, type, "t");
        check.optional_kind(j, type, "links", json::value_t::object, "an object {link handle: pose}");
        if (j.contains("links"))
          for (const auto& [handle, pose] : j.at("links").items()) check.numbers(pose, "frame.links." + handle, 7);
        check.optional_kind(j, type, "soft", json::value_t::object, "an object {actor handle: node positions}");
        if (j.contains("soft"))
          for (const auto& [handle, x] : j.at("soft").items()) check.numbers(x, "frame.soft." + handle, 0);
        check.optional_kind(j, type, "contacts", json::value_t::array, "an array");
        check.optional_kind(j, type, "joints", json::value_t::object, "an object");
        check.optional_kind(j, type, "signals", json::value_t::object, "an object");
        ++out.frames;
      }
    }
    out.lines.push_back(std::move(line));
  }
  if (out.lines.empty()) throw Error("debug server: the recording '" + path + "' is empty");
  return out;
}

}  // namespace superdex::physics::debug

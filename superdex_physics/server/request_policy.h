#pragma once
// Which requests the debug server answers (docs/debugger_protocol.md, "URLs"): the session token
// first in every path, a local Host, no foreign Origin, and files only inside the UI's folder.

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

namespace superdex::physics::debug {

/// The outcome of checking a request line and its headers.
struct RequestVerdict {
  int status = 200;   ///< 200: go on; 403: refused; 404: no such path; 301: add the trailing slash
  std::string rest;   ///< the decoded path after "/TOKEN" ("" or starting with '/')
};

/// Checks `target` (the request target, query included), `host` and `origin` (empty when the
/// header is absent) of a request to the server listening on `port` with session `token`.
RequestVerdict check_request(std::string_view token, int port, std::string_view target, std::string_view host,
                             std::string_view origin);

/// Decodes %XX escapes; nullopt for a malformed escape or a NUL byte.
std::optional<std::string> percent_decode(std::string_view s);

/// The file under `root` that the path `rest` (after the token) names: "" and "/" name
/// index.html. nullopt when a segment is "..", the file is outside `root` (symbolic links
/// included) or is not a regular file.
std::optional<std::filesystem::path> resolve_static_file(const std::filesystem::path& root, std::string_view rest);

/// The Content-Type for a file name's extension.
std::string_view mime_type(const std::filesystem::path& file);

/// A random token of 32 hexadecimal characters (from std::random_device).
std::string random_token();

}  // namespace superdex::physics::debug

// Request checks of the debug server (request_policy.h).

#include "request_policy.h"

#include <algorithm>
#include <random>

namespace superdex::physics::debug {

namespace {

int hex_value(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

// Compares without stopping at the first difference (the token is a secret).
bool equal_secret(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  unsigned char diff = 0;
  for (size_t i = 0; i < a.size(); ++i) diff |= static_cast<unsigned char>(a[i] ^ b[i]);
  return diff == 0;
}

// "<host>:<port>" with host 127.0.0.1 or localhost, after `scheme` ("" or "http://")
bool is_local_authority(std::string_view value, std::string_view scheme, int port) {
  if (value.substr(0, scheme.size()) != scheme) return false;
  value.remove_prefix(scheme.size());
  const std::string port_text = std::to_string(port);
  for (std::string_view host : {std::string_view("127.0.0.1"), std::string_view("localhost")})
    if (value.size() == host.size() + 1 + port_text.size() && value.substr(0, host.size()) == host &&
        value[host.size()] == ':' && value.substr(host.size() + 1) == port_text)
      return true;
  return false;
}

}  // namespace

std::optional<std::string> percent_decode(std::string_view s) {
  std::string out;
  out.reserve(s.size());
  for (size_t i = 0; i < s.size(); ++i) {
    char c = s[i];
    if (c == '%') {
      if (i + 2 >= s.size()) return std::nullopt;
      const int hi = hex_value(s[i + 1]), lo = hex_value(s[i + 2]);
      if (hi < 0 || lo < 0) return std::nullopt;
      c = static_cast<char>(hi * 16 + lo);
      i += 2;
    }
    if (c == '\0') return std::nullopt;
    out.push_back(c);
  }
  return out;
}

RequestVerdict check_request(std::string_view token, int port, std::string_view target, std::string_view host,
                             std::string_view origin) {
  // a local Host defeats DNS rebinding; a foreign Origin is another site's page
  if (!is_local_authority(host, "", port)) return {403, {}};
  if (!origin.empty() && !is_local_authority(origin, "http://", port)) return {403, {}};
  const std::string_view path = target.substr(0, target.find_first_of("?#"));
  if (path.size() < token.size() + 1 || path[0] != '/' || !equal_secret(path.substr(1, token.size()), token)) return {403, {}};
  const std::string_view after = path.substr(1 + token.size());
  if (!after.empty() && after[0] != '/') return {403, {}};
  if (after.empty()) return {301, {}};
  auto decoded = percent_decode(after);
  if (!decoded) return {404, {}};
  return {200, *decoded};
}

std::optional<std::filesystem::path> resolve_static_file(const std::filesystem::path& root, std::string_view rest) {
  namespace fs = std::filesystem;
  std::string relative(rest);
  while (!relative.empty() && relative.front() == '/') relative.erase(relative.begin());
  if (relative.empty() || relative.back() == '/') relative += "index.html";
  // no parent segments, no backslashes (another platform's separator)
  if (relative.find('\\') != std::string::npos) return std::nullopt;
  for (const auto& segment : fs::path(relative))
    if (segment == "..") return std::nullopt;
  std::error_code ec;
  const fs::path base = fs::canonical(root, ec);
  if (ec) return std::nullopt;
  const fs::path file = fs::canonical(base / relative, ec);
  if (ec || !fs::is_regular_file(file, ec)) return std::nullopt;
  // the resolved file (after symbolic links) must still be inside the UI's folder
  const auto [root_end, unused] = std::mismatch(base.begin(), base.end(), file.begin(), file.end());
  if (root_end != base.end()) return std::nullopt;
  return file;
}

std::string_view mime_type(const std::filesystem::path& file) {
  const std::string ext = file.extension().string();
  if (ext == ".html") return "text/html; charset=utf-8";
  if (ext == ".js" || ext == ".mjs") return "text/javascript; charset=utf-8";
  if (ext == ".css") return "text/css; charset=utf-8";
  if (ext == ".json" || ext == ".map") return "application/json";
  if (ext == ".svg") return "image/svg+xml";
  if (ext == ".png") return "image/png";
  if (ext == ".ico") return "image/x-icon";
  if (ext == ".woff2") return "font/woff2";
  if (ext == ".wasm") return "application/wasm";
  return "application/octet-stream";
}

std::string random_token() {
  std::random_device device;
  static constexpr char kHex[] = "0123456789abcdef";
  std::string token;
  for (int i = 0; i < 32; ++i) token.push_back(kHex[device() % 16]);
  return token;
}

}  // namespace superdex::physics::debug

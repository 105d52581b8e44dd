// Shared helpers of the mesh file readers (see mesh_io_detail.h).

#include "io/mesh_io_detail.h"

#include <charconv>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {
namespace mesh_io {

void fail(const std::string& path, long line, const std::string& what) {
  if (line > 0) throw Error(path + ":" + std::to_string(line) + ": " + what);
  throw Error(path + ": " + what);
}

std::string read_bytes(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) fail(path, 0, "file not found");
  if (std::filesystem::is_directory(path, ec)) fail(path, 0, "is a directory, not a mesh file");
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, 0, std::string("cannot open the file: ") + std::strerror(errno));
  std::ostringstream buffer;
  buffer << in.rdbuf();
  if (in.bad()) fail(path, 0, "cannot read the file");
  return std::move(buffer).str();
}

std::vector<std::string_view> tokens(std::string_view line) {
  std::vector<std::string_view> out;
  size_t i = 0;
  auto space = [](char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; };
  while (i < line.size()) {
    while (i < line.size() && space(line[i])) ++i;
    const size_t start = i;
    while (i < line.size() && !space(line[i])) ++i;
    if (i > start) out.push_back(line.substr(start, i - start));
  }
  return out;
}

bool parse_number(std::string_view token, double& out) {
  if (!token.empty() && token[0] == '+') token.remove_prefix(1);
  if (token.empty()) return false;
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), out);
  return ec == std::errc() && end == token.data() + token.size();
}

bool parse_integer(std::string_view token, long long& out) {
  if (!token.empty() && token[0] == '+') token.remove_prefix(1);
  if (token.empty()) return false;
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), out);
  return ec == std::errc() && end == token.data() + token.size();
}

size_t VertexWelder::Hash::operator()(const std::array<double, 3>& k) const {
  size_t h = 1469598103934665603ull;
  for (double x : k) {
    if (x == 0) x = 0;  // -0 and +0 weld together
    std::uint64_t bits;
    std::memcpy(&bits, &x, sizeof bits);
    h = (h ^ bits) * 1099511628211ull;
    h ^= h >> 29;
  }
  return h;
}

int VertexWelder::add(const Eigen::Vector3d& p) {
  const std::array<double, 3> key{p.x() == 0 ? 0.0 : p.x(), p.y() == 0 ? 0.0 : p.y(), p.z() == 0 ? 0.0 : p.z()};
  const auto [it, inserted] = index_.try_emplace(key, static_cast<int>(vertices_.size()));
  if (inserted) vertices_.push_back(p.cast<real>());
  return it->second;
}

void add_fan(TriangleMesh& mesh, const std::vector<int>& polygon) {
  for (size_t i = 1; i + 1 < polygon.size(); ++i) mesh.triangles.push_back({polygon[0], polygon[i], polygon[i + 1]});
}

std::string quote(std::string_view token) {
  std::string s = "'";
  if (token.size() > 40) {
    s += token.substr(0, 37);
    s += "...";
  } else {
    s += token;
  }
  return s += "'";
}

}  // namespace mesh_io
}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

#pragma once
// Pieces shared by the mesh file readers: error messages with file and line, strict number
// parsing, whitespace tokenising, vertex welding and polygon fan triangulation.

#include <Eigen/Core>

#include <array>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "superdex/physics/error.h"
#include "superdex/physics/shape.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {
namespace mesh_io {

// Throws "<path>:<line>: <what>", or "<path>: <what>" when line <= 0.
[[noreturn]] void fail(const std::string& path, long line, const std::string& what);

// The whole file as bytes; throws "<path>: file not found" or "cannot read".
std::string read_bytes(const std::string& path);

// Splits on spaces, tabs and carriage returns.
std::vector<std::string_view> tokens(std::string_view line);

// Parses the whole token as a number (a leading '+' is allowed); false when malformed.
// "nan" and "inf" parse: callers check finiteness to name that defect separately.
bool parse_number(std::string_view token, double& out);
// Parses the whole token as an integer; false when malformed.
bool parse_integer(std::string_view token, long long& out);

// Calls f(line_number, line) for every line (1-based), without the line terminator.
template <class F>
void for_each_line(std::string_view text, F&& f) {
  long number = 0;
  size_t start = 0;
  while (start < text.size()) {
    size_t end = text.find('\n', start);
    if (end == std::string_view::npos) end = text.size();
    f(++number, text.substr(start, end - start));
    start = end + 1;
  }
}

// Merges vertices with identical coordinates (STL lists each facet's corners separately).
class VertexWelder {
 public:
  int add(const Eigen::Vector3d& p);
  std::vector<Vec3> take() { return std::move(vertices_); }

 private:
  struct Hash {
    size_t operator()(const std::array<double, 3>& k) const;
  };
  std::unordered_map<std::array<double, 3>, int, Hash> index_;
  std::vector<Vec3> vertices_;
};

// Appends polygon (v0, v1, ..., vn) as triangles (v0, vi, vi+1).
void add_fan(TriangleMesh& mesh, const std::vector<int>& polygon);

// "'x' (12 characters)" style rendering of a bad token, cut to a readable length.
std::string quote(std::string_view token);

}  // namespace mesh_io
}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

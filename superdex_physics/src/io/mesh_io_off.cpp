// The Object File Format (OFF) reader: a header, vertex and face counts, then the vertices and the
// polygons (0-based), fan-triangulated.

#include <cmath>
#include <limits>

#include "io/mesh_io_detail.h"
#include "superdex/physics/mesh_io.h"
#include "superdex/physics/mesh_validation.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

using mesh_io::fail;

namespace {

// The file's tokens with their line numbers, comments removed.
struct Token {
  long line;
  std::string_view text;
};

std::vector<Token> off_tokens(const std::string& text) {
  std::vector<Token> out;
  mesh_io::for_each_line(text, [&](long line_no, std::string_view line) {
    if (const size_t hash = line.find('#'); hash != std::string_view::npos) line = line.substr(0, hash);
    for (std::string_view t : mesh_io::tokens(line)) out.push_back({line_no, t});
  });
  return out;
}

}  // namespace

TriangleMesh read_off_file(const std::string& path) { return read_off_bytes(mesh_io::read_bytes(path), path); }

TriangleMesh read_off_bytes(const std::string& bytes, const std::string& path) {
  const std::vector<Token> tok = off_tokens(bytes);
  size_t next = 0;
  // "OFF" (also "COFF", "NOFF", ... whose extra per-vertex values are skipped by the line rule below)
  if (next < tok.size() && tok[next].text.size() >= 3 && tok[next].text.substr(tok[next].text.size() - 3) == "OFF") ++next;
  auto integer = [&](const char* what) {
    if (next >= tok.size()) fail(path, tok.empty() ? 0 : tok.back().line, std::string("missing ") + what);
    long long v;
    if (!mesh_io::parse_integer(tok[next].text, v) || v < 0)
      fail(path, tok[next].line, std::string("malformed ") + what + " " + mesh_io::quote(tok[next].text));
    return tok[next++];
  };
  auto count = [&](const char* what) {
    const Token t = integer(what);
    long long v;
    mesh_io::parse_integer(t.text, v);
    if (v > std::numeric_limits<int>::max()) fail(path, t.line, std::string(what) + " too large: " + std::string(t.text));
    return static_cast<int>(v);
  };
  const int num_vertices = count("vertex count");
  const int num_faces = count("face count");
  (void)count("edge count");
  // a count the file cannot hold is a corrupt header: refuse before allocating
  if (static_cast<size_t>(num_vertices) * 3 > tok.size() || static_cast<size_t>(num_faces) > tok.size())
    fail(path, 0, "the header declares " + std::to_string(num_vertices) + " vertices and " + std::to_string(num_faces) +
                      " faces, more than the file holds");

  TriangleMesh mesh;
  mesh.vertices.reserve(static_cast<size_t>(num_vertices));
  for (int v = 0; v < num_vertices; ++v) {
    if (next + 3 > tok.size()) fail(path, tok.back().line, "vertex " + std::to_string(v) + ": expected 3 coordinates, the file ends");
    Eigen::Vector3d p;
    const long line = tok[next].line;
    for (int k = 0; k < 3; ++k, ++next) {
      if (!mesh_io::parse_number(tok[next].text, p[k]))
        fail(path, tok[next].line, "malformed number " + mesh_io::quote(tok[next].text) + " in vertex " + std::to_string(v));
      if (!std::isfinite(p[k])) fail(path, tok[next].line, "vertex " + std::to_string(v) + " has a non-finite coordinate");
    }
    // anything else on the vertex's line (normals, colours) is skipped
    while (next < tok.size() && tok[next].line == line) ++next;
    mesh.vertices.push_back(p.cast<real>());
  }
  std::vector<int> polygon;
  for (int f = 0; f < num_faces; ++f) {
    const Token n_tok = integer("face size");
    long long n;
    mesh_io::parse_integer(n_tok.text, n);
    if (n < 3) fail(path, n_tok.line, "face " + std::to_string(f) + " has " + std::to_string(n) + " vertices (at least 3 needed)");
    polygon.clear();
    for (long long k = 0; k < n; ++k) {
      if (next >= tok.size() || tok[next].line != n_tok.line)
        fail(path, n_tok.line, "face " + std::to_string(f) + ": expected " + std::to_string(n) + " vertex indices");
      long long index;
      if (!mesh_io::parse_integer(tok[next].text, index)) fail(path, tok[next].line, "malformed face index " + mesh_io::quote(tok[next].text));
      if (index < 0 || index >= num_vertices)
        fail(path, tok[next].line, "face index " + std::to_string(index) + " out of range: the file has " + std::to_string(num_vertices) +
                                       " vertices");
      polygon.push_back(static_cast<int>(index));
      ++next;
    }
    while (next < tok.size() && tok[next].line == n_tok.line) ++next;  // face colour
    mesh_io::add_fan(mesh, polygon);
  }
  // exporters leave slivers: they are dropped with a warning, other defects are errors
  remove_degenerate_triangles(mesh, path);
  check_triangle_mesh(mesh, path);
  return mesh;
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

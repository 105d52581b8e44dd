// The STL reader: binary (80-byte header, uint32 triangle count, 50-byte little-endian records)
// or ASCII (solid / facet / outer loop / vertex x y z / endloop / endfacet / endsolid).
// Facets list their own corners, so identical positions are welded into shared vertices.

#include <cmath>
#include <cstdint>
#include <cstring>

#include "io/mesh_io_detail.h"
#include "superdex/physics/mesh_io.h"
#include "superdex/physics/mesh_validation.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

using mesh_io::fail;

namespace {

constexpr size_t kHeaderBytes = 84;  // 80-byte header + uint32 count
constexpr size_t kRecordBytes = 50;  // normal, 3 corners (12 floats) + uint16 attribute

float read_f32_le(const char* p) {
  std::uint32_t bits = static_cast<std::uint8_t>(p[0]) | (static_cast<std::uint32_t>(static_cast<std::uint8_t>(p[1])) << 8) |
                       (static_cast<std::uint32_t>(static_cast<std::uint8_t>(p[2])) << 16) |
                       (static_cast<std::uint32_t>(static_cast<std::uint8_t>(p[3])) << 24);
  float f;
  std::memcpy(&f, &bits, sizeof f);
  return f;
}

std::uint32_t read_u32_le(const char* p) {
  return static_cast<std::uint8_t>(p[0]) | (static_cast<std::uint32_t>(static_cast<std::uint8_t>(p[1])) << 8) |
         (static_cast<std::uint32_t>(static_cast<std::uint8_t>(p[2])) << 16) |
         (static_cast<std::uint32_t>(static_cast<std::uint8_t>(p[3])) << 24);
}

TriangleMesh read_binary(const std::string& path, const std::string& bytes, std::uint32_t count) {
  mesh_io::VertexWelder welder;
  TriangleMesh mesh;
  mesh.triangles.reserve(count);
  for (std::uint32_t t = 0; t < count; ++t) {
    const char* record = bytes.data() + kHeaderBytes + kRecordBytes * t + 12;  // skip the normal
    std::array<int, 3> tri;
    for (int c = 0; c < 3; ++c) {
      Eigen::Vector3d p;
      for (int k = 0; k < 3; ++k) p[k] = read_f32_le(record + 12 * c + 4 * k);
      if (!p.allFinite()) fail(path, 0, "triangle " + std::to_string(t) + " has a non-finite coordinate (NaN or infinity)");
      tri[c] = welder.add(p);
    }
    mesh.triangles.push_back(tri);
  }
  mesh.vertices = welder.take();
  return mesh;
}

TriangleMesh read_ascii(const std::string& path, const std::string& text) {
  mesh_io::VertexWelder welder;
  TriangleMesh mesh;
  std::vector<int> loop;
  long loop_line = 0;
  bool in_loop = false;
  mesh_io::for_each_line(text, [&](long line_no, std::string_view line) {
    const auto tok = mesh_io::tokens(line);
    if (tok.empty()) return;
    if (tok[0] == "outer") {
      in_loop = true;
      loop.clear();
      loop_line = line_no;
    } else if (tok[0] == "vertex") {
      if (!in_loop) fail(path, line_no, "'vertex' outside an 'outer loop'");
      if (tok.size() != 4) fail(path, line_no, "a vertex needs 3 coordinates, got " + std::to_string(tok.size() - 1));
      Eigen::Vector3d p;
      for (int k = 0; k < 3; ++k) {
        if (!mesh_io::parse_number(tok[1 + k], p[k])) fail(path, line_no, "malformed number " + mesh_io::quote(tok[1 + k]) + " in vertex");
        if (!std::isfinite(p[k])) fail(path, line_no, "non-finite coordinate " + mesh_io::quote(tok[1 + k]) + " in vertex");
      }
      loop.push_back(welder.add(p));
    } else if (tok[0] == "endloop") {
      if (loop.size() < 3) fail(path, loop_line, "a facet needs at least 3 vertices, got " + std::to_string(loop.size()));
      mesh_io::add_fan(mesh, loop);
      in_loop = false;
    } else if (tok[0] == "facet") {
      // the normal is recomputed from the corners: only check that it parses
      for (size_t k = 2; k < tok.size(); ++k) {
        double x;
        if (!mesh_io::parse_number(tok[k], x)) fail(path, line_no, "malformed number " + mesh_io::quote(tok[k]) + " in facet normal");
      }
    }
    // solid, endfacet, endsolid: structure only
  });
  if (in_loop) fail(path, loop_line, "'outer loop' without 'endloop'");
  mesh.vertices = welder.take();
  return mesh;
}

}  // namespace

TriangleMesh read_stl_file(const std::string& path) { return read_stl_bytes(mesh_io::read_bytes(path), path); }

TriangleMesh read_stl_bytes(const std::string& bytes, const std::string& path) {
  TriangleMesh mesh;
  const bool sized_as_binary = bytes.size() >= kHeaderBytes &&
                               kHeaderBytes + kRecordBytes * static_cast<std::uint64_t>(read_u32_le(bytes.data() + 80)) == bytes.size();
  const size_t first = bytes.find_first_not_of(" \t\r\n");
  const bool starts_solid = first != std::string::npos && bytes.compare(first, 5, "solid") == 0;
  if (sized_as_binary) {
    mesh = read_binary(path, bytes, read_u32_le(bytes.data() + 80));
  } else if (starts_solid) {
    mesh = read_ascii(path, bytes);
  } else if (bytes.size() < kHeaderBytes) {
    fail(path, 0, "not an STL file: " + std::to_string(bytes.size()) + " bytes is too short for binary STL and there is no 'solid' header");
  } else {
    const std::uint64_t count = read_u32_le(bytes.data() + 80);
    fail(path, 0, "not a valid STL file: no 'solid' header, and the binary header announces " + std::to_string(count) + " triangles (" +
                      std::to_string(kHeaderBytes + kRecordBytes * count) + " bytes) but the file has " + std::to_string(bytes.size()) + " bytes");
  }
  // exporters leave slivers: they are dropped with a warning, other defects are errors
  remove_degenerate_triangles(mesh, path);
  check_triangle_mesh(mesh, path);
  return mesh;
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

// Mesh file dispatch by extension, and the Wavefront OBJ reader.

#include "superdex/physics/mesh_io.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>

#include "io/file_extension.h"
#include "io/mesh_io_detail.h"
#include "superdex/physics/mesh_validation.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

using mesh_io::fail;

TriangleMesh read_mesh_file(const std::string& path) {
  const std::string ext = lower_extension(path);
  if (ext == ".obj") return read_obj_file(path);
  if (ext == ".stl") return read_stl_file(path);
  if (ext == ".ply") return read_ply_file(path);
  if (ext == ".off") return read_off_file(path);
  if (ext == ".dae" || ext == ".gltf" || ext == ".glb") return read_assimp_file(path);
  fail(path, 0, "unknown mesh file extension '" + ext + "' (expected .obj, .stl, .ply, .off, .dae, .gltf or .glb)");
}

bool is_surface_mesh_file(const std::string& path) {
  const std::string ext = lower_extension(path);
  return ext == ".obj" || ext == ".stl" || ext == ".ply" || ext == ".dae" || ext == ".gltf" || ext == ".glb";
}

TriangleMesh read_obj_file(const std::string& path) { return read_obj_bytes(mesh_io::read_bytes(path), path); }

TriangleMesh read_obj_bytes(const std::string& text, const std::string& path) {
  TriangleMesh mesh;
  // 1-based positive indices may refer to vertices defined later: checked once all are read
  struct PendingFace {
    long line;
    std::vector<long long> indices;
  };
  std::vector<PendingFace> faces;
  mesh_io::for_each_line(text, [&](long line_no, std::string_view line) {
    if (const size_t hash = line.find('#'); hash != std::string_view::npos) line = line.substr(0, hash);
    const auto tok = mesh_io::tokens(line);
    if (tok.empty()) return;
    if (tok[0] == "v") {
      if (tok.size() < 4) fail(path, line_no, "a vertex needs 3 coordinates, got " + std::to_string(tok.size() - 1));
      Eigen::Vector3d p;
      for (int k = 0; k < 3; ++k) {
        if (!mesh_io::parse_number(tok[1 + k], p[k])) fail(path, line_no, "malformed number " + mesh_io::quote(tok[1 + k]) + " in vertex");
        if (!std::isfinite(p[k]))
          fail(path, line_no, "vertex " + std::to_string(mesh.vertices.size() + 1) + " has a non-finite coordinate " + mesh_io::quote(tok[1 + k]));
      }
      mesh.vertices.push_back(p.cast<real>());
    } else if (tok[0] == "f") {
      if (tok.size() < 4) fail(path, line_no, "a face needs at least 3 vertices, got " + std::to_string(tok.size() - 1));
      PendingFace face{line_no, {}};
      for (size_t k = 1; k < tok.size(); ++k) {
        // "v", "v/vt", "v//vn" or "v/vt/vn": only the vertex index matters
        const std::string_view ref = tok[k].substr(0, tok[k].find('/'));
        long long index;
        if (!mesh_io::parse_integer(ref, index)) fail(path, line_no, "malformed face index " + mesh_io::quote(tok[k]));
        if (index == 0) fail(path, line_no, "face index 0 is invalid (OBJ indices start at 1)");
        if (index < 0) {
          const long long resolved = static_cast<long long>(mesh.vertices.size()) + index;
          if (resolved < 0)
            fail(path, line_no, "face index " + std::to_string(index) + " out of range: only " + std::to_string(mesh.vertices.size()) +
                                    " vertices precede it");
          index = resolved;
        } else {
          index -= 1;
        }
        face.indices.push_back(index);
      }
      faces.push_back(std::move(face));
    }
    // vt, vn, o, g, s, usemtl, mtllib, l, p and anything else: not geometry we need
  });
  const long long n = static_cast<long long>(mesh.vertices.size());
  for (const PendingFace& face : faces) {
    std::vector<int> polygon;
    for (long long index : face.indices) {
      if (index >= n)
        fail(path, face.line, "face index " + std::to_string(index + 1) + " out of range: the file has " + std::to_string(n) + " vertices");
      polygon.push_back(static_cast<int>(index));
    }
    mesh_io::add_fan(mesh, polygon);
  }
  // exporters leave slivers: they are dropped with a warning, other defects are errors
  remove_degenerate_triangles(mesh, path);
  check_triangle_mesh(mesh, path);
  return mesh;
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

// Scene formats read through Assimp: COLLADA (.dae), glTF (.gltf, .glb). Every mesh of the file's
// node tree is placed by its node's accumulated transform (a COLLADA file's unit and up axis are
// in the root's), triangles only (points and lines are skipped).

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <filesystem>
#include <string>

#include "io/file_extension.h"
#include "io/mesh_io_detail.h"
#include "superdex/physics/mesh_io.h"
#include "superdex/physics/mesh_validation.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace {

void add_node(const aiScene& scene, const aiNode& node, const aiMatrix4x4& parent, TriangleMesh& mesh) {
  const aiMatrix4x4 X = parent * node.mTransformation;
  for (unsigned k = 0; k < node.mNumMeshes; ++k) {
    const aiMesh& m = *scene.mMeshes[node.mMeshes[k]];
    const int base = static_cast<int>(mesh.vertices.size());
    for (unsigned v = 0; v < m.mNumVertices; ++v) {
      const aiVector3D p = X * m.mVertices[v];
      mesh.vertices.push_back(Vec3(real(p.x), real(p.y), real(p.z)));
    }
    for (unsigned f = 0; f < m.mNumFaces; ++f) {
      const aiFace& face = m.mFaces[f];
      if (face.mNumIndices == 3)
        mesh.triangles.push_back({base + static_cast<int>(face.mIndices[0]), base + static_cast<int>(face.mIndices[1]),
                                  base + static_cast<int>(face.mIndices[2])});
    }
  }
  for (unsigned c = 0; c < node.mNumChildren; ++c) add_node(scene, *node.mChildren[c], X, mesh);
}

// A COLLADA file's count attributes (of arrays, accessors and primitives) are sizes Assimp
// allocates before it reads what they count: each counted value takes at least a byte of the
// file, so a count beyond the file's size is an error here, not an allocation of gigabytes there.
void check_collada_counts(const std::string& path) {
  const std::string text = mesh_io::read_bytes(path);
  auto skip_space = [&](size_t k) {
    while (k < text.size() && (text[k] == ' ' || text[k] == '\t' || text[k] == '\n' || text[k] == '\r')) ++k;
    return k;
  };
  for (size_t at = text.find("count"); at != std::string::npos; at = text.find("count", at + 5)) {
    size_t k = skip_space(at + 5);
    if (k >= text.size() || text[k] != '=') continue;
    k = skip_space(k + 1);
    if (k >= text.size() || (text[k] != '"' && text[k] != '\'')) continue;
    ++k;
    // the value's digits, stopped once it exceeds the file size (no overflow)
    unsigned long long value = 0;
    bool too_large = false;
    for (; k < text.size() && text[k] >= '0' && text[k] <= '9'; ++k) {
      value = 10 * value + static_cast<unsigned long long>(text[k] - '0');
      if (value > text.size()) {
        too_large = true;
        break;
      }
    }
    if (!too_large) continue;
    const long line = 1 + static_cast<long>(std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(at), '\n'));
    mesh_io::fail(path, line, "a count attribute exceeds what a file of " + std::to_string(text.size()) + " bytes can hold");
  }
}

}  // namespace

TriangleMesh read_assimp_file(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) mesh_io::fail(path, 0, "file not found");
  if (lower_extension(path) == ".dae") check_collada_counts(path);
  Assimp::Importer importer;
  // only positions are needed: normals, colours, texture coordinates and materials are dropped
  importer.SetPropertyInteger(AI_CONFIG_PP_RVC_FLAGS, aiComponent_NORMALS | aiComponent_TANGENTS_AND_BITANGENTS | aiComponent_COLORS |
                                                          aiComponent_TEXCOORDS | aiComponent_BONEWEIGHTS | aiComponent_ANIMATIONS |
                                                          aiComponent_TEXTURES | aiComponent_LIGHTS | aiComponent_CAMERAS |
                                                          aiComponent_MATERIALS);
  // COLLADA's up axis stays as authored: robot meshes are modelled in their link's frame (z up for
  // ROS), and URDF tools keep them so; the unit still scales
  importer.SetPropertyBool(AI_CONFIG_IMPORT_COLLADA_IGNORE_UP_DIRECTION, true);
  const aiScene* scene = importer.ReadFile(path, aiProcess_RemoveComponent | aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                                                     aiProcess_SortByPType);
  if (!scene || !scene->mRootNode) mesh_io::fail(path, 0, std::string("cannot read: ") + importer.GetErrorString());
  // a file without meshes comes back flagged incomplete, with a placeholder of Assimp's own
  if (scene->mNumMeshes == 0 || (scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE)) mesh_io::fail(path, 0, "no triangles in the file");
  TriangleMesh mesh;
  add_node(*scene, *scene->mRootNode, aiMatrix4x4(), mesh);
  for (const Vec3& v : mesh.vertices)
    if (!v.allFinite()) mesh_io::fail(path, 0, "a vertex has a non-finite coordinate");
  if (mesh.triangles.empty()) mesh_io::fail(path, 0, "no triangles in the file");
  remove_degenerate_triangles(mesh, path);
  check_triangle_mesh(mesh, path);
  return mesh;
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

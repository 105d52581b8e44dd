// Mesh shapes from triangle arrays or shape files: checks, orientation, distance grid, baking.

#include "superdex/physics/mesh_shape.h"

#include <filesystem>
#include <sstream>

#include "io/file_extension.h"
#include "shape/convex_faces.h"
#include "superdex/physics/convex_hull.h"
#include "superdex/physics/error.h"
#include "superdex/physics/mesh_io.h"
#include "superdex/physics/mesh_validation.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

bool ShapeBake::is_identity() const {
  return scale == Vec3::Ones() && translation.isZero() && rotation.angularDistance(Quat::Identity()) == 0;
}

namespace {

// `convex`: the mesh is known to be convex (a hull); otherwise a closed mesh is tested.
MeshShape mesh_shape(TriangleMesh mesh, const std::string& source, const SdfOptions& options, std::shared_ptr<const SdfGrid> sdf,
                     bool convex) {
  check_triangle_mesh(mesh, source);
  MeshShape shape;
  shape.source = source;
  if (is_closed(mesh)) {
    // inside-out meshes (clockwise seen from outside) are turned right side out
    if (signed_volume(mesh) < 0)
      for (auto& t : mesh.triangles) std::swap(t[1], t[2]);
    shape.convex = convex || is_convex(mesh);
    if (shape.convex) shape.faces = std::make_shared<const ConvexFaces>(convex_faces_of(mesh));
    shape.sdf = sdf ? std::move(sdf) : cached_sdf(mesh, options, source);
  } else {
    shape.sdf = std::move(sdf);
  }
  shape.mesh = std::make_shared<const TriangleMesh>(std::move(mesh));
  return shape;
}

}  // namespace

MeshShape make_mesh_shape(TriangleMesh mesh, const std::string& source, const SdfOptions& options, std::shared_ptr<const SdfGrid> sdf) {
  return mesh_shape(std::move(mesh), source, options, std::move(sdf), false);
}

MeshShape make_convex_hull_shape(const std::vector<Vec3>& points, const std::string& source) {
  return mesh_shape(convex_hull(points, source), source + " (convex hull)", {}, nullptr, true);
}

void check_bake(const ShapeBake& bake, const std::string& where) {
  if (!bake.scale.allFinite() || (bake.scale.array() <= 0).any()) {
    std::ostringstream os;
    os << where << ": bake scale must be positive and finite, got (" << bake.scale.x() << ", " << bake.scale.y() << ", " << bake.scale.z() << ")";
    throw Error(os.str());
  }
  if (!bake.translation.allFinite() || !bake.rotation.coeffs().allFinite() || bake.rotation.norm() < real(1e-6))
    throw Error(where + ": bake transform must be finite with a non-zero rotation quaternion");
}

void bake_mesh(TriangleMesh& mesh, const ShapeBake& bake, const std::string& where) {
  check_bake(bake, where);
  const Quat q = bake.rotation.normalized();
  for (Vec3& v : mesh.vertices) v = q * bake.scale.cwiseProduct(v) + bake.translation;
}

ShapeGeometry load_shape_file(const std::string& path, const ShapeBake& bake) {
  const std::string ext = lower_extension(path);
  if (ext == ".h5") return shape_from_mochi_h5(path, bake);
  if (!is_surface_mesh_file(path))
    throw Error(path + ": unknown shape file extension '" + std::filesystem::path(path).extension().string() +
                "' (expected .mochi.h5, .obj, .stl, .ply, .dae, .gltf or .glb)");
  TriangleMesh mesh = read_mesh_file(path);
  if (!bake.is_identity()) bake_mesh(mesh, bake, path);
  return make_mesh_shape(std::move(mesh), path);
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

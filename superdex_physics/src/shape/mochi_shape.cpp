// The shape a `.mochi.h5` file describes: a primitive group, or a triangle mesh with its stored
// or computed distance grid; the optional bake (scale, rotation, translation) applied to it.

#include <sstream>

#include "superdex/physics/error.h"
#include "superdex/physics/mesh_shape.h"
#include "superdex/physics/mesh_validation.h"
#include "superdex/physics/mochi_h5.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace {

std::string vec_text(const Vec3& v) {
  std::ostringstream os;
  os << "[" << v.x() << ", " << v.y() << ", " << v.z() << "]";
  return os.str();
}

bool is_uniform(const Vec3& s) { return std::abs(s.x() - s.y()) <= real(1e-6) * s.x() && std::abs(s.x() - s.z()) <= real(1e-6) * s.x(); }

// A box as 8 vertices and 12 outward-facing triangles.
TriangleMesh box_mesh(const Vec3& h) {
  TriangleMesh m;
  for (int i = 0; i < 8; ++i) m.vertices.push_back(Vec3(i & 1 ? h.x() : -h.x(), i & 2 ? h.y() : -h.y(), i & 4 ? h.z() : -h.z()));
  m.triangles = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                 {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  return m;
}

// The stored grid placed in the baked shape frame, when that stays an axis-aligned grid with
// cubic scaling (uniform scales, rotations that cancel); null otherwise.
std::shared_ptr<const SdfGrid> placed_grid(const MochiSdf& s, const ShapeBake& bake) {
  const Vec3 sg = s.scale.value_or(Vec3::Ones());
  const Quat rg = s.rotation.value_or(Quat::Identity());
  const Vec3 tg = s.translation.value_or(Vec3::Zero());
  const Quat rb = bake.rotation.normalized();
  if (!is_uniform(sg) || !is_uniform(bake.scale) || (rb * rg).angularDistance(Quat::Identity()) > real(1e-6)) return nullptr;
  // p = rb (sb (rg (sg g) + tg)) + tb = sigma g + offset, with rb rg = identity
  const real sigma = sg.x() * bake.scale.x();
  const Vec3 offset = rb * (bake.scale.x() * tg) + bake.translation;
  auto g = std::make_shared<SdfGrid>(s.grid);
  g->grid_min = sigma * s.grid.grid_min + offset;
  g->grid_max = sigma * s.grid.grid_max + offset;
  for (real& v : g->values) v *= sigma;
  return g;
}

}  // namespace

ShapeGeometry shape_from_mochi_h5(const std::string& path, const ShapeBake& bake) { return shape_from_mochi_h5(read_mochi_h5(path), path, bake); }

ShapeGeometry shape_from_mochi_h5(const MochiH5& h, const std::string& path, const ShapeBake& bake) {
  const int primitives = int(h.box.has_value()) + int(h.sphere.has_value()) + int(h.plane.has_value());
  if (primitives > 1) throw Error(path + ": several primitive groups (box/, sphere/, plane/): a shape file holds one shape");
  // bake checks without a mesh: the same rule as bake_mesh
  TriangleMesh probe;
  bake_mesh(probe, bake, path);
  const Quat q = bake.rotation.normalized();

  if (h.box) {
    const bool moves = bake.translation != Vec3::Zero() || q.angularDistance(Quat::Identity()) > real(1e-9);
    if (!moves) return BoxShape{h.box->half_extents.cwiseProduct(bake.scale)};
    // a rotated or moved box is no longer centred and axis-aligned: it becomes a mesh
    TriangleMesh m = box_mesh(h.box->half_extents);
    bake_mesh(m, bake, path);
    return make_mesh_shape(std::move(m), path);
  }
  if (h.sphere) {
    if (!is_uniform(bake.scale)) throw Error(path + ": sphere/: a sphere needs a uniform bake scale, got " + vec_text(bake.scale));
    return SphereShape{q * (bake.scale.x() * h.sphere->center) + bake.translation, h.sphere->radius * bake.scale.x()};
  }
  if (h.plane) {
    // n . x = d  becomes  n' . x' = d' under x' = R (S x) + t
    const Vec3 n_scaled = h.plane->normal.cwiseQuotient(bake.scale);
    const real len = n_scaled.norm();
    PlaneShape p;
    p.normal = q * (n_scaled / len);
    p.distance = h.plane->distance / len + p.normal.dot(bake.translation);
    return p;
  }
  if (!h.mesh) {
    if (h.sdf) throw Error(path + ": sdf/ without mesh/: a distance grid also needs its surface mesh (add a mesh/ group)");
    throw Error(path + ": no shape: expected a mesh/, box/, sphere/ or plane/ group");
  }
  if (h.mesh->nodes_per_element == 4)
    throw Error(path + ": mesh/ holds tetrahedra (connectivity M x 4): tet meshes become soft bodies, not rigid shapes; load it as a soft actor");
  if (h.mesh->nodes_per_element == 2)
    throw Error(path + ": mesh/ holds a polyline (connectivity M x 2): polylines become rods (experimental.create_rod_actor), not rigid shapes");
  TriangleMesh m;
  m.vertices = h.mesh->coordinates;
  for (int e = 0; e < h.mesh->num_elements(); ++e)
    m.triangles.push_back({h.mesh->connectivity[3 * e], h.mesh->connectivity[3 * e + 1], h.mesh->connectivity[3 * e + 2]});
  check_triangle_mesh(m, path + ": mesh/");
  if (!bake.is_identity()) bake_mesh(m, bake, path);
  std::shared_ptr<const SdfGrid> sdf;
  if (h.sdf) {
    sdf = placed_grid(*h.sdf, bake);
    // a rotated or unevenly scaled grid is recomputed from the mesh when it is closed
    if (!sdf && !is_closed(m))
      throw Error(path + ": sdf/: the grid's rotation or non-uniform scale cannot be applied to an open mesh (no distance field to recompute)");
  }
  return make_mesh_shape(std::move(m), path, {}, std::move(sdf));
}

std::optional<TetMesh> tet_mesh_from_mochi_h5(const MochiH5& h, const std::string& path, const ShapeBake& bake) {
  if (!h.mesh || h.mesh->nodes_per_element != 4) return std::nullopt;
  if (!bake.scale.allFinite() || (bake.scale.array() <= 0).any()) throw Error(path + ": the bake scale must be positive");
  TetMesh mesh;
  for (const Vec3& x : h.mesh->coordinates) mesh.nodes.push_back(bake.rotation * bake.scale.cwiseProduct(x) + bake.translation);
  const auto& c = h.mesh->connectivity;
  for (int e = 0; e < h.mesh->num_elements(); ++e) mesh.tets.push_back({c[4 * e], c[4 * e + 1], c[4 * e + 2], c[4 * e + 3]});
  if (h.material) {
    mesh.youngs_modulus = h.material->youngs_modulus;
    mesh.poisson_ratio = h.material->poisson_ratio;
  }
  return mesh;
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

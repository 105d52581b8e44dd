// Signed-distance grids from closed triangle meshes: exact distances through a triangle BVH,
// signs from angle-weighted pseudo-normals (Baerentzen and Aanaes, 2005), slices in parallel.

#include <cmath>
#include <numbers>
#include <unordered_map>

#include <oneapi/tbb/parallel_for.h>

#include "shape/sdf_internal.h"
#include "superdex/physics/error.h"
#include "superdex/physics/mesh_validation.h"
#include "shape/triangle_bvh.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace {

// Outward pseudo-normals of every feature: face, its three edges (ab, bc, ca) and vertices.
struct PseudoNormals {
  std::vector<Eigen::Vector3d> face;
  std::vector<std::array<Eigen::Vector3d, 3>> edge;
  std::vector<Eigen::Vector3d> vertex;
};

PseudoNormals pseudo_normals(const std::vector<Eigen::Vector3d>& v, const std::vector<std::array<int, 3>>& tris) {
  PseudoNormals pn;
  pn.face.resize(tris.size());
  pn.edge.resize(tris.size());
  pn.vertex.assign(v.size(), Eigen::Vector3d::Zero());
  std::unordered_map<std::uint64_t, Eigen::Vector3d> edge_sum;
  auto key = [](int a, int b) {
    return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(std::min(a, b))) << 32) | static_cast<std::uint32_t>(std::max(a, b));
  };
  for (size_t t = 0; t < tris.size(); ++t) {
    const auto& tri = tris[t];
    const Eigen::Vector3d n = (v[tri[1]] - v[tri[0]]).cross(v[tri[2]] - v[tri[0]]).normalized();
    pn.face[t] = n;
    for (int k = 0; k < 3; ++k) {
      // the angle of the triangle at corner k weighs its normal at that vertex
      const Eigen::Vector3d e1 = (v[tri[(k + 1) % 3]] - v[tri[k]]).normalized(), e2 = (v[tri[(k + 2) % 3]] - v[tri[k]]).normalized();
      pn.vertex[tri[k]] += std::acos(std::clamp(e1.dot(e2), -1.0, 1.0)) * n;
      auto [it, inserted] = edge_sum.try_emplace(key(tri[k], tri[(k + 1) % 3]), n);
      if (!inserted) it->second += n;
    }
  }
  for (size_t t = 0; t < tris.size(); ++t)
    for (int k = 0; k < 3; ++k) pn.edge[t][k] = edge_sum[key(tris[t][k], tris[t][(k + 1) % 3])];
  return pn;
}

const Eigen::Vector3d& feature_normal(const PseudoNormals& pn, const std::array<int, 3>& tri, int t, TriangleFeature f) {
  switch (f) {
    case TriangleFeature::VertexA: return pn.vertex[tri[0]];
    case TriangleFeature::VertexB: return pn.vertex[tri[1]];
    case TriangleFeature::VertexC: return pn.vertex[tri[2]];
    case TriangleFeature::EdgeAB: return pn.edge[t][0];
    case TriangleFeature::EdgeBC: return pn.edge[t][1];
    case TriangleFeature::EdgeCA: return pn.edge[t][2];
    case TriangleFeature::Face: break;
  }
  return pn.face[t];
}

}  // namespace

SdfGrid sdf_layout(const TriangleMesh& mesh, const SdfOptions& options, const std::string& where) {
  if (options.resolution < 2 || options.resolution > 1024)
    throw Error(where + ": SDF resolution must be between 2 and 1024 cells, got " + std::to_string(options.resolution));
  if (options.padding_cells < 1 || options.padding_cells > 64)
    throw Error(where + ": SDF padding must be between 1 and 64 cells, got " + std::to_string(options.padding_cells));
  if (mesh.vertices.empty()) throw Error(where + ": empty mesh: no vertices");
  Eigen::Vector3d lo = mesh.vertices[0].cast<double>(), hi = lo;
  for (const Vec3& p : mesh.vertices) lo = lo.cwiseMin(p.cast<double>()), hi = hi.cwiseMax(p.cast<double>());
  const Eigen::Vector3d extent = hi - lo;
  const double h = extent.maxCoeff() / options.resolution;
  if (!(h > 0) || !std::isfinite(h)) throw Error(where + ": the mesh has no extent: cannot lay out a distance grid");
  SdfGrid g;
  for (int a = 0; a < 3; ++a) {
    const int cells = static_cast<int>(std::ceil(extent[a] / h - 1e-9)) + 2 * options.padding_cells;
    g.size[a] = cells + 1;
    const double center = (lo[a] + hi[a]) / 2;
    g.grid_min[a] = static_cast<real>(center - cells * h / 2);
    g.grid_max[a] = static_cast<real>(center + cells * h / 2);
  }
  return g;
}

namespace {
void check_closed(const TriangleMesh& mesh, const std::string& where) {
  check_triangle_mesh(mesh, where);
  if (const EdgeReport edges = edge_report(mesh); !edges.closed())
    throw Error(where + ": computing a signed-distance field needs a closed mesh: " + edges.describe());
}
}  // namespace

SdfGrid compute_sdf(const TriangleMesh& mesh, const SdfOptions& options, const std::string& where) {
  check_closed(mesh, where);
  SdfGrid grid = sdf_layout(mesh, options, where);
  fill_sdf(mesh, grid, where);
  return grid;
}

void fill_sdf(const TriangleMesh& mesh, SdfGrid& grid, const std::string& where) {
  check_closed(mesh, where);

  std::vector<Eigen::Vector3d> v(mesh.vertices.size());
  for (size_t i = 0; i < v.size(); ++i) v[i] = mesh.vertices[i].cast<double>();
  const TriangleBvh bvh(v, mesh.triangles);
  const PseudoNormals pn = pseudo_normals(v, mesh.triangles);
  // an inside-out mesh has inward pseudo-normals: flip the sign back
  const double orientation = signed_volume(mesh) < 0 ? -1.0 : 1.0;

  const int nx = grid.size[0], ny = grid.size[1], nz = grid.size[2];
  grid.values.assign(static_cast<size_t>(nx) * ny * nz, 0);
  const Eigen::Vector3d lo = grid.grid_min.cast<double>();
  const Eigen::Vector3d cell = (grid.grid_max.cast<double>() - lo).cwiseQuotient(Eigen::Vector3d(nx - 1, ny - 1, nz - 1));
  oneapi::tbb::parallel_for(0, nz, [&](int k) {
    int hint = -1;  // the previous node's closest triangle is usually close to the next one's
    for (int j = 0; j < ny; ++j) {
      for (int i = 0; i < nx; ++i) {
        const Eigen::Vector3d p = lo + Eigen::Vector3d(i, j, k).cwiseProduct(cell);
        const TriangleBvh::Hit hit = bvh.closest(p, hint);
        hint = hit.triangle;
        const Eigen::Vector3d& n = feature_normal(pn, mesh.triangles[hit.triangle], hit.triangle, hit.closest.feature);
        const double side = orientation * (p - hit.closest.point).dot(n);
        const double d = std::sqrt(hit.distance_squared);
        grid.values[static_cast<size_t>(i) + static_cast<size_t>(nx) * (j + static_cast<size_t>(ny) * k)] = static_cast<real>(side < 0 ? -d : d);
      }
    }
  });
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

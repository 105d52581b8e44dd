// Geometric queries of mesh shapes (declared in collision_geometry.h): signed distance from the
// grid (trilinear, analytic gradient; extended outside the grid), surface samples, bounding box.

#include <algorithm>
#include <cmath>
#include <map>

#include "collision/collision_geometry.h"
#include "superdex/physics/error.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace {

// Trilinear value and gradient (per metre) of the grid at a point inside [grid_min, grid_max].
real grid_value(const SdfGrid& g, const Vec3& p, Vec3* grad) {
  const Vec3 extent = g.grid_max - g.grid_min;
  int i0[3];
  real t[3], cell[3];
  for (int a = 0; a < 3; ++a) {
    cell[a] = extent[a] / static_cast<real>(g.size[a] - 1);
    const real u = (p[a] - g.grid_min[a]) / cell[a];
    i0[a] = std::clamp(static_cast<int>(std::floor(u)), 0, g.size[a] - 2);
    t[a] = std::clamp(u - static_cast<real>(i0[a]), real(0), real(1));
  }
  auto at = [&](int di, int dj, int dk) {
    return g.values[static_cast<size_t>(i0[0] + di) + static_cast<size_t>(g.size[0]) * (static_cast<size_t>(i0[1] + dj) + static_cast<size_t>(g.size[1]) * (i0[2] + dk))];
  };
  real c[2][2][2];
  for (int di = 0; di < 2; ++di)
    for (int dj = 0; dj < 2; ++dj)
      for (int dk = 0; dk < 2; ++dk) c[di][dj][dk] = at(di, dj, dk);
  // interpolate along x, then y, then z, keeping the partial derivatives
  real cx[2][2], dcx[2][2];
  for (int dj = 0; dj < 2; ++dj)
    for (int dk = 0; dk < 2; ++dk) {
      cx[dj][dk] = c[0][dj][dk] * (1 - t[0]) + c[1][dj][dk] * t[0];
      dcx[dj][dk] = c[1][dj][dk] - c[0][dj][dk];
    }
  real cy[2], dcy_dx[2], dcy_dy[2];
  for (int dk = 0; dk < 2; ++dk) {
    cy[dk] = cx[0][dk] * (1 - t[1]) + cx[1][dk] * t[1];
    dcy_dx[dk] = dcx[0][dk] * (1 - t[1]) + dcx[1][dk] * t[1];
    dcy_dy[dk] = cx[1][dk] - cx[0][dk];
  }
  if (grad) {
    (*grad)[0] = (dcy_dx[0] * (1 - t[2]) + dcy_dx[1] * t[2]) / cell[0];
    (*grad)[1] = (dcy_dy[0] * (1 - t[2]) + dcy_dy[1] * t[2]) / cell[1];
    (*grad)[2] = (cy[1] - cy[0]) / cell[2];
  }
  return cy[0] * (1 - t[2]) + cy[1] * t[2];
}

}  // namespace

real mesh_signed_distance(const MeshShape& mesh, const Vec3& p_S, Vec3* grad_S) {
  if (!mesh.sdf)
    throw Error((mesh.source.empty() ? std::string("mesh shape") : mesh.source) +
                ": the mesh is open and has no signed-distance field, so nothing can test penetration against it "
                "(close the mesh, or let it only touch shapes that have a distance field)");
  const SdfGrid& g = *mesh.sdf;
  const Vec3 q = p_S.cwiseMax(g.grid_min).cwiseMin(g.grid_max);
  Vec3 grad_q;
  const real value = grid_value(g, q, &grad_q);
  const Vec3 out = p_S - q;
  const real outside = out.norm();
  if (outside == 0) {
    if (grad_S) {
      const real n = grad_q.norm();
      *grad_S = n > real(1e-12) ? Vec3(grad_q / n) : Vec3::UnitZ();
    }
    return value;
  }
  // outside the grid: distance to the box plus the value at the clamped point; the gradient
  // points away from the box, plus the grid's slope along the axes that were not clamped
  if (grad_S) {
    Vec3 g_total = out / outside;
    for (int a = 0; a < 3; ++a)
      if (out[a] == 0) g_total[a] += grad_q[a];
    *grad_S = g_total.normalized();
  }
  return outside + value;
}

std::vector<Vec3> mesh_surface_samples(const MeshShape& mesh) {
  std::vector<Vec3> samples;
  if (!mesh.mesh) return samples;
  const TriangleMesh& m = *mesh.mesh;
  samples = m.vertices;
  const Bounds box = mesh_local_aabb(mesh);
  // spacing: 4% of the longest side of the bounding box
  const real spacing = real(0.04) * (box.max - box.min).maxCoeff();
  if (!(spacing > 0)) return samples;
  auto subdivisions = [&](const Vec3& a, const Vec3& b) { return static_cast<int>(std::ceil((b - a).norm() / spacing)); };
  // points along each edge once (ordered map: deterministic order)
  std::map<std::pair<int, int>, bool> edges;
  for (const auto& t : m.triangles)
    for (int k = 0; k < 3; ++k) edges.emplace(std::minmax(t[k], t[(k + 1) % 3]), true);
  for (const auto& [e, unused] : edges) {
    const Vec3 &a = m.vertices[e.first], &b = m.vertices[e.second];
    const int n = subdivisions(a, b);
    for (int i = 1; i < n; ++i) samples.push_back(a + (b - a) * (static_cast<real>(i) / n));
  }
  // interior points of each triangle on a barycentric lattice fine enough for its longest edge;
  // not for convex meshes: a face pressed on by another shape meets that shape's vertices and
  // edges (or its face samples), and a face against a face shows in both faces' edges
  if (mesh.convex) return samples;
  for (const auto& t : m.triangles) {
    const Vec3 &a = m.vertices[t[0]], &b = m.vertices[t[1]], &c = m.vertices[t[2]];
    const int n = std::max({subdivisions(a, b), subdivisions(b, c), subdivisions(c, a)});
    for (int i = 1; i < n; ++i)
      for (int j = 1; i + j < n; ++j) samples.push_back(a + (b - a) * (static_cast<real>(i) / n) + (c - a) * (static_cast<real>(j) / n));
  }
  return samples;
}

Bounds mesh_local_aabb(const MeshShape& mesh) {
  Bounds box;
  if (mesh.mesh)
    for (const Vec3& v : mesh.mesh->vertices) box.extend(v);
  return box;
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

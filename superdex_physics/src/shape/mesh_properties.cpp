// Mesh shape volume and inertia (signed tetrahedra from the bounding-box centre; exact for
// polyhedra) and validation.

#include "shape/mesh_properties.h"

#include <cmath>

#include "superdex/physics/error.h"
#include "superdex/physics/mesh_validation.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace {

std::string name_of(const MeshShape& m) { return m.source.empty() ? std::string("mesh shape") : m.source; }

const TriangleMesh& closed_mesh(const MeshShape& m, const char* what) {
  if (!m.mesh) throw Error(name_of(m) + ": the mesh shape has no mesh");
  if (const EdgeReport e = edge_report(*m.mesh); !e.closed())
    throw Error(name_of(m) + ": " + what + " needs a closed mesh: " + e.describe() +
                " (close the mesh, make the body static, or give it an explicit mass and inertia)");
  return *m.mesh;
}

// Volume, first moment and second moment (integral of x x^T) about `origin`, per unit density.
struct Moments {
  double volume = 0;
  Eigen::Vector3d first = Eigen::Vector3d::Zero();
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero();
};

Moments moments(const TriangleMesh& m, const Eigen::Vector3d& origin) {
  Moments s;
  for (const auto& t : m.triangles) {
    const Eigen::Vector3d a = m.vertices[t[0]].cast<double>() - origin, b = m.vertices[t[1]].cast<double>() - origin,
                          c = m.vertices[t[2]].cast<double>() - origin;
    const double det = a.dot(b.cross(c));  // six times the signed volume of (origin, a, b, c)
    const Eigen::Vector3d sum = a + b + c;
    s.volume += det / 6;
    s.first += det / 24 * sum;
    s.second += det / 120 * (a * a.transpose() + b * b.transpose() + c * c.transpose() + sum * sum.transpose());
  }
  // an inside-out mesh gives the negated integrals
  if (s.volume < 0) s.volume = -s.volume, s.first = -s.first, s.second = -s.second;
  return s;
}

// The centre of the vertices' bounding box: moments about it cancel least, and a shape symmetric
// about its centre gets that centre back exactly.
Eigen::Vector3d box_centre(const TriangleMesh& m) {
  Eigen::Vector3d lo = m.vertices[0].cast<double>(), hi = lo;
  for (const auto& v : m.vertices) lo = lo.cwiseMin(v.cast<double>()), hi = hi.cwiseMax(v.cast<double>());
  return 0.5 * (lo + hi);
}

}  // namespace

real mesh_volume(const MeshShape& mesh) {
  const TriangleMesh& m = closed_mesh(mesh, "computing a volume");
  return static_cast<real>(moments(m, box_centre(m)).volume);
}

MassProperties mesh_mass_properties(const MeshShape& mesh, real density) {
  const TriangleMesh& m = closed_mesh(mesh, "computing mass properties");
  const Eigen::Vector3d origin = box_centre(m);
  const Moments s = moments(m, origin);
  if (!(s.volume > 0)) throw Error(name_of(mesh) + ": the closed mesh encloses no volume");
  const Eigen::Vector3d com = s.first / s.volume;
  const Eigen::Matrix3d second_com = s.second - s.volume * com * com.transpose();
  const Eigen::Matrix3d inertia = second_com.trace() * Eigen::Matrix3d::Identity() - second_com;
  MassProperties mp;
  mp.mass = static_cast<real>(density * s.volume);
  mp.center_of_mass = (origin + com).cast<real>();
  mp.inertia_about_com = (double(density) * inertia).cast<real>();
  return mp;
}

void validate_mesh_shape(const MeshShape& mesh, const std::string& where) {
  const std::string at = mesh.source.empty() ? where : where + " (" + mesh.source + ")";
  if (!mesh.mesh) throw Error(at + ": the mesh shape has no mesh");
  check_triangle_mesh(*mesh.mesh, at);
  if (!mesh.sdf) return;
  const SdfGrid& g = *mesh.sdf;
  auto fail = [&](const std::string& what) { throw Error(at + ": distance grid: " + what); };
  for (int a = 0; a < 3; ++a)
    if (g.size[a] < 2) fail("every dimension needs at least 2 samples");
  const size_t n = static_cast<size_t>(g.size[0]) * g.size[1] * g.size[2];
  if (g.values.size() != n) fail("has " + std::to_string(g.values.size()) + " values for " + std::to_string(n) + " samples");
  if (!g.grid_min.allFinite() || !g.grid_max.allFinite() || !(g.grid_min.array() < g.grid_max.array()).all())
    fail("grid_min must be < grid_max on every axis, and finite");
  for (size_t i = 0; i < n; ++i)
    if (!std::isfinite(g.values[i])) fail("non-finite value at index " + std::to_string(i));
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

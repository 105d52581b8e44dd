#include "import/mjcf_mesh.h"

#include <cstdint>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <vector>

#include "superdex/physics/error.h"

namespace superdex::robotics {
inline namespace SUPERDEX_REAL_NAMESPACE {

using physics::real;
using physics::Vec3;

physics::TriangleMesh read_msh_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot open the mesh file");
  const std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  int32_t n[4] = {0, 0, 0, 0};
  if (bytes.size() < sizeof n) throw Error(path + ": not a MuJoCo .msh file: shorter than its 16-byte header");
  std::memcpy(n, bytes.data(), sizeof n);
  for (int32_t c : n)
    if (c < 0) throw Error(path + ": not a MuJoCo .msh file: negative count in its header");
  const auto nv = static_cast<uint64_t>(n[0]), nn = static_cast<uint64_t>(n[1]), nt = static_cast<uint64_t>(n[2]),
             nf = static_cast<uint64_t>(n[3]);
  const uint64_t expected = sizeof n + 4 * (3 * nv + 3 * nn + 2 * nt + 3 * nf);
  if (bytes.size() != expected)
    throw Error(path + ": not a MuJoCo .msh file: " + std::to_string(bytes.size()) + " bytes where its header announces " +
                std::to_string(expected));
  if (nv < 4) throw Error(path + ": the mesh has " + std::to_string(nv) + " vertices, at least 4 are needed");
  physics::TriangleMesh mesh;
  const char* p = bytes.data() + sizeof n;
  for (uint64_t i = 0; i < nv; ++i, p += 12) {
    float v[3];
    std::memcpy(v, p, sizeof v);
    mesh.vertices.push_back(Vec3(real(v[0]), real(v[1]), real(v[2])));
  }
  p += 4 * (3 * nn + 2 * nt);
  for (uint64_t f = 0; f < nf; ++f, p += 12) {
    int32_t t[3];
    std::memcpy(t, p, sizeof t);
    for (int32_t k : t)
      if (k < 0 || static_cast<uint64_t>(k) >= nv)
        throw Error(path + ": face " + std::to_string(f) + " refers to vertex " + std::to_string(k) + " of " + std::to_string(nv));
    mesh.triangles.push_back({t[0], t[1], t[2]});
  }
  return mesh;
}

namespace {

// Volume, first and second moments of the signed tetrahedra (ref, a, b, c) over the triangles.
struct Sums {
  double volume = 0;
  Eigen::Vector3d first = Eigen::Vector3d::Zero();
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero();
};
Sums tetra_sums(const physics::TriangleMesh& mesh, const Eigen::Vector3d& ref, bool absolute) {
  Sums s;
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d a = mesh.vertices[t[0]].cast<double>() - ref, b = mesh.vertices[t[1]].cast<double>() - ref,
                          c = mesh.vertices[t[2]].cast<double>() - ref;
    const double signed_volume = a.dot(b.cross(c)) / 6;
    const double v = absolute ? std::abs(signed_volume) : signed_volume;
    const Eigen::Vector3d sum = a + b + c;
    s.volume += v;
    s.first += v * sum / 4;
    // integral of x x^T over the tetrahedron with one corner at the origin
    s.second += v / 20 * (a * a.transpose() + b * b.transpose() + c * c.transpose() + sum * sum.transpose());
  }
  return s;
}

}  // namespace

MeshMoments mesh_moments(const physics::TriangleMesh& mesh, bool absolute) {
  // first pass: the centre of mass, from tetrahedra on the area-weighted centroid of the surface
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  double area = 0;
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d a = mesh.vertices[t[0]].cast<double>(), b = mesh.vertices[t[1]].cast<double>(),
                          c = mesh.vertices[t[2]].cast<double>();
    const double A = (b - a).cross(c - a).norm() / 2;
    area += A;
    centroid += A * (a + b + c) / 3;
  }
  if (area > 0) centroid /= area;
  const Sums s1 = tetra_sums(mesh, centroid, absolute);
  MeshMoments m;
  if (s1.volume == 0) return m;
  m.center = centroid + s1.first / s1.volume;
  // second pass: volume and inertia from tetrahedra on that centre (as MuJoCo does; for an open
  // mesh both depend on the point the tetrahedra share)
  const Sums s2 = tetra_sums(mesh, m.center, absolute);
  m.volume = s2.volume;
  m.inertia = s2.second.trace() * Eigen::Matrix3d::Identity() - s2.second;
  return m;
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::robotics

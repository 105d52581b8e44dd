#include "import/import_support.h"

#include <charconv>
#include <cmath>
#include <sstream>
#include <system_error>

#include "superdex/physics/error.h"
#include "superdex/physics/mesh_shape.h"

namespace superdex::robotics {
inline namespace SUPERDEX_REAL_NAMESPACE {

using physics::real;
using physics::TriangleMesh;
using physics::Vec3;

std::string in_quotes(const std::string& s) { return "'" + s + "'"; }

std::string format_number(double x) {
  std::ostringstream os;
  os << x;
  return os.str();
}

physics::Transform to_transform(const Eigen::Isometry3d& X) {
  physics::Transform t;
  t.rotation = Eigen::Quaterniond(X.linear()).normalized().cast<real>();
  t.translation = X.translation().cast<real>();
  return t;
}

std::optional<std::vector<double>> parse_numbers(const std::string& text, std::string* bad_word) {
  std::vector<double> out;
  std::istringstream words(text);
  std::string w;
  while (words >> w) {
    const char* first = w.data() + (w[0] == '+' ? 1 : 0);
    const char* last = w.data() + w.size();
    double x = 0;
    const auto [end, ec] = std::from_chars(first, last, x);
    if (ec != std::errc() || end != last || !std::isfinite(x)) {
      if (bad_word) *bad_word = w;
      return std::nullopt;
    }
    out.push_back(x);
  }
  return out;
}

TriangleMesh cylinder_mesh(double radius, double length, int segments) {
  TriangleMesh m;
  const int n = segments;
  for (int k = 0; k < n; ++k) {
    const double a = 2 * EIGEN_PI * k / n;
    const double x = radius * std::cos(a), y = radius * std::sin(a);
    m.vertices.push_back(Vec3(real(x), real(y), real(-length / 2)));
    m.vertices.push_back(Vec3(real(x), real(y), real(length / 2)));
  }
  const int bottom = 2 * n, top = 2 * n + 1;
  m.vertices.push_back(Vec3(0, 0, real(-length / 2)));
  m.vertices.push_back(Vec3(0, 0, real(length / 2)));
  for (int k = 0; k < n; ++k) {
    const int b0 = 2 * k, t0 = 2 * k + 1, b1 = 2 * ((k + 1) % n), t1 = b1 + 1;
    m.triangles.push_back({b0, b1, t1});  // side, counter-clockwise seen from outside
    m.triangles.push_back({b0, t1, t0});
    m.triangles.push_back({bottom, b1, b0});
    m.triangles.push_back({top, t0, t1});
  }
  return m;
}

TriangleMesh ellipsoid_mesh(const Vec3& radii, int segments) {
  TriangleMesh m;
  const int rings = segments / 2, n = segments;
  // poles, then rings of n vertices from the south pole up
  m.vertices.push_back(Vec3(0, 0, -radii.z()));
  m.vertices.push_back(Vec3(0, 0, radii.z()));
  for (int r = 1; r < rings; ++r) {
    const double theta = EIGEN_PI * r / rings - EIGEN_PI / 2;
    for (int k = 0; k < n; ++k) {
      const double phi = 2 * EIGEN_PI * k / n;
      m.vertices.push_back(Vec3(real(radii.x() * std::cos(theta) * std::cos(phi)), real(radii.y() * std::cos(theta) * std::sin(phi)),
                                real(radii.z() * std::sin(theta))));
    }
  }
  auto at = [&](int r, int k) { return 2 + (r - 1) * n + (k % n); };
  for (int k = 0; k < n; ++k) {
    m.triangles.push_back({0, at(1, k + 1), at(1, k)});
    m.triangles.push_back({1, at(rings - 1, k), at(rings - 1, k + 1)});
    for (int r = 1; r + 1 < rings; ++r) {
      m.triangles.push_back({at(r, k), at(r, k + 1), at(r + 1, k + 1)});
      m.triangles.push_back({at(r, k), at(r + 1, k + 1), at(r + 1, k)});
    }
  }
  return m;
}

void scale_mesh(TriangleMesh& mesh, const Vec3& s) {
  for (Vec3& v : mesh.vertices) v = v.cwiseProduct(s);
  if (s.prod() < 0)
    for (auto& t : mesh.triangles) std::swap(t[1], t[2]);
}

physics::ShapeGeometry mesh_collider(TriangleMesh mesh, const std::string& source, MeshCollision mode, std::string* warning) {
  if (mode == MeshCollision::ConvexHull) {
    try {
      return physics::make_convex_hull_shape(mesh.vertices, source);
    } catch (const Error& e) {
      // a flat mesh (a plate, a single quad) has no hull with volume: its triangles collide
      if (warning) *warning = std::string(e.what()) + "; the mesh itself collides";
    }
  }
  return physics::make_mesh_shape(std::move(mesh), source);
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::robotics

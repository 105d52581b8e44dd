// Triangle mesh checks: well-formedness, closedness (edge pairing), enclosed volume, convexity.

#include "superdex/physics/mesh_validation.h"

#include <cmath>
#include <sstream>
#include <unordered_map>

#include "superdex/physics/error.h"
#include "superdex/physics/log.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace {

Eigen::Vector3d vertex(const TriangleMesh& m, int i) { return m.vertices[static_cast<size_t>(i)].cast<double>(); }

double bounding_diagonal(const TriangleMesh& m) {
  if (m.vertices.empty()) return 0;
  Eigen::Vector3d lo = vertex(m, 0), hi = lo;
  for (size_t i = 1; i < m.vertices.size(); ++i) {
    lo = lo.cwiseMin(vertex(m, static_cast<int>(i)));
    hi = hi.cwiseMax(vertex(m, static_cast<int>(i)));
  }
  return (hi - lo).norm();
}

std::string plural(long n, const char* one, const char* many) { return std::to_string(n) + " " + (n == 1 ? one : many); }

}  // namespace

void check_triangle_mesh(const TriangleMesh& mesh, const std::string& where) {
  auto fail = [&](const std::string& what) { throw Error(where + ": " + what); };
  if (mesh.vertices.empty()) fail("empty mesh: no vertices");
  if (mesh.triangles.empty()) fail("empty mesh: no triangles");
  for (size_t i = 0; i < mesh.vertices.size(); ++i) {
    if (!mesh.vertices[i].allFinite()) {
      std::ostringstream os;
      os << "vertex " << i << " has a non-finite coordinate (" << mesh.vertices[i].x() << ", " << mesh.vertices[i].y() << ", "
         << mesh.vertices[i].z() << ")";
      fail(os.str());
    }
  }
  const long n = static_cast<long>(mesh.vertices.size());
  for (size_t t = 0; t < mesh.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k)
      if (mesh.triangles[t][k] < 0 || mesh.triangles[t][k] >= n)
        fail("triangle " + std::to_string(t) + " has vertex index " + std::to_string(mesh.triangles[t][k]) + " out of range [0, " +
             std::to_string(n) + ")");
  const std::vector<size_t> degenerate = degenerate_triangles(mesh);
  if (!degenerate.empty()) {
    const size_t first = degenerate.front();
    const auto& tri = mesh.triangles[first];
    fail(plural(static_cast<long>(degenerate.size()), "degenerate (zero-area) triangle", "degenerate (zero-area) triangles") +
         "; the first is triangle " + std::to_string(first) + " (vertices " + std::to_string(tri[0]) + ", " + std::to_string(tri[1]) +
         ", " + std::to_string(tri[2]) + ")");
  }
}

std::vector<size_t> degenerate_triangles(const TriangleMesh& mesh) {
  // zero area relative to the mesh size (this also catches repeated indices)
  const double diag = bounding_diagonal(mesh);
  const double min_twice_area = 2e-12 * diag * diag;
  std::vector<size_t> out;
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& tri = mesh.triangles[t];
    const Eigen::Vector3d a = vertex(mesh, tri[0]);
    const double twice_area = (vertex(mesh, tri[1]) - a).cross(vertex(mesh, tri[2]) - a).norm();
    if (!(twice_area > min_twice_area)) out.push_back(t);
  }
  return out;
}

long remove_degenerate_triangles(TriangleMesh& mesh, const std::string& where) {
  // only a well-formed mesh is judged: other defects stay for check_triangle_mesh to report
  const long n = static_cast<long>(mesh.vertices.size());
  for (const Vec3& v : mesh.vertices)
    if (!v.allFinite()) return 0;
  for (const auto& tri : mesh.triangles)
    for (int k = 0; k < 3; ++k)
      if (tri[k] < 0 || tri[k] >= n) return 0;
  const std::vector<size_t> degenerate = degenerate_triangles(mesh);
  if (degenerate.empty() || degenerate.size() == mesh.triangles.size()) return 0;
  const auto& tri = mesh.triangles[degenerate.front()];
  log_warning(where + ": " + plural(static_cast<long>(degenerate.size()), "degenerate (zero-area) triangle", "degenerate (zero-area) triangles") +
              " ignored; the first was triangle " + std::to_string(degenerate.front()) + " (vertices " + std::to_string(tri[0]) + ", " +
              std::to_string(tri[1]) + ", " + std::to_string(tri[2]) + ")");
  std::vector<std::array<int, 3>> kept;
  kept.reserve(mesh.triangles.size() - degenerate.size());
  size_t next = 0;
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    if (next < degenerate.size() && degenerate[next] == t) {
      ++next;
      continue;
    }
    kept.push_back(mesh.triangles[t]);
  }
  mesh.triangles = std::move(kept);
  return static_cast<long>(degenerate.size());
}

std::string EdgeReport::describe() const {
  std::string s = plural(boundary_edges, "boundary edge", "boundary edges");
  if (nonmanifold_edges > 0) s += ", " + plural(nonmanifold_edges, "edge", "edges") + " shared by more than two triangles";
  if (misoriented_edges > 0) s += ", " + plural(misoriented_edges, "edge", "edges") + " whose two triangles disagree in orientation";
  return s;
}

EdgeReport edge_report(const TriangleMesh& mesh) {
  struct Use {
    int count = 0;
    int direction = 0;  // +1 per traversal low -> high, -1 per high -> low
  };
  std::unordered_map<std::uint64_t, Use> edges;
  edges.reserve(mesh.triangles.size() * 2);
  for (const auto& tri : mesh.triangles) {
    for (int k = 0; k < 3; ++k) {
      const int a = tri[k], b = tri[(k + 1) % 3];
      const auto lo = static_cast<std::uint32_t>(std::min(a, b)), hi = static_cast<std::uint32_t>(std::max(a, b));
      Use& u = edges[(static_cast<std::uint64_t>(lo) << 32) | hi];
      ++u.count;
      u.direction += a < b ? 1 : -1;
    }
  }
  EdgeReport r;
  for (const auto& [key, u] : edges) {
    if (u.count == 1) ++r.boundary_edges;
    else if (u.count > 2) ++r.nonmanifold_edges;
    else if (u.direction != 0) ++r.misoriented_edges;
  }
  return r;
}

bool is_closed(const TriangleMesh& mesh) { return !mesh.triangles.empty() && edge_report(mesh).closed(); }

double signed_volume(const TriangleMesh& mesh) {
  if (mesh.vertices.empty()) return 0;
  // tetrahedra from a reference vertex keep the sum well conditioned far from the origin
  const Eigen::Vector3d o = vertex(mesh, 0);
  double six_volume = 0;
  for (const auto& tri : mesh.triangles) {
    const Eigen::Vector3d a = vertex(mesh, tri[0]) - o, b = vertex(mesh, tri[1]) - o, c = vertex(mesh, tri[2]) - o;
    six_volume += a.dot(b.cross(c));
  }
  return six_volume / 6;
}

bool is_convex(const TriangleMesh& mesh, double relative_tolerance) {
  if (!is_closed(mesh)) return false;
  const double tol = relative_tolerance * bounding_diagonal(mesh);
  const double orientation = signed_volume(mesh) < 0 ? -1 : 1;
  std::vector<Eigen::Vector3d> v(mesh.vertices.size());
  for (size_t i = 0; i < v.size(); ++i) v[i] = vertex(mesh, static_cast<int>(i));
  for (const auto& tri : mesh.triangles) {
    const Eigen::Vector3d a = v[tri[0]];
    Eigen::Vector3d n = (v[tri[1]] - a).cross(v[tri[2]] - a);
    const double len = n.norm();
    if (len == 0) continue;
    n *= orientation / len;
    const double d = n.dot(a);
    for (const Eigen::Vector3d& p : v)
      if (n.dot(p) - d > tol) return false;
  }
  return true;
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

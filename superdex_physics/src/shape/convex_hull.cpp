// Convex hulls through Qhull's reentrant C library (libqhull_r): merged facets read back as
// polygons, each fanned into triangles facing outward.

#include "superdex/physics/convex_hull.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdint>
#include <cstdlib>
#include <unordered_map>

extern "C" {
#include <libqhull_r/qhull_ra.h>
}

#include "superdex/physics/error.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace {

// Qhull's state with its error stream captured in memory, freed on every path.
struct Qhull {
  qhT qh_storage;
  qhT* qh = &qh_storage;
  char* err_text = nullptr;
  size_t err_size = 0;
  FILE* err = nullptr;

  Qhull() {
    err = open_memstream(&err_text, &err_size);
    qh_zero(qh, err);
  }
  ~Qhull() {
    int curlong = 0, totlong = 0;
    qh_freeqhull(qh, !qh_ALL);
    qh_memfreeshort(qh, &curlong, &totlong);
    if (err) std::fclose(err);
    std::free(err_text);
  }
  // The first line of what Qhull reported ("QH6154 qhull precision error: initial simplex is flat").
  std::string message() {
    std::fflush(err);
    std::string s(err_text ? err_text : "", err_size);
    const size_t start = s.find("QH");
    if (start != std::string::npos) s = s.substr(start);
    return s.substr(0, s.find('\n'));
  }
};

}  // namespace

TriangleMesh convex_hull(const std::vector<Vec3>& points, const std::string& where) {
  if (points.size() < 4)
    throw Error(where + ": a convex hull needs at least 4 points spanning a volume, got " + std::to_string(points.size()));
  for (const Vec3& p : points)
    if (!p.allFinite()) throw Error(where + ": a convex hull needs finite points");
  // points within 1e-4 of the extent of one another are one point: meshes exported from CAD
  // carry near-duplicates microns apart, whose hull facets would be slivers without area
  Eigen::AlignedBox<double, 3> extent;
  for (const Vec3& p : points) extent.extend(p.cast<double>());
  const double weld = 1e-4 * extent.diagonal().norm();
  std::vector<coordT> coords;
  coords.reserve(3 * points.size());
  {
    std::unordered_map<std::uint64_t, std::vector<int>> cells;  // grid cell (side `weld`) -> points kept in it
    auto cell_key = [](long x, long y, long z) {
      return (static_cast<std::uint64_t>(x) & 0x1fffff) | (static_cast<std::uint64_t>(y) & 0x1fffff) << 21 |
             (static_cast<std::uint64_t>(z) & 0x1fffff) << 42;
    };
    int kept = 0;
    for (const Vec3& point : points) {
      const Eigen::Vector3d p = point.cast<double>();
      const Eigen::Vector3d g = weld > 0 ? Eigen::Vector3d((p - extent.min()) / weld) : Eigen::Vector3d::Zero();
      const long cx = static_cast<long>(std::floor(g.x())), cy = static_cast<long>(std::floor(g.y())), cz = static_cast<long>(std::floor(g.z()));
      bool near = false;
      for (long dx = -1; dx <= 1 && !near; ++dx)
        for (long dy = -1; dy <= 1 && !near; ++dy)
          for (long dz = -1; dz <= 1 && !near; ++dz) {
            const auto it = cells.find(cell_key(cx + dx, cy + dy, cz + dz));
            if (it == cells.end()) continue;
            for (int k : it->second)
              if ((Eigen::Vector3d(coords[3 * k], coords[3 * k + 1], coords[3 * k + 2]) - p).norm() <= weld) near = true;
          }
      if (near) continue;
      cells[cell_key(cx, cy, cz)].push_back(kept++);
      for (int a = 0; a < 3; ++a) coords.push_back(static_cast<coordT>(p[a]));
    }
    if (kept < 4)
      throw Error(where + ": a convex hull needs at least 4 points spanning a volume, got " + std::to_string(kept) + " distinct points");
  }
  Qhull q;
  // "Qt" is not used: merged facets come back whole and are fanned here without slivers
  char flags[] = "qhull";
  const int code = qh_new_qhull(q.qh, 3, static_cast<int>(coords.size() / 3), coords.data(), False, flags, nullptr, q.err);
  if (code != 0)
    throw Error(where + ": no convex hull: the points span no volume (they lie on one plane or line): " + q.message());

  qhT* qh = q.qh;
  TriangleMesh hull;
  std::unordered_map<int, int> index;  // Qhull point id -> hull vertex
  auto vertex_index = [&](vertexT* v) {
    const int id = qh_pointid(qh, v->point);
    auto [it, inserted] = index.try_emplace(id, static_cast<int>(hull.vertices.size()));
    if (inserted) hull.vertices.push_back(Vec3(real(v->point[0]), real(v->point[1]), real(v->point[2])));
    return it->second;
  };
  facetT* facet;
  FORALLfacets {
    const Eigen::Vector3d n(facet->normal[0], facet->normal[1], facet->normal[2]);  // outward unit normal
    std::vector<int> corners;
    std::vector<Eigen::Vector3d> at;
    vertexT *vertex, **vertexp;
    FOREACHvertex_(facet->vertices) {
      corners.push_back(vertex_index(vertex));
      at.emplace_back(vertex->point[0], vertex->point[1], vertex->point[2]);
    }
    // the corners in counter-clockwise order seen from outside: by angle about the centroid in
    // the facet's plane
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (const auto& p : at) c += p;
    c /= static_cast<double>(at.size());
    const Eigen::Vector3d u = (at[0] - c).normalized(), v = n.cross(u);
    std::vector<size_t> order(corners.size());
    std::vector<double> angle(corners.size());
    for (size_t k = 0; k < corners.size(); ++k) {
      order[k] = k;
      angle[k] = std::atan2((at[k] - c).dot(v), (at[k] - c).dot(u));
    }
    std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return angle[a] < angle[b]; });
    if (corners.size() == 3) {
      hull.triangles.push_back({corners[order[0]], corners[order[1]], corners[order[2]]});
      continue;
    }
    // a polygon: fanned around its centroid
    const int centre = static_cast<int>(hull.vertices.size());
    hull.vertices.push_back(c.cast<real>());
    for (size_t k = 0; k < order.size(); ++k)
      hull.triangles.push_back({centre, corners[order[k]], corners[order[(k + 1) % order.size()]]});
  }
  return hull;
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

// Contact reduction: a shape pair's many sample contacts cut down to a few that span the
// contact patch, so that a mesh lying on another keeps a small, well-spread manifold.

#include <algorithm>
#include <limits>

#include "collision/collision_detection.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

void reduce_contacts(std::vector<ShapeContact>& points, size_t max_points) {
  const size_t n = points.size();
  if (n <= max_points || max_points == 0) return;
  // normals that differ count as distance, on the scale of the patch: points facing other ways
  // (two faces of a corner, a peg's sides) are kept apart
  Bounds box;
  for (const ShapeContact& p : points) box.extend(p.p_W);
  const real extent = (box.max - box.min).norm();
  auto distance = [&](const ShapeContact& a, const ShapeContact& b) {
    return (a.p_W - b.p_W).norm() + extent * (1 - a.n_W.dot(b.n_W));
  };
  // the point farthest from the patch's centre first (a corner of a flat patch, whatever the
  // depths' round-off), then each time the point farthest from those kept; the deepest point last
  Vec3 centre = Vec3::Zero();
  for (const ShapeContact& p : points) centre += p.p_W;
  centre /= static_cast<real>(n);
  size_t first = 0, deepest = 0;
  for (size_t i = 1; i < n; ++i) {
    if ((points[i].p_W - centre).squaredNorm() > (points[first].p_W - centre).squaredNorm()) first = i;
    if (points[i].phi < points[deepest].phi) deepest = i;
  }
  std::vector<real> nearest(n, std::numeric_limits<real>::infinity());
  std::vector<char> kept(n, 0);
  std::vector<size_t> chosen{first};
  kept[first] = 1;
  while (chosen.size() + 1 < max_points) {
    const ShapeContact& last = points[chosen.back()];
    size_t best = n;
    for (size_t i = 0; i < n; ++i) {
      if (kept[i]) continue;
      nearest[i] = std::min(nearest[i], distance(points[i], last));
      if (best == n || nearest[i] > nearest[best]) best = i;
    }
    if (best == n || !(nearest[best] > 0)) break;
    kept[best] = 1;
    chosen.push_back(best);
  }
  if (!kept[deepest]) chosen.push_back(deepest);
  // kept in their original order: the contact list stays deterministic and ordered
  std::sort(chosen.begin(), chosen.end());
  std::vector<ShapeContact> out;
  out.reserve(chosen.size());
  for (size_t i : chosen) out.push_back(points[i]);
  points.swap(out);
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

// Contact reduction: a shape pair's many sample contacts cut down to a few that span the
// contact patch, so that a mesh lying on another keeps a small, well-spread manifold.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "collision/collision_detection.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

void reduce_contacts(std::vector<ShapeContact>& points, size_t max_points) {
  if (points.size() <= max_points || max_points == 0) return;
  Bounds box;
  for (const ShapeContact& p : points) box.extend(p.p_W);
  const real extent = (box.max - box.min).norm();
  // many points (a mesh lying on another gives thousands) are first thinned to the deepest per
  // cell of a 16^3 grid over the patch and per direction of the normal, in their order
  if (points.size() > std::max<size_t>(8 * max_points, kThinningThreshold) && extent > 0) {
    const real cell = extent / 16;
    // the deepest point of each (cell, direction) key (the earliest of equally deep ones; a NaN
    // depth counts as the shallowest), found in one pass: per key the generation that last wrote
    // it and its point, kept per thread so that no call clears them
    constexpr size_t kKeys = 17 * 17 * 17 * 6;
    thread_local std::vector<std::uint32_t> stamp(kKeys, 0);
    thread_local std::vector<std::uint32_t> best(kKeys, 0);
    thread_local std::uint32_t generation = 0;
    if (++generation == 0) std::fill(stamp.begin(), stamp.end(), 0), generation = 1;
    auto depth = [](const ShapeContact& p) { return std::isnan(p.phi) ? std::numeric_limits<real>::infinity() : p.phi; };
    thread_local std::vector<std::uint32_t> key_of;
    key_of.resize(points.size());
    for (size_t i = 0; i < points.size(); ++i) {
      const ShapeContact& p = points[i];
      // the cell, clamped to the grid (a non-finite coordinate to its first cell)
      int c[3];
      for (int a = 0; a < 3; ++a) {
        const real x = (p.p_W[a] - box.min[a]) / cell;
        c[a] = x >= 16 ? 16 : x >= 0 ? static_cast<int>(x) : 0;
      }
      // the normal's dominant axis and its sign: six directions
      int axis = 0;
      p.n_W.cwiseAbs().maxCoeff(&axis);
      const std::uint32_t key = static_cast<std::uint32_t>(c[0] + 17 * (c[1] + 17 * c[2])) * 6 + 2 * axis + (p.n_W[axis] < 0);
      key_of[i] = key;
      if (stamp[key] != generation) {
        stamp[key] = generation, best[key] = static_cast<std::uint32_t>(i);
      } else if (depth(p) < depth(points[best[key]])) {
        best[key] = static_cast<std::uint32_t>(i);
      }
    }
    // each key's point kept, in their order (moved forward in place: best holds original indices)
    size_t k = 0;
    for (size_t i = 0; i < points.size(); ++i)
      if (best[key_of[i]] == i) points[k++] = points[i];
    points.resize(k);
    if (points.size() <= max_points) return;
  }
  const size_t n = points.size();
  // normals that differ count as distance, on the scale of the patch: points facing other ways
  // (two faces of a corner, a peg's sides) are kept apart
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
  // working storage kept per thread: a pair's reduction runs for most shape pairs of a step
  thread_local std::vector<real> nearest;
  thread_local std::vector<char> kept;
  thread_local std::vector<size_t> chosen;
  nearest.assign(n, std::numeric_limits<real>::infinity());
  kept.assign(n, 0);
  chosen.assign(1, first);
  kept[first] = 1;
  // the point not kept farthest from those kept (after the last one kept); false when none is apart
  auto keep_farthest = [&] {
    const ShapeContact& last = points[chosen.back()];
    size_t best = n;
    for (size_t i = 0; i < n; ++i) {
      if (kept[i]) continue;
      nearest[i] = std::min(nearest[i], distance(points[i], last));
      if (best == n || nearest[i] > nearest[best]) best = i;
    }
    if (best == n || !(nearest[best] > 0)) return false;
    kept[best] = 1;
    chosen.push_back(best);
    return true;
  };
  while (chosen.size() + 1 < max_points && keep_farthest()) {
  }
  // the deepest point takes the last place; when it is among those kept, one more spread point
  if (!kept[deepest]) {
    chosen.push_back(deepest);
  } else if (chosen.size() < max_points) {
    keep_farthest();
  }
  // kept in their original order (the contact list stays deterministic and ordered): moved
  // forward in place, each to a place at or before its own
  std::sort(chosen.begin(), chosen.end());
  for (size_t k = 0; k < chosen.size(); ++k) points[k] = points[chosen[k]];
  points.resize(chosen.size());
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

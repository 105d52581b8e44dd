// Contact reduction: a shape pair's many sample contacts cut down to a few that span the
// contact patch, so that a mesh lying on another keeps a small, well-spread manifold.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <tuple>

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
    // (cell and direction, depth, index) of each point; sorted, each key's first is its deepest
    // (the earliest of equally deep ones)
    thread_local std::vector<std::tuple<std::uint64_t, real, size_t>> keyed;
    keyed.clear();
    for (size_t i = 0; i < points.size(); ++i) {
      const ShapeContact& p = points[i];
      const Eigen::Array3i c = ((p.p_W - box.min) / cell).array().floor().cast<int>().min(16);
      // the normal's dominant axis and its sign: six directions
      int axis = 0;
      p.n_W.cwiseAbs().maxCoeff(&axis);
      const std::uint64_t key = static_cast<std::uint64_t>(c.x() + 17 * (c.y() + 17 * c.z())) * 6 + 2 * axis + (p.n_W[axis] < 0);
      // (a NaN depth sorts last, so that the order stays strict)
      keyed.emplace_back(key, std::isnan(p.phi) ? std::numeric_limits<real>::infinity() : p.phi, i);
    }
    std::sort(keyed.begin(), keyed.end());
    thread_local std::vector<char> keep;
    keep.assign(points.size(), 0);
    for (size_t k = 0; k < keyed.size(); ++k)
      if (k == 0 || std::get<0>(keyed[k]) != std::get<0>(keyed[k - 1])) keep[std::get<2>(keyed[k])] = 1;
    size_t k = 0;
    for (size_t i = 0; i < points.size(); ++i)
      if (keep[i]) points[k++] = points[i];
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
  std::vector<real> nearest(n, std::numeric_limits<real>::infinity());
  std::vector<char> kept(n, 0);
  std::vector<size_t> chosen{first};
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
  // kept in their original order: the contact list stays deterministic and ordered
  std::sort(chosen.begin(), chosen.end());
  std::vector<ShapeContact> out;
  out.reserve(chosen.size());
  for (size_t i : chosen) out.push_back(points[i]);
  points.swap(out);
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

// Closest-point queries on triangle meshes: the exact point-triangle test and a median-split
// bounding-volume hierarchy searched nearest-child first with distance-bound pruning.

#include "shape/triangle_bvh.h"

#include <algorithm>
#include <limits>

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

ClosestPoint closest_point_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                       const Eigen::Vector3d& c) {
  using F = TriangleFeature;
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return {a, F::VertexA};
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return {b, F::VertexB};
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return {a + ab * (d1 / (d1 - d3)), F::EdgeAB};
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return {c, F::VertexC};
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return {a + ac * (d2 / (d2 - d6)), F::EdgeCA};
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return {b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6))), F::EdgeBC};
  const double denom = 1 / (va + vb + vc);
  return {a + ab * (vb * denom) + ac * (vc * denom), F::Face};
}

namespace {
constexpr int kLeafSize = 4;

// Squared distance from p to the box [lo, hi] (0 inside).
double box_distance_squared(const Eigen::Vector3d& p, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  return (lo - p).cwiseMax(p - hi).cwiseMax(0.0).squaredNorm();
}
}  // namespace

TriangleBvh::TriangleBvh(const std::vector<Eigen::Vector3d>& vertices, const std::vector<std::array<int, 3>>& triangles)
    : vertices_(vertices), triangles_(triangles) {
  const int n = static_cast<int>(triangles.size());
  order_.resize(static_cast<size_t>(n));
  centroids_.resize(static_cast<size_t>(n));
  for (int t = 0; t < n; ++t) {
    order_[t] = t;
    const auto& tri = triangles[t];
    centroids_[t] = (vertices[tri[0]] + vertices[tri[1]] + vertices[tri[2]]) / 3;
  }
  nodes_.reserve(static_cast<size_t>(2 * n / kLeafSize + 2));
  if (n > 0) build(0, n);
}

int TriangleBvh::build(int first, int count) {
  const int index = static_cast<int>(nodes_.size());
  nodes_.emplace_back();
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  Eigen::Vector3d clo = lo, chi = hi;
  for (int i = first; i < first + count; ++i) {
    for (int v : triangles_[order_[i]]) lo = lo.cwiseMin(vertices_[v]), hi = hi.cwiseMax(vertices_[v]);
    clo = clo.cwiseMin(centroids_[order_[i]]), chi = chi.cwiseMax(centroids_[order_[i]]);
  }
  nodes_[index].lo = lo;
  nodes_[index].hi = hi;
  if (count <= kLeafSize) {
    nodes_[index].first = first;
    nodes_[index].count = count;
    return index;
  }
  // split at the median centroid along the widest axis of the centroids
  int axis;
  (chi - clo).maxCoeff(&axis);
  const int half = count / 2;
  std::nth_element(order_.begin() + first, order_.begin() + first + half, order_.begin() + first + count,
                   [&](int x, int y) { return centroids_[x][axis] < centroids_[y][axis]; });
  const int left = build(first, half);
  const int right = build(first + half, count - half);
  nodes_[index].left = left;
  nodes_[index].right = right;
  return index;
}

void TriangleBvh::test_triangle(const Eigen::Vector3d& p, int t, Hit& best) const {
  const auto& tri = triangles_[t];
  const ClosestPoint cp = closest_point_on_triangle(p, vertices_[tri[0]], vertices_[tri[1]], vertices_[tri[2]]);
  const double d2 = (cp.point - p).squaredNorm();
  if (d2 < best.distance_squared) best = {d2, t, cp};
}

TriangleBvh::Hit TriangleBvh::closest(const Eigen::Vector3d& p, int hint) const {
  Hit best;
  best.distance_squared = std::numeric_limits<double>::infinity();
  if (nodes_.empty()) return best;
  if (hint >= 0 && hint < static_cast<int>(triangles_.size())) test_triangle(p, hint, best);
  struct Entry {
    int node;
    double bound;
  };
  Entry stack[128];
  int top = 0;
  stack[top++] = {0, box_distance_squared(p, nodes_[0].lo, nodes_[0].hi)};
  while (top > 0) {
    const Entry e = stack[--top];
    if (e.bound >= best.distance_squared) continue;
    const Node& node = nodes_[e.node];
    if (node.left < 0) {
      for (int i = node.first; i < node.first + node.count; ++i) test_triangle(p, order_[i], best);
      continue;
    }
    const double bl = box_distance_squared(p, nodes_[node.left].lo, nodes_[node.left].hi);
    const double br = box_distance_squared(p, nodes_[node.right].lo, nodes_[node.right].hi);
    // push the farther child first so that the nearer one is searched first
    if (bl < br) {
      stack[top++] = {node.right, br};
      stack[top++] = {node.left, bl};
    } else {
      stack[top++] = {node.left, bl};
      stack[top++] = {node.right, br};
    }
  }
  return best;
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

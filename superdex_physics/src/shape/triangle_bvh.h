#pragma once
// A bounding-volume hierarchy over the triangles of a mesh for closest-point queries, and the
// exact point-triangle distance with the feature (vertex, edge, face) the closest point lies on.
// Works in double precision whatever `real` is.

#include <Eigen/Core>

#include <array>
#include <vector>

#include "superdex/physics/real.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

// Where on a triangle (a, b, c) the closest point lies.
enum class TriangleFeature { VertexA, VertexB, VertexC, EdgeAB, EdgeBC, EdgeCA, Face };

struct ClosestPoint {
  Eigen::Vector3d point;
  TriangleFeature feature = TriangleFeature::Face;
};

// Closest point to p on triangle (a, b, c) (Ericson, Real-Time Collision Detection, 5.1.5).
ClosestPoint closest_point_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                       const Eigen::Vector3d& c);

class TriangleBvh {
 public:
  struct Hit {
    double distance_squared = 0;
    int triangle = -1;
    ClosestPoint closest;
  };

  TriangleBvh(const std::vector<Eigen::Vector3d>& vertices, const std::vector<std::array<int, 3>>& triangles);

  // The closest triangle to p. `hint`: a triangle likely to be close (e.g. the answer for a
  // neighbouring point), tested first to prune the search; -1 for none.
  Hit closest(const Eigen::Vector3d& p, int hint = -1) const;

 private:
  struct Node {
    Eigen::Vector3d lo, hi;
    int left = -1;   // inner node: the two children (-1 for a leaf)
    int right = -1;
    int first = 0;   // leaf: triangles order_[first, first + count)
    int count = 0;
  };
  int build(int first, int count);
  void test_triangle(const Eigen::Vector3d& p, int t, Hit& best) const;

  const std::vector<Eigen::Vector3d>& vertices_;
  const std::vector<std::array<int, 3>>& triangles_;
  std::vector<int> order_;
  std::vector<Eigen::Vector3d> centroids_;
  std::vector<Node> nodes_;
};

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

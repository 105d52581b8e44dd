// The distance between two convex polyhedra by GJK (Gilbert, Johnson and Keerthi): a simplex in
// their Minkowski difference walked towards the origin, its closest point found by Voronoi
// regions (Ericson, Real-Time Collision Detection, 5.1), the witness points carried along.

#include <cmath>
#include <limits>

#include "collision/collision_detection.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace {

// A point of the Minkowski difference w = a - b, with a on shape a and b on shape b.
struct Vertex {
  Vec3 w, a, b;
};

// The simplex's closest point to the origin: barycentric weights over its vertices; vertices
// whose weight is zero are dropped. Returns false when the origin lies inside a tetrahedron.
bool closest_on_simplex(Vertex* s, int& n, real* lambda) {
  auto apply = [&](const int* idx, const real* wts, int m) {
    Vertex kept[4];
    for (int i = 0; i < m; ++i) kept[i] = s[idx[i]], lambda[i] = wts[i];
    for (int i = 0; i < m; ++i) s[i] = kept[i];
    n = m;
  };
  if (n == 1) {
    lambda[0] = 1;
    return true;
  }
  if (n == 2) {
    const Vec3 ab = s[1].w - s[0].w;
    const real len2 = ab.squaredNorm();
    const real t = len2 > 0 ? -s[0].w.dot(ab) / len2 : real(0);
    const int idx[2] = {t >= 1 ? 1 : 0, 1};
    const real wts[2] = {t <= 0 || t >= 1 ? real(1) : 1 - t, t};
    apply(idx, wts, t <= 0 || t >= 1 ? 1 : 2);
    return true;
  }
  // a triangle's regions: its corners, edges and face
  auto triangle = [&](int ia, int ib, int ic, int* idx, real* wts, int& m) {
    const Vec3 &a = s[ia].w, &b = s[ib].w, &c = s[ic].w;
    const Vec3 ab = b - a, ac = c - a;
    const real d1 = -ab.dot(a), d2 = -ac.dot(a);
    if (d1 <= 0 && d2 <= 0) return m = 1, idx[0] = ia, wts[0] = 1, void();
    const real d3 = -ab.dot(b), d4 = -ac.dot(b);
    if (d3 >= 0 && d4 <= d3) return m = 1, idx[0] = ib, wts[0] = 1, void();
    const real vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) {
      const real v = d1 / (d1 - d3);
      return m = 2, idx[0] = ia, idx[1] = ib, wts[0] = 1 - v, wts[1] = v, void();
    }
    const real d5 = -ab.dot(c), d6 = -ac.dot(c);
    if (d6 >= 0 && d5 <= d6) return m = 1, idx[0] = ic, wts[0] = 1, void();
    const real vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) {
      const real w = d2 / (d2 - d6);
      return m = 2, idx[0] = ia, idx[1] = ic, wts[0] = 1 - w, wts[1] = w, void();
    }
    const real va = d3 * d6 - d5 * d4;
    if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) {
      const real w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
      return m = 2, idx[0] = ib, idx[1] = ic, wts[0] = 1 - w, wts[1] = w, void();
    }
    const real denom = 1 / (va + vb + vc);
    const real v = vb * denom, w = vc * denom;
    m = 3, idx[0] = ia, idx[1] = ib, idx[2] = ic, wts[0] = 1 - v - w, wts[1] = v, wts[2] = w;
  };
  if (n == 3) {
    int idx[3], m;
    real wts[3];
    triangle(0, 1, 2, idx, wts, m);
    apply(idx, wts, m);
    return true;
  }
  // a tetrahedron: the nearest of the faces whose outer side the origin is on; inside none, the
  // origin is inside
  static constexpr int kFaces[4][4] = {{0, 1, 2, 3}, {0, 3, 1, 2}, {0, 2, 3, 1}, {1, 3, 2, 0}};
  real best = std::numeric_limits<real>::infinity();
  int best_idx[3] = {0, 0, 0}, best_m = 0;
  real best_wts[3] = {0, 0, 0};
  bool outside_any = false;
  for (const auto& f : kFaces) {
    const Vec3 nrm = (s[f[1]].w - s[f[0]].w).cross(s[f[2]].w - s[f[0]].w);
    const real origin_side = -nrm.dot(s[f[0]].w), other_side = nrm.dot(s[f[3]].w - s[f[0]].w);
    // the origin beyond this face (or the tetrahedron flat there)
    if (origin_side * other_side > 0 && std::abs(other_side) > 0) continue;
    outside_any = true;
    int idx[3], m;
    real wts[3];
    triangle(f[0], f[1], f[2], idx, wts, m);
    Vec3 p = Vec3::Zero();
    for (int i = 0; i < m; ++i) p += wts[i] * s[idx[i]].w;
    if (p.squaredNorm() < best) {
      best = p.squaredNorm(), best_m = m;
      for (int i = 0; i < m; ++i) best_idx[i] = idx[i], best_wts[i] = wts[i];
    }
  }
  if (!outside_any) return false;
  apply(best_idx, best_wts, best_m);
  return true;
}

}  // namespace

ConvexDistance convex_distance(const ConvexFaces& fa, const SpatialTransform& X_WA, const ConvexFaces& fb, const SpatialTransform& X_WB,
                               real stop_beyond) {
  int hint_a = -1, hint_b = -1;  // the last support corners (-1: none yet)
  // the difference's support point in direction d: a's farthest along d less b's farthest along -d
  auto support = [&](const Vec3& d) {
    hint_a = fa.support(X_WA.R.transpose() * d, hint_a);
    hint_b = fb.support(-(X_WB.R.transpose() * d), hint_b);
    Vertex v;
    v.a = X_WA.R * fa.corners[hint_a] + X_WA.p;
    v.b = X_WB.R * fb.corners[hint_b] + X_WB.p;
    v.w = v.a - v.b;
    return v;
  };
  ConvexDistance out;
  Vertex s[4];
  real lambda[4] = {1, 0, 0, 0};
  int n = 1;
  const Vec3 start = (X_WA.R * fa.centre + X_WA.p) - (X_WB.R * fb.centre + X_WB.p);
  s[0] = support(start.squaredNorm() > 0 ? Vec3(-start) : Vec3(-Vec3::UnitX()));
  Vec3 v = s[0].w;
  // converged when the next support point brings the origin no nearer than this (relative), or
  // the distance is within a millionth of the shapes' size of its lower bound (curved surfaces
  // meshed finely converge slowly, and contacts need no finer distances)
  const real eps = 64 * std::numeric_limits<real>::epsilon();
  const real tolerance = real(1e-6) * std::max(fa.radius, fb.radius);
  for (int iter = 0; iter < 64; ++iter) {
    const real vv = v.squaredNorm();
    if (!(vv > 0)) {
      out.overlap = true;
      return out;
    }
    const Vertex p = support(-v);
    // every point of the difference lies at least v . p / |v| from the origin (the plane through
    // p normal to v bounds it): beyond stop_beyond, the distance is not needed
    const real lower_bound = v.dot(p.w) / std::sqrt(vv);
    if (lower_bound > stop_beyond) {
      out.distance = lower_bound;
      out.beyond = true;
      out.normal = v / std::sqrt(vv);
      return out;
    }
    if (vv - v.dot(p.w) <= eps * vv || std::sqrt(vv) - lower_bound <= tolerance) break;
    bool repeated = false;
    for (int i = 0; i < n; ++i) repeated |= (s[i].w - p.w).squaredNorm() == 0;
    if (repeated) break;
    s[n++] = p;
    if (!closest_on_simplex(s, n, lambda)) {
      out.overlap = true;
      return out;
    }
    Vec3 next = Vec3::Zero();
    for (int i = 0; i < n; ++i) next += lambda[i] * s[i].w;
    // round-off: no progress
    if (next.squaredNorm() >= vv) break;
    v = next;
  }
  out.p_a = Vec3::Zero();
  out.p_b = Vec3::Zero();
  for (int i = 0; i < n; ++i) out.p_a += lambda[i] * s[i].a, out.p_b += lambda[i] * s[i].b;
  out.distance = (out.p_a - out.p_b).norm();
  out.overlap = !(out.distance > 0);
  // the direction: the closest point's own where the simplex is a triangle (the face of the
  // difference it lies on, exact however small the distance); else the closest points'
  out.normal = out.overlap ? Vec3::UnitZ() : Vec3((out.p_a - out.p_b) / out.distance);
  if (n == 3) {
    Vec3 face = (s[1].w - s[0].w).cross(s[2].w - s[0].w);
    if (face.norm() > 0) {
      face.normalize();
      if (face.dot(out.normal) < 0) face = -face;
      out.normal = face;
    }
  }
  return out;
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

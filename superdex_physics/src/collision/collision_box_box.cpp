// Box-box contact by the separating axis test (3 + 3 face axes, 9 edge axes) and, for a face
// axis, clipping the incident face against the reference face's side planes; for an edge
// axis, the closest points of the two supporting edges.

#include <cmath>

#include "collision/collision_detection.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace {

struct PosedBox {
  Mat3 R;  // axes in world (columns)
  Vec3 c;  // centre in world
  Vec3 h;  // half extents

  real radius_along(const Vec3& L) const {
    return h.x() * std::abs(R.col(0).dot(L)) + h.y() * std::abs(R.col(1).dot(L)) + h.z() * std::abs(R.col(2).dot(L));
  }
};

// The face of `b` whose outward normal is most aligned with `dir`, as 4 world corners (counter-clockwise).
std::array<Vec3, 4> face_towards(const PosedBox& b, const Vec3& dir, int& axis, real& sign) {
  axis = 0;
  real best = -1;
  for (int k = 0; k < 3; ++k) {
    const real d = std::abs(b.R.col(k).dot(dir));
    if (d > best) best = d, axis = k;
  }
  sign = b.R.col(axis).dot(dir) >= 0 ? 1 : -1;
  const int u = (axis + 1) % 3, v = (axis + 2) % 3;
  const Vec3 fc = b.c + sign * b.h[axis] * b.R.col(axis);
  const Vec3 eu = b.h[u] * b.R.col(u), ev = b.h[v] * b.R.col(v);
  return {fc + eu + ev, fc - eu + ev, fc - eu - ev, fc + eu - ev};
}

// The support edge of `b` in direction `dir` parallel to axis k: its two ends.
void support_edge(const PosedBox& b, int k, const Vec3& dir, Vec3& e0, Vec3& e1) {
  Vec3 p = b.c;
  for (int j = 0; j < 3; ++j)
    if (j != k) p += (b.R.col(j).dot(dir) >= 0 ? 1 : -1) * b.h[j] * b.R.col(j);
  e0 = p - b.h[k] * b.R.col(k);
  e1 = p + b.h[k] * b.R.col(k);
}

}  // namespace

void collide_box_box(const BoxShape& sa, const SpatialTransform& X_WA, const BoxShape& sb, const SpatialTransform& X_WB,
                     real margin, std::vector<ShapeContact>& out) {
  const PosedBox A{X_WA.R, X_WA.p, sa.half_extents}, B{X_WB.R, X_WB.p, sb.half_extents};
  const Vec3 T = A.c - B.c;  // from b to a
  // separating axis with the largest separation; face axes preferred over nearly equal edge axes
  real best_sep = -std::numeric_limits<real>::infinity();
  Vec3 best_axis = Vec3::UnitZ();
  int best_kind = -1, edge_a = 0, edge_b = 0;
  // ties go to the earlier axis (A's faces, then B's, then edges) unless clearly better, so that
  // flush faces do not switch reference face from step to step
  const real size = A.h.norm() + B.h.norm();
  auto test = [&](Vec3 L, int kind, int ea, int eb) {
    const real len = L.norm();
    if (len < real(1e-6)) return;
    L /= len;
    if (L.dot(T) < 0) L = -L;  // orient from b towards a
    const real sep = L.dot(T) - A.radius_along(L) - B.radius_along(L);
    const real tolerance = best_kind < 0 ? 0 : (kind == 2 ? real(1e-4) : real(1e-5)) * size;
    if (best_kind < 0 || sep > best_sep + tolerance) best_sep = sep, best_axis = L, best_kind = kind, edge_a = ea, edge_b = eb;
  };
  for (int k = 0; k < 3; ++k) test(A.R.col(k), 0, k, 0);
  for (int k = 0; k < 3; ++k) test(B.R.col(k), 1, 0, k);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) test(A.R.col(i).cross(B.R.col(j)), 2, i, j);
  if (best_sep >= margin || best_kind < 0) return;
  const Vec3 n = best_axis;  // from b towards a

  if (best_kind == 2) {
    Vec3 a0, a1, b0, b1, pa, pb;
    support_edge(A, edge_a, -n, a0, a1);
    support_edge(B, edge_b, n, b0, b1);
    closest_segment_points(a0, a1, b0, b1, pa, pb);
    const real phi = n.dot(pa - pb);
    out.push_back({(pa + pb) / 2, n, phi});
    return;
  }
  // reference face on the box whose axis separates; incident face on the other
  const bool ref_is_b = best_kind == 1;
  const PosedBox& ref = ref_is_b ? B : A;
  const PosedBox& inc = ref_is_b ? A : B;
  const Vec3 n_ref = ref_is_b ? n : Vec3(-n);  // outward normal of the reference face
  int ref_axis;
  real ref_sign;
  const auto ref_face = face_towards(ref, n_ref, ref_axis, ref_sign);
  int inc_axis;
  real inc_sign;
  const auto inc_face = face_towards(inc, -n_ref, inc_axis, inc_sign);
  std::vector<Vec3> poly(inc_face.begin(), inc_face.end()), clipped;
  // clip by the four side planes of the reference face
  const Vec3 ref_centre = (ref_face[0] + ref_face[2]) / 2;
  for (int k = 0; k < 3 && !poly.empty(); ++k) {
    if (k == ref_axis) continue;
    const Vec3 side = ref.R.col(k);
    const real tol = real(1e-5) * size;
    clip_polygon(poly, side, side.dot(ref.c) + ref.h[k], tol, clipped);
    poly.swap(clipped);
    if (poly.empty()) break;
    clip_polygon(poly, -side, -side.dot(ref.c) + ref.h[k], tol, clipped);
    poly.swap(clipped);
  }
  for (const Vec3& p : poly) {
    const real phi = n_ref.dot(p - ref_centre);
    if (phi >= margin) continue;
    out.push_back({p - n_ref * (phi / 2), n, phi});
  }
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

// Convex-convex contact (convex meshes and boxes): the gap and normal from GJK's closest points
// when the two are apart, from EPA (libccd) when they overlap; then, when the normal is a face
// normal of either side, the other side's face most opposed to it clipped against that reference
// face, as a box pair's faces are; else one point between the two sides.

#include <cmath>
#include <limits>
#include <optional>

extern "C" {
#include <ccd/ccd.h>
}

#include "collision/collision_detection.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace {

// A convex shape posed in the world, for libccd.
struct PosedConvex {
  const ConvexFaces* faces;
  const SpatialTransform* X_WS;
  mutable int last = -1;  // the last support corner: where the next search starts (-1: none yet)
};

Vec3 from_ccd(const ccd_vec3_t* v) { return Vec3(real(v->v[0]), real(v->v[1]), real(v->v[2])); }
void to_ccd(const Vec3& x, ccd_vec3_t* v) { ccdVec3Set(v, x.x(), x.y(), x.z()); }

void support(const void* obj, const ccd_vec3_t* dir_W, ccd_vec3_t* out) {
  const auto& c = *static_cast<const PosedConvex*>(obj);
  c.last = c.faces->support(c.X_WS->R.transpose() * from_ccd(dir_W), c.last);
  to_ccd(c.X_WS->R * c.faces->corners[c.last] + c.X_WS->p, out);
}

void centre(const void* obj, ccd_vec3_t* out) {
  const auto& c = *static_cast<const PosedConvex*>(obj);
  to_ccd(c.X_WS->R * c.faces->centre + c.X_WS->p, out);
}

// The face of `f` whose outward normal (world) is most aligned with the unit `dir_W`, and that
// alignment.
int face_towards(const ConvexFaces& f, const Mat3& R_WS, const Vec3& dir_W, real& alignment) {
  return f.face_towards(R_WS.transpose() * dir_W, alignment);
}

// The edge of `f` (posed by X_WS) farthest along `dir_W`: the farthest corner and, of its
// neighbours (of every corner without an edge graph), the next farthest.
void supporting_edge(const ConvexFaces& f, const SpatialTransform& X_WS, const Vec3& dir_W, Vec3& e0, Vec3& e1) {
  const Vec3 d_S = X_WS.R.transpose() * dir_W;
  const int v = f.support(d_S);
  int w = -1;
  real best = -std::numeric_limits<real>::infinity();
  auto consider = [&](int c) {
    if (c == v) return;
    const real d = f.corners[c].dot(d_S);
    if (d > best) best = d, w = c;
  };
  if (f.neighbour_start.size() == f.corners.size() + 1) {
    for (int k = f.neighbour_start[v]; k < f.neighbour_start[v + 1]; ++k) consider(f.neighbours[k]);
  } else {
    for (int c = 0; c < static_cast<int>(f.corners.size()); ++c) consider(c);
  }
  e0 = X_WS.R * f.corners[v] + X_WS.p;
  e1 = w >= 0 ? Vec3(X_WS.R * f.corners[w] + X_WS.p) : e0;
}

}  // namespace

void keep_at_most(std::vector<ShapeContact>& out, size_t first, size_t max_points) {
  if (out.size() - first <= max_points) return;
  thread_local std::vector<ShapeContact> tail;
  tail.assign(out.begin() + static_cast<std::ptrdiff_t>(first), out.end());
  reduce_contacts(tail, max_points);
  out.resize(first);
  out.insert(out.end(), tail.begin(), tail.end());
}

void collide_convex_convex(const ConvexFaces& a, const SpatialTransform& X_WA, const ConvexFaces& b,
                           const SpatialTransform& X_WB, real margin, std::vector<ShapeContact>& out) {
  if (a.corners.empty() || b.corners.empty()) return;
  // the pair's size, for tolerances
  const real size = std::max(a.radius, b.radius);
  real gap = 0;
  Vec3 n;
  std::optional<Vec3> witness;  // the contact point, when the closest points give it
  const ConvexDistance d = convex_distance(a, X_WA, b, X_WB, margin);
  if (d.beyond) return;
  // GJK ends near (not at) the origin for shapes that touch or overlap: below this it is EPA's
  const real touching = std::max(real(1e-9) * size, 64 * std::numeric_limits<real>::epsilon() * (1 + X_WA.p.norm() + X_WB.p.norm()));
  auto from_closest_points = [&] {
    gap = d.distance;
    n = d.normal;
    witness = (d.p_a + d.p_b) / 2;
  };
  if (!d.overlap && d.distance > touching) {
    // apart: GJK's distance and closest points
    if (d.distance >= margin) return;
    from_closest_points();
  } else {
    // overlapping: EPA's minimal translation (b moved by `depth` along `dir` leaves a)
    PosedConvex A{&a, &X_WA}, B{&b, &X_WB};
    ccd_t ccd;
    CCD_INIT(&ccd);
    ccd.support1 = support;
    ccd.support2 = support;
    ccd.center1 = centre;
    ccd.center2 = centre;
    ccd.max_iterations = 100;
    // EPA stops once a new support point advances the polytope's nearest face by little: its
    // advance times the face's distance (m^2) below the square of a millionth of the pair's size,
    // or below the support points' round-off times that size (else, in float, EPA chases the
    // round-off, its polytope growing without end)
    const double tol = 1e-6 * std::max(double(size), 1e-3);
    const double round_off = 16.0 * std::numeric_limits<real>::epsilon() * (1.0 + X_WA.p.norm() + X_WB.p.norm());
    ccd.epa_tolerance = std::max(tol * tol, round_off * std::max(double(size), 1e-3));
    ccd.dist_tolerance = tol;
    ccd_real_t depth = 0;
    ccd_vec3_t dir, pos;
    if (ccdGJKPenetration(&A, &B, &ccd, &depth, &dir, &pos) == 0) {
      n = -from_ccd(&dir);
      gap = -real(depth);
    } else if (!d.overlap && d.distance > 0) {
      from_closest_points();  // touching
    } else {
      return;
    }
  }
  if (!(n.norm() > 0) || !n.allFinite() || !std::isfinite(gap)) return;
  n.normalize();  // from b towards a
  // one contact: at the closest points, or midway between the closest points of the two sides'
  // supporting edges (an edge crossing an edge, or a corner)
  auto single_contact = [&] {
    if (witness) return out.push_back({*witness, n, gap});
    Vec3 a0, a1, b0, b1, pa, pb;
    supporting_edge(a, X_WA, -n, a0, a1);
    supporting_edge(b, X_WB, n, b0, b1);
    closest_segment_points(a0, a1, b0, b1, pa, pb);
    out.push_back({(pa + pb) / 2, n, gap});
  };

  // a face of either side that the normal is (nearly) perpendicular to: the reference face
  real align_a, align_b;
  const int face_a = face_towards(a, X_WA.R, -n, align_a);
  const int face_b = face_towards(b, X_WB.R, n, align_b);
  constexpr real kFaceCos = real(0.9995);  // within about 1.8 degrees
  if (std::max(align_a, align_b) < kFaceCos) return single_contact();
  const bool ref_is_b = align_b >= align_a;
  const ConvexFaces& ref = ref_is_b ? b : a;
  const ConvexFaces& inc = ref_is_b ? a : b;
  const SpatialTransform& X_WR = ref_is_b ? X_WB : X_WA;
  const SpatialTransform& X_WI = ref_is_b ? X_WA : X_WB;
  const int rf = ref_is_b ? face_b : face_a;
  const Vec3 n_ref = X_WR.R * ref.normals[rf];  // outward from the reference side
  real unused;
  const int inc_face = face_towards(inc, X_WI.R, -n_ref, unused);
  thread_local std::vector<Vec3> poly, clipped;
  poly.clear();
  for (int k = inc.loop_start[inc_face]; k < inc.loop_start[inc_face + 1]; ++k) poly.push_back(X_WI.R * inc.corners[inc.loops[k]] + X_WI.p);
  // clipped by the side planes of the reference face, each through an edge, facing out
  const int r0 = ref.loop_start[rf], r1 = ref.loop_start[rf + 1];
  const real side_tol = real(1e-6) * size;
  for (int k = r0; k < r1 && !poly.empty(); ++k) {
    const Vec3 p = X_WR.R * ref.corners[ref.loops[k]] + X_WR.p;
    const Vec3 q = X_WR.R * ref.corners[ref.loops[k + 1 < r1 ? k + 1 : r0]] + X_WR.p;
    const Vec3 side = (q - p).cross(n_ref);
    const real len = side.norm();
    if (!(len > std::numeric_limits<real>::epsilon() * size * size)) continue;
    clip_polygon(poly, side / len, (side / len).dot(p), side_tol, clipped);
    poly.swap(clipped);
  }
  const real ref_offset = ref.offsets[rf] + n_ref.dot(X_WR.p);  // world plane n_ref . x = ref_offset
  const Vec3 n_out = ref_is_b ? n_ref : Vec3(-n_ref);            // from b towards a
  // the face's direction must part the two as the contact normal does (GJK's and EPA's gaps are
  // exact; along any other direction the gap is smaller): else the contact is an edge's, near
  // the face's normal, or the deepest point was clipped away
  real face_gap = std::numeric_limits<real>::infinity();
  for (const Vec3& p : poly) face_gap = std::min(face_gap, n_ref.dot(p) - ref_offset);
  const real tol_gap = real(4e-6) * size + 16 * std::numeric_limits<real>::epsilon() * (1 + X_WA.p.norm() + X_WB.p.norm());
  if (poly.empty() || std::abs(face_gap - gap) > tol_gap) return single_contact();
  const size_t first = out.size();
  for (const Vec3& p : poly) {
    const real phi = n_ref.dot(p) - ref_offset;
    if (phi >= margin) continue;
    out.push_back({p - n_ref * (phi / 2), n_out, phi});
  }
  keep_at_most(out, first, kMaxConvexContacts);
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

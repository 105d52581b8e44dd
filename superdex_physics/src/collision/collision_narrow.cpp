// Narrow phase: contact points between two posed shapes. Exact analytic tests for sphere,
// capsule and plane pairs and sphere/capsule against any distance field; otherwise the
// surface samples of each shape against the other's signed-distance field.

#include <algorithm>
#include <cmath>
#include <limits>

#include "collision/collision_detection.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace {

// A ball (centre c, radius r) against a point-queryable field; normal from the field towards the
// ball. Returns the ball's signed gap (m).
real ball_vs_field(const Vec3& c_W, real r, const LinkCollider& field, const SpatialTransform& X_WF, real margin,
                   std::vector<ShapeContact>& out) {
  Vec3 g_F;
  const Vec3 c_F = X_WF.R.transpose() * (c_W - X_WF.p);
  const real phi = shape_signed_distance(field.shape, c_F, &g_F) - r;
  if (phi >= margin) return phi;
  const Vec3 n = X_WF.R * g_F;
  out.push_back({c_W - n * (r + phi / 2), n, phi});
  return phi;
}

void ball_vs_ball(const Vec3& ca, real ra, const Vec3& cb, real rb, real margin, std::vector<ShapeContact>& out) {
  const Vec3 d = ca - cb;
  const real dist = d.norm();
  const real phi = dist - ra - rb;
  if (phi >= margin) return;
  const Vec3 n = dist > real(1e-12) ? Vec3(d / dist) : Vec3::UnitZ();
  out.push_back({ca - n * (ra + phi / 2), n, phi});
}

// The balls that make a rounded shape, posed in the world: one for a sphere; for a capsule the
// segment ends and interior balls no further apart than the radius (so that its side meets edges
// and faces), at most 17. A centre is computed when asked for.
struct RoundedBalls {
  static constexpr int kMaxSegments = 16;
  const SpatialTransform* X_WS = nullptr;
  const SphereShape* sphere = nullptr;    // or
  const CapsuleShape* capsule = nullptr;
  int count = 0;     // balls
  real radius = 0;   // theirs (m)
  real spacing = 0;  // between consecutive centres (m); 0 for a sphere
  Vec3 centre(int k) const {
    if (sphere) return X_WS->R * sphere->center + X_WS->p;
    const real z = -capsule->half_length + 2 * capsule->half_length * k / (count - 1);
    return X_WS->R * Vec3(0, 0, z) + X_WS->p;
  }
  Vec3 front() const { return centre(0); }
  Vec3 back() const { return centre(count - 1); }
};

// `c`'s balls when it is a rounded shape (sphere or capsule) posed at X_WS.
bool rounded_balls(const LinkCollider& c, const SpatialTransform& X_WS, RoundedBalls& balls) {
  balls = RoundedBalls{};
  balls.X_WS = &X_WS;
  if (auto* s = std::get_if<SphereShape>(&c.shape)) {
    balls.sphere = s;
    balls.count = 1;
    balls.radius = s->radius;
    return true;
  }
  if (auto* s = std::get_if<CapsuleShape>(&c.shape)) {
    const int segments = std::max(1, static_cast<int>(std::ceil(2 * s->half_length / std::max(s->radius, real(1e-6)))));
    const int used = std::min(segments, RoundedBalls::kMaxSegments);
    balls.capsule = s;
    balls.count = used + 1;
    balls.radius = s->radius;
    balls.spacing = 2 * s->half_length / used;
    return true;
  }
  return false;
}

// A rounded shape's balls against a field. An exact distance field (every shape but a mesh's
// sampled one) changes by at most the distance moved, so a ball with gap phi keeps the balls
// within phi - margin of it along the line of centres out of contact: those are skipped without
// a query (sphere tracing along the capsule's core).
void balls_vs_field(const RoundedBalls& balls, const LinkCollider& field, const SpatialTransform& X_WF, real margin,
                    std::vector<ShapeContact>& out) {
  const bool exact = !std::holds_alternative<MeshShape>(field.shape);
  for (int k = 0; k < balls.count;) {
    const Vec3 c_W = balls.centre(k);
    const real phi = ball_vs_field(c_W, balls.radius, field, X_WF, margin, out);
    ++k;
    if (!exact || balls.spacing <= 0) continue;
    // the gap's round-off, from the coordinates' magnitude
    const real round_off = 64 * std::numeric_limits<real>::epsilon() * (1 + c_W.cwiseAbs().maxCoeff() + X_WF.p.cwiseAbs().maxCoeff());
    const real clear = phi - margin - round_off;
    if (clear > 0) k += static_cast<int>(std::min<real>(clear / balls.spacing, real(balls.count)));
  }
}

// A convex shape's corners and faces: a convex mesh's own, a box's made here (per thread, per
// side); null for other shapes.
const ConvexFaces* convex_faces(const ShapeGeometry& shape) {
  if (auto* m = std::get_if<MeshShape>(&shape)) return m->faces.get();
  if (auto* box = std::get_if<BoxShape>(&shape)) {
    thread_local ConvexFaces made[2];
    thread_local int next = 0;
    ConvexFaces& f = made[next];
    next ^= 1;
    box_convex_faces(box->half_extents, f);
    return &f;
  }
  return nullptr;
}

bool has_field(const LinkCollider& c) {
  if (auto* m = std::get_if<MeshShape>(&c.shape)) return m->sdf != nullptr;
  return true;
}

void points_vs_field(const LinkCollider& a, const SpatialTransform& X_WA, const LinkCollider& field,
                     const SpatialTransform& X_WF, real margin, std::vector<ShapeContact>& out) {
  if (!has_field(field)) return;
  const SpatialTransform X_FA = X_WF.inverse() * X_WA;
  // a sample outside the field's bounds grown by the margin is at least the margin away
  const Vec3 lo = field.aabb_S.min.array() - margin, hi = field.aabb_S.max.array() + margin;
  for (const Vec3& s_A : a.samples_S) {
    Vec3 g_F;
    const Vec3 p_F = X_FA.R * s_A + X_FA.p;
    if ((p_F.array() < lo.array()).any() || (p_F.array() > hi.array()).any()) continue;
    const real phi = shape_signed_distance(field.shape, p_F, &g_F);
    if (phi >= margin) continue;
    const Vec3 n = X_WF.R * g_F;
    out.push_back({X_WA.R * s_A + X_WA.p - n * (phi / 2), n, phi});
  }
}

// Contacts with the normal flipped: from the caller's b towards a.
void flip_into(std::vector<ShapeContact>& tmp, std::vector<ShapeContact>& out) {
  for (ShapeContact& c : tmp) out.push_back({c.p_W, -c.n_W, c.phi});
  tmp.clear();
}

}  // namespace

void collide_shapes(const LinkCollider& a, const SpatialTransform& X_WA, const LinkCollider& b,
                    const SpatialTransform& X_WB, real margin, std::vector<ShapeContact>& out) {
  const bool a_plane = std::holds_alternative<PlaneShape>(a.shape), b_plane = std::holds_alternative<PlaneShape>(b.shape);
  if (a_plane && b_plane) return;
  std::vector<ShapeContact> tmp;
  if (a_plane) {
    collide_shapes(b, X_WB, a, X_WA, margin, tmp);
    flip_into(tmp, out);
    return;
  }
  if (b_plane) {
    const WorldPlane pl = world_plane(std::get<PlaneShape>(b.shape), X_WB);
    auto add = [&](const Vec3& p, real r) {
      const real phi = pl.n.dot(p) - pl.d - r;
      if (phi < margin) out.push_back({p - pl.n * (r + phi / 2), pl.n, phi});
    };
    if (auto* sphere = std::get_if<SphereShape>(&a.shape)) {
      add(X_WA.R * sphere->center + X_WA.p, sphere->radius);
    } else if (auto* cap = std::get_if<CapsuleShape>(&a.shape)) {
      // a segment's closest points to a plane are its ends
      add(X_WA.R * Vec3(0, 0, -cap->half_length) + X_WA.p, cap->radius);
      add(X_WA.R * Vec3(0, 0, cap->half_length) + X_WA.p, cap->radius);
    } else if (auto* box = std::get_if<BoxShape>(&a.shape)) {
      for (int i = 0; i < 8; ++i) {
        const Vec3 c((i & 1 ? 1 : -1) * box->half_extents.x(), (i & 2 ? 1 : -1) * box->half_extents.y(),
                     (i & 4 ? 1 : -1) * box->half_extents.z());
        add(X_WA.R * c + X_WA.p, 0);
      }
    } else if (const auto* mesh = std::get_if<MeshShape>(&a.shape); mesh && mesh->convex) {
      // a convex mesh reaches deepest into a plane at its vertices: its contact polygon is theirs,
      // kept to a few corners that span it
      const size_t first = out.size();
      const ConvexFaces* f = mesh->faces.get();
      if (f != nullptr && !f->corners.empty() && f->neighbour_start.size() == f->corners.size() + 1) {
        // the deepest corner, and the corners within the margin farthest along 8 directions in
        // the plane: support corners along the plane's inward normal tilted towards each, the
        // tilt (from 0.3) scaled, as on a quadratic surface, towards a corner 80 % of the margin
        // above the deepest, up to four climbs (from the deepest, then each from the last); on a
        // flat face lying on the plane (hundreds of corners within the margin) the first climb
        // ends on its rim
        const Vec3 n_S = X_WA.R.transpose() * pl.n;
        const real level = pl.d + margin - pl.n.dot(X_WA.p);  // corners x_S with n_S . x_S below it are within the margin
        const int deepest = f->support(-n_S);
        if (n_S.dot(f->corners[deepest]) < level) {
          add(X_WA.R * f->corners[deepest] + X_WA.p, 0);
          constexpr int kDirections = 8;
          const Vec3 t1 = n_S.unitOrthogonal(), t2 = n_S.cross(t1);
          const real c45 = std::sqrt(real(0.5));
          const real dir_u[kDirections] = {1, c45, 0, -c45, -1, -c45, 0, c45};
          const real dir_v[kDirections] = {0, c45, 1, c45, 0, -c45, -1, -c45};
          // the height above the deepest corner that the margin leaves
          const real room = level - n_S.dot(f->corners[deepest]);
          int found[kDirections];
          for (int d = 0; d < kDirections; ++d) {
            found[d] = deepest;
            real tilt = real(0.3);
            int at = deepest;
            for (int attempt = 0; attempt < 4; ++attempt) {
              at = f->support(-n_S + tilt * (dir_u[d] * t1 + dir_v[d] * t2), at);
              const real rise = n_S.dot(f->corners[at] - f->corners[deepest]);
              if (rise < room) found[d] = at;
              // flat (the rim of a face) or near the margin: done
              if (rise < room && (rise <= real(1e-3) * room || rise > real(0.5) * room)) break;
              tilt *= std::clamp(std::sqrt(real(0.8) * room / std::max(rise, real(1e-3) * room)), real(0.3), real(3));
            }
            // each corner once, and only within the margin
            const int c = found[d];
            if (c == deepest || std::find(found, found + d, c) != found + d || !(n_S.dot(f->corners[c]) < level)) continue;
            add(X_WA.R * f->corners[c] + X_WA.p, 0);
          }
        }
      } else {
        for (const Vec3& v : mesh->mesh->vertices) add(X_WA.R * v + X_WA.p, 0);
      }
      keep_at_most(out, first, kMaxConvexContacts);
    } else {
      for (const Vec3& s : a.samples_S) add(X_WA.R * s + X_WA.p, 0);
    }
    return;
  }
  RoundedBalls balls_a, balls_b;
  const bool a_round = rounded_balls(a, X_WA, balls_a);
  const bool b_round = rounded_balls(b, X_WB, balls_b);
  const real ra = balls_a.radius, rb = balls_b.radius;
  const bool a_sphere = std::holds_alternative<SphereShape>(a.shape), b_sphere = std::holds_alternative<SphereShape>(b.shape);
  const auto* a_cap = std::get_if<CapsuleShape>(&a.shape);
  const auto* b_cap = std::get_if<CapsuleShape>(&b.shape);
  if (a_sphere && b_sphere) return ball_vs_ball(balls_a.front(), ra, balls_b.front(), rb, margin, out);
  if (a_cap && (b_sphere || b_cap)) {
    // closest points of the two cores, then two balls
    const Vec3 a0 = X_WA.R * Vec3(0, 0, -a_cap->half_length) + X_WA.p, a1 = X_WA.R * Vec3(0, 0, a_cap->half_length) + X_WA.p;
    Vec3 b0 = balls_b.front(), b1 = balls_b.back();
    if (b_cap) b0 = X_WB.R * Vec3(0, 0, -b_cap->half_length) + X_WB.p, b1 = X_WB.R * Vec3(0, 0, b_cap->half_length) + X_WB.p;
    Vec3 ca, cb;
    closest_segment_points(a0, a1, b0, b1, ca, cb);
    return ball_vs_ball(ca, ra, cb, rb, margin, out);
  }
  if (a_sphere && b_cap) {
    collide_shapes(b, X_WB, a, X_WA, margin, tmp);
    return flip_into(tmp, out);
  }
  if (a_round) return balls_vs_field(balls_a, b, X_WB, margin, out);
  if (b_round) {
    balls_vs_field(balls_b, a, X_WA, margin, tmp);
    return flip_into(tmp, out);
  }
  if (std::holds_alternative<BoxShape>(a.shape) && std::holds_alternative<BoxShape>(b.shape))
    return collide_box_box(std::get<BoxShape>(a.shape), X_WA, std::get<BoxShape>(b.shape), X_WB, margin, out);
  // convex polyhedra (convex meshes, boxes): GJK/EPA and face clipping
  const ConvexFaces* faces_a = convex_faces(a.shape);
  const ConvexFaces* faces_b = faces_a ? convex_faces(b.shape) : nullptr;
  if (faces_a && faces_b) return collide_convex_convex(*faces_a, X_WA, *faces_b, X_WB, margin, out);
  // other meshes: samples of each against the other's field
  points_vs_field(a, X_WA, b, X_WB, margin, out);
  points_vs_field(b, X_WB, a, X_WA, margin, tmp);
  flip_into(tmp, out);
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

// Soft node contacts against rigid and articulated colliders (soft_contact.h).

#include "soft/soft_contact.h"

#include <algorithm>
#include <optional>

#include "collision/collision_geometry.h"
#include "shape/triangle_bvh.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace {

// Barycentric points inside a triangle: the centroid and the midpoints between it and the corners.
constexpr real kThird = real(1) / 3, kCentreToCorner = real(2) / 3, kOther = real(1) / 6;
constexpr std::array<std::array<real, 3>, 4> kFacePoints = {{{kThird, kThird, kThird},
                                                             {kCentreToCorner, kOther, kOther},
                                                             {kOther, kCentreToCorner, kOther},
                                                             {kOther, kOther, kCentreToCorner}}};

// Bounds of a surface face at node positions x (3N, world).
Bounds face_bounds(const VecX& x, const std::array<int, 3>& face) {
  Bounds bounds;
  for (int v : face) bounds.extend(x.segment<3>(3 * v));
  return bounds;
}

// Collider samples up to this many are matched against the near faces one by one; more, through
// a closest-triangle hierarchy built over those faces.
constexpr size_t kSamplesWithoutHierarchy = 32;

// The closest of `faces` to p (double precision) among those whose bounds `boxes` lie within
// `max_distance`; triangle -1 when none.
TriangleBvh::Hit closest_face(const Eigen::Vector3d& p, const std::vector<std::array<int, 3>>& faces, const std::vector<Bounds>& boxes,
                              const std::vector<Eigen::Vector3d>& vertices, double max_distance) {
  TriangleBvh::Hit best;
  best.distance_squared = max_distance * max_distance;
  for (size_t f = 0; f < faces.size(); ++f) {
    const Eigen::Vector3d gap = (boxes[f].min.cast<double>() - p).cwiseMax(p - boxes[f].max.cast<double>()).cwiseMax(0.0);
    if (gap.squaredNorm() >= best.distance_squared) continue;
    const ClosestPoint cp = closest_point_on_triangle(p, vertices[faces[f][0]], vertices[faces[f][1]], vertices[faces[f][2]]);
    const double d2 = (cp.point - p).squaredNorm();
    if (d2 < best.distance_squared) best = {d2, static_cast<int>(f), cp};
  }
  return best;
}

}  // namespace

std::vector<SoftContact> detect_soft_contacts(const SceneData& s, real margin, real dt) {
  std::vector<SoftContact> out;
  for (size_t k = 0; k < s.soft_bodies.size(); ++k) {
    const SoftBody& soft = *s.soft_bodies[k];
    const VecX& x = soft.state.x;
    const VecX& v = soft.state.v;
    // how far a surface node can move within the step
    real node_sweep = 0;
    Bounds bounds;
    for (int i : soft.model.surface_nodes) {
      if (soft.model.pinned[i]) continue;
      node_sweep = std::max(node_sweep, dt * (v.segment<3>(3 * i).norm() + dt * s.gravity.norm()));
      bounds.extend(x.segment<3>(3 * i));
    }
    if (!(bounds.min.array() <= bounds.max.array()).all()) continue;  // every surface node pinned
    // samples deeper than a quarter of the body's smallest extent are left to the node contacts
    const real max_depth = (bounds.max - bounds.min).minCoeff() / 4;
    std::vector<Eigen::Vector3d> vertices;  // the node positions in double, when a collider with samples comes near
    // the bounds of the surface faces, when a bounded collider comes near
    std::vector<Bounds> face_box;
    auto face_boxes = [&]() -> const std::vector<Bounds>& {
      if (face_box.empty())
        for (const auto& face : soft.model.surface_faces) face_box.push_back(face_bounds(x, face));
      return face_box;
    };
    for (size_t b = 0; b < s.articulations.size(); ++b) {
      const Articulation& a = *s.articulations[b];
      for (const LinkCollider& col : a.model.colliders) {
        if (!layers_may_touch(s, soft.layer_index, col.layer)) continue;
        if (!actors_may_touch(s, soft.handle, soft.handle, a.link_handles[col.link], a.handle, true)) continue;
        const SpatialTransform X_WS = a.kin.X_WL[col.link] * col.X_LS;
        const real sweep = node_sweep + collider_sweep(a, col, dt);
        const real reach = margin + sweep;
        const ContactMaterial material = combine_materials(soft.model.contact, col.material);
        auto add = [&](const std::array<int, 3>& nodes, const std::array<real, 3>& weights, const Vec3& p_W, const Vec3& n_W,
                       real phi) {
          SoftContact c;
          c.soft = static_cast<int>(k), c.nodes = nodes, c.weights = weights, c.body = static_cast<int>(b), c.link = col.link;
          c.p_W = p_W, c.n_W = n_W, c.phi = phi, c.sweep = sweep, c.material = material;
          out.push_back(c);
        };
        if (const PlaneShape* half_space = std::get_if<PlaneShape>(&col.shape)) {
          // the surface nodes against a half-space, whose distance is affine in the world point;
          // none when the body's bounds are out of its reach
          const WorldPlane plane = world_plane(*half_space, X_WS);
          const Vec3 lowest = (plane.n.array() > 0).select(bounds.min, bounds.max);
          if (plane.n.dot(lowest) - plane.d >= reach) continue;
          for (int i : soft.model.surface_nodes) {
            const real phi = plane.n.dot(x.segment<3>(3 * i)) - plane.d;
            if (phi < reach && !soft.model.pinned[i]) add({i, -1, -1}, {1, 0, 0}, x.segment<3>(3 * i), plane.n, phi);
          }
          continue;
        }
        // a bounded collider's box grown by the reach: no point outside it can touch
        Bounds box = world_bounds(col.aabb_S, X_WS);
        box.min.array() -= reach;
        box.max.array() += reach;
        if (!box.overlaps(bounds)) continue;
        auto near = [&](const Vec3& p) { return (p.array() >= box.min.array()).all() && (p.array() <= box.max.array()).all(); };
        // a point of the soft surface (weights over its nodes) against the collider's distance field
        auto against_field = [&](const std::array<int, 3>& nodes, const std::array<real, 3>& weights, const Vec3& p) {
          Vec3 g_S;
          const real phi = shape_signed_distance(col.shape, X_WS.R.transpose() * (p - X_WS.p), &g_S);
          if (phi < reach) add(nodes, weights, p, X_WS.R * g_S, phi);
        };
        for (int i : soft.model.surface_nodes)
          if (!soft.model.pinned[i] && near(x.segment<3>(3 * i))) against_field({i, -1, -1}, {1, 0, 0}, x.segment<3>(3 * i));
        // points inside the surface triangles (barycentric quadrature points) against bounded
        // colliders: a body smaller than a few elements is then held by the faces it rests on,
        // not only by the nearest nodes, and its contact force does not jump from node to node
        // as it slides
        for (size_t f = 0; f < soft.model.surface_faces.size(); ++f) {
          const auto& face = soft.model.surface_faces[f];
          if (!face_boxes()[f].overlaps(box)) continue;
          if (soft.model.pinned[face[0]] && soft.model.pinned[face[1]] && soft.model.pinned[face[2]]) continue;
          const Vec3 a0 = x.segment<3>(3 * face[0]), a1 = x.segment<3>(3 * face[1]), a2 = x.segment<3>(3 * face[2]);
          for (const auto& w : kFacePoints) against_field(face, w, w[0] * a0 + w[1] * a1 + w[2] * a2);
        }
        // the collider's samples against the deformed surface triangles
        if (col.samples_S.empty()) continue;
        // the faces within reach of the collider, or within the deepest penetration kept
        Bounds near_box = box;
        near_box.min.array() -= std::max<real>(0, max_depth - reach);
        near_box.max.array() += std::max<real>(0, max_depth - reach);
        if (vertices.empty())
          for (int i = 0; i < static_cast<int>(x.size() / 3); ++i) vertices.push_back(x.segment<3>(3 * i).cast<double>());
        std::vector<std::array<int, 3>> faces;
        std::vector<Bounds> boxes;
        for (size_t f = 0; f < soft.model.surface_faces.size(); ++f)
          if (face_boxes()[f].overlaps(near_box)) faces.push_back(soft.model.surface_faces[f]), boxes.push_back(face_boxes()[f]);
        if (faces.empty()) continue;
        // a hierarchy pays for itself only over many samples
        std::optional<TriangleBvh> bvh;
        if (col.samples_S.size() > kSamplesWithoutHierarchy) bvh.emplace(vertices, faces);
        const double max_distance = std::max(reach, max_depth);
        int hint = -1;
        for (const Vec3& sample_S : col.samples_S) {
          const Vec3 p = X_WS.R * sample_S + X_WS.p;
          if (!(p.array() >= bounds.min.array() - reach).all() || !(p.array() <= bounds.max.array() + reach).all()) continue;
          const TriangleBvh::Hit hit = bvh ? bvh->closest(p.cast<double>(), hint) : closest_face(p.cast<double>(), faces, boxes, vertices, max_distance);
          if (hit.triangle < 0) continue;
          hint = hit.triangle;
          const auto& face = faces[hit.triangle];
          const Eigen::Vector3d a = vertices[face[0]], bb = vertices[face[1]], cc = vertices[face[2]];
          const Eigen::Vector3d normal = (bb - a).cross(cc - a);
          if (normal.norm() <= 0) continue;
          const Eigen::Vector3d n_out = normal.normalized();
          const Eigen::Vector3d q = hit.closest.point;
          // signed distance along the face normal: negative inside the soft body
          const real phi = static_cast<real>((p.cast<double>() - q).dot(n_out));
          if (!(phi < reach) || phi < -max_depth) continue;
          // barycentric weights of q
          const Eigen::Vector3d v0 = bb - a, v1 = cc - a, v2 = q - a;
          const double d00 = v0.dot(v0), d01 = v0.dot(v1), d11 = v1.dot(v1), d20 = v2.dot(v0), d21 = v2.dot(v1);
          const double det = d00 * d11 - d01 * d01;
          if (!(det > 0)) continue;
          const double w1 = (d11 * d20 - d01 * d21) / det, w2 = (d00 * d21 - d01 * d20) / det;
          add(face, {static_cast<real>(1 - w1 - w2), static_cast<real>(w1), static_cast<real>(w2)}, p, (-n_out).cast<real>(), phi);
        }
      }
    }
  }
  return out;
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

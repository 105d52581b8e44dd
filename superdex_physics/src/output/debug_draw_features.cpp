// The debug-draw features (debug_draw_features.h): each turns the scene's current state, or the
// contacts of its last step, into line segments and spheres in the world frame. Sizes follow the
// actors drawn (the diagonal of their bounds in their own frame, the same however they turn), so
// that a scene of millimetre parts and one of a room both read well; actors without finite
// bounds (planes, links without shapes) get kFallbackSize.

#include "output/debug_draw_features.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>
#include <utility>

#include "scene/scene_data.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

const std::array<DebugDrawFeatureInfo, kNumDebugDrawFeatures> kDebugDrawFeatures = {{
    {"contact_points", "Spheres at the contact points of the last step (red), radius 2% of the smaller actor's size (the "
                       "diagonal of its bounds in its own frame)."},
    {"contact_normals", "Segments from each contact point along its unit normal (white), 25% of the smaller actor's size."},
    {"contact_forces", "Segments from each contact point along the force on its first actor (orange), the largest 25% of the "
                       "smaller actor's size, the others in proportion."},
    {"actor_aabbs", "The 12 edges of each rigid, link and soft actor's world axis-aligned bounding box (green); unbounded actors "
                    "(planes) are skipped."},
    {"actor_frames", "The x (red), y (green) and z (blue) axes of each rigid, link and soft actor's frame, 25% of its size "
                     "long."},
    {"centers_of_mass", "Spheres at the centre of mass of each dynamic rigid, link and soft actor (yellow), radius 4% of its size."},
    {"joint_axes", "The axis of each revolute (magenta) and prismatic (cyan) joint through the joint origin, 50% of its child "
                   "link's size long."},
    {"soft_surface_edges", "The edges of each soft actor's surface triangles at the current node positions (grey)."},
}};

namespace {

constexpr real kFallbackSize = real(0.1);  // m: the size of an actor without finite bounds
constexpr Color kRed{230, 40, 40, 255}, kGreen{40, 200, 60, 255}, kBlue{50, 90, 240, 255}, kWhite{255, 255, 255, 255},
    kOrange{255, 150, 20, 255}, kYellow{250, 220, 30, 255}, kMagenta{230, 60, 230, 255}, kCyan{40, 220, 230, 255},
    kGrey{170, 170, 170, 255};

struct Writer {
  DebugDrawBuffers& out;
  void line(const Vec3& a, const Vec3& b, const Color& c) {
    out.line_positions.push_back(a);
    out.line_positions.push_back(b);
    out.line_colors.push_back(c);
    out.line_colors.push_back(c);
  }
  void sphere(const Vec3& p, real r, const Color& c) {
    out.sphere_positions.push_back(p);
    out.sphere_radii.push_back(r);
    out.sphere_colors.push_back(c);
  }
  // the 12 edges of [lo, hi]: the 4 edges along each axis
  void box_edges(const Vec3& lo, const Vec3& hi, const Color& c) {
    for (int axis = 0; axis < 3; ++axis) {
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      for (int corner = 0; corner < 4; ++corner) {
        Vec3 a = lo;
        a[u] = corner & 1 ? hi[u] : lo[u];
        a[v] = corner & 2 ? hi[v] : lo[v];
        Vec3 b = a;
        b[axis] = hi[axis];
        line(a, b, c);
      }
    }
  }
};

// One drawable actor (a rigid actor, a link or a soft actor) and its world bounds.
struct Drawn {
  Aabb box;                   // world (m)
  bool bounded = false;       // finite, non-empty world bounds
  bool sized = false;         // finite, non-empty bounds in its own frame
  real size = kFallbackSize;  // m: the diagonal of those (which turning the actor leaves alone), or kFallbackSize
};

// The actors a gather may draw, by handle: rigid actors, links and soft actors whose own flag
// and whose articulation's flag are on.
class DrawnActors {
 public:
  DrawnActors(const SceneData& s, const DebugDrawSettings& settings) : scene_(s.handle) {
    const auto on = [&](ActorHandle h) { return !settings.disabled_actors.count(h); };
    for (const auto& a : s.articulations) {
      if (!on(a->handle)) continue;
      for (int l = 0; l < a->model.num_links; ++l)
        if (on(a->link_handles[l])) add(a->link_handles[l]);
    }
    for (const auto& b : s.soft_bodies)
      if (on(b->handle)) add(b->handle);
  }
  const Drawn* find(ActorHandle h) const {
    auto it = drawn_.find(h);
    return it == drawn_.end() ? nullptr : &it->second;
  }

 private:
  void add(ActorHandle h) {
    Drawn d;
    // unbounded (a plane), or empty: a link without shapes has the zero box
    const auto usable = [](const Aabb& b) { return b.min.allFinite() && b.max.allFinite() && (b.max - b.min).norm() > 0; };
    d.box = scene_.aabb_world(h);
    d.bounded = usable(d.box);
    const Aabb local = scene_.aabb_local(h);
    d.sized = usable(local);
    if (d.sized) d.size = (local.max - local.min).norm();
    drawn_.emplace(h, d);
  }
  Scene scene_;
  std::unordered_map<ActorHandle, Drawn> drawn_;
};

// Contacts whose two actors are drawn, with the size that scales their primitives: the smaller
// of the two actors' sizes (a plane takes the other's).
void draw_contacts(const SceneData& s, const DebugDrawSettings& settings, const DrawnActors& drawn, Writer& w) {
  const auto& f = settings.features;
  const bool points = f[int(DebugDrawFeature::ContactPoints)], normals = f[int(DebugDrawFeature::ContactNormals)],
             forces = f[int(DebugDrawFeature::ContactForces)];
  if (!points && !normals && !forces) return;
  const auto shown = [&](const ContactRecord& c) { return drawn.find(c.actor_a) && drawn.find(c.actor_b); };
  real max_force = 0;
  for (const ContactRecord& c : s.contacts)
    if (shown(c)) max_force = std::max(max_force, c.force.norm());
  for (const ContactRecord& c : s.contacts) {
    if (!shown(c)) continue;
    const Drawn* a = drawn.find(c.actor_a);
    const Drawn* b = drawn.find(c.actor_b);
    real size = kFallbackSize;
    if (a->sized || b->sized) size = std::min(a->sized ? a->size : b->size, b->sized ? b->size : a->size);
    if (points) w.sphere(c.position, real(0.02) * size, kRed);
    if (normals) w.line(c.position, c.position + real(0.25) * size * c.normal, kWhite);
    if (forces && max_force > 0) w.line(c.position, c.position + real(0.25) * size / max_force * c.force, kOrange);
  }
}

void draw_bounds_and_frames(const SceneData& s, const DebugDrawSettings& settings, const DrawnActors& drawn, Writer& w) {
  const auto& f = settings.features;
  const bool boxes = f[int(DebugDrawFeature::ActorAabbs)], frames = f[int(DebugDrawFeature::ActorFrames)],
             coms = f[int(DebugDrawFeature::CentersOfMass)];
  if (!boxes && !frames && !coms) return;
  const Scene scene(s.handle);
  const auto draw = [&](ActorHandle h, bool dynamic) {
    const Drawn* d = drawn.find(h);
    if (!d) return;
    if (boxes && d->bounded) w.box_edges(d->box.min, d->box.max, kGreen);
    const Transform X_WL = scene.root_transform(h);
    if (frames) {
      const real length = real(0.25) * d->size;
      const Mat3 R_WL = X_WL.rotation.toRotationMatrix();
      w.line(X_WL.translation, X_WL.translation + length * R_WL.col(0), kRed);
      w.line(X_WL.translation, X_WL.translation + length * R_WL.col(1), kGreen);
      w.line(X_WL.translation, X_WL.translation + length * R_WL.col(2), kBlue);
    }
    if (coms && dynamic) w.sphere(X_WL * scene.center_of_mass_local(h), real(0.04) * d->size, kYellow);
  };
  for (const auto& a : s.articulations)
    for (ActorHandle link : a->link_handles) draw(link, !a->is_static);
  for (const auto& b : s.soft_bodies) draw(b->handle, true);
}

// Revolute and prismatic joints: the axis through the joint frame's origin, which stays fixed in
// the parent link (the base frame for a root joint).
void draw_joint_axes(const SceneData& s, const DrawnActors& drawn, Writer& w) {
  for (const auto& a : s.articulations) {
    if (a->is_rigid) continue;
    for (int l = 0; l < a->model.num_links; ++l) {
      const JointModel& joint = a->model.joints[l];
      if (joint.type != JointType::Revolute && joint.type != JointType::Prismatic) continue;
      const Drawn* d = drawn.find(a->link_handles[l]);
      if (!d) continue;
      const int parent = a->model.parent[l];
      const SpatialTransform X_WJ = (parent < 0 ? a->state.X_W_base : a->kin.X_WL[parent]) * joint.X_PJ;
      const Vec3 half = real(0.25) * d->size * (X_WJ.R * joint.axis);
      w.line(X_WJ.p - half, X_WJ.p + half, joint.type == JointType::Revolute ? kMagenta : kCyan);
    }
  }
}

// Each edge of a soft body's surface triangles once.
void draw_soft_surfaces(const SceneData& s, const DrawnActors& drawn, Writer& w) {
  std::vector<std::pair<int, int>> edges;
  for (const auto& b : s.soft_bodies) {
    if (!drawn.find(b->handle)) continue;
    edges.clear();
    for (const auto& t : b->model.surface_faces)
      for (int k = 0; k < 3; ++k) edges.emplace_back(std::minmax(t[k], t[(k + 1) % 3]));
    std::sort(edges.begin(), edges.end());
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
    for (const auto& [i, j] : edges) w.line(b->state.x.segment<3>(3 * i), b->state.x.segment<3>(3 * j), kGrey);
  }
}

}  // namespace

void gather_debug_draw(const SceneData& s, const DebugDrawSettings& settings, DebugDrawBuffers& out) {
  out.line_positions.clear();
  out.line_colors.clear();
  out.sphere_positions.clear();
  out.sphere_radii.clear();
  out.sphere_colors.clear();
  if (!settings.enabled || std::none_of(settings.features.begin(), settings.features.end(), [](bool on) { return on; })) return;
  const DrawnActors drawn(s, settings);
  Writer w{out};
  draw_contacts(s, settings, drawn, w);
  draw_bounds_and_frames(s, settings, drawn, w);
  if (settings.features[int(DebugDrawFeature::JointAxes)]) draw_joint_axes(s, drawn, w);
  if (settings.features[int(DebugDrawFeature::SoftSurfaceEdges)]) draw_soft_surfaces(s, drawn, w);
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

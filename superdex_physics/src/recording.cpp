// Recordings of simulation runs as JSON lines (superdex/physics/recording.h,
// docs/recording_format.md).

#include "superdex/physics/recording.h"

#include <cmath>
#include <fstream>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <set>

#include "recording_internal.h"
#include "scene_data.h"
#include "superdex/physics/error.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace {

using json = nlohmann::json;
constexpr int kFormatVersion = 1;

struct Recording {
  std::mutex mutex;
  std::ofstream out;
  std::string path;
  double frame_interval = 0;
  double latest_time = 0;
  std::map<SceneHandle, double> last_frame;           // per scene: time of its last frame
  std::map<SceneHandle, std::set<ActorHandle>> seen;  // per scene: actors already described
};

std::unique_ptr<Recording>& recording() {
  static std::unique_ptr<Recording> r;
  return r;
}

// Rounds to 7 significant digits: recordings are for display, and this keeps them small.
double round7(double v) {
  if (v == 0 || !std::isfinite(v)) return v;
  const double scale = std::pow(10.0, 6 - std::floor(std::log10(std::abs(v))));
  return std::round(v * scale) / scale;
}

json vec(const Vec3& v) { return json::array({round7(v.x()), round7(v.y()), round7(v.z())}); }

json pose(const SpatialTransform& X) {
  const Quat q(X.R);
  return json::array({round7(X.p.x()), round7(X.p.y()), round7(X.p.z()), round7(q.x()), round7(q.y()), round7(q.z()), round7(q.w())});
}

json shape_json(const ShapeGeometry& shape) {
  return std::visit(
      [](const auto& s) -> json {
        using T = std::decay_t<decltype(s)>;
        if constexpr (std::is_same_v<T, PlaneShape>) return {{"plane", {{"normal", vec(s.normal)}, {"distance", round7(s.distance)}}}};
        if constexpr (std::is_same_v<T, SphereShape>) return {{"sphere", {{"radius", round7(s.radius)}, {"center", vec(s.center)}}}};
        if constexpr (std::is_same_v<T, BoxShape>) return {{"box", {{"halfExtents", vec(s.half_extents)}}}};
        if constexpr (std::is_same_v<T, CapsuleShape>) return {{"capsule", {{"radius", round7(s.radius)}, {"halfLength", round7(s.half_length)}}}};
        if constexpr (std::is_same_v<T, MeshShape>) {
          json v = json::array(), t = json::array();
          for (const Vec3& p : s.mesh->vertices) v.push_back(vec(p));
          for (const auto& tri : s.mesh->triangles) t.push_back(tri);
          return {{"mesh", {{"vertices", v}, {"triangles", t}}}};
        }
        return json::object();
      },
      shape);
}

json articulation_json(const SceneData& s, const Articulation& a) {
  json links = json::array();
  for (int l = 0; l < a.model.num_links; ++l) {
    json colliders = json::array();
    for (const LinkCollider& c : a.model.colliders)
      if (c.link == l) colliders.push_back({{"shape", shape_json(c.shape)}, {"linkFromShape", pose(c.X_LS)}});
    links.push_back({{"handle", a.link_handles[l]}, {"name", a.model.link_names[l]}, {"parent", a.model.parent[l]},
                     {"colliders", colliders}});
  }
  return {{"type", "actor"}, {"scene", s.handle}, {"handle", a.handle}, {"name", a.model.name},
          {"kind", a.is_rigid ? (a.is_static ? "static" : "rigid") : "articulated"}, {"links", links}};
}

json soft_json(const SceneData& s, const SoftBody& b) {
  json nodes = json::array(), faces = json::array();
  for (Eigen::Index i = 0; i + 2 < b.state.x.size(); i += 3) nodes.push_back(vec(b.state.x.segment<3>(i)));
  for (const auto& f : b.model.surface_faces) faces.push_back(f);
  return {{"type", "actor"}, {"scene", s.handle}, {"handle", b.handle}, {"name", b.model.name}, {"kind", "soft"},
          {"nodes", nodes}, {"surfaceTriangles", faces}};
}

}  // namespace

void start_recording(const std::string& path, double frame_interval) {
  auto& r = recording();
  if (r) throw Error("start_recording: a recording to '" + r->path + "' is already running");
  if (!(frame_interval >= 0) || !std::isfinite(frame_interval))
    throw Error("start_recording: frame_interval must be >= 0 seconds");
  auto rec = std::make_unique<Recording>();
  rec->out.open(path, std::ios::out | std::ios::trunc);
  if (!rec->out) throw Error("start_recording: cannot write '" + path + "'");
  rec->path = path;
  rec->frame_interval = frame_interval;
  rec->out << json{{"type", "header"}, {"format", "superdex-recording"}, {"version", kFormatVersion}, {"units", "m, s, kg, N"},
                   {"frameInterval", frame_interval}}
                  .dump()
           << '\n';
  r = std::move(rec);
}

void stop_recording() {
  auto& r = recording();
  if (!r) return;
  r->out.flush();
  r.reset();
}

bool is_recording() { return recording() != nullptr; }

double recorded_time() { return recording() ? recording()->latest_time : 0; }

std::string recording_path() { return recording() ? recording()->path : std::string(); }

void record_step(const SceneData& s) {
  auto& r = recording();
  if (!r) return;
  std::lock_guard lock(r->mutex);
  r->latest_time = std::max(r->latest_time, s.time);
  auto last = r->last_frame.find(s.handle);
  // (float builds step by float dt: allow its rounding)
  if (last != r->last_frame.end() && s.time - last->second < r->frame_interval * (1 - 1e-6) - 1e-12) return;
  // describe the scene and any actor not seen before; note the ones that are gone
  auto& seen = r->seen[s.handle];
  if (last == r->last_frame.end())
    r->out << json{{"type", "scene"}, {"scene", s.handle}, {"name", s.name}, {"gravity", vec(s.gravity)}}.dump() << '\n';
  std::set<ActorHandle> live;
  for (const auto& a : s.articulations) {
    live.insert(a->handle);
    if (seen.insert(a->handle).second) r->out << articulation_json(s, *a).dump() << '\n';
  }
  for (const auto& b : s.soft_bodies) {
    live.insert(b->handle);
    if (seen.insert(b->handle).second) r->out << soft_json(s, *b).dump() << '\n';
  }
  for (auto it = seen.begin(); it != seen.end();) {
    if (live.count(*it)) {
      ++it;
      continue;
    }
    r->out << json{{"type", "destroy"}, {"scene", s.handle}, {"handle", *it}}.dump() << '\n';
    it = seen.erase(it);
  }
  // the frame: link poses, soft node positions, contacts
  json links = json::object(), soft = json::object(), contacts = json::array();
  for (const auto& a : s.articulations) {
    if (a->is_static) continue;
    for (int l = 0; l < a->model.num_links; ++l) links[std::to_string(a->link_handles[l])] = pose(a->kin.X_WL[l]);
  }
  for (const auto& b : s.soft_bodies) {
    json x = json::array();
    for (Eigen::Index i = 0; i < b->state.x.size(); ++i) x.push_back(round7(b->state.x[i]));
    soft[std::to_string(b->handle)] = std::move(x);
  }
  for (const ContactRecord& c : s.contacts)
    contacts.push_back({{"a", c.actor_a}, {"b", c.actor_b}, {"p", vec(c.position)}, {"n", vec(c.normal)}, {"f", vec(c.force)}});
  r->out << json{{"type", "frame"}, {"scene", s.handle}, {"step", s.step_count}, {"t", s.time}, {"links", links}, {"soft", soft},
                 {"contacts", contacts}}
                .dump()
         << '\n';
  r->last_frame[s.handle] = s.time;
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

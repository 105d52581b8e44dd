// Scene descriptions and frames as JSON lines (scene_messages.h).

#include "output/scene_messages.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <sstream>

#include "constraint/constraint_terms.h"
#include "core/base64.h"
#include "output/rod_display.h"
#include "scene/step_stages.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace {

using json = nlohmann::json;
constexpr int kFormatVersion = 1;

// Rounds to 7 significant digits: frames are for display, and this keeps them small.
double round7(double v) {
  if (v == 0 || !std::isfinite(v)) return v;
  const double scale = std::pow(10.0, 6 - std::floor(std::log10(std::abs(v))));
  return std::round(v * scale) / scale;
}

json vec(const Vec3& v) { return json::array({round7(v.x()), round7(v.y()), round7(v.z())}); }

json values(const VecX& x) {
  json out = json::array();
  for (Eigen::Index i = 0; i < x.size(); ++i) out.push_back(round7(x[i]));
  return out;
}

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

// A link's render model (.glb) embedded in base64, so that recordings replay without the files;
// files are read once per path.
json render_model_json(const LinkDesc& link) {
  static std::mutex mutex;
  static std::map<std::string, std::shared_ptr<const std::string>> encoded;
  std::shared_ptr<const std::string> glb;
  {
    std::lock_guard lock(mutex);
    auto& cached = encoded[link.render_model];
    if (!cached) {
      std::ifstream in(link.render_model, std::ios::binary);
      std::ostringstream bytes;
      bytes << in.rdbuf();
      cached = std::make_shared<const std::string>(in ? base64_encode(bytes.str()) : std::string());
    }
    glb = cached;
  }
  if (glb->empty()) return nullptr;
  return {{"name", std::filesystem::path(link.render_model).filename().string()}, {"scale", vec(link.render_model_scale)}, {"glb", *glb}};
}

json articulation_json(const SceneData& s, const Articulation& a) {
  json links = json::array();
  for (int l = 0; l < a.model.num_links; ++l) {
    json colliders = json::array();
    for (const LinkCollider& c : a.model.colliders)
      if (c.link == l) colliders.push_back({{"shape", shape_json(c.shape)}, {"linkFromShape", pose(c.X_LS)}});
    const JointModel& joint = a.model.joints[l];
    links.push_back({{"handle", a.link_handles[l]}, {"name", a.model.link_names[l]}, {"parent", a.model.parent[l]},
                     {"mass", round7(a.model.inertia[l].mass)},
                     {"joint", {{"type", joint_type_name(joint.type)}, {"dofs", joint.nv}, {"offset", joint.v_offset}}},
                     {"colliders", colliders}});
    if (l < static_cast<int>(a.model.desc.links.size()) && !a.model.desc.links[l].render_model.empty()) {
      json model = render_model_json(a.model.desc.links[l]);
      if (!model.is_null()) links.back()["renderModel"] = std::move(model);
    }
  }
  return {{"type", "actor"}, {"scene", s.handle}, {"handle", a.handle}, {"name", a.model.name},
          {"kind", a.is_rigid ? (a.is_static ? "static" : "rigid") : "articulated"}, {"numDofs", a.model.nv}, {"links", links}};
}

// A soft body's nodes now (world, 3 per node): a rod's are its tube's (rod_display.h).
void soft_display_nodes(const SoftBody& b, VecX& x) {
  if (b.model.rod) {
    rod_display_vertices(b, x);
  } else {
    x = b.state.x;
  }
}

json soft_json(const SceneData& s, const SoftBody& b) {
  json nodes = json::array(), faces = json::array();
  VecX x;
  soft_display_nodes(b, x);
  for (Eigen::Index i = 0; i + 2 < x.size(); i += 3) nodes.push_back(vec(x.segment<3>(i)));
  if (b.model.rod) {
    for (const auto& f : rod_display_faces(b)) faces.push_back(f);
  } else {
    for (const auto& f : b.model.surface_faces) faces.push_back(f);
  }
  json out = {{"type", "actor"}, {"scene", s.handle}, {"handle", b.handle}, {"name", b.model.name}, {"kind", "soft"},
              {"mass", round7(b.model.total_mass)}, {"nodes", nodes}, {"surfaceTriangles", faces}};
  if (b.model.rod) out["rod"] = {{"nodes", b.model.rod->num_nodes}, {"closed", b.model.rod->closed}};
  return out;
}

// A skinned articulation's skin, drawn as a deforming surface under its own display id.
json skin_json(const SceneData& s, const Articulation& a) {
  VecX x;
  skin_positions_world(*a.skin, a.kin.X_WL, x);
  json nodes = json::array(), faces = json::array();
  for (Eigen::Index i = 0; i + 2 < x.size(); i += 3) nodes.push_back(vec(x.segment<3>(i)));
  for (const auto& f : a.skin->faces) faces.push_back(f);
  return {{"type", "actor"}, {"scene", s.handle}, {"handle", a.skin->display}, {"name", a.model.name + "/skin"}, {"kind", "soft"},
          {"skinOf", a.handle}, {"mass", 0}, {"nodes", nodes}, {"surfaceTriangles", faces}};
}

// Named signals of the frame: joint velocities and efforts of one-DOF joints, contact force
// totals on moving links and soft bodies, then the scene's signal sources.
std::vector<NamedSignal> frame_signals(const SceneData& s) {
  std::vector<NamedSignal> out;
  std::map<ActorHandle, Vec3> contact_force;
  for (const ContactRecord& c : s.contacts) {
    // (Eigen vectors are not zeroed by their default constructor)
    contact_force.try_emplace(c.actor_a, Vec3::Zero()).first->second += c.force;
    contact_force.try_emplace(c.actor_b, Vec3::Zero()).first->second -= c.force;
  }
  const auto force_of = [&](const std::string& name, ActorHandle h) {
    auto it = contact_force.find(h);
    const Vec3 f = it == contact_force.end() ? Vec3(Vec3::Zero()) : it->second;
    out.push_back({name + ".contact_force", {double(f.x()), double(f.y()), double(f.z())}, "contact"});
  };
  for (const auto& a : s.articulations) {
    if (a->is_static) continue;
    if (a->is_rigid) {
      force_of(a->model.name, a->handle);
      continue;
    }
    for (int l = 0; l < a->model.num_links; ++l) {
      const std::string prefix = a->model.name + "." + a->model.link_names[l];
      const JointModel& joint = a->model.joints[l];
      if (joint.nv == 1) {
        out.push_back({prefix + ".velocity", {double(a->state.v[joint.v_offset])}, "velocity"});
        out.push_back({prefix + ".effort", {double(a->state.tau_external[joint.v_offset])}, "effort"});
      }
      force_of(prefix, a->link_handles[l]);
    }
  }
  for (const auto& b : s.soft_bodies) force_of(b->model.name, b->handle);
  for (const auto& [id, source] : s.signal_sources) source(out);
  return out;
}

}  // namespace

std::string header_line(double frame_interval) {
  return json{{"type", "header"}, {"format", "superdex-recording"}, {"version", kFormatVersion}, {"units", "m, s, kg, N"},
              {"frameInterval", frame_interval}}
             .dump() +
         '\n';
}

void append_frame_lines(const SceneData& s, StreamState& state, std::string& out) {
  const auto line = [&out](const json& j) {
    out += j.dump();
    out += '\n';
  };
  // describe the scene and any actor not seen before; note the ones that are gone
  auto& seen = state.seen[s.handle];
  if (!state.last_frame.count(s.handle)) line({{"type", "scene"}, {"scene", s.handle}, {"name", s.name}, {"gravity", vec(s.gravity)}});
  std::set<ActorHandle> live;
  for (const auto& a : s.articulations) {
    live.insert(a->handle);
    if (seen.insert(a->handle).second) line(articulation_json(s, *a));
    if (!a->skin) continue;
    live.insert(a->skin->display);
    if (seen.insert(a->skin->display).second) line(skin_json(s, *a));
  }
  for (const auto& b : s.soft_bodies) {
    live.insert(b->handle);
    if (seen.insert(b->handle).second) line(soft_json(s, *b));
  }
  for (auto it = seen.begin(); it != seen.end();) {
    if (live.count(*it)) {
      ++it;
      continue;
    }
    line({{"type", "destroy"}, {"scene", s.handle}, {"handle", *it}});
    it = seen.erase(it);
  }
  // the kinds of signals this consumer has not been told of
  const std::vector<NamedSignal> named = frame_signals(s);
  json new_kinds = json::object(), signals = json::object();
  auto& kinds_sent = state.signal_kinds[s.handle];
  for (const NamedSignal& n : named) {
    if (kinds_sent.insert(n.name).second) new_kinds[n.name] = n.kind.empty() ? "user" : n.kind;
    if (n.values.size() == 1) {
      signals[n.name] = round7(n.values[0]);
      continue;
    }
    json v = json::array();
    for (double x : n.values) v.push_back(round7(x));
    signals[n.name] = std::move(v);
  }
  if (!new_kinds.empty()) line({{"type", "signals"}, {"scene", s.handle}, {"kinds", new_kinds}});
  // the frame: link poses, joint coordinates, soft node positions, contacts, signals
  json links = json::object(), joints = json::object(), soft = json::object(), contacts = json::array();
  for (const auto& a : s.articulations) {
    if (a->is_static) continue;
    for (int l = 0; l < a->model.num_links; ++l) links[std::to_string(a->link_handles[l])] = pose(a->kin.X_WL[l]);
    joints[std::to_string(a->handle)] = {{"q", values(a->state.q)}, {"qd", values(a->state.v)}};
  }
  for (const auto& b : s.soft_bodies) {
    VecX x;
    soft_display_nodes(*b, x);
    soft[std::to_string(b->handle)] = values(x);
  }
  for (const auto& a : s.articulations)
    if (a->skin) {
      VecX x;
      skin_positions_world(*a->skin, a->kin.X_WL, x);
      soft[std::to_string(a->skin->display)] = values(x);
    }
  for (const ContactRecord& c : s.contacts)
    contacts.push_back({{"a", c.actor_a}, {"b", c.actor_b}, {"p", vec(c.position)}, {"n", vec(c.normal)}, {"f", vec(c.force)}});
  // constraints: the two points each draws between
  json constraints = json::array();
  for (const auto& [h, c] : s.constraints) {
    // a spring-damper without stiffness or damping does nothing: not drawn
    if (c.stiffness <= 0 && c.damping <= 0) continue;
    Vec3 p_a, p_b;
    constraint_anchor_points(c, constraint_side(s, c, 0), constraint_side(s, c, 1), p_a, p_b);
    constraints.push_back({{"h", h}, {"type", constraint_type_name(c.type)}, {"a", vec(p_a)}, {"b", vec(p_b)}});
  }
  // spatial tendons: the segments of each route, flat [a, b, a, b, ...] (m, world)
  json tendons = json::array();
  for (const auto& a : s.articulations)
    for (size_t i = 0; i < a->model.transmissions.size(); ++i) {
      const ArticulationModel::Transmission& t = a->model.transmissions[i];
      std::vector<real> segments;
      for (size_t k = 0; k + 1 < t.waypoints.size(); ++k) {
        if (!t.waypoints[k].to_next) continue;
        for (const ArticulationModel::Waypoint* w : {&t.waypoints[k], &t.waypoints[k + 1]}) {
          const SpatialTransform& X = a->kin.X_WL[w->link];
          const Vec3 p = X.R * w->p_L + X.p;
          segments.insert(segments.end(), {p.x(), p.y(), p.z()});
        }
      }
      if (!segments.empty()) tendons.push_back({{"a", a->handle}, {"i", i}, {"s", segments}});
    }
  line({{"type", "frame"}, {"scene", s.handle}, {"step", s.step_count}, {"t", s.time}, {"links", links}, {"joints", joints},
        {"soft", soft}, {"contacts", contacts}, {"constraints", constraints}, {"tendons", tendons}, {"signals", signals}});
  state.last_frame[s.handle] = s.time;
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

// A scene's HDF5 recording (scene_recording.h; layout in docs/recording_format.md).

#include "output/scene_recording.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <map>
#include <type_traits>
#include <variant>

#include "scene/actor_lookup.h"
#include "scene/scene_data.h"
#include "superdex/physics/error.h"
#include "superdex/physics/log.h"
#include "superdex/physics/scene.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace {

constexpr int kFormatVersion = 1;

using Dims = std::vector<hsize_t>;

// Rows of three values as a (rows x 3) float64 dataset.
void write_rows3(h5::Writer& f, const std::string& path, const std::vector<Vec3>& rows) {
  std::vector<double> v;
  v.reserve(3 * rows.size());
  for (const Vec3& r : rows) v.insert(v.end(), {double(r.x()), double(r.y()), double(r.z())});
  f.dataset(path, Dims{rows.size(), 3}, v);
}

// A flat array of reals as a (size / cols x cols) float64 dataset, or a vector when cols is 0.
template <class Reals>
void write_matrix(h5::Writer& f, const std::string& path, const Reals& values, size_t cols) {
  std::vector<double> v(values.begin(), values.end());
  f.dataset(path, cols ? Dims{v.size() / cols, cols} : Dims{v.size()}, v);
}

void write_mesh(h5::Writer& f, const std::string& group, const MeshData& mesh) {
  f.group(group);
  write_matrix(f, group + "/coordinates", mesh.coordinates, 3);
  const size_t k = static_cast<size_t>(std::max(mesh.nodes_per_element, 0));
  f.dataset(group + "/connectivity", Dims{k ? mesh.connectivity.size() / k : 0, k}, mesh.connectivity);
  f.attribute(group, "nodes_per_element", {double(mesh.nodes_per_element)});
}

// One collision shape of a body: its kind and parameters, its pose in the body frame (x, y, z,
// qx, qy, qz, qw) and, for a mesh, its vertices and triangles (shape frame).
void write_collider(h5::Writer& f, const std::string& group, const LinkCollider& c) {
  f.group(group);
  const Quat q(c.X_LS.R);
  f.attribute(group, "link_from_shape", {double(c.X_LS.p.x()), double(c.X_LS.p.y()), double(c.X_LS.p.z()), double(q.x()),
                                         double(q.y()), double(q.z()), double(q.w())});
  const auto kind = [&](const char* name) { f.string_attribute(group, "shape", name); };
  std::visit(
      [&](const auto& s) {
        using T = std::decay_t<decltype(s)>;
        if constexpr (std::is_same_v<T, PlaneShape>) {
          kind("plane");
          f.attribute(group, "normal", {double(s.normal.x()), double(s.normal.y()), double(s.normal.z())});
          f.attribute(group, "distance", {double(s.distance)});
        } else if constexpr (std::is_same_v<T, SphereShape>) {
          kind("sphere");
          f.attribute(group, "center", {double(s.center.x()), double(s.center.y()), double(s.center.z())});
          f.attribute(group, "radius", {double(s.radius)});
        } else if constexpr (std::is_same_v<T, BoxShape>) {
          kind("box");
          f.attribute(group, "half_extents", {double(s.half_extents.x()), double(s.half_extents.y()), double(s.half_extents.z())});
        } else if constexpr (std::is_same_v<T, CapsuleShape>) {
          kind("capsule");
          f.attribute(group, "radius", {double(s.radius)});
          f.attribute(group, "half_length", {double(s.half_length)});
        } else if constexpr (std::is_same_v<T, MeshShape>) {
          kind("mesh");
          write_rows3(f, group + "/vertices", s.mesh->vertices);
          std::vector<int> triangles;
          for (const auto& t : s.mesh->triangles) triangles.insert(triangles.end(), {t[0], t[1], t[2]});
          f.dataset(group + "/triangles", Dims{s.mesh->triangles.size(), 3}, triangles);
        } else {
          kind("other");
        }
      },
      c.shape);
}

// "rigid", "articulated", "soft": actor_type_name in lower case.
std::string type_name(ActorType t) {
  std::string name = actor_type_name(t);
  for (char& c : name) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return name;
}

// The first DOF of each top-level actor in the scene's DOF vector: every top-level actor's DOFs
// one after the other, in creation order.
std::map<long long, int> dof_offsets(const Scene& scene) {
  std::map<long long, int> offset;
  int next = 0;
  for (ActorHandle h : scene.all_actors()) {
    if (scene.is_nested_link_actor(h)) continue;
    offset[h] = next;
    next += scene.num_dofs(h);
  }
  return offset;
}

}  // namespace

SceneRecording::SceneRecording(const Scene& scene, const std::string& path, const RecordingParams& params)
    : path_(path), params_(params), file_(path) {
  auto guard = h5::lock();
  const SceneData& s = scene_data(scene.handle());
  file_.string_attribute("/", "format", "superdex-scene-recording");
  file_.attribute("/", "version", {double(kFormatVersion)});
  file_.string_attribute("/", "scene", s.name);
  file_.string_attribute("/", "units", "m, s, kg, N");
  file_.string_attribute("/", "precision", sizeof(real) == sizeof(float) ? "float32" : "float64");
  file_.attribute("/", "gravity", {double(s.gravity.x()), double(s.gravity.y()), double(s.gravity.z())});
  const bool flags[] = {params.record_actor_meshes, params.record_actor_local_to_global_map, params.record_actor_mass_matrix,
                        params.record_target_state, params.record_dynamic_actor_state, params.record_static_actor_state,
                        params.record_contact_points, params.record_node_contact_forces, params.record_sdf_distances};
  const char* names[] = {"record_actor_meshes", "record_actor_local_to_global_map", "record_actor_mass_matrix",
                         "record_target_state", "record_dynamic_actor_state", "record_static_actor_state",
                         "record_contact_points", "record_node_contact_forces", "record_sdf_distances"};
  file_.group("params");
  for (int i = 0; i < 9; ++i) file_.attribute("params", names[i], {flags[i] ? 1.0 : 0.0});
  file_.group("actors", true);
  file_.group("frames", true);
  describe_new_actors(scene);
  file_.flush();
}

void SceneRecording::describe_new_actors(const Scene& scene) {
  SceneData& s = scene_data(scene.handle());
  std::map<long long, int> offsets;
  for (ActorHandle h : scene.all_actors()) {
    if (!described_.insert(h).second) continue;
    const std::string g = "actors/" + std::to_string(h);
    const ActorRef r = lookup(s, h, "start_recording");
    file_.group(g);
    file_.string_attribute(g, "name", scene.actor_name(h));
    file_.string_attribute(g, "type", type_name(scene.actor_type(h)));
    file_.attribute(g, "is_static", {scene.is_static(h) ? 1.0 : 0.0});
    file_.attribute(g, "first_frame", {double(frames_)});
    if (is_link_actor(r)) file_.attribute(g, "articulation", {double(r.articulation->handle)});
    // the geometry in the actor frame: a soft actor's tetrahedra and surface, the collision
    // shapes of a rigid body or link (not of a whole articulation: its links have theirs)
    if (params_.record_actor_meshes && r.soft) {
      const ShapeMeshes m = scene.meshes(h);
      if (m.mesh) write_mesh(file_, g + "/mesh", *m.mesh);
      if (m.surface) write_mesh(file_, g + "/surface", *m.surface);
    } else if (params_.record_actor_meshes && (r.link >= 0 || r.articulation->is_rigid)) {
      const int link = std::max(r.link, 0);
      file_.group(g + "/colliders", true);
      int k = 0;
      for (const LinkCollider& c : r.articulation->model.colliders)
        if (c.link == link) write_collider(file_, g + "/colliders/" + std::to_string(k++), c);
    }
    if (params_.record_actor_local_to_global_map) {
      if (offsets.empty()) offsets = dof_offsets(scene);
      // a link's DOFs are its joint's, within its articulation's range
      int first = 0, count = scene.num_dofs(h);
      if (is_link_actor(r)) {
        const JointModel& j = r.articulation->model.joints[r.link];
        first = offsets[r.articulation->handle] + j.v_offset, count = j.nv;
      } else {
        first = offsets[h];
      }
      std::vector<int> dofs(static_cast<size_t>(count));
      for (int i = 0; i < count; ++i) dofs[i] = first + i;
      file_.dataset(g + "/local_to_global", Dims{dofs.size()}, dofs);
    }
    if (params_.record_actor_mass_matrix) {
      if (r.soft) {
        write_matrix(file_, g + "/node_masses", r.soft->model.node_mass, 0);
      } else if (!is_link_actor(r)) {
        const MatX M = scene.mass_matrix(h);
        std::vector<double> v(static_cast<size_t>(M.size()));
        for (Eigen::Index i = 0; i < M.rows(); ++i)
          for (Eigen::Index k = 0; k < M.cols(); ++k) v[i * M.cols() + k] = M(i, k);
        file_.dataset(g + "/mass_matrix", Dims{hsize_t(M.rows()), hsize_t(M.cols())}, v);
      }
    }
  }
}

void SceneRecording::write_frame(const Scene& scene, double time_step) {
  SceneData& s = scene_data(scene.handle());
  describe_new_actors(scene);
  // (a frame that fails half-way keeps its number: the next one does not collide with it)
  char index[32];
  std::snprintf(index, sizeof index, "%08lld", frames_++);
  const std::string g = std::string("frames/") + index;
  file_.group(g);
  file_.attribute(g, "time", {s.time});
  file_.attribute(g, "time_step", {time_step});
  file_.attribute(g, "step", {double(s.step_count)});
  // the frame's sub-groups, created when first written to
  std::set<std::string> made;
  const auto in = [&](const std::string& group) {
    if (made.insert(group).second) file_.group(g + "/" + group);
    return g + "/" + group;
  };
  const auto wanted = [&](bool is_static) {
    return is_static ? params_.record_static_actor_state : params_.record_dynamic_actor_state;
  };
  // rigid bodies and links: pose of the actor frame, velocity of the centre of mass (world)
  std::vector<std::int64_t> bodies;
  std::vector<Vec3> translations, linear, angular;
  std::vector<double> rotations;
  const auto add_body = [&](ActorHandle h) {
    const Transform X_WL = scene.root_transform(h);
    const Vec6 V = scene.velocity(h);
    bodies.push_back(h);
    translations.push_back(X_WL.translation);
    const Quat& q = X_WL.rotation;
    rotations.insert(rotations.end(), {double(q.x()), double(q.y()), double(q.z()), double(q.w())});
    linear.push_back(V.head<3>());
    angular.push_back(V.tail<3>());
  };
  for (const auto& a : s.articulations) {
    if (wanted(a->is_static)) {
      if (a->is_rigid) {
        add_body(a->handle);
      } else {
        for (ActorHandle link : a->link_handles) add_body(link);
        const std::string ag = in("articulated") + "/" + std::to_string(a->handle);
        file_.group(ag);
        write_matrix(file_, ag + "/joint_positions", a->state.q, 0);
        write_matrix(file_, ag + "/joint_velocities", a->state.v, 0);
      }
    }
    // drive targets and gains: joint drives (stiffness, damping, target position, target
    // velocity, max effort) and link drives (target pose, velocities, gains, limits)
    if (params_.record_target_state && (!a->state.drives.empty() || !a->state.link_drives.empty())) {
      const std::string tg = in("targets") + "/" + std::to_string(a->handle);
      file_.group(tg);
      std::vector<double> joint, link;
      for (const JointDrive& d : a->state.drives)
        joint.insert(joint.end(), {double(d.stiffness), double(d.damping), double(d.target_position), double(d.target_velocity),
                                   double(d.max_effort)});
      for (const LinkDrive& d : a->state.link_drives) {
        const Quat& q = d.target.rotation;
        const Vec3 &p = d.target.translation, &v = d.target_linear_velocity, &w = d.target_angular_velocity;
        link.insert(link.end(), {double(q.x()), double(q.y()), double(q.z()), double(q.w()), double(p.x()), double(p.y()),
                                 double(p.z()), double(v.x()), double(v.y()), double(v.z()), double(w.x()), double(w.y()),
                                 double(w.z()), double(d.linear_stiffness), double(d.linear_damping), double(d.angular_stiffness),
                                 double(d.angular_damping), double(d.max_force), double(d.max_torque)});
      }
      write_matrix(file_, tg + "/joint_drives", joint, 5);
      write_matrix(file_, tg + "/link_drives", link, 19);
    }
  }
  if (!bodies.empty()) {
    const std::string bg = in("bodies");
    file_.dataset(bg + "/actors", Dims{bodies.size()}, bodies);
    write_rows3(file_, bg + "/translations", translations);
    file_.dataset(bg + "/rotations", Dims{bodies.size(), 4}, rotations);
    write_rows3(file_, bg + "/linear_velocities", linear);
    write_rows3(file_, bg + "/angular_velocities", angular);
  }
  // soft actors: node displacements from the rest mesh and velocities (world), node contact forces
  for (const auto& b : s.soft_bodies) {
    const bool state = params_.record_dynamic_actor_state, forces = params_.record_node_contact_forces;
    if (!state && !forces) continue;
    const std::string sg = in("soft") + "/" + std::to_string(b->handle);
    file_.group(sg);
    if (state) {
      write_matrix(file_, sg + "/displacements", scene.displacements(b->handle), 3);
      write_matrix(file_, sg + "/velocities", b->state.v, 3);
    }
    if (forces) {
      VecX f = b->node_contact_forces;
      if (f.size() != b->state.v.size()) f = VecX::Zero(b->state.v.size());
      write_matrix(file_, sg + "/node_contact_forces", f, 3);
    }
  }
  // the step's contacts: the actor pair (force on the first), point, normal, force, signed gap
  if (params_.record_contact_points || params_.record_sdf_distances) {
    const std::string cg = in("contacts");
    std::vector<std::int64_t> pairs;
    std::vector<Vec3> positions, normals, contact_forces;
    std::vector<double> distances;
    for (const ContactRecord& c : s.contacts) {
      pairs.insert(pairs.end(), {c.actor_a, c.actor_b});
      positions.push_back(c.position);
      normals.push_back(c.normal);
      contact_forces.push_back(c.force);
      distances.push_back(c.distance);
    }
    file_.dataset(cg + "/actors", Dims{s.contacts.size(), 2}, pairs);
    if (params_.record_contact_points) {
      write_rows3(file_, cg + "/positions", positions);
      write_rows3(file_, cg + "/normals", normals);
      write_rows3(file_, cg + "/forces", contact_forces);
    }
    if (params_.record_sdf_distances) file_.dataset(cg + "/distances", Dims{distances.size()}, distances);
  }
}

void SceneRecording::record_frame(const Scene& scene, double time_step) {
  auto guard = h5::lock();
  try {
    write_frame(scene, time_step);
    file_.flush();
  } catch (const Error& e) {
    if (!warned_) log_warning("scene recording: " + std::string(e.what()) + " (the recording goes on; later failures are not logged)");
    warned_ = true;
  }
}

SceneRecording::~SceneRecording() {
  auto guard = h5::lock();
  try {
    file_.close();
  } catch (const Error& e) {
    log_warning("scene recording: " + std::string(e.what()));
  }
}

void Scene::start_recording(const std::string& file_path, const RecordingParams& params) {
  SceneData& s = scene_data(handle_);
  // the running recording is closed before its file may be replaced
  s.recording.reset();
  s.recording = std::make_shared<SceneRecording>(*this, file_path, params);
}

void Scene::stop_recording() { scene_data(handle_).recording.reset(); }

bool Scene::is_recording() const { return scene_data(handle_).recording != nullptr; }

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

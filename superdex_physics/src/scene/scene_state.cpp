// Capture and restore of a scene's evolving state as bytes.
//
// Layout (little-endian, this machine's representation): "SDXS", u32 version, u8 sizeof(real),
// i64 step count, f64 time, f64 last time step, u32 body count; per body: i64 handle, u32 nq, u32 nv, then nq + 2 nv
// + 12 reals (q, v, external forces, base rotation row-major and translation), then 5 nv reals of
// joint drives (stiffness, damping, target position, target velocity, max effort per DOF), then
// 19 reals per link of link drives (target rotation xyzw, translation, linear and angular target
// velocity, linear stiffness and damping, angular stiffness and damping, max force and torque),
// then u32 transmission actuator count and per actuator u8 kind and 8 reals (state variable,
// stiffness, damping, allow_compressive_force as 0 or 1, and a McKibben muscle's minimum
// pressure, thread length, wraps and deflated length).
// Then u32 soft body count; per soft body: its frame X_WL (rotation xyzw, translation: 7 reals),
// u32 3N, node positions, velocities and forces (3N each),
// u32 r (the modes of a reduced body, else 0) and, when r > 0, its modal amplitudes and their
// velocities (r each) and residual contact displacement (3N).
// Then u32 constraint count; per constraint (creation order): u8 type, then 37 reals: stiffness,
// damping, saturation, target position and its value at the last step (3 each), target rotation
// and its last (xyzw, 4 each), target transform and its last (rotation xyzw, translation: 7
// each), B's joint frame (xyzw), target value and its last.
// Then u32 pose controller count; per articulation with one (body order): i64 its handle, u8 1
// when a target velocity is pending, then nv reals of target pose, 7 per link of target link
// frames (rotation xyzw, translation) and nv of the pending target velocity (zeros when none).

#include <array>
#include <cmath>
#include <cstring>
#include <span>

#include "multibody/kinematics.h"
#include "scene/scene_data.h"
#include "superdex/physics/error.h"
#include "superdex/physics/scene.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace {

constexpr char kMagic[4] = {'S', 'D', 'X', 'S'};
constexpr std::uint32_t kVersion = 9;

class Writer {
 public:
  template <class T>
  void put(const T& x) {
    const auto* p = reinterpret_cast<const std::uint8_t*>(&x);
    bytes.insert(bytes.end(), p, p + sizeof(T));
  }
  void put_reals(const real* x, size_t n) {
    const auto* p = reinterpret_cast<const std::uint8_t*>(x);
    bytes.insert(bytes.end(), p, p + n * sizeof(real));
  }
  std::vector<std::uint8_t> bytes;
};

class Reader {
 public:
  explicit Reader(std::span<const std::uint8_t> b) : bytes_(b) {}
  template <class T>
  T get(const char* what) {
    T x;
    take(&x, sizeof(T), what);
    return x;
  }
  void get_reals(real* x, size_t n, const char* what) { take(x, n * sizeof(real), what); }
  bool done() const { return pos_ == bytes_.size(); }

 private:
  void take(void* dst, size_t n, const char* what) {
    if (pos_ + n > bytes_.size()) throw Error(std::string("restore_state: the state is truncated (reading ") + what + ")");
    // an empty vector (a body without DOFs) has no storage: memcpy must not see its null pointer
    if (n == 0) return;
    std::memcpy(dst, bytes_.data() + pos_, n);
    pos_ += n;
  }
  std::span<const std::uint8_t> bytes_;
  size_t pos_ = 0;
};

// A constraint's evolving part (the layout above) and its restoration.
constexpr size_t kConstraintReals = 37;
std::array<real, kConstraintReals> constraint_state(const ConstraintRecord& c) {
  std::array<real, kConstraintReals> x;
  size_t k = 0;
  const auto put = [&](const auto& v) {
    for (Eigen::Index i = 0; i < v.size(); ++i) x[k++] = v[i];
  };
  put(Vec3(c.stiffness, c.damping, c.saturation));
  put(c.target_position), put(c.old_target_position);
  put(c.target_rotation.coeffs()), put(c.old_target_rotation.coeffs());
  put(c.target_transform.rotation.coeffs()), put(c.target_transform.translation);
  put(c.old_target_transform.rotation.coeffs()), put(c.old_target_transform.translation);
  put(c.J_B.coeffs());
  put(Eigen::Matrix<real, 2, 1>(c.target_value, c.old_target_value));
  return x;
}
void restore_constraint_state(ConstraintRecord& c, const std::array<real, kConstraintReals>& x) {
  size_t k = 0;
  const auto get = [&](auto&& v) {
    for (Eigen::Index i = 0; i < v.size(); ++i) v[i] = x[k++];
  };
  Vec3 spring;
  get(spring);
  // a joint limit's spring is its joint's (the model, which a state does not hold)
  if (c.type != ConstraintType::ArticulatedSingleDofRange) c.stiffness = spring[0], c.damping = spring[1], c.saturation = spring[2];
  get(c.target_position), get(c.old_target_position);
  get(c.target_rotation.coeffs()), get(c.old_target_rotation.coeffs());
  get(c.target_transform.rotation.coeffs()), get(c.target_transform.translation);
  get(c.old_target_transform.rotation.coeffs()), get(c.old_target_transform.translation);
  get(c.J_B.coeffs());
  Eigen::Matrix<real, 2, 1> value;
  get(value);
  c.target_value = value[0], c.old_target_value = value[1];
}

// A pose controller's evolving part: its targets and any pending target velocity (the layout above).
std::vector<real> controller_state(const Articulation& a) {
  const PoseController& pc = *a.pose_controller;
  std::vector<real> x(pc.target_pose.data(), pc.target_pose.data() + pc.target_pose.size());
  for (const Transform& X : pc.target_links) {
    x.insert(x.end(), X.rotation.coeffs().data(), X.rotation.coeffs().data() + 4);
    x.insert(x.end(), X.translation.data(), X.translation.data() + 3);
  }
  const VecX v = pc.target_velocity ? *pc.target_velocity : VecX::Zero(a.model.nv);
  x.insert(x.end(), v.data(), v.data() + v.size());
  return x;
}
void restore_controller_state(Articulation& a, bool pending, const std::vector<real>& x) {
  PoseController& pc = *a.pose_controller;
  const int nv = a.model.nv;
  pc.target_pose = Eigen::Map<const VecX>(x.data(), nv);
  for (size_t i = 0; i < pc.target_links.size(); ++i) {
    const real* p = x.data() + nv + 7 * i;
    pc.target_links[i] = {Quat(p[3], p[0], p[1], p[2]).normalized(), Vec3(p[4], p[5], p[6])};
  }
  if (pending) {
    pc.target_velocity = Eigen::Map<const VecX>(x.data() + nv + 7 * pc.target_links.size(), nv);
  } else {
    pc.target_velocity.reset();
  }
}

}  // namespace

std::vector<std::uint8_t> state_bytes(const SceneData& s) {
  Writer w;
  for (char c : kMagic) w.put(c);
  w.put(kVersion);
  w.put(static_cast<std::uint8_t>(sizeof(real)));
  w.put(static_cast<std::int64_t>(s.step_count));
  w.put(s.time);
  w.put(s.last_time_step);
  w.put(static_cast<std::uint32_t>(s.articulations.size()));
  for (const auto& a : s.articulations) {
    w.put(static_cast<std::int64_t>(a->handle));
    w.put(static_cast<std::uint32_t>(a->model.nq));
    w.put(static_cast<std::uint32_t>(a->model.nv));
    w.put_reals(a->state.q.data(), a->state.q.size());
    w.put_reals(a->state.v.data(), a->state.v.size());
    w.put_reals(a->state.tau_external.data(), a->state.tau_external.size());
    const Eigen::Matrix<real, 3, 3, Eigen::RowMajor> R = a->state.X_W_base.R;
    w.put_reals(R.data(), 9);
    w.put_reals(a->state.X_W_base.p.data(), 3);
    for (const JointDrive& d : a->state.drives) {
      const real x[5] = {d.stiffness, d.damping, d.target_position, d.target_velocity, d.max_effort};
      w.put_reals(x, 5);
    }
    for (const LinkDrive& d : a->state.link_drives) {
      const real x[19] = {d.target.rotation.x(), d.target.rotation.y(), d.target.rotation.z(), d.target.rotation.w(),
                          d.target.translation.x(), d.target.translation.y(), d.target.translation.z(),
                          d.target_linear_velocity.x(), d.target_linear_velocity.y(), d.target_linear_velocity.z(),
                          d.target_angular_velocity.x(), d.target_angular_velocity.y(), d.target_angular_velocity.z(),
                          d.linear_stiffness, d.linear_damping, d.angular_stiffness, d.angular_damping, d.max_force, d.max_torque};
      w.put_reals(x, 19);
    }
    w.put(static_cast<std::uint32_t>(a->state.transmission_actuators.size()));
    for (const TransmissionActuator& t : a->state.transmission_actuators) {
      w.put(static_cast<std::uint8_t>(t.kind));
      const real x[8] = {t.value, t.stiffness, t.damping, real(t.allow_compressive_force ? 1 : 0),
                         t.minimum_pressure, t.thread_length, t.wraps, t.deflated_length};
      w.put_reals(x, 8);
    }
  }
  w.put(static_cast<std::uint32_t>(s.soft_bodies.size()));
  for (const auto& b : s.soft_bodies) {
    const real X[7] = {b->X_WL.rotation.x(), b->X_WL.rotation.y(), b->X_WL.rotation.z(), b->X_WL.rotation.w(),
                       b->X_WL.translation.x(), b->X_WL.translation.y(), b->X_WL.translation.z()};
    w.put_reals(X, 7);
    w.put(static_cast<std::uint32_t>(b->state.x.size()));
    w.put_reals(b->state.x.data(), b->state.x.size());
    w.put_reals(b->state.v.data(), b->state.v.size());
    w.put_reals(b->state.tau_external.data(), b->state.tau_external.size());
    w.put(static_cast<std::uint32_t>(b->state.q.size()));
    if (b->state.q.size() == 0) continue;
    w.put_reals(b->state.q.data(), b->state.q.size());
    w.put_reals(b->state.qd.data(), b->state.qd.size());
    w.put_reals(b->state.u_c.data(), b->state.u_c.size());
  }
  w.put(static_cast<std::uint32_t>(s.constraints.size()));
  for (const auto& [h, c] : s.constraints) {
    w.put(static_cast<std::uint8_t>(c.type));
    w.put_reals(constraint_state(c).data(), kConstraintReals);
  }
  std::uint32_t controllers = 0;
  for (const auto& a : s.articulations) controllers += a->pose_controller ? 1 : 0;
  w.put(controllers);
  for (const auto& a : s.articulations) {
    if (!a->pose_controller) continue;
    w.put(static_cast<std::int64_t>(a->handle));
    w.put(static_cast<std::uint8_t>(a->pose_controller->target_velocity ? 1 : 0));
    const std::vector<real> x = controller_state(*a);
    w.put_reals(x.data(), x.size());
  }
  return std::move(w.bytes);
}

void restore_state_bytes(SceneData& s, std::span<const std::uint8_t> bytes) {
  Reader r(bytes);
  for (char c : kMagic)
    if (r.get<char>("header") != c) throw Error("restore_state: not a SuperDex scene state (bad header)");
  const auto version = r.get<std::uint32_t>("version");
  if (version != kVersion) throw Error("restore_state: unsupported state version " + std::to_string(version));
  const auto real_size = r.get<std::uint8_t>("precision");
  if (real_size != sizeof(real))
    throw Error(std::string("restore_state: the state was captured by the ") + (real_size == 8 ? "double" : "float") +
                " build; this is the " + (kUsesDoublePrecision ? "double" : "float") + " build");
  const auto step_count = r.get<std::int64_t>("step count");
  const auto time = r.get<double>("time");
  const auto last_time_step = r.get<double>("last time step");
  const auto count = r.get<std::uint32_t>("body count");
  if (count != s.articulations.size())
    throw Error("restore_state: the state has " + std::to_string(count) + " actors but the scene has " +
                std::to_string(s.articulations.size()));
  // read everything first so that a bad state changes nothing
  std::vector<ArticulationState> states(count);
  // the actors' handles in the captured scene (another scene built the same way has others)
  std::vector<std::int64_t> state_handles(count);
  for (std::uint32_t i = 0; i < count; ++i) {
    const Articulation& a = *s.articulations[i];
    state_handles[i] = r.get<std::int64_t>("actor handle");
    const auto nq = r.get<std::uint32_t>("sizes"), nv = r.get<std::uint32_t>("sizes");
    // actors match by creation order and size, so a state restores into a scene built the same way
    if (nq != static_cast<std::uint32_t>(a.model.nq) || nv != static_cast<std::uint32_t>(a.model.nv))
      throw Error("restore_state: actor " + std::to_string(i) + " of the state (" + std::to_string(nq) + " positions, " +
                  std::to_string(nv) + " velocities) does not match actor '" + a.model.name + "' of the scene (" +
                  std::to_string(a.model.nq) + ", " + std::to_string(a.model.nv) + ")");
    ArticulationState& st = states[i];
    st.q.resize(nq), st.v.resize(nv), st.tau_external.resize(nv);
    r.get_reals(st.q.data(), nq, "positions");
    r.get_reals(st.v.data(), nv, "velocities");
    r.get_reals(st.tau_external.data(), nv, "forces");
    Eigen::Matrix<real, 3, 3, Eigen::RowMajor> R;
    r.get_reals(R.data(), 9, "base pose");
    st.X_W_base.R = R;
    r.get_reals(st.X_W_base.p.data(), 3, "base pose");
    st.drives.resize(nv);
    for (JointDrive& d : st.drives) {
      real x[5];
      r.get_reals(x, 5, "joint drives");
      d = {x[0], x[1], x[2], x[3], x[4]};
    }
    st.link_drives.resize(a.model.num_links);
    for (LinkDrive& d : st.link_drives) {
      real x[19];
      r.get_reals(x, 19, "link drives");
      d.target.rotation = Quat(x[3], x[0], x[1], x[2]);
      d.target.translation = Vec3(x[4], x[5], x[6]);
      d.target_linear_velocity = Vec3(x[7], x[8], x[9]);
      d.target_angular_velocity = Vec3(x[10], x[11], x[12]);
      d.linear_stiffness = x[13], d.linear_damping = x[14], d.angular_stiffness = x[15], d.angular_damping = x[16];
      d.max_force = x[17], d.max_torque = x[18];
    }
    const auto actuators = r.get<std::uint32_t>("transmission actuator count");
    if (actuators > a.model.transmissions.size())
      throw Error("restore_state: actor " + std::to_string(i) + " of the state has " + std::to_string(actuators) +
                  " transmissions but '" + a.model.name + "' has " + std::to_string(a.model.transmissions.size()));
    st.transmission_actuators.resize(a.model.transmissions.size());
    for (std::uint32_t k = 0; k < actuators; ++k) {
      TransmissionActuator& t = st.transmission_actuators[k];
      const auto kind = r.get<std::uint8_t>("transmission actuator kind");
      if (kind > static_cast<std::uint8_t>(TransmissionActuator::Kind::McKibben))
        throw Error("restore_state: actor " + std::to_string(i) + ": unknown transmission actuator kind " + std::to_string(kind));
      real x[8];
      r.get_reals(x, 8, "transmission actuators");
      t.kind = static_cast<TransmissionActuator::Kind>(kind);
      t.value = x[0], t.stiffness = x[1], t.damping = x[2], t.allow_compressive_force = x[3] != 0;
      t.minimum_pressure = x[4], t.thread_length = x[5], t.wraps = x[6], t.deflated_length = x[7];
    }
    if (!st.q.allFinite() || !st.v.allFinite() || !st.tau_external.allFinite())
      throw Error("restore_state: actor " + std::to_string(i) + " has non-finite values in the state");
  }
  const auto soft_count = r.get<std::uint32_t>("soft body count");
  if (soft_count != s.soft_bodies.size())
    throw Error("restore_state: the state has " + std::to_string(soft_count) + " soft actors but the scene has " +
                std::to_string(s.soft_bodies.size()));
  std::vector<SoftState> soft_states(soft_count);
  std::vector<Transform> soft_frames(soft_count);
  for (std::uint32_t i = 0; i < soft_count; ++i) {
    real X[7];
    r.get_reals(X, 7, "soft frame");
    soft_frames[i] = Transform{Quat(X[3], X[0], X[1], X[2]), Vec3(X[4], X[5], X[6])};
    const auto n = r.get<std::uint32_t>("soft sizes");
    if (n != s.soft_bodies[i]->state.x.size())
      throw Error("restore_state: soft actor " + std::to_string(i) + " of the state does not match '" + s.soft_bodies[i]->model.name + "'");
    SoftState& st = soft_states[i];
    st.x.resize(n), st.v.resize(n), st.tau_external.resize(n);
    r.get_reals(st.x.data(), n, "soft positions");
    r.get_reals(st.v.data(), n, "soft velocities");
    r.get_reals(st.tau_external.data(), n, "soft forces");
    const auto modes = r.get<std::uint32_t>("soft modes");
    if (modes != s.soft_bodies[i]->state.q.size())
      throw Error("restore_state: soft actor " + std::to_string(i) + " of the state has " + std::to_string(modes) + " reduced modes but '" +
                  s.soft_bodies[i]->model.name + "' has " + std::to_string(s.soft_bodies[i]->state.q.size()));
    if (modes > 0) {
      st.q.resize(modes), st.qd.resize(modes), st.u_c.resize(n);
      r.get_reals(st.q.data(), modes, "soft modal amplitudes");
      r.get_reals(st.qd.data(), modes, "soft modal velocities");
      r.get_reals(st.u_c.data(), n, "soft residual displacements");
      if (!st.q.allFinite() || !st.qd.allFinite() || !st.u_c.allFinite())
        throw Error("restore_state: soft actor " + std::to_string(i) + " has non-finite values in the state");
    }
    if (!st.x.allFinite() || !st.v.allFinite() || !st.tau_external.allFinite())
      throw Error("restore_state: soft actor " + std::to_string(i) + " has non-finite values in the state");
  }
  // constraints match by creation order and type
  const auto constraint_count = r.get<std::uint32_t>("constraint count");
  if (constraint_count != s.constraints.size())
    throw Error("restore_state: the state has " + std::to_string(constraint_count) + " constraints but the scene has " +
                std::to_string(s.constraints.size()));
  std::vector<std::array<real, kConstraintReals>> constraint_states(constraint_count);
  auto constraint = s.constraints.begin();
  for (std::uint32_t i = 0; i < constraint_count; ++i, ++constraint) {
    const auto type = r.get<std::uint8_t>("constraint type");
    if (type != static_cast<std::uint8_t>(constraint->second.type))
      throw Error("restore_state: constraint " + std::to_string(i) + " of the state is not of the type of the scene's (" +
                  constraint_type_name(constraint->second.type) + ")");
    r.get_reals(constraint_states[i].data(), kConstraintReals, "constraints");
    for (real x : constraint_states[i])
      if (!std::isfinite(x)) throw Error("restore_state: constraint " + std::to_string(i) + " has non-finite values in the state");
  }
  // pose controllers match by articulation, in body order
  std::vector<size_t> controlled_body;
  for (size_t b = 0; b < s.articulations.size(); ++b)
    if (s.articulations[b]->pose_controller) controlled_body.push_back(b);
  const auto controller_count = r.get<std::uint32_t>("pose controller count");
  if (controller_count != controlled_body.size())
    throw Error("restore_state: the state has " + std::to_string(controller_count) + " pose controllers but the scene has " +
                std::to_string(controlled_body.size()));
  std::vector<std::pair<bool, std::vector<real>>> controller_states(controller_count);
  for (std::uint32_t i = 0; i < controller_count; ++i) {
    const Articulation& a = *s.articulations[controlled_body[i]];
    // on the captured scene's actor in the same place
    if (r.get<std::int64_t>("pose controller actor") != state_handles[controlled_body[i]])
      throw Error("restore_state: pose controller " + std::to_string(i) + " of the state is not on actor '" + a.model.name + "' (actor " +
                  std::to_string(controlled_body[i]) + " in creation order)");
    controller_states[i].first = r.get<std::uint8_t>("pose controller velocity flag") != 0;
    controller_states[i].second.resize(2 * a.model.nv + 7 * a.model.num_links);
    r.get_reals(controller_states[i].second.data(), controller_states[i].second.size(), "pose controllers");
    for (real x : controller_states[i].second)
      if (!std::isfinite(x)) throw Error("restore_state: pose controller " + std::to_string(i) + " has non-finite values in the state");
  }
  if (!r.done()) throw Error("restore_state: unexpected bytes after the last pose controller");
  for (std::uint32_t i = 0; i < controller_count; ++i) restore_controller_state(*s.articulations[controlled_body[i]], controller_states[i].first, controller_states[i].second);
  constraint = s.constraints.begin();
  for (std::uint32_t i = 0; i < constraint_count; ++i, ++constraint) restore_constraint_state(constraint->second, constraint_states[i]);
  for (std::uint32_t i = 0; i < soft_count; ++i) {
    s.soft_bodies[i]->state = std::move(soft_states[i]);
    s.soft_bodies[i]->X_WL = soft_frames[i];
  }
  for (std::uint32_t i = 0; i < count; ++i) {
    s.articulations[i]->state = std::move(states[i]);
    refresh_kinematics(*s.articulations[i]);
  }
  s.step_count = step_count;
  s.time = time;
  s.last_time_step = last_time_step;
  s.contacts.clear();
  // results need a step after the restore
  for (auto& [id, q] : s.queries) q.since_step = s.step_count;
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

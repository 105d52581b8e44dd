// FORCE_TORQUE: the wrench transmitted through a link's joint, from its parent to the link
// and everything the link carries (its subtree S).
//
// Method: the momentum balance of S over the step. With P the linear momentum of S and H its
// angular momentum about the world origin O (fixed),
//   F_J = dP/dt - sum_i m_i g - F_contact
//   T_J,O = dH/dt - sum_i c_i x m_i g - T_contact,O
//   T_J = T_J,O - p_J x F_J                     (about the joint origin = the link origin)
// where dP/dt and dH/dt are finite differences over the time since the previous sample (the
// step, at rate 0), c_i are the links' centres of mass, F/T_contact the contact wrench on S
// (the sensor registers TOTAL_CONTACT_FORCE queries on every link of S), and
//   P = sum_i m_i v_ci,   H = sum_i (R_i I_i R_i^T w_i + c_i x m_i v_ci).
// Gravity moments, the joint origin p_J and the output frame use the poses at the start of the
// step, where the engine evaluates the step's forces. The result includes everything the joint
// transmits: constraint reaction, actuation, joint friction and damping. It is the impulse
// balance of the engine's step: at rest it is exact, and in motion the torque about a driven
// joint's axis equals the joint's torque to rounding (tested). At a rate below the step rate
// it is the average wrench over the sample period (first-order in the period).
// Mass properties come from the bot's prefab (the engine does not expose link inertias);
// links whose inertia would come from a scaled shape must give mass and momentOfInertia.
//
// Signal: [Fx, Fy, Fz (N), Tx, Ty, Tz (N m)], applied BY the parent ON the link, about the
// sensor origin in the sensor frame S (the link frame moved by parentFromSensor; by default the
// link frame at the link origin), or in world axes (still about the sensor origin). A link
// hanging at rest reads its subtree's weight upward: F_W = -m_S g.
//
// Params
//   "frame"  "link" | "world"   default "link"

#include "builtin_support.h"
#include "builtins.h"
#include "superdex/physics/engine.h"
#include "superdex/physics/shape.h"

namespace superdex::robotics {
inline namespace SUPERDEX_REAL_NAMESPACE {

using physics::Mat3;
using physics::Transform;
using physics::Vec6;

namespace {

struct LinkMass {
  real mass = 0;
  Vec3 com_L = Vec3::Zero();       // centre of mass in the link frame (m)
  Mat3 inertia_L = Mat3::Zero();   // rotational inertia about the COM, link axes (kg m^2)
  bool has_gravity = true;
};

// The mass properties of a link as the engine builds them from its description.
LinkMass link_mass(const physics::LinkDesc& L, real engine_mass, const std::string& where) {
  LinkMass out;
  out.has_gravity = L.has_gravity;
  if (L.mass && L.moment_of_inertia) {
    const auto& c = *L.moment_of_inertia;
    out.mass = *L.mass;
    out.com_L = L.center_of_mass.value_or(Vec3::Zero());
    out.inertia_L << c[0], c[1], c[2], c[1], c[3], c[4], c[2], c[4], c[5];
  } else {
    if (!L.shape || std::holds_alternative<physics::PlaneShape>(*L.shape) || !L.shape_scale.isOnes())
      throw Error(where + ": link '" + L.name + "': give its mass and momentOfInertia (its inertia cannot be derived here)");
    const physics::MassProperties unit = physics::shape_mass_properties(*L.shape, 1);
    const Mat3 R_LS = L.link_from_shape.rotation.normalized().toRotationMatrix();
    out.mass = L.mass ? *L.mass : unit.mass * L.density.value_or(real(1000));
    out.com_L = L.center_of_mass.value_or(R_LS * unit.center_of_mass + L.link_from_shape.translation);
    out.inertia_L = R_LS * unit.inertia_about_com * R_LS.transpose() * (out.mass / unit.mass);
  }
  if (std::abs(out.mass - engine_mass) > real(1e-4) * engine_mass)
    throw Error(where + ": link '" + L.name + "': its mass in the prefab (" + std::to_string(out.mass) +
                " kg) differs from the articulation's (" + std::to_string(engine_mass) + " kg)");
  return out;
}

class ForceTorqueSensor final : public SensorComponent {
 public:
  explicit ForceTorqueSensor(const ComponentArgs& args) : scene_(args.scene), link_(args.actor), X_LS_(args.parent_from_sensor) {
    require_link(scene_, link_, "FORCE_TORQUE");
    if (!args.prefab) throw Error("FORCE_TORQUE: needs the bot's prefab (create it on a link of a bot)");
    articulation_ = scene_.articulated_actor_of_link(link_);
    const auto links = scene_.nested_link_actors(articulation_);
    const std::vector<int> parents = scene_.articulated_shape_info(articulation_).parents;
    if (args.prefab->articulation.links.size() != links.size())
      throw Error("FORCE_TORQUE: the prefab given does not describe the link's articulation");
    // the subtree: the link and every link whose parent is in it (parents precede children)
    const int j = scene_.link_index(link_);
    std::vector<bool> in(links.size(), false);
    for (size_t i = j; i < links.size(); ++i) {
      in[i] = static_cast<int>(i) == j || (parents[i] >= 0 && in[parents[i]]);
      if (!in[i]) continue;
      subtree_.push_back({links[i], static_cast<int>(i), link_mass(args.prefab->articulation.links[i], scene_.mass(links[i]), "FORCE_TORQUE")});
    }
    configure(args.params);
    for (Member& m : subtree_) m.query = scene_.register_query(m.actor, physics::QueryType::TotalContactForce);
    reset();
  }

  ~ForceTorqueSensor() override {
    if (!physics::scene_exists(scene_.handle())) return;
    for (const Member& m : subtree_)
      if (scene_.has_actor(m.actor)) scene_.cancel_query(m.actor, m.query);
  }

  void reset() override {
    const Momentum mom = momentum();
    P_prev_ = mom.P, H_prev_ = mom.H;
    X_prev_ = scene_.link_transforms(articulation_);
    t_prev_ = scene_.total_simulation_time();
    signal_.setZero();
  }

  void configure(const std::string& json) override {
    ComponentParams p(json, "FORCE_TORQUE");
    p.allow_only({"frame"});
    const std::string frame = p.text("frame", in_world_ ? "world" : "link");
    if (frame != "world" && frame != "link") throw Error(p.at("frame") + ": expected \"link\" or \"world\", got \"" + frame + "\"");
    p.apply_rate(*this);
    in_world_ = frame == "world";
  }

  void update(const Tick& tick) override {
    const double elapsed = tick.time - t_prev_;
    if (elapsed <= 0) return;
    const Momentum mom = momentum();
    const Vec3 g = scene_.gravity();
    const auto X = scene_.link_transforms(articulation_);
    // gravity (at the start-of-step poses) and contact wrenches on the subtree, about O
    Vec3 F_ext = Vec3::Zero(), T_ext = Vec3::Zero();
    for (const Member& m : subtree_) {
      if (m.mass.has_gravity) {
        const Vec3 c_W = X_prev_[m.index] * m.mass.com_L;
        F_ext += m.mass.mass * g;
        T_ext += c_W.cross(m.mass.mass * g);
      }
      // contact torque about the link origin, moved to O (independent of the origin used)
      const Vec3 f_c = scene_.contact_force(m.actor);
      F_ext += f_c;
      T_ext += contact_torque_about_origin(scene_, m.actor) + X[m.index].translation.cross(f_c);
    }
    const real inv_dt = static_cast<real>(1.0 / elapsed);
    const Vec3 F_W = (mom.P - P_prev_) * inv_dt - F_ext;
    const Vec3 T_O = (mom.H - H_prev_) * inv_dt - T_ext;
    // about the sensor origin, in the sensor frame (the link frame at the start of the step, moved by X_LS)
    const Transform X_WS = X_prev_[subtree_.front().index] * X_LS_;
    const Vec3 T_W = T_O - X_WS.translation.cross(F_W);
    if (in_world_) {
      signal_ << F_W, T_W;
    } else {
      const Quat R_SW = X_WS.rotation.conjugate();
      signal_ << R_SW * F_W, R_SW * T_W;
    }
    P_prev_ = mom.P, H_prev_ = mom.H;
    X_prev_ = X;
    t_prev_ = tick.time;
  }

  VecX signal() const override { return signal_; }

 private:
  struct Member {
    ActorHandle actor;
    int index;
    LinkMass mass;
    std::int64_t query = 0;
  };
  struct Momentum {
    Vec3 P, H;  // linear (kg m/s) and angular about the world origin (kg m^2/s), world
  };

  Momentum momentum() const {
    const auto X = scene_.link_transforms(articulation_);
    Momentum out{Vec3::Zero(), Vec3::Zero()};
    for (const Member& m : subtree_) {
      const Transform& X_WL = X[m.index];
      const Vec6 V = link_origin_velocity(scene_, m.actor);
      const Mat3 R = X_WL.rotation.toRotationMatrix();
      const Vec3 r_W = R * m.mass.com_L;
      const Vec3 v_c = V.head<3>() + V.tail<3>().cross(r_W);
      const Vec3 c_W = X_WL.translation + r_W;
      out.P += m.mass.mass * v_c;
      out.H += R * m.mass.inertia_L * R.transpose() * V.tail<3>() + c_W.cross(m.mass.mass * v_c);
    }
    return out;
  }

  Scene scene_;
  ActorHandle link_, articulation_ = 0;
  std::vector<Member> subtree_;
  bool in_world_ = false;
  // the previous sample: momenta and link poses
  Vec3 P_prev_ = Vec3::Zero(), H_prev_ = Vec3::Zero();
  std::vector<Transform> X_prev_;
  double t_prev_ = 0;
  Vec6 signal_ = Vec6::Zero();
  Transform X_LS_;  // sensor frame in the link frame
};

}  // namespace

std::unique_ptr<Component> make_force_torque_sensor(const ComponentArgs& args) { return std::make_unique<ForceTorqueSensor>(args); }

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::robotics

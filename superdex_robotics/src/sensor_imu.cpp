// IMU: the specific force and angular velocity at the sensor frame S on a link (S is the link
// frame moved by parentFromSensor; the link frame itself by default).
//
// Signal: [f_x, f_y, f_z (m/s^2), w_x, w_y, w_z (rad/s)], S axes:
//   f_S = R_WS^T (a_W - g_W),  a_W = (v_W(t) - v_W(t_prev)) / (t - t_prev)
// where v_W = v_origin + w x (p_S - p_origin) is the world velocity of the sensor's ORIGIN,
// finite-differenced over the time since the previous sample (the step, at rate 0), and g_W
// the scene's gravity. This is the accelerometer convention: at rest the IMU reads +|g| along
// the upward axis (0, 0, +9.81 for a level sensor under gravity (0, 0, -9.81)); in free fall it
// reads 0; on a spinning link it reads the centripetal acceleration of its mounting point.
// w_S = R_WS^T w_W at the end of the step. The first sample differences against the state at
// creation (or reset).
//
// Params: only "rate".

#include "builtin_support.h"
#include "builtins.h"

namespace superdex::robotics {
inline namespace SUPERDEX_REAL_NAMESPACE {

using physics::Vec6;

namespace {

class ImuSensor final : public SensorComponent {
 public:
  explicit ImuSensor(const ComponentArgs& args) : scene_(args.scene), link_(args.actor), X_LS_(args.parent_from_sensor) {
    require_link(scene_, link_, "IMU");
    configure(args.params);
    reset();
  }

  void reset() override {
    v_prev_ = point_velocity();
    t_prev_ = scene_.total_simulation_time();
    signal_.setZero();
  }

  void configure(const std::string& json) override {
    ComponentParams p(json, "IMU");
    p.allow_only({});
    p.apply_rate(*this);
  }

  void update(const Tick& tick) override {
    const double elapsed = tick.time - t_prev_;
    if (elapsed <= 0) return;
    const Vec3 v_W = point_velocity();
    const Vec3 a_W = (v_W - v_prev_) / static_cast<real>(elapsed);
    const Quat R_SW = (scene_.root_transform(link_).rotation * X_LS_.rotation).conjugate();
    signal_.head<3>() = R_SW * (a_W - scene_.gravity());
    signal_.tail<3>() = R_SW * Vec3(link_origin_velocity(scene_, link_).tail<3>());
    v_prev_ = v_W;
    t_prev_ = tick.time;
  }

  // world velocity of the sensor origin: v_origin + w x (R_WL p_LS)
  Vec3 point_velocity() const {
    const Vec6 V_W = link_origin_velocity(scene_, link_);
    const Vec3 r_W = scene_.root_transform(link_).rotation * X_LS_.translation;
    return V_W.head<3>() + Vec3(V_W.tail<3>()).cross(r_W);
  }

  VecX signal() const override { return signal_; }

 private:
  Scene scene_;
  ActorHandle link_;
  Transform X_LS_;  // sensor frame in the link frame
  Vec3 v_prev_ = Vec3::Zero();
  double t_prev_ = 0;
  Vec6 signal_ = Vec6::Zero();
};

}  // namespace

std::unique_ptr<Component> make_imu_sensor(const ComponentArgs& args) { return std::make_unique<ImuSensor>(args); }

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::robotics

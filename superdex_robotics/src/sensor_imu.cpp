// IMU: a link's specific force and angular velocity, in the link frame L.
//
// Signal: [f_x, f_y, f_z (m/s^2), w_x, w_y, w_z (rad/s)], L axes:
//   f_L = R_WL^T (a_W - g_W),  a_W = (v_W(t) - v_W(t_prev)) / (t - t_prev)
// where v_W is the world velocity of the link ORIGIN, finite-differenced over the time since
// the previous sample (the step, at rate 0) and g_W the scene's gravity. This is the
// accelerometer convention: at rest the IMU reads +|g| along the upward axis (0, 0, +9.81 for
// a level link under gravity (0, 0, -9.81)); in free fall it reads 0. w_L = R_WL^T w_W at the
// end of the step. The first sample differences against the state at creation (or reset).
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
  explicit ImuSensor(const ComponentArgs& args) : scene_(args.scene), link_(args.actor) {
    require_link(scene_, link_, "IMU");
    configure(args.params);
    reset();
  }

  void reset() override {
    v_prev_ = scene_.velocity(link_).head<3>();
    t_prev_ = scene_.total_simulation_time();
    signal_.setZero();
  }

  void configure(const std::string& json) override {
    ComponentParams p(json, "IMU");
    p.allow_only({});
    p.apply_rate(*this);
  }

  void update(const Tick& tick) override {
    const Vec6 V_W = scene_.velocity(link_);
    const double elapsed = tick.time - t_prev_;
    if (elapsed <= 0) return;
    const Vec3 a_W = (V_W.head<3>() - v_prev_) / static_cast<real>(elapsed);
    const Quat R_LW = scene_.root_transform(link_).rotation.conjugate();
    signal_.head<3>() = R_LW * (a_W - scene_.gravity());
    signal_.tail<3>() = R_LW * Vec3(V_W.tail<3>());
    v_prev_ = V_W.head<3>();
    t_prev_ = tick.time;
  }

  VecX signal() const override { return signal_; }

 private:
  Scene scene_;
  ActorHandle link_;
  Vec3 v_prev_ = Vec3::Zero();
  double t_prev_ = 0;
  Vec6 signal_ = Vec6::Zero();
};

}  // namespace

std::unique_ptr<Component> make_imu_sensor(const ComponentArgs& args) { return std::make_unique<ImuSensor>(args); }

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::robotics

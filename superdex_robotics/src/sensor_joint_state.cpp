// JOINT_STATE: joint positions and velocities, optionally with Gaussian noise and quantisation.
//
// On a link actor it reads the DOFs of the link's joint; on an articulation, all its DOFs
// (root joint first). Signal: [q_0 .. q_n-1, v_0 .. v_n-1] (rad or m, rad/s or m/s), each
//   x = quantise(x_true + N(0, std^2)),  quantise(x) = resolution * round(x / resolution)
// (no noise when std = 0, no quantisation when resolution = 0). The noise generator is a
// 64-bit Mersenne twister seeded with "seed": the same seed gives the same readings, and
// reset() restarts the sequence.
//
// Params
//   "position_noise_std"    rad (m) >= 0      default 0
//   "velocity_noise_std"    rad/s (m/s) >= 0  default 0
//   "position_resolution"   rad (m) >= 0      default 0
//   "velocity_resolution"   rad/s (m/s) >= 0  default 0
//   "seed"                  integer           default 0

#include <cmath>
#include <random>

#include "builtin_support.h"
#include "builtins.h"

namespace superdex::robotics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace {

class JointStateSensor final : public SensorComponent {
 public:
  explicit JointStateSensor(const ComponentArgs& args) : scene_(args.scene) {
    if (args.actor == 0) throw Error("JOINT_STATE: needs an actor (a link or an articulation)");
    if (scene_.is_nested_link_actor(args.actor)) {
      articulation_ = scene_.articulated_actor_of_link(args.actor);
      const physics::ArticulatedDofInfo d = joint_dofs_of_link(scene_, args.actor, "JOINT_STATE");
      offset_ = d.offset, count_ = d.size();
    } else {
      articulation_ = articulation_of(scene_, args.actor, "JOINT_STATE");
      offset_ = 0, count_ = scene_.num_dofs(articulation_);
    }
    signal_ = VecX::Zero(2 * count_);
    configure(args.params);
    rng_.seed(seed_);
  }

  void reset() override {
    rng_.seed(seed_);
    signal_.setZero();
  }

  void configure(const std::string& json) override {
    ComponentParams p(json, "JOINT_STATE");
    p.allow_only({"position_noise_std", "velocity_noise_std", "position_resolution", "velocity_resolution", "seed"});
    const real values[4] = {p.number("position_noise_std", position_std_), p.number("velocity_noise_std", velocity_std_),
                            p.number("position_resolution", position_resolution_),
                            p.number("velocity_resolution", velocity_resolution_)};
    for (real x : values)
      if (x < 0) throw Error("JOINT_STATE: noise std and resolution must be >= 0");
    if (p.has("seed")) {
      const auto& s = p.json().at("seed");
      if (!s.is_number_integer()) throw Error(p.at("seed") + ": expected an integer");
      seed_ = s.get<std::int64_t>();
      rng_.seed(seed_);
    }
    p.apply_rate(*this);
    position_std_ = values[0], velocity_std_ = values[1], position_resolution_ = values[2], velocity_resolution_ = values[3];
  }

  void update(const Tick&) override {
    const VecX q = scene_.pose(articulation_);
    const VecX v = scene_.joint_velocities(articulation_);
    for (int i = 0; i < count_; ++i) {
      signal_[i] = measure(q[offset_ + i], position_std_, position_resolution_);
      signal_[count_ + i] = measure(v[offset_ + i], velocity_std_, velocity_resolution_);
    }
  }

  VecX signal() const override { return signal_; }

 private:
  real measure(real x, real std, real resolution) {
    double y = x;
    if (std > 0) y += std::normal_distribution<double>(0.0, std)(rng_);
    if (resolution > 0) y = resolution * std::round(y / resolution);
    return static_cast<real>(y);
  }

  Scene scene_;
  ActorHandle articulation_ = 0;
  int offset_ = 0, count_ = 0;
  real position_std_ = 0, velocity_std_ = 0, position_resolution_ = 0, velocity_resolution_ = 0;
  std::int64_t seed_ = 0;
  std::mt19937_64 rng_;
  VecX signal_;
};

}  // namespace

std::unique_ptr<Component> make_joint_state_sensor(const ComponentArgs& args) { return std::make_unique<JointStateSensor>(args); }

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::robotics

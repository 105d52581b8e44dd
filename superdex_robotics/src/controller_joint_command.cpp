// JOINT_COMMAND: constant per-DOF setpoints, set by params and changed at run time with
// configure. This is how a script (or a test) commands actuators through the pipeline.
//
// Params (joint DOFs: bot DOF order without the root joint's DOFs; null: not commanded)
//   "position"  [rad or m]      default: none
//   "velocity"  [rad/s or m/s]  default: none
//   "effort"    [N m or N]      default: none; an actuator on the DOF receives it as its
//                               command, a DOF without an actuator gets it as its force

#include <cmath>
#include <limits>

#include "builtin_support.h"
#include "builtins.h"

namespace superdex::robotics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace {

class JointCommandController final : public ControllerComponent {
 public:
  explicit JointCommandController(const ComponentArgs& args)
      : scene_(args.scene), articulation_(articulation_of(args.scene, args.actor, "JOINT_COMMAND")) {
    root_ = root_dofs(scene_, articulation_);
    const int n = scene_.num_dofs(articulation_) - root_;
    const VecX none = VecX::Constant(n, std::numeric_limits<real>::quiet_NaN());
    position_ = velocity_ = effort_ = none;
    configure(args.params);
  }

  void reset() override {}

  void configure(const std::string& json) override {
    ComponentParams p(json, "JOINT_COMMAND");
    p.allow_only({"position", "velocity", "effort"});
    p.apply_rate(*this);
    const int n = static_cast<int>(position_.size());
    position_ = p.vector("position", n, position_, true);
    velocity_ = p.vector("velocity", n, velocity_, true);
    effort_ = p.vector("effort", n, effort_, true);
  }

  void compute(const Tick&, DofCommands& out) override {
    for (int i = 0; i < position_.size(); ++i) {
      if (!std::isnan(position_[i])) out.set_position(root_ + i, position_[i]);
      if (!std::isnan(velocity_[i])) out.set_velocity(root_ + i, velocity_[i]);
      if (!std::isnan(effort_[i])) out.set_effort(root_ + i, effort_[i]);
    }
  }

 private:
  Scene scene_;
  ActorHandle articulation_;
  int root_ = 0;
  VecX position_, velocity_, effort_;  // NaN: not commanded
};

}  // namespace

std::unique_ptr<Component> make_joint_command_controller(const ComponentArgs& args) {
  return std::make_unique<JointCommandController>(args);
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::robotics

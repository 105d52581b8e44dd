// ARTICULATED_POSE: stiff joint pose tracking solved inside the physics step.
//
// Each controlled joint DOF gets an engine joint drive (Scene::set_joint_drive): the effort
// K (q* - q+) + D (v* - v+) evaluated at the END of the step, inside the step's implicit solve,
// so any stiffness is stable and contacts, limits and damping are solved together with it
// (an explicit PD with a large K is unstable once dt sqrt(K / M) is of order one). The
// controller sets the drives' targets each time it runs and removes them when it is destroyed.
// With compensate_bias, the bias forces c(q, v) (gravity, Coriolis) are added as an effort
// command (explicit feed-forward), so the drive only corrects the pose error.
// Link (Cartesian) pose targets are left for later.
// Drives act on revolute and prismatic joints; a floating base's DOFs are not driven.
//
// Params (joint DOFs: bot DOF order without the root joint's DOFs; a number is broadcast)
//   "stiffness"        N m/rad (N/m)       default 1000
//   "damping"          N m s/rad (N s/m)   default 50
//   "saturation"       N m (N), < 0: none  default -1 (clamps the drive's effort)
//   "target_pose"      rad (m)             default: the pose at creation
//   "target_velocity"  rad/s (m/s)         default 0
//   "compensate_bias"  bool                default true (gravity, Coriolis, centrifugal)

#include <algorithm>

#include "superdex/physics/engine.h"

#include "builtin_support.h"
#include "builtins.h"

namespace superdex::robotics {
inline namespace SUPERDEX_REAL_NAMESPACE {


namespace {

class ArticulatedPoseController final : public ControllerComponent {
 public:
  explicit ArticulatedPoseController(const ComponentArgs& args)
      : scene_(args.scene), articulation_(articulation_of(args.scene, args.actor, "ARTICULATED_POSE")) {
    root_ = root_dofs(scene_, articulation_);
    const int n = scene_.num_dofs(articulation_) - root_;
    stiffness_ = VecX::Constant(n, 1000);
    damping_ = VecX::Constant(n, 50);
    saturation_ = VecX::Constant(n, -1);
    target_pose_ = scene_.pose(articulation_).tail(n);
    target_velocity_ = VecX::Zero(n);
    configure(args.params);
    // refuse joints a drive cannot act on now, not in the middle of a step
    try {
      for (int i = 0; i < n; ++i) scene_.set_joint_drive(articulation_, root_ + i, physics::JointDrive{});
    } catch (const Error& e) {
      throw Error(std::string("ARTICULATED_POSE: ") + e.what());
    }
  }

  void reset() override {}

  void configure(const std::string& json) override {
    ComponentParams p(json, "ARTICULATED_POSE");
    p.allow_only({"stiffness", "damping", "saturation", "target_pose", "target_velocity", "compensate_bias"});
    p.apply_rate(*this);
    const int n = static_cast<int>(stiffness_.size());
    stiffness_ = p.vector("stiffness", n, stiffness_);
    damping_ = p.vector("damping", n, damping_);
    saturation_ = p.vector("saturation", n, saturation_);
    target_pose_ = p.vector("target_pose", n, target_pose_);
    target_velocity_ = p.vector("target_velocity", n, target_velocity_);
    compensate_bias_ = p.flag("compensate_bias", compensate_bias_);
    if ((stiffness_.array() < 0).any() || (damping_.array() < 0).any())
      throw Error("ARTICULATED_POSE: stiffness and damping must be >= 0");
  }

  ~ArticulatedPoseController() override {
    // the drives belong to this controller: remove them if the articulation is still there
    try {
      if (physics::scene_exists(scene_.handle()) && scene_.has_actor(articulation_)) {
        for (int i = 0; i < stiffness_.size(); ++i) scene_.set_joint_drive(articulation_, root_ + i, physics::JointDrive{});
      }
    } catch (const Error&) {
    }
  }

  void compute(const Tick& tick, DofCommands& out) override {
    for (int i = 0; i < stiffness_.size(); ++i) {
      const int d = root_ + i;
      scene_.set_joint_drive(articulation_, d,
                             physics::JointDrive{stiffness_[i], damping_[i], target_pose_[i], target_velocity_[i], saturation_[i]});
    }
    if (compensate_bias_) {
      const VecX c = scene_.bias_forces(articulation_);
      for (int i = 0; i < stiffness_.size(); ++i) out.set_effort(root_ + i, c[root_ + i]);
    }
  }

 private:
  Scene scene_;
  ActorHandle articulation_;
  int root_ = 0;
  VecX stiffness_, damping_, saturation_, target_pose_, target_velocity_;
  bool compensate_bias_ = true;
};

}  // namespace

std::unique_ptr<Component> make_articulated_pose_controller(const ComponentArgs& args) {
  return std::make_unique<ArticulatedPoseController>(args);
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::robotics

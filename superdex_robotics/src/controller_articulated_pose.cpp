// ARTICULATED_POSE: stiff joint pose tracking solved inside the physics step.
//
// Each controlled joint DOF gets an engine joint drive (Scene::set_joint_drive): the effort
// K (q* - q+) + D (v* - v+) evaluated at the END of the step, inside the step's implicit solve,
// so any stiffness is stable and contacts, limits and damping are solved together with it
// (an explicit PD with a large K is unstable once dt sqrt(K / M) is of order one). The
// controller sets the drives' targets each time it runs and removes them when it is destroyed.
// With compensate_bias, the bias forces c(q, v) (gravity, Coriolis) are added as an effort
// command (explicit feed-forward), so the drive only corrects the pose error.
// Drives act on revolute and prismatic joints; a floating base's DOFs are not driven.
//
// With "link", the controller instead drives that link towards a world pose with an engine link
// drive (Scene::set_link_drive), also inside the solve: params "link" (name), "target_position"
// (m, world; default: the link's position at creation), "target_orientation" ([x, y, z, w];
// default: at creation), "linear_stiffness" (N/m, 1000), "linear_damping" (N s/m, 50),
// "angular_stiffness" (N m/rad, 100), "angular_damping" (N m s/rad, 5), "max_force" (N) and
// "max_torque" (N m) per axis (< 0: none), "compensate_bias".
//
// Joint mode params (joint DOFs: bot DOF order without the root joint's DOFs; a number is broadcast)
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
    // link mode: the named link, with its pose at creation as the default target
    const ComponentParams p(args.params, "ARTICULATED_POSE");
    if (p.has("link")) {
      const std::string name = p.text("link", "");
      const auto info = scene_.articulated_shape_info(articulation_);
      const auto links = scene_.nested_link_actors(articulation_);
      for (size_t i = 0; i < info.link_names.size(); ++i)
        if (info.link_names[i] == name) link_actor_ = links[i];
      if (link_actor_ == 0) throw Error(p.at("link") + ": the articulation has no link named '" + name + "'");
      link_drive_.target = scene_.root_transform(link_actor_);
      link_drive_.linear_stiffness = 1000, link_drive_.linear_damping = 50;
      link_drive_.angular_stiffness = 100, link_drive_.angular_damping = 5;
    }
    configure(args.params);
    // refuse joints a drive cannot act on now, not in the middle of a step
    try {
      if (link_actor_ == 0)
        for (int i = 0; i < n; ++i) scene_.set_joint_drive(articulation_, root_ + i, physics::JointDrive{});
    } catch (const Error& e) {
      throw Error(std::string("ARTICULATED_POSE: ") + e.what());
    }
  }

  void reset() override {}

  void configure(const std::string& json) override {
    ComponentParams p(json, "ARTICULATED_POSE");
    if (link_actor_ != 0) {
      p.allow_only({"link", "target_position", "target_orientation", "linear_stiffness", "linear_damping",
                    "angular_stiffness", "angular_damping", "max_force", "max_torque", "compensate_bias"});
      p.apply_rate(*this);
      physics::LinkDrive& d = link_drive_;
      d.target.translation = p.vec3("target_position", d.target.translation);
      d.target.rotation = p.quaternion("target_orientation", d.target.rotation);
      d.linear_stiffness = p.number("linear_stiffness", d.linear_stiffness);
      d.linear_damping = p.number("linear_damping", d.linear_damping);
      d.angular_stiffness = p.number("angular_stiffness", d.angular_stiffness);
      d.angular_damping = p.number("angular_damping", d.angular_damping);
      d.max_force = p.number("max_force", d.max_force);
      d.max_torque = p.number("max_torque", d.max_torque);
      compensate_bias_ = p.flag("compensate_bias", compensate_bias_);
      return;
    }
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
        if (link_actor_ != 0) scene_.set_link_drive(link_actor_, physics::LinkDrive{});
        else
          for (int i = 0; i < stiffness_.size(); ++i) scene_.set_joint_drive(articulation_, root_ + i, physics::JointDrive{});
      }
    } catch (const Error&) {
    }
  }

  void compute(const Tick& tick, DofCommands& out) override {
    if (link_actor_ != 0) scene_.set_link_drive(link_actor_, link_drive_);
    for (int i = 0; i < stiffness_.size() && link_actor_ == 0; ++i) {
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
  ActorHandle link_actor_ = 0;  // link mode: the driven link
  physics::LinkDrive link_drive_;
};

}  // namespace

std::unique_ptr<Component> make_articulated_pose_controller(const ComponentArgs& args) {
  return std::make_unique<ArticulatedPoseController>(args);
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::robotics

// ARTICULATED_POSE: stiff joint pose tracking, implicit in the step's dt.
//
// An explicit PD with a large stiffness K is unstable once dt sqrt(K / M) is of order one.
// This controller instead picks the effort that makes the next step's velocity v+ satisfy
// the PD law evaluated at the END of the step (backward Euler), given the engine's
// semi-implicit integration v+ = v + dt M^-1 (tau - c), q+ = q + dt v+:
//   M (v+ - v) / dt = K (q* - q - dt v+) + D (v* - v+)
//   =>  (M + dt D + dt^2 K) a = K (q* - q - dt v) + D (v* - v),   a = (v+ - v) / dt
//       tau = M a [+ c(q, v) with compensate_bias]
// It is computed before each step from the mass matrix M (with armature) and the bias forces
// c, so the unconstrained articulation follows the implicit PD exactly and stays stable for any
// stiffness; joint damping, limits and contacts act on top (they are not in this estimate).
// The fully implicit version, with the PD rows inside the physics solve (so that contacts see
// them too), and link (Cartesian) pose targets are left for later.
// Run it every step (rate 0): a held effort is no longer implicit.
// For a floating base the root DOFs get no effort (K = D = 0 there); the estimate then ignores
// the base reaction and is approximate.
//
// Params (joint DOFs: bot DOF order without the root joint's DOFs; a number is broadcast)
//   "stiffness"        N m/rad (N/m)       default 1000
//   "damping"          N m s/rad (N s/m)   default 50
//   "saturation"       N m (N), < 0: none  default -1
//   "target_pose"      rad (m)             default: the pose at creation
//   "target_velocity"  rad/s (m/s)         default 0
//   "compensate_bias"  bool                default true (gravity, Coriolis, centrifugal)

#include <algorithm>

#include <Eigen/Cholesky>

#include "builtin_support.h"
#include "builtins.h"

namespace superdex::robotics {
inline namespace SUPERDEX_REAL_NAMESPACE {

using physics::MatX;

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

  void compute(const Tick& tick, DofCommands& out) override {
    const real h = tick.step_dt;
    const VecX q = scene_.pose(articulation_);
    const VecX v = scene_.joint_velocities(articulation_);
    const int nv = static_cast<int>(v.size());
    const MatX M = scene_.mass_matrix(articulation_);
    // (M + h D + h^2 K) a = K (q* - q - h v) + D (v* - v) on the joint DOFs
    MatX A = M;
    VecX rhs = VecX::Zero(nv);
    for (int i = 0; i < stiffness_.size(); ++i) {
      const int d = root_ + i;
      const real K = stiffness_[i], D = damping_[i];
      A(d, d) += h * D + h * h * K;
      rhs[d] = K * (target_pose_[i] - q[d] - h * v[d]) + D * (target_velocity_[i] - v[d]);
    }
    const VecX a = A.ldlt().solve(rhs);
    VecX tau = M * a;
    if (compensate_bias_) tau += scene_.bias_forces(articulation_);
    for (int i = 0; i < stiffness_.size(); ++i) {
      const int d = root_ + i;
      real t = tau[d];
      if (saturation_[i] >= 0) t = std::clamp(t, -saturation_[i], saturation_[i]);
      out.set_effort(d, t);
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

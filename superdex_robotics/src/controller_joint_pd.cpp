// BASIC_JSC_PD: joint-space PD control writing per-DOF efforts.
//
//   e_i   = q*_i - q_i, set to 0 where |e_i| < deadband_i
//   tau_i = kp_i e_i + kd_i (v*_i - v_i) [+ c_i(q, v) with gravity_compensation]
//   |tau_i| <= saturation_i when saturation_i >= 0
//
// Params (joint DOFs: bot DOF order without the root joint's DOFs; a number is broadcast)
//   "kp"                    N m/rad (N/m)        default 100
//   "kd"                    N m s/rad (N s/m)    default 10
//   "saturation"            N m (N), < 0: none   default -1
//   "deadband"              rad (m)              default 0
//   "target_pose"           rad (m)              default: the pose at creation
//   "target_velocity"       rad/s (m/s)          default 0
//   "gravity_compensation"  bool                 default false; adds the bias forces c(q, v)
//                                                (gravity, Coriolis, centrifugal)
// The efforts are applied explicitly (computed before the step): choose gains for the robot,
// stable while kd dt / I_min < 2 and kp dt^2 / I_min << 1, with I_min the smallest eigenvalue
// of the mass matrix (armature included). For stiffer tracking use ARTICULATED_POSE.

#include <algorithm>
#include <cmath>

#include "builtin_support.h"
#include "builtins.h"
#include "superdex/robotics/controller_basic_jsc_pd.h"

namespace superdex::robotics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace {

bool is_blank(const std::string& s) { return s.find_first_not_of(" \t\r\n") == std::string::npos; }

// One value per joint DOF from a params vector: empty -> the default, one value -> broadcast.
VecX per_dof(const std::vector<real>& v, int n, real fallback, const char* field) {
  if (v.empty()) return VecX::Constant(n, fallback);
  if (v.size() == 1) return VecX::Constant(n, v[0]);
  if (static_cast<int>(v.size()) != n)
    throw Error(std::string("BASIC_JSC_PD.set_params: params.") + field + ": expected " +
                (n == 1 ? std::string("1 value") : "1 or " + std::to_string(n) + " values") + " (one per joint DOF), got " +
                std::to_string(v.size()));
  VecX out(n);
  for (int i = 0; i < n; ++i) {
    if (!std::isfinite(v[i])) throw Error(std::string("BASIC_JSC_PD.set_params: params.") + field + "[" + std::to_string(i) + "]: must be finite");
    out[i] = v[i];
  }
  return out;
}

// kp, kd and deadband are magnitudes: a negative one would push away from the target
void check_gains(const VecX& kp, const VecX& kd, const VecX& deadband, const char* prefix) {
  for (auto [name, v] : {std::pair{"kp", &kp}, {"kd", &kd}, {"deadband", &deadband}})
    for (int i = 0; i < v->size(); ++i)
      if ((*v)[i] < 0) throw Error(std::string(prefix) + name + "[" + std::to_string(i) + "]: must be >= 0, got " + std::to_string((*v)[i]));
}

class JointPdController final : public ControllerBasicJscPd {
 public:
  explicit JointPdController(const ComponentArgs& args)
      : scene_(args.scene), articulation_(articulation_of(args.scene, args.actor, "BASIC_JSC_PD")) {
    root_ = root_dofs(scene_, articulation_);
    const int n = scene_.num_dofs(articulation_) - root_;
    set_params(ControllerBasicJscPdParams{});
    target_pose_ = scene_.pose(articulation_).tail(n);
    target_velocity_ = VecX::Zero(n);
    configure(args.params);
  }

  void reset() override {}

  void configure(const std::string& json) override {
    ComponentParams p(json, "BASIC_JSC_PD");
    p.allow_only({"kp", "kd", "saturation", "deadband", "target_pose", "target_velocity", "gravity_compensation"});
    p.apply_rate(*this);
    const int n = static_cast<int>(kp_.size());
    check_gains(p.vector("kp", n, kp_), p.vector("kd", n, kd_), p.vector("deadband", n, deadband_), p.at("").c_str());
    kp_ = p.vector("kp", n, kp_);
    kd_ = p.vector("kd", n, kd_);
    saturation_ = p.vector("saturation", n, saturation_);
    deadband_ = p.vector("deadband", n, deadband_);
    target_pose_ = p.vector("target_pose", n, target_pose_);
    target_velocity_ = p.vector("target_velocity", n, target_velocity_);
    gravity_compensation_ = p.flag("gravity_compensation", gravity_compensation_);
  }

  ControllerBasicJscPdParams params() const override {
    auto list = [](const VecX& v) { return std::vector<real>(v.data(), v.data() + v.size()); };
    return {list(kp_), list(kd_), list(saturation_), list(deadband_)};
  }

  void set_params(const ControllerBasicJscPdParams& p) override {
    const int n = scene_.num_dofs(articulation_) - root_;
    const VecX kp = per_dof(p.kp, n, 100, "kp"), kd = per_dof(p.kd, n, 10, "kd");
    const VecX saturation = per_dof(p.saturation, n, -1, "saturation"), deadband = per_dof(p.deadband, n, 0, "deadband");
    check_gains(kp, kd, deadband, "BASIC_JSC_PD.set_params: params.");
    kp_ = kp, kd_ = kd, saturation_ = saturation, deadband_ = deadband;
  }

  // scene files: empty params restore the default gains; init args carry the targets
  void configure_from_scene_entry(const std::string& params, const std::string& init_args) override {
    const std::string where = "BASIC_JSC_PD.configure_from_scene_entry";
    set_params(is_blank(params) ? ControllerBasicJscPdParams{} : ControllerBasicJscPdParams::from_json_text(params, where + ": param_args"));
    if (!is_blank(init_args)) configure(init_args);
  }

  void compute(const Tick&, DofCommands& out) override {
    scene_.pose(articulation_, q_);
    scene_.joint_velocities(articulation_, v_);
    if (gravity_compensation_) c_ = scene_.bias_forces(articulation_);
    for (int i = 0; i < kp_.size(); ++i) {
      const int d = root_ + i;
      real e = target_pose_[i] - q_[d];
      if (std::abs(e) < deadband_[i]) e = 0;
      real tau = kp_[i] * e + kd_[i] * (target_velocity_[i] - v_[d]) + (gravity_compensation_ ? c_[d] : real(0));
      if (saturation_[i] >= 0) tau = std::clamp(tau, -saturation_[i], saturation_[i]);
      out.set_effort(d, tau);
    }
  }

 private:
  Scene scene_;
  ActorHandle articulation_;
  int root_ = 0;
  VecX kp_, kd_, saturation_, deadband_, target_pose_, target_velocity_;
  bool gravity_compensation_ = false;
  VecX q_, v_, c_;  // the state read each step, kept so that a step does not allocate
};

}  // namespace

std::unique_ptr<Component> make_joint_pd_controller(const ComponentArgs& args) { return std::make_unique<JointPdController>(args); }

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::robotics

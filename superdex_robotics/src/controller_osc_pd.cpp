// BASIC_OSC_PD: operational-space PD control of an end-effector link relative to a base link.
//
// Frames: W world, B the base link, E the end-effector link (its origin is the controlled
// point). The target pose (p_BT, R_BT) is given in B, so it moves with the base.
//   e_p = clamp(p_WT - p_WE)                     position error (m), world
//   e_r = clamp(log(R_WT R_WE^T))                orientation error (rad), rotation vector, world
//   F   = [kp_p e_p + kd_p (v_WT - v_WE);        task force (N, N m), world; the target
//          kp_r e_r + kd_r (w_WB - w_WE)]        velocity is the base's motion at the target
//   Lambda = (J M^-1 J^T)^+                      task-space inertia (J = J_WE: 6 x nv, or its
//                                                3 linear rows without orientation control);
//                                                a pseudo-inverse: directions the arm cannot
//                                                move in (too few DOFs, singularities) get none
//   tau = J^T Lambda F
//         [+ c(q, v)                             with gravity_compensation: gravity, Coriolis]
//         [- (I - J^T Jbar^T) d_n v]             null-space damping, Jbar = M^-1 J^T Lambda
// and |tau_i| <= saturation (< 0: none). Uses the engine's link Jacobian J_WE (at E's origin,
// world axes) and mass matrix M (with armature). Efforts are written for the joint DOFs
// (the root joint's DOFs of a floating base are left alone).
//
// Params
//   "base_link"              name           default: the root link
//   "end_effector_link"      name           default: the last link
//   "kp_p", "kd_p"           N/m, N s/m     default 100, 20 (per unit task-space inertia)
//   "kp_r", "kd_r"           N m/rad, N m s/rad  default 100, 20
//   "max_position_error"     m, < 0: none   default -1
//   "max_orientation_error"  rad, < 0: none default -1
//   "control_orientation"    bool           default true (false: position only, 3 rows)
//   "gravity_compensation"   bool           default true
//   "null_space_damping"     N m s/rad      default 0
//   "saturation"             N m (N)        default -1
//   "target_position"        [3] m in B     default: E's position at creation
//   "target_orientation"     [x,y,z,w] in B default: E's orientation at creation

#include <algorithm>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include "builtin_support.h"
#include "builtins.h"

namespace superdex::robotics {
inline namespace SUPERDEX_REAL_NAMESPACE {

using physics::Mat3;
using physics::MatX;
using physics::MatXR;
using physics::Transform;
using physics::Vec6;

namespace {

// Scales `e` down to norm `limit` when limit >= 0.
Vec3 clamp_norm(const Vec3& e, real limit) {
  const real n = e.norm();
  return limit >= 0 && n > limit ? Vec3(e * (limit / n)) : e;
}

class OscPdController final : public ControllerComponent {
 public:
  explicit OscPdController(const ComponentArgs& args)
      : scene_(args.scene), articulation_(articulation_of(args.scene, args.actor, "BASIC_OSC_PD")) {
    root_ = root_dofs(scene_, articulation_);
    links_ = scene_.nested_link_actors(articulation_);
    const auto names = scene_.articulated_shape_info(articulation_).link_names;
    ComponentParams p(args.params, "BASIC_OSC_PD");
    base_ = link_index_by_name(scene_, articulation_, p.text("base_link", names.front()), p.at("base_link"));
    end_effector_ = link_index_by_name(scene_, articulation_, p.text("end_effector_link", names.back()), p.at("end_effector_link"));
    // default target: where the end effector is now, relative to the base
    const auto X = scene_.link_transforms(articulation_);
    const Transform X_BE = X[base_].inverse() * X[end_effector_];
    p_BT_ = X_BE.translation;
    R_BT_ = X_BE.rotation;
    configure(args.params);
  }

  void reset() override {}

  void configure(const std::string& json) override {
    ComponentParams p(json, "BASIC_OSC_PD");
    p.allow_only({"base_link", "end_effector_link", "kp_p", "kd_p", "kp_r", "kd_r", "max_position_error",
                  "max_orientation_error", "control_orientation", "gravity_compensation", "null_space_damping",
                  "saturation", "target_position", "target_orientation"});
    p.apply_rate(*this);
    // the links are fixed at creation
    for (const char* key : {"base_link", "end_effector_link"}) {
      if (!p.has(key)) continue;
      const int index = link_index_by_name(scene_, articulation_, p.text(key, ""), p.at(key));
      if (index != (std::string(key) == "base_link" ? base_ : end_effector_))
        throw Error(p.at(key) + ": the links are chosen at creation and cannot be changed");
    }
    kp_p_ = p.number("kp_p", kp_p_), kd_p_ = p.number("kd_p", kd_p_);
    kp_r_ = p.number("kp_r", kp_r_), kd_r_ = p.number("kd_r", kd_r_);
    max_position_error_ = p.number("max_position_error", max_position_error_);
    max_orientation_error_ = p.number("max_orientation_error", max_orientation_error_);
    control_orientation_ = p.flag("control_orientation", control_orientation_);
    gravity_compensation_ = p.flag("gravity_compensation", gravity_compensation_);
    null_space_damping_ = p.number("null_space_damping", null_space_damping_);
    saturation_ = p.number("saturation", saturation_);
    p_BT_ = p.vec3("target_position", p_BT_);
    R_BT_ = p.quaternion("target_orientation", R_BT_);
  }

  void compute(const Tick&, DofCommands& out) override {
    const auto X = scene_.link_transforms(articulation_);
    const Transform& X_WB = X[base_];
    const Transform& X_WE = X[end_effector_];
    const VecX v = scene_.joint_velocities(articulation_);
    const int nv = static_cast<int>(v.size());

    // target pose and velocity in world: the target rides on the base
    const Vec3 p_WT = X_WB * p_BT_;
    const Quat R_WT = X_WB.rotation * R_BT_;
    const Vec6 V_WB = link_origin_velocity(scene_, links_[base_]);
    const Vec3 v_WT = V_WB.head<3>() + V_WB.tail<3>().cross(p_WT - X_WB.translation);

    // errors and task force
    const MatXR J_full = scene_.link_jacobian(links_[end_effector_]);
    const Vec6 V_WE = J_full * v;
    const Vec3 e_p = clamp_norm(p_WT - X_WE.translation, max_position_error_);
    const Eigen::AngleAxis<real> R_err(R_WT * X_WE.rotation.conjugate());
    const Vec3 e_r = clamp_norm(R_err.angle() * R_err.axis(), max_orientation_error_);
    const int rows = control_orientation_ ? 6 : 3;
    VecX F(rows);
    F.head<3>() = kp_p_ * e_p + kd_p_ * (v_WT - V_WE.head<3>());
    if (control_orientation_) F.tail<3>() = kp_r_ * e_r + kd_r_ * (V_WB.tail<3>() - V_WE.tail<3>());
    const MatX J = J_full.topRows(rows);

    // task-space inertia: a pseudo-inverse that drops the directions the arm cannot move in
    // (fewer DOFs than task rows, or a singular configuration)
    const MatX M = scene_.mass_matrix(articulation_);
    const Eigen::LDLT<MatX> M_ldlt(M);
    const MatX Minv_Jt = M_ldlt.solve(J.transpose());
    const Eigen::SelfAdjointEigenSolver<MatX> eig(J * Minv_Jt);
    const real cutoff = eig.eigenvalues().maxCoeff() * (physics::kUsesDoublePrecision ? real(1e-10) : real(1e-5));
    VecX inv_values = VecX::Zero(rows);
    for (int i = 0; i < rows; ++i)
      if (eig.eigenvalues()[i] > cutoff) inv_values[i] = 1 / eig.eigenvalues()[i];
    const MatX Lambda = eig.eigenvectors() * inv_values.asDiagonal() * eig.eigenvectors().transpose();
    VecX tau = J.transpose() * (Lambda * F);
    if (gravity_compensation_) tau += scene_.bias_forces(articulation_);
    if (null_space_damping_ > 0) {
      // N^T = I - J^T Jbar^T with Jbar = M^-1 J^T Lambda: damping that does not disturb the task
      const MatX Jbar = Minv_Jt * Lambda;
      const VecX tau_0 = -null_space_damping_ * v;
      tau += tau_0 - J.transpose() * (Jbar.transpose() * tau_0);
    }
    for (int d = root_; d < nv; ++d) {
      real t = tau[d];
      if (saturation_ >= 0) t = std::clamp(t, -saturation_, saturation_);
      out.set_effort(d, t);
    }
  }

 private:
  Scene scene_;
  ActorHandle articulation_;
  std::vector<ActorHandle> links_;
  int root_ = 0, base_ = 0, end_effector_ = 0;
  real kp_p_ = 100, kd_p_ = 20, kp_r_ = 100, kd_r_ = 20;
  real max_position_error_ = -1, max_orientation_error_ = -1;
  bool control_orientation_ = true, gravity_compensation_ = true;
  real null_space_damping_ = 0, saturation_ = -1;
  Vec3 p_BT_ = Vec3::Zero();
  Quat R_BT_ = Quat::Identity();
};

}  // namespace

std::unique_ptr<Component> make_osc_pd_controller(const ComponentArgs& args) { return std::make_unique<OscPdController>(args); }

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::robotics

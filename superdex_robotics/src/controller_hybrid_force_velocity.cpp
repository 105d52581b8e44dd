// HYBRID_FORCE_VELOCITY: resolved-rate velocity control of a link's origin E along a Cartesian
// target, with force regulation along one world axis while the link presses on something
// (hybrid force/velocity control). It writes joint velocity commands, which velocity actuators
// (VELOCITY_SERVO) follow.
//
// Frames: W world; p_WE, J_WE the origin of the link and its linear Jacobian (3 x nv, world).
//   v_des = v_WT(t) + kp (p_WT(t) - p_WE)           desired velocity of E (m/s, world)
//   f     = a . f_W                                  contact force on the link along the unit
//                                                    axis a (N; pressing down on a surface with
//                                                    a = +z reads f > 0), as of the last step
//   force mode: entered when f > force_target; left when the target lies more than exit_margin
//   beyond E along a (a . (p_WT - p_WE) > exit_margin: the path leaves the surface) or f <= 0.
//   In force mode the velocity along a is replaced: v_des += (kf (f - force_target) - a . v_des) a
//   qd = pinv(S J_WE) S v_des                        S selects the controlled world `axes`;
//                                                    minimum-norm joint velocities (rad/s)
// Velocities are commanded for the joint DOFs (the root joint's DOFs of a floating base are not).
//
// Target: constant ("target_position", "target_velocity"; default E's position at creation, at
// rest), or a "trajectory" sampled in time, linearly interpolated (held at its ends, at rest
// after the last sample).
//
// Params
//   "link"             name                 default: the last link
//   "axes"             [world axis indices] default [0, 1, 2]
//   "kp"               1/s                  default 5
//   "kf"               m/(N s)              default 0.05
//   "force_axis"       [3] world, unit      default [0, 0, 1]
//   "force_target"     N                    default 0.5
//   "exit_margin"      m                    default 0.005
//   "target_position"  [3] m, world         default: E's position at creation
//   "target_velocity"  [3] m/s, world       default [0, 0, 0]
//   "trajectory"       {"times": [s, ascending], "positions": [[3] m], "velocities": [[3] m/s]}
//                      velocities optional (default: the slope between samples); replaces the
//                      constant target; an empty object or null returns to it

#include <algorithm>
#include <cmath>

#include <Eigen/QR>

#include "builtin_support.h"
#include "builtins.h"
#include "superdex/physics/engine.h"

namespace superdex::robotics {
inline namespace SUPERDEX_REAL_NAMESPACE {

using physics::MatX;

namespace {

// A target point moving through samples (times ascending), linearly interpolated.
struct CartesianTrajectory {
  std::vector<double> times;
  std::vector<Vec3> positions, velocities;

  bool empty() const { return times.empty(); }
  // The target at time t (s): held at the ends, at rest after the last sample.
  void at(double t, Vec3& p, Vec3& v) const {
    if (t <= times.front()) {
      p = positions.front(), v = times.size() > 1 ? velocities.front() : Vec3::Zero();
      return;
    }
    if (t >= times.back()) {
      p = positions.back(), v = Vec3::Zero();
      return;
    }
    const size_t k = static_cast<size_t>(std::upper_bound(times.begin(), times.end(), t) - times.begin()) - 1;
    const real s = static_cast<real>((t - times[k]) / (times[k + 1] - times[k]));
    p = (1 - s) * positions[k] + s * positions[k + 1];
    v = (1 - s) * velocities[k] + s * velocities[k + 1];
  }
};

// A list of [x, y, z] entries; errors name `where`.
std::vector<Vec3> vec3_list(const nlohmann::json& j, const std::string& where) {
  if (!j.is_array()) throw Error(where + ": expected a list of [x, y, z]");
  std::vector<Vec3> out;
  for (size_t i = 0; i < j.size(); ++i) {
    const auto& e = j[i];
    if (!e.is_array() || e.size() != 3 || !std::all_of(e.begin(), e.end(), [](const auto& x) { return x.is_number(); }))
      throw Error(where + "[" + std::to_string(i) + "]: expected [x, y, z] numbers");
    out.emplace_back(e[0].get<real>(), e[1].get<real>(), e[2].get<real>());
    if (!out.back().allFinite()) throw Error(where + "[" + std::to_string(i) + "]: not finite");
  }
  return out;
}

CartesianTrajectory parse_trajectory(const nlohmann::json& j, const std::string& where) {
  CartesianTrajectory tr;
  if (j.is_null() || (j.is_object() && j.empty())) return tr;
  if (!j.is_object()) throw Error(where + ": expected {\"times\": [...], \"positions\": [...]}");
  for (const auto& [key, value] : j.items())
    if (key != "times" && key != "positions" && key != "velocities")
      throw Error(where + "." + key + ": unknown key (known: times, positions, velocities)");
  if (!j.contains("times") || !j.at("times").is_array() || j.at("times").empty())
    throw Error(where + ".times: expected a non-empty list of times (s)");
  for (const auto& t : j.at("times")) {
    if (!t.is_number() || !std::isfinite(t.get<double>())) throw Error(where + ".times: expected finite numbers");
    if (!tr.times.empty() && !(t.get<double>() > tr.times.back())) throw Error(where + ".times: must be strictly ascending");
    tr.times.push_back(t.get<double>());
  }
  tr.positions = vec3_list(j.contains("positions") ? j.at("positions") : nlohmann::json(), where + ".positions");
  if (tr.positions.size() != tr.times.size())
    throw Error(where + ".positions: " + std::to_string(tr.positions.size()) + " entries for " + std::to_string(tr.times.size()) + " times");
  if (j.contains("velocities")) {
    tr.velocities = vec3_list(j.at("velocities"), where + ".velocities");
    if (tr.velocities.size() != tr.times.size())
      throw Error(where + ".velocities: " + std::to_string(tr.velocities.size()) + " entries for " + std::to_string(tr.times.size()) + " times");
  } else {
    // the slope of the segment after each sample (before it, for the last)
    const size_t n = tr.times.size();
    tr.velocities.assign(n, Vec3::Zero());
    for (size_t k = 0; k + 1 < n; ++k)
      tr.velocities[k] = (tr.positions[k + 1] - tr.positions[k]) / static_cast<real>(tr.times[k + 1] - tr.times[k]);
    if (n > 1) tr.velocities[n - 1] = tr.velocities[n - 2];
  }
  return tr;
}

class HybridForceVelocityController final : public ControllerComponent {
 public:
  explicit HybridForceVelocityController(const ComponentArgs& args)
      : scene_(args.scene), articulation_(articulation_of(args.scene, args.actor, kType)) {
    root_ = root_dofs(scene_, articulation_);
    const auto links = scene_.nested_link_actors(articulation_);
    const auto names = scene_.articulated_shape_info(articulation_).link_names;
    ComponentParams p(args.params, kType);
    link_ = links[link_index_by_name(scene_, articulation_, p.text("link", names.back()), p.at("link"))];
    p_WT_ = scene_.root_transform(link_).translation;
    configure(args.params);
    query_ = scene_.register_query(link_, physics::QueryType::TotalContactForce);
  }

  ~HybridForceVelocityController() override {
    if (physics::scene_exists(scene_.handle()) && scene_.has_actor(link_)) scene_.cancel_query(link_, query_);
  }

  void reset() override { force_mode_ = false; }

  void configure(const std::string& json) override {
    ComponentParams p(json, kType);
    p.allow_only({"link", "axes", "kp", "kf", "force_axis", "force_target", "exit_margin", "target_position", "target_velocity",
                  "trajectory"});
    if (p.has("link") && scene_.nested_link_actors(articulation_)[link_index_by_name(scene_, articulation_, p.text("link", ""), p.at("link"))] != link_)
      throw Error(p.at("link") + ": the link is chosen at creation and cannot be changed");
    // everything is checked before anything changes
    std::vector<int> axes = axes_;
    if (p.has("axes")) {
      const auto& j = p.json().at("axes");
      axes.clear();
      if (!j.is_array() || j.empty()) throw Error(p.at("axes") + ": expected a non-empty list of world axis indices (0, 1, 2)");
      for (const auto& a : j) {
        if (!a.is_number_integer() || a.get<int>() < 0 || a.get<int>() > 2 || std::count(axes.begin(), axes.end(), a.get<int>()))
          throw Error(p.at("axes") + ": expected distinct world axis indices 0, 1 or 2");
        axes.push_back(a.get<int>());
      }
    }
    const Vec3 force_axis = p.vec3("force_axis", force_axis_);
    if (!(force_axis.norm() > 0)) throw Error(p.at("force_axis") + ": expected a non-zero vector");
    CartesianTrajectory trajectory =
        p.json().contains("trajectory") ? parse_trajectory(p.json().at("trajectory"), p.at("trajectory")) : trajectory_;
    const Vec3 p_WT = p.vec3("target_position", p_WT_), v_WT = p.vec3("target_velocity", v_WT_);
    const real kp = p.number("kp", kp_), kf = p.number("kf", kf_), exit_margin = p.number("exit_margin", exit_margin_);
    const real force_target = p.number("force_target", force_target_);
    p.apply_rate(*this);
    axes_ = std::move(axes);
    force_axis_ = force_axis.normalized();
    trajectory_ = std::move(trajectory);
    kp_ = kp, kf_ = kf, exit_margin_ = exit_margin, force_target_ = force_target;
    p_WT_ = p_WT, v_WT_ = v_WT;
  }

  void compute(const Tick& tick, DofCommands& out) override {
    Vec3 p_WT = p_WT_, v_WT = v_WT_;
    if (!trajectory_.empty()) trajectory_.at(tick.time, p_WT, v_WT);
    const Vec3 p_WE = scene_.root_transform(link_).translation;
    Vec3 v_des = v_WT + kp_ * (p_WT - p_WE);
    // the contact force of the last step along the force axis (none before the first step since
    // the query was registered)
    const real f = stepped_ ? force_axis_.dot(scene_.contact_force(link_)) : 0;
    stepped_ = true;
    if (!force_mode_)
      force_mode_ = f > force_target_;
    else if (force_axis_.dot(p_WT - p_WE) > exit_margin_ || f <= 0)
      force_mode_ = false;
    if (force_mode_) v_des += (kf_ * (f - force_target_) - force_axis_.dot(v_des)) * force_axis_;
    // minimum-norm joint velocities for the controlled axes
    const physics::MatXR J_WE = scene_.link_jacobian(link_);
    const int nv = static_cast<int>(J_WE.cols()), k = static_cast<int>(axes_.size());
    MatX J(k, nv - root_);
    VecX v(k);
    for (int i = 0; i < k; ++i) J.row(i) = J_WE.row(axes_[i]).tail(nv - root_), v[i] = v_des[axes_[i]];
    const VecX qd = Eigen::CompleteOrthogonalDecomposition<MatX>(J).solve(v);
    for (int d = root_; d < nv; ++d) out.set_velocity(d, qd[d - root_]);
  }

 private:
  static constexpr const char* kType = "HYBRID_FORCE_VELOCITY";
  Scene scene_;
  ActorHandle articulation_, link_ = 0;
  std::int64_t query_ = 0;
  int root_ = 0;
  std::vector<int> axes_{0, 1, 2};
  real kp_ = 5, kf_ = real(0.05), force_target_ = real(0.5), exit_margin_ = real(0.005);
  Vec3 force_axis_ = Vec3::UnitZ();
  Vec3 p_WT_ = Vec3::Zero(), v_WT_ = Vec3::Zero();
  CartesianTrajectory trajectory_;
  bool force_mode_ = false;
  bool stepped_ = false;  // a step has been taken since the contact force query was registered
};

}  // namespace

std::unique_ptr<Component> make_hybrid_force_velocity_controller(const ComponentArgs& args) {
  return std::make_unique<HybridForceVelocityController>(args);
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::robotics

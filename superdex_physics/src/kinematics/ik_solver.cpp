// Inverse kinematics (ik_solver.h): damped Gauss-Newton on the joint DOFs of the articulations the
// scene's constraints hold, minimizing the energy of their equality rows.

#include "superdex/physics/ik_solver.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

#include "constraint/constraint_terms.h"
#include "core/spatial.h"
#include "multibody/kinematics.h"
#include "scene/actor_lookup.h"
#include "scene/step_stages.h"
#include "superdex/physics/log.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace {

void check_weight(real weight, const char* what) {
  if (!(std::isfinite(weight) && weight > 0)) throw Error(std::string(what) + ": weight must be finite and > 0, got " + std::to_string(weight));
}

// The equality rows of the scene's constraints on articulations: per row, its error e (target
// minus current, m or rad) and its weight, and the row's coefficients on the stacked DOFs (its
// rate is -de/dt).
struct Rows {
  std::vector<real> e, weight;
  MatX A;  // rows x stacked DOFs
};

class Problem {
 public:
  explicit Problem(SceneData& s) : s_(s) {
    // the variables: every articulation with DOFs that a constraint holds
    for (const auto& [h, c] : s.constraints)
      for (ActorHandle actor : {c.actor_a, c.actor_b}) {
        if (!actor.is_valid()) continue;
        const ActorRef& r = s.actors.at(actor);
        if (r.soft || r.articulation->model.nv == 0 || offset_.count(r.articulation)) continue;
        offset_[r.articulation] = n_;
        n_ += r.articulation->model.nv;
      }
  }
  int size() const { return n_; }

  // The rows at the articulations' current state.
  void rows(Rows& out) const {
    out.e.clear(), out.weight.clear();
    std::vector<Eigen::Matrix<real, 1, Eigen::Dynamic>> coefficients;
    MatXR J;
    ConstraintTerms t;
    for (const auto& [h, c] : s_.constraints) {
      t.a = constraint_side(s_, c, 0);
      t.b = constraint_side(s_, c, 1);
      if (t.a.soft >= 0 || t.b.soft >= 0 || c.stiffness <= 0) continue;
      // unit stiffness, no damping, a unit step: each equality row's vhat is its error
      ConstraintRecord unit = c;
      unit.stiffness = 1, unit.damping = 0, unit.saturation = -1;
      settle_constraint_targets(unit);
      constraint_terms(unit, 1, t);
      for (const ConstraintRow& row : t.rows) {
        if (row.block.kind != BlockKind::Bounded) continue;
        Eigen::Matrix<real, 1, Eigen::Dynamic> a = Eigen::Matrix<real, 1, Eigen::Dynamic>::Zero(n_);
        add_side(t.a, row.g_a, J, a);
        add_side(t.b, row.g_b, J, a);
        coefficients.push_back(std::move(a));
        out.e.push_back(row.block.vhat);
        out.weight.push_back(c.stiffness);
      }
    }
    out.A.resize(static_cast<Eigen::Index>(coefficients.size()), n_);
    for (size_t k = 0; k < coefficients.size(); ++k) out.A.row(static_cast<Eigen::Index>(k)) = coefficients[k];
  }

  // 1/2 sum weight e^2.
  static real energy(const Rows& r) {
    real f = 0;
    for (size_t k = 0; k < r.e.size(); ++k) f += real(0.5) * r.weight[k] * r.e[k] * r.e[k];
    return f;
  }

  // The stacked joint positions, and setting them (joint limits enforced, kinematics refreshed).
  std::vector<VecX> positions() const {
    std::vector<VecX> q;
    for (const auto& [a, o] : offset_) q.push_back(a->state.q);
    return q;
  }
  void set_positions(const std::vector<VecX>& q) {
    size_t i = 0;
    for (const auto& [a, o] : offset_) {
      a->state.q = q[i++];
      refresh_kinematics(*a);
    }
  }
  // q (+) delta over every articulation, each joint then clamped to its limits.
  std::vector<VecX> moved(const std::vector<VecX>& q, const VecX& delta) const {
    std::vector<VecX> out = q;
    size_t i = 0;
    for (const auto& [a, o] : offset_) {
      VecX& qa = out[i++];
      integrate_positions(a->model, qa, delta.segment(o, a->model.nv), 1);
      for (const JointModel& j : a->model.joints) {
        if (j.nv != 1) continue;
        if (j.has_lower) qa[j.q_offset] = std::max(qa[j.q_offset], j.lower);
        if (j.has_upper) qa[j.q_offset] = std::min(qa[j.q_offset], j.upper);
      }
    }
    return out;
  }
  void zero_velocities() {
    for (const auto& [a, o] : offset_) {
      a->state.v.setZero();
      refresh_kinematics(*a);
    }
  }

 private:
  // A side's part of a row: g on its link's spatial velocity through J_WL, or on joint DOFs.
  void add_side(const ConstraintSide& side, const Vec6& g, MatXR& J, Eigen::Matrix<real, 1, Eigen::Dynamic>& a) const {
    if (side.body < 0) return;
    Articulation* art = s_.articulations[side.body].get();
    const auto it = offset_.find(art);
    if (it == offset_.end()) return;
    const int o = it->second;
    if (side.dof >= 0) {
      for (int i = 0; i < 6 && side.dof + i < art->model.nv; ++i) a[o + side.dof + i] += g[i];
      return;
    }
    link_jacobian_world(art->model, art->kin, side.link, J);
    a.segment(o, art->model.nv) += (J.transpose() * g).transpose();
  }

  SceneData& s_;
  std::map<Articulation*, int> offset_;
  int n_ = 0;
};

}  // namespace

void IKSolver::set_params(const IKSolverParams& p) {
  const char* what = "IKSolver.set_solver_params";
  if (p.max_iter < 0) throw Error(std::string(what) + ": max_iter must be >= 0");
  if (p.line_search_max_iter < 0) throw Error(std::string(what) + ": line_search_max_iter must be >= 0");
  for (const auto& [value, name] : {std::pair{p.abs_tol, "abs_tol"}, {p.rel_tol, "rel_tol"}, {p.position_error_thres, "position_error_thres"},
                                    {p.rotation_error_thres, "rotation_error_thres"}})
    if (!(std::isfinite(value) && value >= 0)) throw Error(std::string(what) + ": " + name + " must be finite and >= 0");
  if (!(std::isfinite(p.max_elapsed_time_seconds) && p.max_elapsed_time_seconds >= 0))
    throw Error(std::string(what) + ": max_elapsed_time_seconds must be finite and >= 0");
  params_ = p;
}

namespace {

// Destroys the target of `link` in `targets` (a position or rotation target), if any.
void clear_target(Scene& scene, std::map<ActorHandle, ConstraintHandle>& targets, ActorHandle link) {
  const auto it = targets.find(link);
  if (it == targets.end()) return;
  if (scene.has_constraint(it->second)) scene.destroy_constraint(it->second);
  targets.erase(it);
}

}  // namespace

ConstraintHandle IKSolver::create_position_target(ActorHandle link, const Vec3& local_position, const Vec3& target_position, real weight) {
  check_weight(weight, "IKSolver.create_position_target");
  RigidPivotPositionConstraintParams p;
  p.actor = link, p.local_position = local_position, p.target_position = target_position;
  p.stiffness = weight, p.damping = 0;
  const ConstraintHandle h = scene_.create_rigid_pivot_position_constraint(p);
  clear_position_target(link);
  position_targets_[link] = h;
  return h;
}

void IKSolver::clear_position_target(ActorHandle link) { clear_target(scene_, position_targets_, link); }

ConstraintHandle IKSolver::create_rotation_target(ActorHandle link, const Vec3& local_rotation, const Vec3& target_rotation, real weight) {
  check_weight(weight, "IKSolver.create_rotation_target");
  RigidPivotRotationConstraintParams p;
  p.actor = link, p.local_rotation = local_rotation, p.target_rotation = target_rotation;
  p.stiffness = weight, p.damping = 0;
  const ConstraintHandle h = scene_.create_rigid_pivot_rotation_constraint(p);
  clear_rotation_target(link);
  rotation_targets_[link] = h;
  return h;
}

void IKSolver::clear_rotation_target(ActorHandle link) { clear_target(scene_, rotation_targets_, link); }

bool IKSolver::solve() {
  SceneData& s = scene_data(scene_.handle());
  Problem problem(s);
  const int n = problem.size();
  const auto start = std::chrono::steady_clock::now();
  const auto out_of_time = [&] {
    return params_.max_elapsed_time_seconds > 0 &&
           std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() > params_.max_elapsed_time_seconds;
  };
  Rows rows, trial;
  problem.rows(rows);
  real f = Problem::energy(rows);
  // the solve's statistics, as a step's: the scene's solver stats report them
  StepStats stats;
  stats.num_islands = 1;
  bool converged = n == 0;
  real gradient_norm = 0;
  for (int it = 0; it < params_.max_iter && n > 0 && !out_of_time(); ++it) {
    // the energy's gradient -A^T W e, and the Gauss-Newton system A^T W A delta = A^T W e
    const Eigen::Map<const VecX> e(rows.e.data(), static_cast<Eigen::Index>(rows.e.size()));
    const Eigen::Map<const VecX> w(rows.weight.data(), static_cast<Eigen::Index>(rows.weight.size()));
    const VecX b = rows.A.transpose() * w.cwiseProduct(e);
    gradient_norm = b.norm();
    if (gradient_norm < params_.abs_tol) {
      converged = true;
      break;
    }
    stats.newton_iterations = stats.total_newton_iterations = it + 1;
    MatX H = rows.A.transpose() * w.asDiagonal() * rows.A;
    // a little damping keeps a singular pose's step finite (Levenberg)
    const real mu = real(1e-9) * std::max(H.diagonal().maxCoeff(), real(1)) + std::numeric_limits<real>::epsilon();
    H.diagonal().array() += mu;
    const VecX delta = H.ldlt().solve(b);
    const std::vector<VecX> q = problem.positions();
    // halve the step until the energy goes down
    real step = 1, f_new = f;
    bool lowered = false;
    for (int ls = 0; ls <= params_.line_search_max_iter; ++ls, step /= 2) {
      problem.set_positions(problem.moved(q, step * delta));
      problem.rows(trial);
      f_new = Problem::energy(trial);
      stats.line_search_iterations = std::max(stats.line_search_iterations, ls + 1);
      if (f_new < f) {
        lowered = true;
        break;
      }
    }
    if (!lowered) {
      problem.set_positions(q);
      break;
    }
    if (params_.verbosity == VerbosityLevel::Verbose)
      log_info("IKSolver: iteration " + std::to_string(it) + ", energy " + std::to_string(f_new) + ", step " + std::to_string(step));
    std::swap(rows, trial);
    const real decrease = f - f_new;
    f = f_new;
    if (decrease <= params_.rel_tol * f) {
      converged = true;
      break;
    }
  }
  stats.residual = gradient_norm;
  stats.converged = converged;
  stats.status = converged ? ConvergenceStatus::Converged : ConvergenceStatus::Stopped;
  s.stats = stats;
  problem.zero_velocities();
  // the solution shows in the debugger, as a step's state would
  scene_.update_debugger();
  // success: every target within its threshold
  bool ok = true;
  for (const auto* targets : {&position_targets_, &rotation_targets_}) {
    const real thres = targets == &position_targets_ ? params_.position_error_thres : params_.rotation_error_thres;
    for (const auto& [link, h] : *targets) {
      if (!scene_.has_constraint(h)) continue;
      const std::vector<real> d = scene_.constraint_deviation(h);
      ok = ok && Vec3(d[0], d[1], d[2]).norm() <= thres;
    }
  }
  if (!ok && params_.verbosity >= VerbosityLevel::Warning) log_warning("IKSolver: a target is beyond its error threshold after the solve");
  return ok;
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

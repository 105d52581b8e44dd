// The public solver parameters: their validation, a new scene's defaults, and the settings the
// step's solvers read (step_settings.h).

#include "solver/step_settings.h"

#include <cmath>

#include "superdex/physics/error.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace {

void require(bool ok, const std::string& where, const char* field, const std::string& what) {
  if (!ok) throw Error(where + "." + field + ": " + what);
}
bool finite_nonneg(real x) { return std::isfinite(x) && x >= 0; }

template <class E>
std::string enum_value(E e) {
  return std::to_string(static_cast<int>(e));
}

}  // namespace

const char* convergence_status_name(ConvergenceStatus status) {
  switch (status) {
    case ConvergenceStatus::None: return "None";
    case ConvergenceStatus::Converged: return "Converged";
    case ConvergenceStatus::Stopped: return "Stopped";
    case ConvergenceStatus::Diverged: return "Diverged";
  }
  return "?";
}

SolverParams default_scene_solver_params() {
  SolverParams p;
  p.non_linear_solver.max_iter = 50;
  p.non_linear_solver.abs_tol = real(1e-10);
  p.non_linear_solver.rel_tol = kUsesDoublePrecision ? real(1e-8) : real(1e-5);
  p.non_linear_solver.line_search_max_iter = 40;
  return p;
}

void validate(const SolverParams& params, const std::string& where) {
  const NonLinearSolverParams& n = params.non_linear_solver;
  const std::string nl = where + ".non_linear_solver";
  require(n.solver_type == NonLinearSolverType::Newton, nl, "solver_type",
          "only NEWTON (DEFAULT) is available: this engine solves each step by Newton's method, got " + enum_value(n.solver_type));
  require(n.d_residual_assembly_period >= 1, nl, "d_residual_assembly_period", "must be >= 1");
  require(n.max_iter >= 1, nl, "max_iter", "must be >= 1, got " + std::to_string(n.max_iter));
  require(std::isfinite(n.max_elapsed_time_seconds) && n.max_elapsed_time_seconds >= 0, nl, "max_elapsed_time_seconds",
          "must be finite and >= 0 (0: no limit)");
  require(n.convergence_mode == NonLinearSolverConvergenceMode::Global || n.convergence_mode == NonLinearSolverConvergenceMode::PerActorWeighted,
          nl, "convergence_mode", "must be GLOBAL or PER_ACTOR_WEIGHTED");
  require(finite_nonneg(n.abs_tol), nl, "abs_tol", "must be finite and >= 0");
  require(finite_nonneg(n.rel_tol), nl, "rel_tol", "must be finite and >= 0");
  require(finite_nonneg(n.rel_step_tol), nl, "rel_step_tol", "must be finite and >= 0 (0 disables)");
  require(static_cast<int>(n.psd_proj_mode) >= 0 && static_cast<int>(n.psd_proj_mode) <= 3, nl, "psd_proj_mode", "unknown value");
  require(n.abs_div_tol > 0 && !std::isnan(n.abs_div_tol), nl, "abs_div_tol", "must be > 0");
  require(n.rel_div_tol > 0 && !std::isnan(n.rel_div_tol), nl, "rel_div_tol", "must be > 0");
  require(n.line_search_max_iter >= 1, nl, "line_search_max_iter", "must be >= 1");
  require(n.line_search_alpha > 0 && n.line_search_alpha < 1, nl, "line_search_alpha", "must be in (0, 1)");
  require(n.line_search_wolfe1 > 0 && n.line_search_wolfe1 < 1, nl, "line_search_wolfe1", "must be in (0, 1)");
  require(n.line_search_wolfe2 > n.line_search_wolfe1 && n.line_search_wolfe2 < 1, nl, "line_search_wolfe2",
          "must be in (line_search_wolfe1, 1)");
  require(finite_nonneg(n.line_search_max_rel_increase), nl, "line_search_max_rel_increase", "must be finite and >= 0");
  require(n.line_search_type == LineSearchType::Default, nl, "line_search_type",
          "only DEFAULT is available: this engine's line search is exact (its problem is convex), got " + enum_value(n.line_search_type));
  require(n.linear_tolerance_strategy == LinearToleranceStrategy::Constant || n.linear_tolerance_strategy == LinearToleranceStrategy::Default,
          nl, "linear_tolerance_strategy", "only CONSTANT or DEFAULT is available, got " + enum_value(n.linear_tolerance_strategy));
  const LinearSolverParams& l = params.linear_solver;
  const std::string ls = where + ".linear_solver";
  require(l.solver_type == LinearSolverType::Auto || l.solver_type == LinearSolverType::LDLT || l.solver_type == LinearSolverType::CG, ls,
          "solver_type", "only AUTO (DEFAULT), LDLT or CG is available, got " + enum_value(l.solver_type));
  require(static_cast<int>(l.preconditioner_type) >= 0 && static_cast<int>(l.preconditioner_type) <= 12, ls, "preconditioner_type", "unknown value");
  require(static_cast<int>(l.norm_type) >= 0 && static_cast<int>(l.norm_type) <= 2, ls, "norm_type", "unknown value");
  require(finite_nonneg(l.abs_tol), ls, "abs_tol", "must be finite and >= 0");
  require(finite_nonneg(l.rel_tol), ls, "rel_tol", "must be finite and >= 0");
  require(l.rel_div_tol > 0 && !std::isnan(l.rel_div_tol), ls, "rel_div_tol", "must be > 0");
  require(l.max_iter > 0 || l.max_iter == kAutoLinearSolverMaxIter, ls, "max_iter",
          "must be > 0 or AUTO_LINEAR_SOLVER_MAX_ITER (-1), got " + std::to_string(l.max_iter));
  require(l.restart_size >= 1, ls, "restart_size", "must be >= 1");
  require(params.integration_method == IntegrationMethod::BackwardEuler || params.integration_method == IntegrationMethod::BDF2, where,
          "integration_method", "BACKWARD_EULER (DEFAULT) and BDF2 are available, got " + enum_value(params.integration_method));
  const ExperimentalEvalParams& e = params.experimental_eval;
  require(!(e.implicit_normal_force_for_dissipation && e.explicit_normals), where + ".experimental_eval", "implicit_normal_force_for_dissipation",
          "cannot be combined with explicit_normals");
  require(std::isfinite(e.consistency_res_norm_step) && e.consistency_res_norm_step > 0, where + ".experimental_eval",
          "consistency_res_norm_step", "must be finite and > 0");
  const ImplicitStepParams& s = params.implicit_step;
  const std::string is = where + ".implicit_step";
  require(std::isfinite(s.near_rigid_beta) && s.near_rigid_beta > 0, is, "near_rigid_beta", "must be finite and > 0");
  require(std::isfinite(s.friction_sigma) && s.friction_sigma > 0, is, "friction_sigma", "must be finite and > 0");
  require(finite_nonneg(s.contact_margin), is, "contact_margin", "must be finite and >= 0");
  require(s.drift_correction_iterations >= 0, is, "drift_correction_iterations", "must be >= 0");
  require(s.dense_island_max_dofs >= 0, is, "dense_island_max_dofs", "must be >= 0");
  require(finite_nonneg(s.soft_hessian_reuse_strain), is, "soft_hessian_reuse_strain", "must be finite and >= 0");
}

StepSettings step_settings_from(const SolverParams& params) {
  const NonLinearSolverParams& n = params.non_linear_solver;
  const ImplicitStepParams& s = params.implicit_step;
  StepSettings out;
  out.max_newton_iterations = n.max_iter;
  out.absolute_tolerance = n.abs_tol;
  out.relative_tolerance = n.rel_tol;
  out.max_line_search_iterations = n.line_search_max_iter;
  out.max_elapsed_time_seconds = n.max_elapsed_time_seconds;
  out.rel_step_tolerance = n.rel_step_tol;
  out.stop_if_no_improvement = n.stop_if_no_improvement;
  out.explosion_control = n.explosion_control;
  out.absolute_divergence_tolerance = n.abs_div_tol;
  out.relative_divergence_tolerance = n.rel_div_tol;
  out.verbose = n.verbosity == VerbosityLevel::Verbose;
  out.near_rigid_beta = s.near_rigid_beta;
  out.friction_sigma = s.friction_sigma;
  out.contact_margin = s.contact_margin;
  out.drift_correction_iterations = s.drift_correction_iterations;
  out.dense_island_max_dofs = s.dense_island_max_dofs;
  out.defer_inactive_joint_limits = s.defer_inactive_joint_limits;
  out.defer_separating_contacts = s.defer_separating_contacts;
  out.soft_hessian_reuse_strain = s.soft_hessian_reuse_strain;
  return out;
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

#pragma once
/// @file solver_params.h
/// Parameters and statistics of the implicit step, with SuperDex's names and defaults. This
/// engine solves each island's step as one convex problem by Newton's method with an exact line
/// search (Cholesky factorizations of its SPD Newton matrix; soft bodies' sparse systems by
/// conjugate gradients preconditioned with the last factorization). Each field says how it maps
/// onto that solver; choices the solver does not have (other non-linear or linear solver types,
/// backtracking line searches, higher-order integrators) are rejected by Scene::set_solver_params
/// with an error naming the field.

#include <string>

#include "superdex/physics/real.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

enum class VerbosityLevel { Silent, Error, Warning, Verbose };

/// How a step's non-linear solve ended, ordered by severity.
enum class ConvergenceStatus {
  None,       ///< not set: no dynamic actor, nothing stepped, or a zero time step
  Converged,  ///< reached the tolerance
  Stopped,    ///< stopped by a limit (iterations, time, step size) before reaching it
  Diverged,   ///< the residual grew beyond the divergence tolerances (a numerical fault)
};
const char* convergence_status_name(ConvergenceStatus status);

enum class NonLinearSolverType { Newton, BFGS, SR1, Default = Newton };
enum class NonLinearSolverConvergenceMode { Global, PerActorWeighted, Default = PerActorWeighted };
enum class PsdProjectionMode { Never, Always, IfFailRetry, IfFailAlways, Default = Always };
enum class LineSearchType { None, Simple, Armijo, WolfeWeak, WolfeStrong, ResidualNorm, ArmijoOrResidualNorm, Default = ResidualNorm };
enum class LinearToleranceStrategy { Constant, EisenstatWalker1, EisenstatWalker2, EisenstatWalker3, Default = EisenstatWalker2 };
enum class LinearSolverType {
  CG, GMRES, CudaCG, CudaGMRES, AugmentedCG, LDLT, LU, AsyncCG, ParallelCG, MINRES,
  ExperimentalCudaSparseCholesky, ExperimentalCudaSparseLDLT, ExperimentalCudaSparseLU, Auto, Default = Auto
};
enum class PreconditionerType { None, Jacobi, BlockJacobi, SSOR, BlockSSOR, LU, AMG, SymInverse, LDLT, ILU0, IC0, PerActor, ColoredSSOR, Default = PerActor };
enum class LinearSolverConvergenceNorm { ResidualL2, PreconditionedResidualL2, ResidualPreconditionerInduced, Default = PreconditionedResidualL2 };
enum class IntegrationMethod { BackwardEuler, BDF2, BDF3, DIRK22, DIRK23, DIRK33, SymplecticDIRK12, SymplecticDIRK22, Default = BackwardEuler };
enum class CoulombFrictionModel { C1Regularized, CinfRegularized, Default = C1Regularized };

/// The default relative step tolerance: 10 machine epsilons of the build's `real`.
inline constexpr real kDefaultRelStepTol = 10 * std::numeric_limits<real>::epsilon();
/// LinearSolverParams::max_iter: let the engine choose.
inline constexpr int kAutoLinearSolverMaxIter = -1;

/// The Newton solve of each island.
struct NonLinearSolverParams {
  NonLinearSolverType solver_type = NonLinearSolverType::Default;  ///< Newton only
  int d_residual_assembly_period = 1;  ///< >= 1; Newton assembles its matrix every iteration (1 is the only period it uses)
  int max_iter = 4;                    ///< >= 1: Newton iterations; reaching it ends the solve as Stopped
  double max_elapsed_time_seconds = 0; ///< s, >= 0; 0: no limit; else the solve stops (Stopped) once it has run this long
  NonLinearSolverConvergenceMode convergence_mode = NonLinearSolverConvergenceMode::Default;  ///< both modes test the island's scaled residual
  real abs_tol = real(1e-3);           ///< >= 0: converged when the scaled momentum residual is below abs_tol + rel_tol * (its scale)
  real rel_tol = real(1e-6);           ///< >= 0
  real rel_step_tol = kDefaultRelStepTol;  ///< >= 0: a Newton step shorter than rel_step_tol * |x| ends the solve (Stopped); 0 disables
  bool stop_if_no_improvement = false;  ///< end the solve (Stopped) when an iteration does not lower the residual
  PsdProjectionMode psd_proj_mode = PsdProjectionMode::Default;  ///< the Newton matrix is SPD by construction: every mode solves the same system
  bool gradient_descent_fallback = false;  ///< when a Newton matrix fails to factor, step along the negative gradient instead of failing
  bool explosion_control = true;       ///< report Diverged (a numerical fault) when the residual exceeds abs_div_tol or rel_div_tol x its initial value
  real abs_div_tol = real(1e9);
  real rel_div_tol = real(1e4);
  int line_search_max_iter = 4;        ///< >= 1: iterations of the exact line search (a 1-D convex minimisation)
  real line_search_alpha = real(0.5);  ///< in (0, 1); backtracking searches only
  real line_search_wolfe1 = real(1e-4);  ///< in (0, 1); backtracking searches only
  real line_search_wolfe2 = real(0.9);   ///< in (wolfe1, 1); backtracking searches only
  real line_search_max_rel_increase = 0;  ///< >= 0; Simple search only
  LineSearchType line_search_type = LineSearchType::Default;  ///< Default (the exact search) only
  LinearToleranceStrategy linear_tolerance_strategy = LinearToleranceStrategy::Default;  ///< iterative soft-body solves: Constant or Default
  VerbosityLevel verbosity = VerbosityLevel::Warning;  ///< Verbose logs each iteration's residual (log channel Verbose)
  bool operator==(const NonLinearSolverParams&) const = default;
};

/// The linear solves inside Newton's method.
struct LinearSolverParams {
  LinearSolverType solver_type = LinearSolverType::Default;  ///< Auto (Cholesky; CG for large soft bodies), LDLT or CG
  PreconditionerType preconditioner_type = PreconditionerType::Default;  ///< CG is preconditioned with the last factorization
  LinearSolverConvergenceNorm norm_type = LinearSolverConvergenceNorm::Default;
  real abs_tol = real(1e-9);            ///< >= 0 (iterative solves)
  real rel_tol = real(1e-5);            ///< >= 0 (iterative solves)
  real rel_div_tol = real(1e10);        ///< > 0 (iterative solves)
  int max_iter = kAutoLinearSolverMaxIter;  ///< > 0, or kAutoLinearSolverMaxIter (iterative solves)
  int restart_size = 1000;              ///< >= 1 (GMRES only)
  bool abort_if_not_spd = false;        ///< fail a solve whose matrix is not positive definite instead of regularising it
  VerbosityLevel verbosity = VerbosityLevel::Warning;
  bool operator==(const LinearSolverParams&) const = default;
};

/// Whether friction, joint friction and saturated constraints use a fitted quadratic Hessian.
struct SaturationHessianParams {
  bool contact_friction = true;
  bool joint_friction = false;
  bool constraint_saturation = true;
  static SaturationHessianParams all(bool value) { return {value, value, value}; }
  bool all_true() const { return contact_friction && joint_friction && constraint_saturation; }
  bool operator==(const SaturationHessianParams&) const = default;
};

/// Scene-wide evaluation settings of SuperDex's internal penalty models (experimental there).
/// This engine's contact is not that model (see ContactParams): the fields are validated and kept.
struct ExperimentalEvalParams {
  bool explicit_normals = false;
  bool fade_friction = true;
  bool implicit_normal_force_for_dissipation = false;
  SaturationHessianParams fitted_saturation_hessian;
  CoulombFrictionModel friction_model = CoulombFrictionModel::Default;
  bool consistency_res_norm = false;
  real consistency_res_norm_step = real(1e-4);
  bool operator==(const ExperimentalEvalParams&) const = default;
};

/// This engine's own settings of the implicit step (additions beyond SuperDex's fields).
struct ImplicitStepParams {
  /// Near-rigid regularisation of contacts and limits: compliance = beta^2 / (4 pi^2) * w.
  real near_rigid_beta = 1;
  /// Regularisation of friction rows relative to their effective compliance w.
  real friction_sigma = real(1e-3);
  /// Pairs of shapes closer than this (m) produce contact candidates (speculative contact).
  real contact_margin = real(0.01);
  /// Coulomb friction without the cone model's drift: during up to this many Newton iterations,
  /// each sliding contact's normal target velocity is lowered by mu s (s its slip speed) at the
  /// current iterate, to a fixed point, so that it keeps its normal target while its friction
  /// stays mu times its normal impulse. 0 keeps the pure cone model.
  int drift_correction_iterations = 20;
  /// Islands with more DOFs than this are solved with (block-)sparse linear algebra.
  int dense_island_max_dofs = 12;
  /// Leave out of the solve the joint-limit rows the free motion keeps well inside their limits,
  /// and solve again with them when one would act (the same result at less cost).
  bool defer_inactive_joint_limits = true;
  /// Leave out of the solve the rigid contacts the motion keeps more than half their gap apart,
  /// solving again with those its result would close (the same result at less cost).
  bool defer_separating_contacts = true;
  /// Soft bodies: after a Newton iteration's first, recompute the Hessian only of elements whose
  /// deformation gradient changed by more than this since the start of the step.
  real soft_hessian_reuse_strain = real(1e-3);
  bool operator==(const ImplicitStepParams&) const = default;
};

/// Everything that configures a scene's solve.
struct SolverParams {
  NonLinearSolverParams non_linear_solver;
  LinearSolverParams linear_solver;
  IntegrationMethod integration_method = IntegrationMethod::Default;  ///< BackwardEuler or BDF2 (scene/bdf2_step.h)
  ExperimentalEvalParams experimental_eval;
  ImplicitStepParams implicit_step;
  bool operator==(const SolverParams&) const = default;
};

/// The settings a new scene starts with: SuperDex's fields at their defaults except the Newton
/// solve's, which this engine drives to convergence (max_iter 50, abs_tol 1e-10, rel_tol 1e-8 in
/// double precision and 1e-5 in float, line_search_max_iter 40).
SolverParams default_scene_solver_params();

/// Throws superdex::Error naming `where`.field for a value out of range or a choice the solver
/// does not have.
void validate(const SolverParams& params, const std::string& where);

/// What the last step's solve did.
struct SolverStats {
  int max_non_linear_iters = 0;   ///< largest number of Newton iterations over islands
  double residual_norm = 0;       ///< largest final scaled residual over islands
  int max_line_search_iters = 0;  ///< largest number of line-search iterations of one Newton iteration
  ConvergenceStatus convergence_status = ConvergenceStatus::None;  ///< the worst over islands with dynamic actors
  // this engine's additions
  int total_non_linear_iters = 0;  ///< Newton iterations summed over islands
  int num_islands = 0;
  int num_constraints = 0;         ///< active constraint rows (limits, friction)
  int num_contacts = 0;
  int soft_element_hessians = 0;   ///< element Hessians of soft bodies computed
  int soft_factorizations = 0;     ///< sparse factorizations of soft bodies' Newton matrices
  /// Convex solves of islands: one per island, and one more each time deferred joint-limit rows
  /// or contacts turn out to act at a solve's result and join the next
  /// (ImplicitStepParams::defer_inactive_joint_limits, defer_separating_contacts).
  int num_island_solves = 0;
  bool operator==(const SolverStats&) const = default;
};

/// How long the last step took (s).
struct PerformanceStats {
  double total_step_duration_sec = 0;         ///< the whole step, callbacks included
  double solve_step_duration_sec = 0;         ///< the physics (callbacks excluded)
  double pre_step_callbacks_duration_sec = 0;
  double post_step_callbacks_duration_sec = 0;
  double recording_step_duration_sec = 0;
  // this engine's additions: the physics by stage
  double kinematics_duration_sec = 0;  ///< kinematics and dynamics terms
  double collision_duration_sec = 0;   ///< collision detection
  double island_solve_duration_sec = 0;  ///< the implicit solves
  bool operator==(const PerformanceStats&) const = default;
};

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

#pragma once
// The settings the step's solvers read (made from the public SolverParams by
// step_settings_from) and the statistics they report (turned into SolverStats and
// PerformanceStats).

#include "superdex/physics/params/solver_params.h"
#include "superdex/physics/real.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

// Parameters of the implicit solve.
struct StepSettings {
  int max_newton_iterations = 50;
  /// Stop when the scaled momentum residual is below abs + rel * scale.
  real absolute_tolerance = real(1e-10);
  real relative_tolerance = kUsesDoublePrecision ? real(1e-8) : real(1e-5);
  int max_line_search_iterations = 40;
  /// Stops a solve (ConvergenceStatus::Stopped) that has run this long (s); 0: no limit.
  double max_elapsed_time_seconds = 0;
  /// Stops a solve (Stopped) whose Newton step is shorter than this times |v|; 0 disables.
  real rel_step_tolerance = 0;
  /// Stops a solve (Stopped) at the first iteration that does not lower the residual.
  bool stop_if_no_improvement = false;
  /// A residual above absolute_divergence_tolerance, or relative_divergence_tolerance times the
  /// first iteration's, ends the solve as Diverged (a numerical fault).
  bool explosion_control = true;
  real absolute_divergence_tolerance = real(1e9);
  real relative_divergence_tolerance = real(1e4);
  /// Logs each Newton iteration's residual (log channel Verbose).
  bool verbose = false;
  /// Near-rigid regularisation of limits: constraint compliance = beta^2 / (4 pi^2) * w.
  real near_rigid_beta = 1;
  /// Regularisation of friction rows relative to their effective compliance w.
  real friction_sigma = real(1e-3);
  /// Pairs of shapes closer than this (m) produce contact candidates (speculative contact).
  real contact_margin = real(0.01);
  /// Fastest a rigid contact is pushed out of penetration (m/s): a robot spawned with its feet 8 cm
  /// in the ground rises out of it over 0.08 s instead of being thrown at 0.08 m / dt. Also the
  /// fastest a joint that starts beyond one of its limits is brought back (rad/s or m/s).
  real max_depenetration_speed = 1;
  /// Coulomb friction without the cone model's drift: in the convex cone model a contact that
  /// slides at speed s (m/s, beyond its friction regularisation) moves apart at mu s. During up
  /// to this many Newton iterations of a solve, each contact's normal target velocity is lowered
  /// by mu s at the current iterate, to a fixed point (within 100 times the solve's tolerance),
  /// so that a sliding contact keeps its normal target while its friction stays mu times its
  /// normal impulse; the remaining iterations converge on the corrected problem. The first
  /// correction is made at the solve's start (the bodies' last velocities, so the last step's
  /// slip), which leaves the others little to change; with up to 8 sliding contacts in an
  /// island, each Newton step also predicts the corrections from its own linearization, which
  /// reaches the fixed point in a few iterations. 0 keeps the pure cone model.
  int drift_correction_iterations = 20;
  /// Islands with more DOFs than this are solved with (block-)sparse linear algebra; up to it,
  /// dense. Above two free bodies (12 DOFs) the sparse path costs less per Newton iteration: on
  /// piles of 18 boxes (islands of 3 to 18 boxes) a step took 25 % less than with dense islands
  /// up to 96 DOFs.
  int dense_island_max_dofs = 12;
  /// Leave out of the solve the joint-limit rows that the free motion keeps well inside their
  /// limits, and check them on its result: when one would act, the island is solved again with
  /// them. The result is the same (a left-out row contributes nothing where it is inactive);
  /// only the cost differs. false keeps every limit row in every solve.
  bool defer_inactive_joint_limits = true;
  /// Leave out of the solve the rigid contacts that neither the current nor the free motion
  /// brings within half their gap (friction's reach included), and check them on its result:
  /// when one would close, the island is solved again with it. The result is the same; most
  /// speculative contacts of a grasp or of links near each other cost nothing.
  bool defer_separating_contacts = true;
  /// Soft bodies: a Newton iteration after the first recomputes the Hessian only of the elements
  /// whose deformation gradient changed by more than this (in any entry, dimensionless) since
  /// the start of the step; the others keep their Hessian there. The problem and its tolerance
  /// are unchanged (the gradient is always exact); only the Newton direction is approximate.
  /// 0 recomputes every element that moved.
  real soft_hessian_reuse_strain = real(1e-3);
};

/// What the last step did.
struct StepStats {
  int newton_iterations = 0;      ///< largest number of Newton iterations over islands
  int total_newton_iterations = 0;
  real residual = 0;              ///< largest final scaled residual over islands
  bool converged = true;
  ConvergenceStatus status = ConvergenceStatus::None;  ///< the worst over islands with dynamic bodies
  int line_search_iterations = 0;  ///< largest number of line-search trials of one Newton iteration
  int num_islands = 0;
  int num_constraints = 0;        ///< active constraint rows (limits, friction)
  int num_contacts = 0;
  int soft_element_hessians = 0;  ///< element Hessians of soft bodies computed (see SolverParams::soft_hessian_reuse_strain)
  /// Sparse factorizations of soft bodies' Newton matrices. A Newton iteration after the first
  /// of a solve is solved by conjugate gradients preconditioned by the last factorization, and
  /// factors its matrix only when they do not converge in a few iterations.
  int soft_factorizations = 0;
  int island_solves = 0;          ///< convex solves of islands, those again with deferred rows or contacts included
  double time_kinematics = 0;     ///< seconds in kinematics and dynamics terms
  double time_collision = 0;      ///< seconds in collision detection
  double time_solve = 0;          ///< seconds in the implicit solves
  double time_total = 0;
};

// The solver settings of public params (validated beforehand).
StepSettings step_settings_from(const SolverParams& params);

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

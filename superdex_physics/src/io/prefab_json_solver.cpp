// The solver settings of a prefab's `scene` (prefab_json.h): SolverParams as JSON. One list of
// fields (solver_fields) serves the writer and the reader, so that every field written is read
// back. The Newton iteration limit and the contact margin keep their short names
// (maxNewtonIterations, contactMargin); the other fields are grouped as SolverParams groups them
// (nonLinearSolver, linearSolver, experimentalEval, implicitStep, integrationMethod) and written
// only when they differ from default_scene_solver_params(). Enumerations are written by the names
// the Python enums use (NEWTON, RESIDUAL_NORM, ...).

#include <cmath>
#include <cstdint>
#include <limits>
#include <type_traits>

#include "io/prefab_json.h"
#include "superdex/physics/error.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {
namespace prefab {

using json = nlohmann::json;

namespace {

// enumerators by value (each enumeration counts up from 0)
const std::vector<const char*> kVerbosity = {"SILENT", "ERROR", "WARNING", "VERBOSE"};
const std::vector<const char*> kNonLinearSolverType = {"NEWTON", "BFGS", "SR1"};
const std::vector<const char*> kConvergenceMode = {"GLOBAL", "PER_ACTOR_WEIGHTED"};
const std::vector<const char*> kPsdProjectionMode = {"NEVER", "ALWAYS", "IF_FAIL_RETRY", "IF_FAIL_ALWAYS"};
const std::vector<const char*> kLineSearchType = {"NONE", "SIMPLE", "ARMIJO", "WOLFE_WEAK", "WOLFE_STRONG", "RESIDUAL_NORM",
                                                  "ARMIJO_OR_RESIDUAL_NORM"};
const std::vector<const char*> kLinearToleranceStrategy = {"CONSTANT", "EISENSTAT_WALKER1", "EISENSTAT_WALKER2", "EISENSTAT_WALKER3"};
const std::vector<const char*> kLinearSolverType = {"CG", "GMRES", "CUDA_CG", "CUDA_GMRES", "AUGMENTED_CG", "LDLT", "LU", "ASYNC_CG",
                                                    "PARALLEL_CG", "MINRES", "EXPERIMENTAL_CUDA_SPARSE_CHOLESKY",
                                                    "EXPERIMENTAL_CUDA_SPARSE_LDLT", "EXPERIMENTAL_CUDA_SPARSE_LU", "AUTO"};
const std::vector<const char*> kPreconditionerType = {"NONE", "JACOBI", "BLOCK_JACOBI", "SSOR", "BLOCK_SSOR", "LU", "AMG",
                                                      "SYM_INVERSE", "LDLT", "ILU0", "IC0", "PER_ACTOR", "COLORED_SSOR"};
const std::vector<const char*> kNormType = {"RESIDUAL_L2", "PRECONDITIONED_RESIDUAL_L2", "RESIDUAL_PRECONDITIONER_INDUCED"};
const std::vector<const char*> kIntegrationMethod = {"BACKWARD_EULER", "BDF2", "BDF3", "DIRK22", "DIRK23", "DIRK33",
                                                     "SYMPLECTIC_DIRK12", "SYMPLECTIC_DIRK22"};
const std::vector<const char*> kFrictionModel = {"C1_REGULARIZED", "CINF_REGULARIZED"};

// Every field but the two with short names, as (group, key, field of `a`, same field of `b`[, names]);
// group "" is the top level. `v` is called once per field.
template <class A, class B, class V>
void solver_fields(A& a, B& b, V&& v) {
  {
    auto &x = a.non_linear_solver, &y = b.non_linear_solver;
    const char* g = "nonLinearSolver";
    v(g, "solverType", x.solver_type, y.solver_type, kNonLinearSolverType);
    v(g, "dResidualAssemblyPeriod", x.d_residual_assembly_period, y.d_residual_assembly_period);
    v(g, "maxElapsedTimeSeconds", x.max_elapsed_time_seconds, y.max_elapsed_time_seconds);
    v(g, "convergenceMode", x.convergence_mode, y.convergence_mode, kConvergenceMode);
    v(g, "absTol", x.abs_tol, y.abs_tol);
    v(g, "relTol", x.rel_tol, y.rel_tol);
    v(g, "relStepTol", x.rel_step_tol, y.rel_step_tol);
    v(g, "stopIfNoImprovement", x.stop_if_no_improvement, y.stop_if_no_improvement);
    v(g, "psdProjMode", x.psd_proj_mode, y.psd_proj_mode, kPsdProjectionMode);
    v(g, "gradientDescentFallback", x.gradient_descent_fallback, y.gradient_descent_fallback);
    v(g, "explosionControl", x.explosion_control, y.explosion_control);
    v(g, "absDivTol", x.abs_div_tol, y.abs_div_tol);
    v(g, "relDivTol", x.rel_div_tol, y.rel_div_tol);
    v(g, "lineSearchMaxIter", x.line_search_max_iter, y.line_search_max_iter);
    v(g, "lineSearchAlpha", x.line_search_alpha, y.line_search_alpha);
    v(g, "lineSearchWolfe1", x.line_search_wolfe1, y.line_search_wolfe1);
    v(g, "lineSearchWolfe2", x.line_search_wolfe2, y.line_search_wolfe2);
    v(g, "lineSearchMaxRelIncrease", x.line_search_max_rel_increase, y.line_search_max_rel_increase);
    v(g, "lineSearchType", x.line_search_type, y.line_search_type, kLineSearchType);
    v(g, "linearToleranceStrategy", x.linear_tolerance_strategy, y.linear_tolerance_strategy, kLinearToleranceStrategy);
    v(g, "verbosity", x.verbosity, y.verbosity, kVerbosity);
  }
  {
    auto &x = a.linear_solver, &y = b.linear_solver;
    const char* g = "linearSolver";
    v(g, "solverType", x.solver_type, y.solver_type, kLinearSolverType);
    v(g, "preconditionerType", x.preconditioner_type, y.preconditioner_type, kPreconditionerType);
    v(g, "normType", x.norm_type, y.norm_type, kNormType);
    v(g, "absTol", x.abs_tol, y.abs_tol);
    v(g, "relTol", x.rel_tol, y.rel_tol);
    v(g, "relDivTol", x.rel_div_tol, y.rel_div_tol);
    v(g, "maxIter", x.max_iter, y.max_iter);
    v(g, "restartSize", x.restart_size, y.restart_size);
    v(g, "abortIfNotSpd", x.abort_if_not_spd, y.abort_if_not_spd);
    v(g, "verbosity", x.verbosity, y.verbosity, kVerbosity);
  }
  v("", "integrationMethod", a.integration_method, b.integration_method, kIntegrationMethod);
  {
    auto &x = a.experimental_eval, &y = b.experimental_eval;
    const char* g = "experimentalEval";
    v(g, "explicitNormals", x.explicit_normals, y.explicit_normals);
    v(g, "fadeFriction", x.fade_friction, y.fade_friction);
    v(g, "implicitNormalForceForDissipation", x.implicit_normal_force_for_dissipation, y.implicit_normal_force_for_dissipation);
    v(g, "fittedSaturationHessianContactFriction", x.fitted_saturation_hessian.contact_friction, y.fitted_saturation_hessian.contact_friction);
    v(g, "fittedSaturationHessianJointFriction", x.fitted_saturation_hessian.joint_friction, y.fitted_saturation_hessian.joint_friction);
    v(g, "fittedSaturationHessianConstraintSaturation", x.fitted_saturation_hessian.constraint_saturation,
      y.fitted_saturation_hessian.constraint_saturation);
    v(g, "frictionModel", x.friction_model, y.friction_model, kFrictionModel);
    v(g, "consistencyResNorm", x.consistency_res_norm, y.consistency_res_norm);
    v(g, "consistencyResNormStep", x.consistency_res_norm_step, y.consistency_res_norm_step);
  }
  {
    auto &x = a.implicit_step, &y = b.implicit_step;
    const char* g = "implicitStep";
    v(g, "nearRigidBeta", x.near_rigid_beta, y.near_rigid_beta);
    v(g, "frictionSigma", x.friction_sigma, y.friction_sigma);
    v(g, "driftCorrectionIterations", x.drift_correction_iterations, y.drift_correction_iterations);
    v(g, "denseIslandMaxDofs", x.dense_island_max_dofs, y.dense_island_max_dofs);
    v(g, "deferInactiveJointLimits", x.defer_inactive_joint_limits, y.defer_inactive_joint_limits);
    v(g, "deferSeparatingContacts", x.defer_separating_contacts, y.defer_separating_contacts);
    v(g, "softHessianReuseStrain", x.soft_hessian_reuse_strain, y.soft_hessian_reuse_strain);
  }
}

// Writes the fields that differ from the defaults.
struct FieldWriter {
  json& out;
  json& slot(const char* group, const char* key) { return *group ? out[group][key] : out[key]; }
  template <class T>
  void operator()(const char* group, const char* key, const T& value, const T& fallback) {
    if (value != fallback) slot(group, key) = value;
  }
  template <class E>
  void operator()(const char* group, const char* key, const E& value, const E& fallback, const std::vector<const char*>& names) {
    if (value != fallback) slot(group, key) = names.at(static_cast<size_t>(value));
  }
};

// Reads the fields present; errors name the file and the field's path.
struct FieldReader {
  const json& in;
  const std::string& file;
  const std::string& path;

  const json* find(const char* group, const char* key) const {
    const json* g = &in;
    if (*group) {
      if (!in.contains(group) || in.at(group).is_null()) return nullptr;
      g = &in.at(group);
      if (!g->is_object()) fail(group, "", "expected an object");
    }
    return g->contains(key) && !g->at(key).is_null() ? &g->at(key) : nullptr;
  }
  [[noreturn]] void fail(const char* group, const char* key, const std::string& what) const {
    std::string field = path + "." + group;
    if (*key) field += (*group ? "." : "") + std::string(key);
    throw Error(file + ": " + field + ": " + what);
  }
  void operator()(const char* group, const char* key, bool& value, const bool&) const {
    if (const json* j = find(group, key)) {
      if (!j->is_boolean()) fail(group, key, "expected true or false, got " + j->dump());
      value = j->get<bool>();
    }
  }
  void operator()(const char* group, const char* key, int& value, const int&) const {
    if (const json* j = find(group, key)) {
      if (!j->is_number_integer() || j->get<std::int64_t>() < std::numeric_limits<int>::min() ||
          j->get<std::int64_t>() > std::numeric_limits<int>::max())
        fail(group, key, "expected an integer, got " + j->dump());
      value = j->get<int>();
    }
  }
  template <class T>
    requires std::is_floating_point_v<T>
  void operator()(const char* group, const char* key, T& value, const T&) const {
    if (const json* j = find(group, key)) {
      if (!j->is_number()) fail(group, key, "expected a number, got " + j->dump());
      value = j->get<T>();
      if (!std::isfinite(value)) fail(group, key, "must be finite");
    }
  }
  template <class E>
  void operator()(const char* group, const char* key, E& value, const E&, const std::vector<const char*>& names) const {
    const json* j = find(group, key);
    if (!j) return;
    if (j->is_string())
      for (size_t i = 0; i < names.size(); ++i)
        if (j->get<std::string>() == names[i]) {
          value = static_cast<E>(i);
          return;
        }
    std::string expected;
    for (const char* n : names) expected += (expected.empty() ? "" : ", ") + std::string(n);
    fail(group, key, "expected one of " + expected + ", got " + j->dump());
  }
};

}  // namespace

json solver_params_to_json(const SolverParams& p) {
  json j = {{"maxNewtonIterations", p.non_linear_solver.max_iter}, {"contactMargin", p.implicit_step.contact_margin}};
  const SolverParams d = default_scene_solver_params();
  solver_fields(p, d, FieldWriter{j});
  return j;
}

SolverParams solver_params_from_json(const json& j, const std::string& file, const std::string& path) {
  if (!j.is_object()) throw Error(file + ": " + path + ": expected an object {maxNewtonIterations, contactMargin, nonLinearSolver, ...}");
  SolverParams p = default_scene_solver_params();
  const FieldReader r{j, file, path};
  r("", "maxNewtonIterations", p.non_linear_solver.max_iter, p.non_linear_solver.max_iter);
  r("", "contactMargin", p.implicit_step.contact_margin, p.implicit_step.contact_margin);
  solver_fields(p, p, r);
  return p;
}

}  // namespace prefab
}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

// The enums, with SuperDex's Python names (UPPER_SNAKE_CASE members; DEFAULT aliases the default).

#include "bind_common.h"
#include "superdex/physics/log.h"
#include "superdex/physics/params/actor_params.h"
#include "superdex/physics/params/solver_params.h"
#include "superdex/physics/scene.h"

namespace superdex::python {

void export_enums(nb::module_& m) {
  nb::enum_<LogChannel>(m, "LogChannel", "The channel of a log message.")
      .value("VERBOSE", LogChannel::Verbose).value("INFO", LogChannel::Info)
      .value("WARNING", LogChannel::Warning).value("ERROR", LogChannel::Error);
  nb::enum_<VerbosityLevel>(m, "VerbosityLevel", "How much a solver reports (log channels).")
      .value("SILENT", VerbosityLevel::Silent).value("ERROR", VerbosityLevel::Error)
      .value("WARNING", VerbosityLevel::Warning).value("VERBOSE", VerbosityLevel::Verbose);
  nb::enum_<ConvergenceStatus>(m, "ConvergenceStatus", "How a step's non-linear solve ended, by severity.")
      .value("NONE", ConvergenceStatus::None).value("CONVERGED", ConvergenceStatus::Converged)
      .value("STOPPED", ConvergenceStatus::Stopped).value("DIVERGED", ConvergenceStatus::Diverged);
  nb::enum_<NonLinearSolverType>(m, "NonLinearSolverType", "This engine solves by Newton's method (NEWTON, DEFAULT).")
      .value("NEWTON", NonLinearSolverType::Newton).value("BFGS", NonLinearSolverType::BFGS).value("SR1", NonLinearSolverType::SR1);
  add_default_alias<NonLinearSolverType>(m, "NonLinearSolverType");
  nb::enum_<NonLinearSolverConvergenceMode>(m, "NonLinearSolverConvergenceMode")
      .value("GLOBAL", NonLinearSolverConvergenceMode::Global).value("PER_ACTOR_WEIGHTED", NonLinearSolverConvergenceMode::PerActorWeighted);
  add_default_alias<NonLinearSolverConvergenceMode>(m, "NonLinearSolverConvergenceMode");
  nb::enum_<PsdProjectionMode>(m, "PsdProjectionMode")
      .value("NEVER", PsdProjectionMode::Never).value("ALWAYS", PsdProjectionMode::Always)
      .value("IF_FAIL_RETRY", PsdProjectionMode::IfFailRetry).value("IF_FAIL_ALWAYS", PsdProjectionMode::IfFailAlways);
  add_default_alias<PsdProjectionMode>(m, "PsdProjectionMode");
  nb::enum_<LineSearchType>(m, "LineSearchType", "This engine's line search is exact (DEFAULT).")
      .value("NONE", LineSearchType::None).value("SIMPLE", LineSearchType::Simple).value("ARMIJO", LineSearchType::Armijo)
      .value("WOLFE_WEAK", LineSearchType::WolfeWeak).value("WOLFE_STRONG", LineSearchType::WolfeStrong)
      .value("RESIDUAL_NORM", LineSearchType::ResidualNorm).value("ARMIJO_OR_RESIDUAL_NORM", LineSearchType::ArmijoOrResidualNorm);
  add_default_alias<LineSearchType>(m, "LineSearchType");
  nb::enum_<LinearToleranceStrategy>(m, "LinearToleranceStrategy")
      .value("CONSTANT", LinearToleranceStrategy::Constant).value("EISENSTAT_WALKER1", LinearToleranceStrategy::EisenstatWalker1)
      .value("EISENSTAT_WALKER2", LinearToleranceStrategy::EisenstatWalker2).value("EISENSTAT_WALKER3", LinearToleranceStrategy::EisenstatWalker3);
  add_default_alias<LinearToleranceStrategy>(m, "LinearToleranceStrategy");
  nb::enum_<LinearSolverType>(m, "LinearSolverType", "This engine offers AUTO (DEFAULT), LDLT and CG.")
      .value("CG", LinearSolverType::CG).value("GMRES", LinearSolverType::GMRES).value("CUDA_CG", LinearSolverType::CudaCG)
      .value("CUDA_GMRES", LinearSolverType::CudaGMRES).value("AUGMENTED_CG", LinearSolverType::AugmentedCG)
      .value("LDLT", LinearSolverType::LDLT).value("LU", LinearSolverType::LU).value("ASYNC_CG", LinearSolverType::AsyncCG)
      .value("PARALLEL_CG", LinearSolverType::ParallelCG).value("MINRES", LinearSolverType::MINRES)
      .value("EXPERIMENTAL_CUDA_SPARSE_CHOLESKY", LinearSolverType::ExperimentalCudaSparseCholesky)
      .value("EXPERIMENTAL_CUDA_SPARSE_LDLT", LinearSolverType::ExperimentalCudaSparseLDLT)
      .value("EXPERIMENTAL_CUDA_SPARSE_LU", LinearSolverType::ExperimentalCudaSparseLU).value("AUTO", LinearSolverType::Auto);
  add_default_alias<LinearSolverType>(m, "LinearSolverType");
  nb::enum_<PreconditionerType>(m, "PreconditionerType")
      .value("NONE", PreconditionerType::None).value("JACOBI", PreconditionerType::Jacobi).value("BLOCK_JACOBI", PreconditionerType::BlockJacobi)
      .value("SSOR", PreconditionerType::SSOR).value("BLOCK_SSOR", PreconditionerType::BlockSSOR).value("LU", PreconditionerType::LU)
      .value("AMG", PreconditionerType::AMG).value("SYM_INVERSE", PreconditionerType::SymInverse).value("LDLT", PreconditionerType::LDLT)
      .value("ILU0", PreconditionerType::ILU0).value("IC0", PreconditionerType::IC0).value("PER_ACTOR", PreconditionerType::PerActor)
      .value("COLORED_SSOR", PreconditionerType::ColoredSSOR);
  add_default_alias<PreconditionerType>(m, "PreconditionerType");
  nb::enum_<LinearSolverConvergenceNorm>(m, "LinearSolverConvergenceNorm")
      .value("RESIDUAL_L2", LinearSolverConvergenceNorm::ResidualL2)
      .value("PRECONDITIONED_RESIDUAL_L2", LinearSolverConvergenceNorm::PreconditionedResidualL2)
      .value("RESIDUAL_PRECONDITIONER_INDUCED", LinearSolverConvergenceNorm::ResidualPreconditionerInduced);
  add_default_alias<LinearSolverConvergenceNorm>(m, "LinearSolverConvergenceNorm");
  nb::enum_<IntegrationMethod>(m, "IntegrationMethod", "BACKWARD_EULER (DEFAULT) or BDF2 (second order: a backward Euler step of 2/3 h from the extrapolated state of the "
                                                          "last two steps; the first step, and the first after the state was changed outside a step, "
                                                          "is backward Euler). The others are refused.")
      .value("BACKWARD_EULER", IntegrationMethod::BackwardEuler).value("BDF2", IntegrationMethod::BDF2).value("BDF3", IntegrationMethod::BDF3)
      .value("DIRK22", IntegrationMethod::DIRK22).value("DIRK23", IntegrationMethod::DIRK23).value("DIRK33", IntegrationMethod::DIRK33)
      .value("SYMPLECTIC_DIRK12", IntegrationMethod::SymplecticDIRK12).value("SYMPLECTIC_DIRK22", IntegrationMethod::SymplecticDIRK22);
  add_default_alias<IntegrationMethod>(m, "IntegrationMethod");
  nb::enum_<CoulombFrictionModel>(m, "CoulombFrictionModel")
      .value("C1_REGULARIZED", CoulombFrictionModel::C1Regularized).value("CINF_REGULARIZED", CoulombFrictionModel::CinfRegularized);
  add_default_alias<CoulombFrictionModel>(m, "CoulombFrictionModel");
  nb::enum_<ColliderType>(m, "ColliderType", "How OTHER actors detect contact with an actor.")
      .value("NONE", ColliderType::None).value("AUTO", ColliderType::Auto).value("SPHERE", ColliderType::Sphere)
      .value("BOX", ColliderType::Box).value("MESH", ColliderType::Mesh).value("PLANE", ColliderType::Plane)
      .value("SDF", ColliderType::Sdf).value("POINT_CLOUD", ColliderType::PointCloud);
  nb::enum_<SoftMaterialType>(m, "SoftMaterialType", "Constitutive models of soft bodies.")
      .value("NEO_HOOKEAN", SoftMaterialType::NeoHookean).value("ST_VENANT_KIRCHHOFF", SoftMaterialType::StVenantKirchhoff)
      .value("LINEAR_ELASTIC", SoftMaterialType::LinearElastic).value("ACTIVE_NEO_HOOKEAN", SoftMaterialType::ActiveNeoHookean)
      .value("ACTIVE_SHAPE_TARGETING_ARAP", SoftMaterialType::ActiveShapeTargetingArap).value("ARAP", SoftMaterialType::Arap);
  nb::enum_<MaterialPsdStrategy>(m, "MaterialPsdStrategy")
      .value("MATERIAL_DEFAULT", MaterialPsdStrategy::MaterialDefault).value("NONE", MaterialPsdStrategy::None)
      .value("PROJECTION", MaterialPsdStrategy::Projection).value("FAST", MaterialPsdStrategy::Fast)
      .value("ABS_EIGEN_PROJECTION", MaterialPsdStrategy::AbsEigenProjection).value("PER_TERM_PROJECTION", MaterialPsdStrategy::PerTermProjection);
  nb::enum_<GridSdfResolutionMode>(m, "GridSdfResolutionMode")
      .value("LARGEST_AXIS", GridSdfResolutionMode::LargestAxis).value("SMALLEST_AXIS", GridSdfResolutionMode::SmallestAxis)
      .value("MEAN_AXIS", GridSdfResolutionMode::MeanAxis).value("LARGEST_EDGE", GridSdfResolutionMode::LargestEdge)
      .value("SMALLEST_EDGE", GridSdfResolutionMode::SmallestEdge).value("MEAN_EDGE", GridSdfResolutionMode::MeanEdge)
      .value("EXPLICIT", GridSdfResolutionMode::Explicit);
  nb::enum_<ActorType>(m, "ActorType", "The kind of an actor (an articulation's links are RIGID actors nested in it).")
      .value("NONE", ActorType::None).value("RIGID", ActorType::Rigid).value("SOFT", ActorType::Soft)
      .value("ARTICULATED", ActorType::Articulated).value("SHELL", ActorType::Shell).value("ROD", ActorType::Rod);
  nb::enum_<ActorBoundaryElementType>(m, "ActorBoundaryElementType")
      .value("P1Q1", ActorBoundaryElementType::P1Q1).value("P1Q3", ActorBoundaryElementType::P1Q3).value("P1Q6", ActorBoundaryElementType::P1Q6)
      .value("EXPERIMENTAL_P1Q7", ActorBoundaryElementType::ExperimentalP1Q7)
      .value("EXPERIMENTAL_P1Q12", ActorBoundaryElementType::ExperimentalP1Q12)
      .value("EXPERIMENTAL_P1Q16", ActorBoundaryElementType::ExperimentalP1Q16);
  add_default_alias<ActorBoundaryElementType>(m, "ActorBoundaryElementType");
  nb::enum_<BoundarySubsamplingStrategy>(m, "BoundarySubsamplingStrategy")
      .value("UNIFORM_PROBABILITY", BoundarySubsamplingStrategy::UniformProbability)
      .value("AREA_PROPORTIONAL", BoundarySubsamplingStrategy::AreaProportional);
  nb::enum_<ArticulatedJointType>(m, "ArticulatedJointType", "How a link moves relative to its parent.")
      .value("FREE", ArticulatedJointType::Free).value("PRISMATIC", ArticulatedJointType::Prismatic)
      .value("REVOLUTE", ArticulatedJointType::Revolute).value("SPHERICAL", ArticulatedJointType::Spherical)
      .value("HARD", ArticulatedJointType::Hard).value("CYCLE", ArticulatedJointType::Cycle)
      .value("INVALID", ArticulatedJointType::Invalid);
  nb::enum_<QueryType>(m, "QueryType", "What an actor can be asked to report (register the query first).")
      .value("NODE_POSITIONS", QueryType::NodePositions).value("ELEMENTS_DEFORMATION_GRADIENT", QueryType::ElementsDeformationGradient)
      .value("SURFACE_NODE_POSITIONS", QueryType::SurfaceNodePositions).value("SURFACE_NODE_NORMALS", QueryType::SurfaceNodeNormals)
      .value("VISUAL_NODE_POSITIONS", QueryType::VisualNodePositions).value("VISUAL_NODE_NORMALS", QueryType::VisualNodeNormals)
      .value("CONTACT_POINTS", QueryType::ContactPoints).value("ELASTIC_ENERGY", QueryType::ElasticEnergy)
      .value("NODE_CONTACT_FORCES", QueryType::NodeContactForces).value("CONSTRAINT_FORCE", QueryType::ConstraintForce)
      .value("ARTICULATED_CONTROLLER_FORCE", QueryType::ArticulatedControllerForce).value("SDF_DISTANCES", QueryType::SdfDistances)
      .value("TOTAL_CONTACT_FORCE", QueryType::TotalContactForce);
  nb::enum_<IncludeNestedActors>(m, "IncludeNestedActors", "Whether an actor contact rule covers an articulation's links.")
      .value("NO", IncludeNestedActors::No).value("YES", IncludeNestedActors::Yes);
}

}  // namespace superdex::python

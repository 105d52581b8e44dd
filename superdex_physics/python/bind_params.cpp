// The params structs that configure solves, contacts and materials, and the stats the step
// reports, with SuperDex's Python names; each is constructed by keyword, compared, copied and
// pickled (struct_binder.h). Values are checked where they are used (set_solver_params,
// create_*_actor, ...), each error naming the field.

#include <nanobind/stl/string.h>

#include "bind_common.h"
#include "bind_container.h"
#include "struct_binder.h"
#include "superdex/physics/params/actor_params.h"
#include "superdex/physics/params/solver_params.h"

namespace superdex::python {

void export_solver_params(nb::module_& m) {
  StructBinder<NonLinearSolverParams>(m, "NonLinearSolverParams", "The Newton solve of each island (solver_params.h says how each field maps).")
      .field("solver_type", &NonLinearSolverParams::solver_type)
      .field("d_residual_assembly_period", &NonLinearSolverParams::d_residual_assembly_period)
      .field("max_iter", &NonLinearSolverParams::max_iter, "Newton iterations; reaching it ends the solve as STOPPED")
      .field("max_elapsed_time_seconds", &NonLinearSolverParams::max_elapsed_time_seconds, "s; 0: no limit")
      .field("convergence_mode", &NonLinearSolverParams::convergence_mode)
      .field("abs_tol", &NonLinearSolverParams::abs_tol)
      .field("rel_tol", &NonLinearSolverParams::rel_tol)
      .field("rel_step_tol", &NonLinearSolverParams::rel_step_tol)
      .field("stop_if_no_improvement", &NonLinearSolverParams::stop_if_no_improvement)
      .field("psd_proj_mode", &NonLinearSolverParams::psd_proj_mode)
      .field("gradient_descent_fallback", &NonLinearSolverParams::gradient_descent_fallback)
      .field("explosion_control", &NonLinearSolverParams::explosion_control)
      .field("abs_div_tol", &NonLinearSolverParams::abs_div_tol)
      .field("rel_div_tol", &NonLinearSolverParams::rel_div_tol)
      .field("line_search_max_iter", &NonLinearSolverParams::line_search_max_iter)
      .field("line_search_alpha", &NonLinearSolverParams::line_search_alpha)
      .field("line_search_wolfe1", &NonLinearSolverParams::line_search_wolfe1)
      .field("line_search_wolfe2", &NonLinearSolverParams::line_search_wolfe2)
      .field("line_search_max_rel_increase", &NonLinearSolverParams::line_search_max_rel_increase)
      .field("line_search_type", &NonLinearSolverParams::line_search_type)
      .field("linear_tolerance_strategy", &NonLinearSolverParams::linear_tolerance_strategy)
      .field("verbosity", &NonLinearSolverParams::verbosity)
      .done();
  StructBinder<LinearSolverParams>(m, "LinearSolverParams", "The linear solves inside Newton's method.")
      .field("solver_type", &LinearSolverParams::solver_type)
      .field("preconditioner_type", &LinearSolverParams::preconditioner_type)
      .field("norm_type", &LinearSolverParams::norm_type)
      .field("abs_tol", &LinearSolverParams::abs_tol)
      .field("rel_tol", &LinearSolverParams::rel_tol)
      .field("rel_div_tol", &LinearSolverParams::rel_div_tol)
      .field("max_iter", &LinearSolverParams::max_iter)
      .field("restart_size", &LinearSolverParams::restart_size)
      .field("abort_if_not_spd", &LinearSolverParams::abort_if_not_spd)
      .field("verbosity", &LinearSolverParams::verbosity)
      .done();
  StructBinder<SaturationHessianParams>(m, "SaturationHessianParams", "")
      .field("contact_friction", &SaturationHessianParams::contact_friction)
      .field("joint_friction", &SaturationHessianParams::joint_friction)
      .field("constraint_saturation", &SaturationHessianParams::constraint_saturation)
      .done()
      .def_static("all", &SaturationHessianParams::all, "value"_a)
      .def("all_true", &SaturationHessianParams::all_true);
  StructBinder<ExperimentalEvalParams>(m, "ExperimentalEvalParams", "Evaluation settings of SuperDex's penalty models (kept; see ContactParams).")
      .field("explicit_normals", &ExperimentalEvalParams::explicit_normals)
      .field("fade_friction", &ExperimentalEvalParams::fade_friction)
      .field("implicit_normal_force_for_dissipation", &ExperimentalEvalParams::implicit_normal_force_for_dissipation)
      .field("fitted_saturation_hessian", &ExperimentalEvalParams::fitted_saturation_hessian)
      .field("friction_model", &ExperimentalEvalParams::friction_model)
      .field("consistency_res_norm", &ExperimentalEvalParams::consistency_res_norm)
      .field("consistency_res_norm_step", &ExperimentalEvalParams::consistency_res_norm_step)
      .done();
  StructBinder<ImplicitStepParams>(m, "ImplicitStepParams", "This engine's own settings of the implicit step.")
      .field("near_rigid_beta", &ImplicitStepParams::near_rigid_beta, "near-rigid regularisation: compliance = beta^2 / (4 pi^2) w")
      .field("friction_sigma", &ImplicitStepParams::friction_sigma, "friction rows' regularisation relative to their compliance")
      .field("contact_margin", &ImplicitStepParams::contact_margin, "m: pairs closer than this produce contact candidates")
      .field("drift_correction_iterations", &ImplicitStepParams::drift_correction_iterations,
             "Newton iterations that correct the friction cone's drift (0: pure cone model)")
      .field("dense_island_max_dofs", &ImplicitStepParams::dense_island_max_dofs, "islands above it use sparse algebra")
      .field("defer_inactive_joint_limits", &ImplicitStepParams::defer_inactive_joint_limits)
      .field("defer_separating_contacts", &ImplicitStepParams::defer_separating_contacts,
             "leave out of the solve the contacts the motion keeps apart; solve again if one would close")
      .field("soft_hessian_reuse_strain", &ImplicitStepParams::soft_hessian_reuse_strain)
      .done();
  StructBinder<SolverParams>(m, "SolverParams", "Everything that configures a scene's solve.")
      .field("non_linear_solver", &SolverParams::non_linear_solver)
      .field("linear_solver", &SolverParams::linear_solver)
      .field("integration_method", &SolverParams::integration_method)
      .field("experimental_eval", &SolverParams::experimental_eval)
      .field("implicit_step", &SolverParams::implicit_step)
      .done();
  m.def("default_scene_solver_params", &default_scene_solver_params, "The solver params a new scene starts with.");
  StructBinder<SolverStats>(m, "SolverStats", "What the last step's solve did.")
      .field("max_non_linear_iters", &SolverStats::max_non_linear_iters)
      .field("residual_norm", &SolverStats::residual_norm)
      .field("max_line_search_iters", &SolverStats::max_line_search_iters)
      .field("convergence_status", &SolverStats::convergence_status)
      .field("total_non_linear_iters", &SolverStats::total_non_linear_iters)
      .field("num_islands", &SolverStats::num_islands)
      .field("num_constraints", &SolverStats::num_constraints)
      .field("num_contacts", &SolverStats::num_contacts)
      .field("soft_element_hessians", &SolverStats::soft_element_hessians)
      .field("soft_factorizations", &SolverStats::soft_factorizations)
      .field("num_island_solves", &SolverStats::num_island_solves)
      .done();
  StructBinder<PerformanceStats>(m, "PerformanceStats", "How long the last step took (s).")
      .field("total_step_duration_sec", &PerformanceStats::total_step_duration_sec)
      .field("solve_step_duration_sec", &PerformanceStats::solve_step_duration_sec)
      .field("pre_step_callbacks_duration_sec", &PerformanceStats::pre_step_callbacks_duration_sec)
      .field("post_step_callbacks_duration_sec", &PerformanceStats::post_step_callbacks_duration_sec)
      .field("recording_step_duration_sec", &PerformanceStats::recording_step_duration_sec)
      .field("kinematics_duration_sec", &PerformanceStats::kinematics_duration_sec)
      .field("collision_duration_sec", &PerformanceStats::collision_duration_sec)
      .field("island_solve_duration_sec", &PerformanceStats::island_solve_duration_sec)
      .done();
}

void export_material_params(nb::module_& m) {
  StructBinder<LinearElasticMaterialParams>(m, "LinearElasticMaterialParams", "Pa; Poisson's ratio in (-1, 0.5).")
      .field("youngs_modulus", &LinearElasticMaterialParams::youngs_modulus)
      .field("poisson_ratio", &LinearElasticMaterialParams::poisson_ratio)
      .done();
  StructBinder<StVenantKirchhoffMaterialParams>(m, "StVenantKirchhoffMaterialParams", "")
      .field("youngs_modulus", &StVenantKirchhoffMaterialParams::youngs_modulus)
      .field("poisson_ratio", &StVenantKirchhoffMaterialParams::poisson_ratio)
      .field("psd_strategy", &StVenantKirchhoffMaterialParams::psd_strategy)
      .done();
  StructBinder<NeoHookeanMaterialParams>(m, "NeoHookeanMaterialParams", "Stable Neo-Hookean.")
      .field("youngs_modulus", &NeoHookeanMaterialParams::youngs_modulus)
      .field("poisson_ratio", &NeoHookeanMaterialParams::poisson_ratio)
      .field("psd_strategy", &NeoHookeanMaterialParams::psd_strategy)
      .done();
  StructBinder<ActiveAnisoArapMaterialParams>(m, "ActiveAnisoArapMaterialParams", "The active fibre of ACTIVE_NEO_HOOKEAN.")
      .field("alpha", &ActiveAnisoArapMaterialParams::alpha)
      .field("length", &ActiveAnisoArapMaterialParams::length)
      .field("aniso_dir", &ActiveAnisoArapMaterialParams::aniso_dir)
      .field("psd_strategy", &ActiveAnisoArapMaterialParams::psd_strategy)
      .done()
      .def("get_theta", &ActiveAnisoArapMaterialParams::theta)
      .def("get_phi", &ActiveAnisoArapMaterialParams::phi)
      .def_static("compute_fiber_direction", &ActiveAnisoArapMaterialParams::fiber_direction, "theta"_a, "phi"_a);
  StructBinder<ActiveNeoHookeanMaterialParams>(m, "ActiveNeoHookeanMaterialParams", "")
      .field("passive_isotropic", &ActiveNeoHookeanMaterialParams::passive_isotropic)
      .field("active_anisotropic", &ActiveNeoHookeanMaterialParams::active_anisotropic)
      .done();
  StructBinder<ArapMaterialParams>(m, "ArapMaterialParams", "")
      .field("stiffness", &ArapMaterialParams::stiffness)
      .field("psd_strategy", &ArapMaterialParams::psd_strategy)
      .done();
  StructBinder<ActiveShapeTargetingArapMaterialParams>(m, "ActiveShapeTargetingArapMaterialParams", "")
      .field("stiffness", &ActiveShapeTargetingArapMaterialParams::stiffness)
      .field("shape_target_tensor", &ActiveShapeTargetingArapMaterialParams::shape_target_tensor)
      .field("psd_strategy", &ActiveShapeTargetingArapMaterialParams::psd_strategy)
      .done();
  StructBinder<SoftMaterialParams>(m, "SoftMaterialParams", "A homogeneous soft material; `type` selects the model struct used.")
      .field("type", &SoftMaterialParams::type)
      .field("neo_hookean", &SoftMaterialParams::neo_hookean)
      .field("st_venant_kirchhoff", &SoftMaterialParams::st_venant_kirchhoff)
      .field("linear_elastic", &SoftMaterialParams::linear_elastic)
      .field("active_neo_hookean", &SoftMaterialParams::active_neo_hookean)
      .field("active_shape_targeting_arap", &SoftMaterialParams::active_shape_targeting_arap)
      .field("arap", &SoftMaterialParams::arap)
      .field("density", &SoftMaterialParams::density, "kg/m^3")
      .field("mass_damping_coefficient", &SoftMaterialParams::mass_damping_coefficient, "1/s")
      .field("stiffness_damping_coefficient", &SoftMaterialParams::stiffness_damping_coefficient, "s")
      .field("stiffness_damping_include_geometric_term", &SoftMaterialParams::stiffness_damping_include_geometric_term)
      .done();
}

void export_actor_params(nb::module_& m) {
  StructBinder<ContactParams>(m, "ContactParams", "Contact parameters of an actor's surface (contact_params.h says which the solve uses).")
      .field("penalty_coefficient", &ContactParams::penalty_coefficient, "Pa/m")
      .field("penalty_smoothing_half_distance", &ContactParams::penalty_smoothing_half_distance, "m")
      .field("penalty_threshold_default", &ContactParams::penalty_threshold_default, "m")
      .field("penalty_threshold_extra_padding", &ContactParams::penalty_threshold_extra_padding, "m")
      .field("friction_with_collider_normal", &ContactParams::friction_with_collider_normal)
      .field("max_alignment_normals", &ContactParams::max_alignment_normals)
      .field("viscous_friction_coefficient", &ContactParams::viscous_friction_coefficient, "s/m")
      .field("coulomb_friction_coefficient", &ContactParams::coulomb_friction_coefficient)
      .field("friction_falloff_vel", &ContactParams::friction_falloff_vel, "m/s")
      .field("normal_viscous_damping_coefficient", &ContactParams::normal_viscous_damping_coefficient, "s/m")
      .field("distance_error_bound", &ContactParams::distance_error_bound, "m")
      .field("obj_scale", &ContactParams::obj_scale)
      .field("colliding_penalty_length_scale", &ContactParams::colliding_penalty_length_scale, "m")
      .field("contact_stiffness", &ContactParams::contact_stiffness, "N/m per contact point; 0: near-rigid (this engine's addition)")
      .field("dissipation_time_scale", &ContactParams::dissipation_time_scale, "s: normal damping = contact_stiffness x this")
      .done()
      .def("get_penalty_threshold_dist", &ContactParams::penalty_threshold_dist, "add_padding"_a);
  StructBinder<BoundarySubsamplingParams>(m, "BoundarySubsamplingParams", "")
      .field("subsampling_density", &BoundarySubsamplingParams::subsampling_density)
      .field("strategy", &BoundarySubsamplingParams::strategy)
      .done();
  StructBinder<GridSdfParams>(m, "GridSdfParams", "Resolution of distance grids computed for mesh colliders.")
      .field("resolution_mode", &GridSdfParams::resolution_mode)
      .field("resolution_delta", &GridSdfParams::resolution_delta)
      .field("boundary_padding_dist", &GridSdfParams::boundary_padding_dist, "m")
      .field("min_grid_resolution", &GridSdfParams::min_grid_resolution)
      .done();
  StructBinder<RecenteringParams>(m, "RecenteringParams", "A soft actor's frame following the body's rigid motion.")
      .field("use_recentering", &RecenteringParams::use_recentering)
      .field("rotation_epsilon_deg", &RecenteringParams::rotation_epsilon_deg)
      .field("translation_epsilon", &RecenteringParams::translation_epsilon)
      .done();
  StructBinder<RigidActorParams>(m, "RigidActorParams", "Creates a rigid actor (Scene.create_rigid_actor).")
      .field("name", &RigidActorParams::name)
      .field("layer", &RigidActorParams::layer)
      .field("shape", &RigidActorParams::shape)
      .field("world_from_local", &RigidActorParams::world_from_local)
      .field("collider_type", &RigidActorParams::collider_type)
      .field("is_static", &RigidActorParams::is_static)
      .field("contact", &RigidActorParams::contact)
      .field("sdf", &RigidActorParams::sdf)
      .field("has_gravity", &RigidActorParams::has_gravity)
      .field("density", &RigidActorParams::density, "kg/m^3")
      .field("mass", &RigidActorParams::mass, "kg")
      .field("center_of_mass", &RigidActorParams::center_of_mass, "m, actor frame")
      .field("moment_of_inertia", &RigidActorParams::moment_of_inertia, "kg m^2 about the centre of mass: ixx, ixy, ixz, iyy, iyz, izz")
      .field("boundary_element_type", &RigidActorParams::boundary_element_type)
      .field("boundary_subsampling", &RigidActorParams::boundary_subsampling)
      .field("linear_velocity", &RigidActorParams::linear_velocity, "m/s, world, of the centre of mass")
      .field("angular_velocity", &RigidActorParams::angular_velocity, "rad/s, world")
      .done();
  StructBinder<SoftActorParams>(m, "SoftActorParams", "Creates a soft actor (Scene.create_soft_actor).")
      .field("name", &SoftActorParams::name)
      .field("layer", &SoftActorParams::layer)
      .field("world_from_local", &SoftActorParams::world_from_local)
      .field("shape", &SoftActorParams::shape)
      .field("material", &SoftActorParams::material)
      .field("contact", &SoftActorParams::contact)
      .field("has_gravity", &SoftActorParams::has_gravity)
      .field("has_inertia", &SoftActorParams::has_inertia)
      .field("has_stress", &SoftActorParams::has_stress)
      .field("boundary_element_type", &SoftActorParams::boundary_element_type)
      .done();
  StructBinder<ArticulatedJointFrictionParams>(m, "ArticulatedJointFrictionParams", "Viscous and dry friction of a joint.")
      .field("viscous", &ArticulatedJointFrictionParams::viscous)
      .field("coulomb", &ArticulatedJointFrictionParams::coulomb)
      .field("falloff_vel", &ArticulatedJointFrictionParams::falloff_vel)
      .field("stiction_extra", &ArticulatedJointFrictionParams::stiction_extra)
      .field("stribeck_vel", &ArticulatedJointFrictionParams::stribeck_vel)
      .done();
  bind_dynamic_array<ArticulatedJointFrictionParams>(m, "DynamicArrayArticulatedJointFrictionParams");
  bind_span<const ArticulatedJointFrictionParams>(m, "SpanConstArticulatedJointFrictionParams");
  StructBinder<ArticulatedJointParams>(m, "ArticulatedJointParams", "joints[i] connects links[i] to its parent.")
      .field("name", &ArticulatedJointParams::name)
      .field("type", &ArticulatedJointParams::type)
      .field("parent_link_from_joint", &ArticulatedJointParams::parent_link_from_joint)
      .field("axis", &ArticulatedJointParams::axis)
      .field("friction", &ArticulatedJointParams::friction)
      .field("inertia", &ArticulatedJointParams::inertia)
      .field("min_limit", &ArticulatedJointParams::min_limit)
      .field("max_limit", &ArticulatedJointParams::max_limit)
      .field("limit_stiffness", &ArticulatedJointParams::limit_stiffness)
      .field("limit_damping", &ArticulatedJointParams::limit_damping)
      .done();
  StructBinder<ArticulatedLinkParams>(m, "ArticulatedLinkParams", "One rigid link of an articulated actor.")
      .field("name", &ArticulatedLinkParams::name)
      .field("parent_link", &ArticulatedLinkParams::parent_link)
      .field("parent_joint_from_link", &ArticulatedLinkParams::parent_joint_from_link)
      .field("shape", &ArticulatedLinkParams::shape)
      .field("layer", &ArticulatedLinkParams::layer)
      .field("collider_type", &ArticulatedLinkParams::collider_type)
      .field("contact", &ArticulatedLinkParams::contact)
      .field("has_gravity", &ArticulatedLinkParams::has_gravity)
      .field("density", &ArticulatedLinkParams::density)
      .field("mass", &ArticulatedLinkParams::mass)
      .field("center_of_mass", &ArticulatedLinkParams::center_of_mass)
      .field("moment_of_inertia", &ArticulatedLinkParams::moment_of_inertia)
      .field("boundary_element_type", &ArticulatedLinkParams::boundary_element_type)
      .field("boundary_subsampling", &ArticulatedLinkParams::boundary_subsampling)
      .done();
  StructBinder<ArticulatedCycleJointParams>(m, "ArticulatedCycleJointParams", "A spring closing a kinematic loop.")
      .field("parent_link", &ArticulatedCycleJointParams::parent_link)
      .field("child_link", &ArticulatedCycleJointParams::child_link)
      .field("joint_from_child_link", &ArticulatedCycleJointParams::joint_from_child_link)
      .field("stiffness", &ArticulatedCycleJointParams::stiffness)
      .done();
  bind_dynamic_array<ArticulatedJointParams>(m, "DynamicArrayArticulatedJointParams");
  bind_dynamic_array<ArticulatedLinkParams>(m, "DynamicArrayArticulatedLinkParams");
  bind_dynamic_array<ArticulatedCycleJointParams>(m, "DynamicArrayArticulatedCycleJointParams");
  StructBinder<ArticulatedSkinParams>(m, "ArticulatedSkinParams",
                                      "A triangle surface bound to the links by linear-blend skinning (its shape's mesh.skinning: "
                                      "weights over link indices), authored in the root joint's parent frame at the rest pose. "
                                      "Colliding only: its nodes probe other actors' colliders.")
      .field("shape", &ArticulatedSkinParams::shape)
      .field("layer", &ArticulatedSkinParams::layer)
      .field("contact", &ArticulatedSkinParams::contact)
      .field("boundary_element_type", &ArticulatedSkinParams::boundary_element_type)
      .field("boundary_subsampling", &ArticulatedSkinParams::boundary_subsampling)
      .done();
  StructBinder<ArticulatedActorParams>(m, "ArticulatedActorParams", "Creates an articulated actor (Scene.create_articulated_actor).")
      .field("name", &ArticulatedActorParams::name)
      .field("world_from_root", &ArticulatedActorParams::world_from_root)
      .field("cycles", &ArticulatedActorParams::cycles)
      .field("joints", &ArticulatedActorParams::joints)
      .field("links", &ArticulatedActorParams::links)
      .field("skin", &ArticulatedActorParams::skin)
      .field("joint_velocities", &ArticulatedActorParams::joint_velocities)
      .done();
  bind_dynamic_array<SoftActorParams>(m, "DynamicArraySoftActorParams");
  StructBinder<SoftSkinnedActorParams>(m, "SoftSkinnedActorParams",
                                       "A skeleton carrying soft bodies whose constrained nodes are tied to its links "
                                       "(Scene.create_soft_skinned_actor).")
      .field("skeleton_params", &SoftSkinnedActorParams::skeleton_params)
      .field("soft_params", &SoftSkinnedActorParams::soft_params)
      .field("soft_attach_links", &SoftSkinnedActorParams::soft_attach_links)
      .field("enable_colliding_links", &SoftSkinnedActorParams::enable_colliding_links)
      .field("has_gravity", &SoftSkinnedActorParams::has_gravity)
      .field("has_inertia", &SoftSkinnedActorParams::has_inertia)
      .field("has_stress", &SoftSkinnedActorParams::has_stress)
      .done();
  StructBinder<ArticulatedDofInfo>(m, "ArticulatedDofInfo", "One joint's slice of the generalized coordinates.")
      .field("offset", &ArticulatedDofInfo::offset)
      .field("trans_size", &ArticulatedDofInfo::trans_size)
      .field("rot_size", &ArticulatedDofInfo::rot_size)
      .done()
      .def("get_trans_offset", &ArticulatedDofInfo::trans_offset)
      .def("get_rot_offset", &ArticulatedDofInfo::rot_offset)
      .def("get_size", &ArticulatedDofInfo::size);
  StructBinder<ArticulatedCycleJoint>(m, "ArticulatedCycleJoint", "")
      .field("child", &ArticulatedCycleJoint::child)
      .field("parent", &ArticulatedCycleJoint::parent)
      .done();
  bind_dynamic_array<ArticulatedDofInfo>(m, "DynamicArrayArticulatedDofInfo");
  bind_dynamic_array<ArticulatedCycleJoint>(m, "DynamicArrayArticulatedCycleJoint");
  bind_dynamic_array<ArticulatedJointType>(m, "DynamicArrayArticulatedJointType");
  bind_span<const ArticulatedDofInfo>(m, "SpanConstArticulatedDofInfo");
  bind_span<const ArticulatedCycleJoint>(m, "SpanConstArticulatedCycleJoint");
  bind_span<const ArticulatedJointType>(m, "SpanConstArticulatedJointType");
  // read-only views of the structure (it never changes after creation)
  nb::class_<ArticulatedShapeInfo>(m, "ArticulatedShapeInfo", "The structure of an articulation, per link and per joint.")
      .def_prop_ro("root_from_links_at_rest", [](const ArticulatedShapeInfo& i) { return SpanOf<const TransformRT>::owning(i.root_from_links_at_rest); })
      .def_prop_ro("link_names", [](const ArticulatedShapeInfo& i) { return SpanOf<const std::string>::owning(i.link_names); })
      .def_prop_ro("parents", [](const ArticulatedShapeInfo& i) { return SpanOf<const int>::owning(i.parents); })
      .def_prop_ro("joint_types", [](const ArticulatedShapeInfo& i) { return SpanOf<const ArticulatedJointType>::owning(i.joint_types); })
      .def_prop_ro("cycles", [](const ArticulatedShapeInfo& i) { return SpanOf<const ArticulatedCycleJoint>::owning(i.cycles); })
      .def_prop_ro("joint_axes", [](const ArticulatedShapeInfo& i) { return SpanOf<const Real3>::owning(i.joint_axes); })
      .def_prop_ro("dof_info", [](const ArticulatedShapeInfo& i) { return SpanOf<const ArticulatedDofInfo>::owning(i.dof_info); })
      .def_prop_ro("joint_from_child_link", [](const ArticulatedShapeInfo& i) { return SpanOf<const TransformRT>::owning(i.joint_from_child_link); })
      .def_prop_ro("parent_link_from_joint", [](const ArticulatedShapeInfo& i) { return SpanOf<const TransformRT>::owning(i.parent_link_from_joint); })
      .def_prop_ro("joint_min_limits", [](const ArticulatedShapeInfo& i) { return SpanOf<const Real3>::owning(i.joint_min_limits); })
      .def_prop_ro("joint_max_limits", [](const ArticulatedShapeInfo& i) { return SpanOf<const Real3>::owning(i.joint_max_limits); })
      .def_prop_ro("joint_names", [](const ArticulatedShapeInfo& i) { return SpanOf<const std::string>::owning(i.joint_names); });
}

}  // namespace superdex::python

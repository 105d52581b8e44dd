#pragma once
/// @file scene.h
/// A scene: actors (rigid bodies, articulations and their links) stepped together.
/// `Scene` is a handle; every method looks the scene up and throws superdex::Error if it
/// was destroyed. Actors are addressed by ActorHandle. Frames: W is the world (Z up),
/// L a link frame; spatial vectors are (linear, angular).

#include <functional>
#include <optional>
#include <string>
#include <span>
#include <utility>
#include <variant>
#include <vector>

#include "superdex/physics/shape_meshes.h"
#include "superdex/physics/articulation_desc.h"
#include "superdex/physics/debug_draw.h"
#include "superdex/physics/handles.h"
#include "superdex/physics/params/actor_params.h"
#include "superdex/physics/params/constraint_params.h"
#include "superdex/physics/params/pose_controller_params.h"
#include "superdex/physics/params/recording_params.h"
#include "superdex/physics/params/solver_params.h"
#include "superdex/physics/params/transmission_params.h"
#include "superdex/physics/real.h"
#include "superdex/physics/shape.h"
#include "superdex/physics/transform.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

/// What an actor (or constraint) can be asked to report. Some are computed from the current state
/// when read (NODE_POSITIONS, ELEMENTS_DEFORMATION_GRADIENT, SURFACE_NODE_*, VISUAL_NODE_*,
/// ELASTIC_ENERGY); the others are results of a step. Register a query before reading it: results
/// are valid after the next step (even a zero one), or at once for the first kind when registered
/// with compute_now.
enum class QueryType {
  NodePositions, ElementsDeformationGradient, SurfaceNodePositions, SurfaceNodeNormals, VisualNodePositions,
  VisualNodeNormals, ContactPoints, ElasticEnergy, NodeContactForces, ConstraintForce, ArticulatedControllerForce,
  SdfDistances, TotalContactForce
};
const char* query_type_name(QueryType type);

/// A named signal for the debugger's plots and recordings: one value or a vector (SI units).
struct NamedSignal {
  std::string name;
  std::vector<double> values;
  /// What it measures, for the debugger's choice of default plots: "sensor", "actuator",
  /// "velocity", "effort", "contact" or "user" (empty).
  std::string kind;
};
/// Appends signals when a debugger frame or recorded frame is built (on the stepping thread,
/// after the step's post-step callbacks).
using SignalSource = std::function<void(std::vector<NamedSignal>& out)>;

/// One contact of the last step, seen from the actor it was asked of (actor_a, or actor_b for the
/// other side of the same contact when both were asked). World frame, SI units.
struct ContactPoint {
  ActorHandle actor_a, actor_b;  ///< rigid, link or soft actors; a == b for self-contact
  real distance = 0;             ///< signed gap at the start of the step (m), negative when penetrating
  Real3 pos_a = Real3::Zero();   ///< the contact point on actor a (m)
  Real3 pos_b = Real3::Zero();   ///< pos_a - normal * distance (m)
  Real3 normal = Real3::Zero();  ///< unit, pointing away from actor b
  Real3 force = Real3::Zero();   ///< on actor a from actor b (N)
  Real3 point_velocity_a = Real3::Zero();  ///< velocity of actor a's material point at pos_a (m/s), after the step
  Real3 point_velocity_b = Real3::Zero();  ///< velocity of actor b's material point at pos_b (m/s), after the step
  int sample_index = 0;          ///< the contact's index among the actor's contacts of the step
  real int_weight = 0;           ///< quadrature weight (m^2); 0: a point contact
  int element_index = -1;        ///< the surface triangle of a soft actor a (-1 for rigid ones)
  Real3 parametric_coords = Real3::Zero();  ///< barycentric coordinates of pos_a in that triangle
  bool operator==(const ContactPoint&) const = default;
};

/// The contact force on one node of a soft actor (N, world).
struct NodeContactForce {
  int index = 0;
  Real3 force = Real3::Zero();
  bool operator==(const NodeContactForce&) const = default;
};

/// A soft actor's contact samples of the last step and the colliders' signed distances at them.
struct SdfDistances {
  std::vector<int> sample_indices;     ///< the node nearest each contact point
  std::vector<Real3> world_positions;  ///< m
  std::vector<real> distances;         ///< m, negative: penetration
  std::vector<Real3> distance_grads;   ///< unit, world: the collider's outward normal
  real max_sdf_far_distance_evaluation = 0;  ///< m
  bool operator==(const SdfDistances&) const = default;
};

/// The material of a soft body (FORMATS.md `material`).
struct SoftMaterial {
  std::string type = "NeoHookean";  ///< NeoHookean, StVK, Corotated or Linear
  /// Pa and (< 0.5) for every element. When absent, the tet mesh's per-element values from its
  /// .mochi.h5 `material/` group are used, or 1e5 Pa and 0.3 when it has none.
  std::optional<real> youngs_modulus;
  std::optional<real> poisson_ratio;
  real density = 1000;              ///< kg/m^3
  real damping_alpha = 0;           ///< Rayleigh mass-proportional damping (1/s)
  real damping_beta = 0;            ///< Rayleigh stiffness-proportional damping (s)
  /// 0: the full nonlinear finite-element model. r > 0: a reduced model, linear about the rest
  /// shape, in its r lowest vibration modes plus the exact static response to gravity and contact
  /// forces; needs pinned nodes (a prop held in place). Much faster, for small deformations.
  int reduced_modes = 0;
};

/// What Scene::step does when the solve of an island produces a non-finite value (NaN or
/// infinity) in a body's next positions, velocities or contact forces, or its Newton solver
/// stops at max_newton_iterations without converging.
enum class NumericalFaultPolicy {
  /// Throw superdex::Error naming each faulty actor and quantity. Nothing of the step is
  /// committed: every actor keeps its last good state and the time does not advance. Default.
  Raise,
  /// Keep going: the actors of a faulty island keep their last good positions with zero
  /// velocity (a non-finite result) or take the unconverged but finite result; the others
  /// step normally. The faults are reported by last_numerical_faults() (Python: RuntimeWarning).
  WarnAndClamp,
};

/// One numerical fault of a step.
struct NumericalFault {
  ActorHandle actor = 0;  ///< the rigid, articulated or soft actor
  std::string quantity;   ///< "positions", "velocities", "contact forces" or "convergence"
  std::string message;    ///< names the scene, the actor and the quantity, and what to check
};

/// A new scene's gravity (m/s^2, world frame): along -Y, as SuperDex scenes; Z-up worlds set
/// (0, 0, -9.81) (robot files are Z-up).
inline const Vec3 kDefaultGravity = Vec3(0, real(-9.8), 0);

class Scene;
/// What a step callback receives: the scene being stepped and the step's time step (s).
struct StepInfo;
/// Whether an actor contact rule covers an articulation's links.
enum class IncludeNestedActors { No, Yes };

/// One actor contact rule of a scene (Scene::enable_actor_contact_*): contact of the colliding
/// actor with the collider is enabled or disabled. A symmetric rule is two rules, one each way.
struct ActorContactRule {
  ActorHandle colliding = 0;
  ActorHandle collider = 0;
  bool enable = true;
  IncludeNestedActors nested = IncludeNestedActors::No;
  bool operator==(const ActorContactRule&) const = default;
};
/// Called before (pre) or after (post) each step.
using StepCallback = std::function<void(const StepInfo& info)>;

class Scene {
 public:
  explicit Scene(SceneHandle handle) : handle_(handle) {}
  SceneHandle handle() const { return handle_; }
  std::string name() const;

  /// Gravity in m/s^2, world frame.
  void set_gravity(const Vec3& g_W);
  Vec3 gravity() const;
  /// Advances by dt seconds: one implicit solve per island. Throws superdex::Error for a
  /// non-positive dt or, under NumericalFaultPolicy::Raise, a numerical fault (the scene then
  /// keeps its last good state). Different scenes may be stepped on different threads at once;
  /// a scene must not be used from two threads at once.
  void step(double time_step_sec);
  /// The time step (s) of the last step with a positive one; 0 before.
  double last_time_step() const;
  /// Shows the scene's current state in the debugger without stepping: a frame to the connected
  /// pages and to a running recording (written only when it differs from the scene's last one).
  /// For scenes a script poses or solves rather than steps (an IK solver's scene, a checkpoint
  /// that worker scenes restore from).
  void update_debugger();
  /// Sets what step() does on a numerical fault (default Raise). Not thread-safe: call it while
  /// no thread steps this scene.
  void set_numerical_fault_policy(NumericalFaultPolicy policy);
  NumericalFaultPolicy numerical_fault_policy() const;
  /// The faults the last step clamped under WarnAndClamp; empty after a clean step.
  std::vector<NumericalFault> last_numerical_faults() const;
  /// Seconds simulated since creation.
  double total_simulation_time() const;
  /// Validates (superdex::Error naming the field) and sets the solve's parameters.
  void set_solver_params(const SolverParams& params);
  /// The parameters as set; a new scene has default_scene_solver_params().
  SolverParams solver_params() const;
  /// What the last step's solve did.
  SolverStats solver_stats() const;
  /// How long the last step took.
  PerformanceStats performance_stats() const;

  /// Creates an actor from its params (validated: superdex::Error naming the field). The shape's
  /// data is shared with the actor: the shape handle may be released afterwards.
  ActorHandle create_rigid_actor(const RigidActorParams& params);
  ActorHandle create_soft_actor(const SoftActorParams& params);
  /// A skeleton with soft bodies tied to its links (SoftSkinnedActorParams): returns the
  /// articulated actor; its soft actors are nested_soft_actors() and go with it when destroyed.
  ActorHandle create_soft_skinned_actor(const SoftSkinnedActorParams& params);
  /// An elastic rod (RodActorParams): a soft actor whose nodes are its polyline's, with stretching,
  /// bending and twisting stiffness. Its node constraints take the polyline's node indices.
  ActorHandle create_rod_actor(const RodActorParams& params);
  ActorHandle create_articulated_actor(const ArticulatedActorParams& params);
  /// A soft body from a tet-mesh shape placed at X_WL, with pinned nodes (indices into the mesh),
  /// in this engine's material description (reduced models included): the form prefab files use.
  ActorHandle create_soft_actor(const std::string& name, const ShapeHandle& tet_mesh, const SoftMaterial& material,
                                const Transform& X_WL, const std::vector<int>& fixed_nodes);
  /// Node positions of a soft actor, world frame.
  std::vector<Vec3> node_positions(ActorHandle soft) const;
  /// Elastic energy of a soft actor at its current positions (J).
  real elastic_energy(ActorHandle soft) const;
  /// An articulation from its description; `source` names it in error messages (a file).
  /// Creates one link actor per link.
  ActorHandle create_articulated_actor(const ArticulationDesc& desc, const std::string& source);
  /// Destroys an actor (an articulation with its links). Link actors cannot be destroyed alone.
  void destroy_actor(ActorHandle actor);
  bool has_actor(ActorHandle actor) const;
  /// Top-level actors (rigid and articulated), in creation order.
  std::vector<ActorHandle> actors() const;

  ActorType actor_type(ActorHandle actor) const;
  /// Whether the actor is a link of an articulation (a Rigid actor nested in its Articulated one).
  bool is_nested_link_actor(ActorHandle actor) const;
  std::string actor_name(ActorHandle actor) const;
  /// World-from-actor: a rigid body's pose, an articulation's root link, a link's pose.
  Transform root_transform(ActorHandle actor) const;
  /// Moves a rigid body or an articulation's root (its base frame if welded).
  void set_root_transform(ActorHandle actor, const Transform& X_WL);
  /// Sets the velocity of a free body's centre of mass (m/s) and its angular velocity (rad/s),
  /// world frame. A soft actor takes a linear velocity only (every node gets it).
  void set_velocity(ActorHandle actor, const Vec3& v_W, const Vec3& w_W);
  /// (linear, angular) velocity of the actor's centre of mass, world frame; for a soft actor the
  /// rigid motion of its nodes (momentum over mass, angular momentum through the inertia).
  Vec6 velocity(ActorHandle actor) const;
  /// Total mass in kg.
  real mass(ActorHandle actor) const;
  int num_dofs(ActorHandle actor) const;

  /// Replaces the whole set of external generalized forces (N or N m) on the given DOFs; the
  /// others become zero. Nothing changes when an index is out of range or repeated, or a value
  /// is not finite.
  void set_external_forces_on_dofs(ActorHandle actor, std::span<const int> dofs, std::span<const real> values);
  void set_external_forces_on_dofs(ActorHandle actor, const std::vector<int>& dofs, const std::vector<real>& values) {
    set_external_forces_on_dofs(actor, std::span<const int>(dofs), std::span<const real>(values));
  }
  void clear_external_forces(ActorHandle actor);
  VecX external_forces(ActorHandle actor) const;

  std::vector<ActorHandle> nested_link_actors(ActorHandle articulation) const;
  /// The soft actors of a soft-skinned actor (create_soft_skinned_actor), in soft_params order;
  /// empty for other articulations.
  std::vector<ActorHandle> nested_soft_actors(ActorHandle articulation) const;
  /// Whether a soft actor belongs to a soft-skinned actor.
  bool is_nested_soft_actor(ActorHandle actor) const;
  ActorHandle articulated_actor_of_link(ActorHandle link) const;
  int link_index(ActorHandle link) const;
  ArticulatedShapeInfo articulated_shape_info(ActorHandle articulation) const;
  /// World-from-link transforms in link order.
  std::vector<Transform> link_transforms(ActorHandle articulation) const;
  /// World-from-link transform of the link with index `link` (in link order).
  Transform link_transform(ActorHandle articulation, int link) const;
  /// DOF-sized pose: joint values; spherical and free rotations as rotation vectors (rad).
  VecX pose(ActorHandle articulation) const;
  /// The same into `out` (resized; no allocation when it has the size already).
  void pose(ActorHandle articulation, VecX& out) const;
  /// Sets the pose (all DOFs) and zeroes nothing else.
  void set_pose(ActorHandle articulation, const VecX& pose);
  VecX joint_velocities(ActorHandle articulation) const;
  /// The same into `out` (resized; no allocation when it has the size already).
  void joint_velocities(ActorHandle articulation, VecX& out) const;
  void set_joint_velocities(ActorHandle articulation, const VecX& v);
  /// J_WL of a link (6 x num_dofs, linear rows first, world axes, at the link origin).
  MatXR link_jacobian(ActorHandle link) const;
  /// The same into `J_WL` (resized; no allocation when it has the size already).
  void link_jacobian(ActorHandle link, MatXR& J_WL) const;
  /// M(q) with armature (nv x nv).
  MatX mass_matrix(ActorHandle articulation) const;
  /// c(q, v) including gravity: M vdot + c = tau.
  VecX bias_forces(ActorHandle articulation) const;
  /// vdot = M^-1 (tau - c): forward dynamics of the unconstrained articulation.
  VecX forward_dynamics(ActorHandle articulation, const VecX& tau) const;

  /// Sets the drive of one DOF of a revolute or prismatic joint (stiffness and damping 0 turn it off).
  void set_joint_drive(ActorHandle articulation, int dof, const JointDrive& drive);
  /// Removes every joint and link drive of the articulation.
  void clear_joint_drives(ActorHandle articulation);
  /// Sets (or, with all gains 0, removes) the drive pulling a link towards a world pose.
  void set_link_drive(ActorHandle link, const LinkDrive& drive);
  /// The drive efforts (N m or N) the last step applied, per DOF (zero where no drive).
  VecX joint_drive_efforts(ActorHandle articulation) const;

  // Transmissions of an articulated actor (transmissions.cpp). Errors name the function and the
  // bad argument: an actor that is not articulated, an index out of range, a bad joint list.
  /// Adds a linear transmission; returns its index (0, 1, ... in order of addition).
  int add_linear_transmission(ActorHandle articulation, const LinearTransmissionParams& params);
  /// Adds a spatial tendon (a transmission: same index sequence, same actuators).
  int add_spatial_tendon(ActorHandle articulation, const SpatialTendonParams& params);
  /// Its displacement d at the current pose (m).
  real transmission_displacement(ActorHandle articulation, int transmission) const;
  /// dd/dv over the actor's DOFs (num_dofs entries).
  VecX transmission_displacement_jacobian(ActorHandle articulation, int transmission) const;
  /// Attaches (replacing any) an actuator to a transmission.
  void attach_displacement_control_actuator(ActorHandle articulation, int transmission, const DisplacementControlActuatorParams& params);
  void attach_force_control_actuator(ActorHandle articulation, int transmission, const ForceControlActuatorParams& params);
  void attach_mc_kibben_actuator(ActorHandle articulation, int transmission, const McKibbenActuatorParams& params);
  /// The attached actuator's state variables (the target displacement, or the force): error
  /// when none is attached.
  int num_transmission_actuator_state_variables(ActorHandle articulation, int transmission) const;
  std::vector<real> transmission_actuator_state_variables(ActorHandle articulation, int transmission) const;
  void set_transmission_actuator_state_variables(ActorHandle articulation, int transmission, std::span<const real> values);

  // ---- Constraints (constraint_params.h): spring-dampers between rigid or link actors and the
  // nodes of soft actors, or between one and a target, in the same implicit solve as contacts. Each create validates its
  // params (superdex::Error naming the field); a constraint goes with either of its actors.
  ConstraintHandle create_rigid_spherical_joint_constraint(const RigidSphericalJointConstraintParams& params);
  ConstraintHandle create_rigid_prismatic_joint_constraint(const RigidPrismaticJointConstraintParams& params);
  ConstraintHandle create_joint_rotation_range_constraint(const JointRotationRangeConstraintParams& params);
  ConstraintHandle create_joint_rotation_tracking_constraint(const JointRotationTrackingConstraintParams& params);
  ConstraintHandle create_rod_element_rotation_to_rigid_constraint(const RodElementRotationToRigidConstraintParams& params);
  ConstraintHandle create_rigid_pivot_position_constraint(const RigidPivotPositionConstraintParams& params);
  ConstraintHandle create_rigid_pivot_to_rigid_target_constraint(const RigidPivotToRigidTargetConstraintParams& params);
  ConstraintHandle create_rigid_pivot_rotation_constraint(const RigidPivotRotationConstraintParams& params);
  ConstraintHandle create_deformable_node_position_constraint(const DeformableNodePositionConstraintParams& params);
  ConstraintHandle create_deformable_node_to_rigid_constraint(const DeformableNodeToRigidConstraintParams& params);
  ConstraintHandle create_deformable_node_to_deformable_node_constraint(const DeformableNodeToDeformableNodeConstraintParams& params);
  ConstraintHandle create_articulated_single_dof_target_constraint(const ArticulatedSingleDofTargetConstraintParams& params);
  ConstraintHandle create_articulated_3d_rotation_target_constraint(const Articulated3dRotationTargetConstraintParams& params);
  /// Errors for a pose controller's constraint (remove the controller instead).
  void destroy_constraint(ConstraintHandle constraint);
  bool has_constraint(ConstraintHandle constraint) const;
  /// An articulated actor's joint-limit constraints (ArticulatedSingleDofRange, one per limited
  /// revolute or prismatic joint, in joint order).
  std::vector<ConstraintHandle> joint_limit_constraints(ActorHandle articulation) const;
  /// The scene's constraints in creation order.
  std::vector<ConstraintHandle> constraints() const;
  ConstraintType constraint_type(ConstraintHandle constraint) const;
  /// Stiffness, damping and saturation as set; set_constraint_params validates them.
  ConstraintParams constraint_params(ConstraintHandle constraint) const;
  void set_constraint_params(ConstraintHandle constraint, const ConstraintParams& params);
  /// Its actors: A, then B for the two-actor kinds.
  std::vector<ActorHandle> constraint_actors(ConstraintHandle constraint) const;
  /// The DOFs of actor `actor_index` it acts on (0-2 translation, 3-5 rotation).
  std::vector<int> constraint_dof_indices(ConstraintHandle constraint, int actor_index) const;
  /// Target minus current per constrained component, from the current state (m, rad).
  std::vector<real> constraint_deviation(ConstraintHandle constraint) const;
  /// The last step's generalized force on each actor's DOFs, actor after actor (N, and N m about
  /// the centre of mass; world). Needs a ConstraintForce query.
  std::vector<real> constraint_force(ConstraintHandle constraint) const;
  /// Moves the target (pivot position, node position, and the pivot to rigid target's
  /// translation; world, m).
  /// The damping follows the target's motion over the next step.
  void set_constraint_target_position(ConstraintHandle constraint, const Vec3& position);
  /// Turns the target: world for the pivot rotation and the pivot to rigid target, B relative to
  /// A for the joint rotation tracking.
  void set_constraint_target_rotation(ConstraintHandle constraint, const Quat& rotation);
  /// Moves the target of a single-DOF joint target (rad or m).
  void set_constraint_target_dof(ConstraintHandle constraint, real value);
  /// Forgets the target's motion since the last step (after a jump of the target).
  void update_constraint_old_target(ConstraintHandle constraint);
  /// The relative rotation of A and B at the rotations rotation_a and rotation_b becomes the
  /// reference: the tracking's target, the range's rest.
  void set_constraint_ref_relative_rotation(ConstraintHandle constraint, const Quat& rotation_a, const Quat& rotation_b);
  /// The bounds of the prismatic joint (m) and of the rotation range (rad per joint axis).
  std::vector<real> constraint_limit_min_values(ConstraintHandle constraint) const;
  std::vector<real> constraint_limit_max_values(ConstraintHandle constraint) const;
  /// Queries of a constraint: ConstraintForce only.
  QueryHandle register_constraint_query(ConstraintHandle constraint, QueryType type);
  void cancel_constraint_query(ConstraintHandle constraint, QueryHandle query);
  bool is_constraint_query_supported(ConstraintHandle constraint, QueryType type) const;

  /// Registers a query on an actor (superdex::Error when the actor does not support it; see
  /// is_query_supported); `compute_now` makes a query computed from the state readable at once.
  QueryHandle register_query(ActorHandle actor, QueryType type, bool compute_now = false);
  /// Cancels a query; no effect for an invalid or already cancelled handle.
  void cancel_query(ActorHandle actor, QueryHandle query);
  bool is_query_supported(ActorHandle actor, QueryType type) const;
  /// Total contact force applied TO the actor by everything touching it (N, world). For an
  /// articulation: all its links; for a link: its own contacts. Needs TotalContactForce.
  Vec3 contact_force(ActorHandle actor) const;
  /// Total contact torque about the actor's centre of mass (N m, world). Needs TotalContactForce.
  Vec3 contact_torque(ActorHandle actor) const;
  /// Contact force applied to `actor` by `other` (N, world). Needs TotalContactForce.
  Vec3 contact_force_from(ActorHandle actor, ActorHandle other) const;
  /// The actor's contacts of the last step, each seen from the actor. Needs ContactPoints.
  std::vector<ContactPoint> contact_points(ActorHandle actor) const;
  /// The soft actor's nodes with a contact force in the last step. Needs NodeContactForces.
  std::vector<NodeContactForce> node_contact_forces(ActorHandle soft) const;
  /// The soft actor's contact samples of the last step. Needs SdfDistances.
  SdfDistances sdf_distances(ActorHandle soft) const;

  // Properties of actors (actor_properties.cpp). "Local" is the actor frame L (root transform).
  bool is_static(ActorHandle actor) const;
  /// How the last step's solve of the actor's island ended (NONE: the actor was in no island, being
  /// static or without DOFs, or the scene was not stepped). A link reports its articulation's.
  ConvergenceStatus convergence_status(ActorHandle actor) const;
  ContactParams contact_params(ActorHandle actor) const;
  /// Validated; applies from the next step (to every link of an articulated actor).
  void set_contact_params(ActorHandle actor, const ContactParams& params);
  /// The collider type in use (AUTO resolved from the shape).
  ColliderType collider_type(ActorHandle actor) const;
  /// Centre of mass (m) in the actor frame: rigid actors, links and soft actors.
  Real3 center_of_mass_local(ActorHandle actor) const;
  /// X_WC: the actor frame's rotation, translated to the centre of mass (dynamic rigid actors).
  TransformRT center_of_mass_transform(ActorHandle actor) const;
  void set_center_of_mass_transform(ActorHandle actor, const TransformRT& X_WC);
  /// Rotational inertia about the centre of mass in the actor frame's axes (kg m^2), as
  /// [ixx, ixy, ixz, iyy, iyz, izz] (tensor entries; off-diagonal ones negative products).
  Real6 moment_of_inertia_local(ActorHandle actor) const;
  /// kg/m^3 (rigid actors, links, soft actors).
  real density(ActorHandle actor) const;
  /// Scales the mass and inertia to a new density (kg/m^3, > 0); the centre of mass stays.
  void set_density(ActorHandle actor, real density);
  /// Sets the mass (kg), centre of mass (m, frame L) and inertia (kg m^2) of a dynamic rigid actor.
  void set_inertia_properties(ActorHandle actor, real mass, const Real3& center_of_mass, const Real6& moment_of_inertia);
  /// Bounds of the actor's geometry in its frame / in the world (m).
  Aabb aabb_local(ActorHandle actor) const;
  Aabb aabb_world(ActorHandle actor) const;
  /// A new reference to the shape the actor was made from (rigid actors, links, soft actors).
  ShapeHandle reference_shape(ActorHandle actor) const;
  /// The meshes of the actor's shape, in its local frame: `mesh` is the simulation mesh (a soft
  /// actor's tetrahedra; a rigid actor's or link's compact surface), `surface` the compact surface,
  /// `visual` the model's visual mesh; null where there is none (primitives, whole articulations).
  ShapeMeshes meshes(ActorHandle actor) const;
  /// Signed distance (m, negative inside) of world points to the actor's collider surface.
  std::vector<real> points_distance_to_surface(ActorHandle actor, std::span<const Real3> points_W) const;
  /// The values of DOFs (empty: all); rigid: COM position (m) and rotation vector (rad) of X_WL;
  /// articulations: joint positions; soft: node displacements (m, frame L).
  std::vector<real> dof_values(ActorHandle actor, std::span<const int> dofs) const;

  // Soft actors (soft_actor_api.cpp). Node arrays hold 3 values per node, actor frame L.
  std::vector<real> displacements(ActorHandle soft) const;
  void set_displacements(ActorHandle soft, std::span<const real> displacements);
  std::vector<real> node_positions_local(ActorHandle soft) const;
  void set_node_positions_local(ActorHandle soft, std::span<const real> positions);
  void set_node_velocities_local(ActorHandle soft, std::span<const real> velocities);
  void set_zero_displacements_and_velocities(ActorHandle soft);
  RecenteringParams recentering_params(ActorHandle actor) const;
  void set_recentering_params(ActorHandle soft, const RecenteringParams& params);
  SoftMaterialParams soft_material_params(ActorHandle soft) const;
  /// The material of every element (per-element values set before are replaced).
  void set_soft_material_params(ActorHandle soft, const SoftMaterialParams& params);
  /// The material of one tetrahedron (index in the volume mesh): its elastic model and moduli,
  /// and its density (the node masses follow). Damping stays the actor's.
  SoftMaterialParams soft_material_params_field(ActorHandle soft, int element) const;
  void set_soft_material_params_field(ActorHandle soft, const SoftMaterialParams& params, int element);
  /// Per element, row-major 3 x 3 (9 values). Needs ElementsDeformationGradient.
  std::vector<real> elements_deformation_gradient(ActorHandle soft) const;
  /// Nodes of the compact surface mesh (Scene::surface_mesh order). Need SurfaceNodePositions/Normals.
  std::vector<real> surface_node_positions_local(ActorHandle soft) const;
  /// The nodes inside a volume given in the actor's local frame (m), as (index, local position):
  /// boundary_only false: every node of a soft actor (index in its mesh; needs NodePositions);
  /// true: the surface nodes of a soft actor (mesh index; needs SurfaceNodePositions) or of a
  /// rigid actor's mesh shape (index in its compact surface, Actor.get_mesh order).
  std::vector<std::pair<int, Real3>> nodes_in_volume_local(ActorHandle actor, const std::variant<Aabb, Obb, Sphere>& volume,
                                                           bool boundary_only) const;
  std::vector<real> surface_node_normals_local(ActorHandle soft) const;
  /// Boundary conditions by DOF (3 per node: its world position, all three together) or by node;
  /// `permanent` ones survive clear_boundary_conditions(). The latest entry of a DOF wins.
  void add_boundary_condition_dofs_world(ActorHandle soft, std::span<const int> dofs, std::span<const real> values_W, bool permanent);
  void add_boundary_condition_nodes_world(ActorHandle soft, std::span<const int> nodes, std::span<const real> positions_W, bool permanent);
  void clear_boundary_conditions(ActorHandle soft);
  /// All entries added, in insertion order (clearable and permanent).
  std::vector<int> boundary_condition_dof_indices(ActorHandle soft) const;
  std::vector<real> boundary_condition_dof_values_world(ActorHandle soft) const;

  // The pose controller of an articulated actor (pose_controller_params.h; pose_controller_api.cpp).
  // Targets are DOF-sized joint poses (rotation vectors for spherical and free joints) or
  // world-from-link transforms, one per link; either sets both (the other by forward kinematics
  // or by projecting the links onto the joints). A target set between steps moves over the next
  // step, and the damping follows that motion; a reset target, or a target velocity (DOF
  // velocities, applied at the next step's start), sets how it moved instead.
  void add_pose_controller(ActorHandle articulation, const PoseControllerParams& params);
  bool has_pose_controller(ActorHandle articulation) const;
  void remove_pose_controller(ActorHandle articulation);
  void set_pose_controller_params(ActorHandle articulation, const PoseControllerParams& params);
  /// All three arrays with one entry per link (zero gains where a link or joint has none).
  PoseControllerParams pose_controller_params(ActorHandle articulation) const;
  /// Link translations (every link), then link rotations (every link), then joints (every joint
  /// but Hard ones).
  std::vector<PoseConstraintInfo> pose_constraints(ActorHandle articulation) const;
  void set_target_pose(ActorHandle articulation, const VecX& pose);
  void reset_target_pose(ActorHandle articulation, const VecX& pose);
  void set_target_link_transforms(ActorHandle articulation, std::span<const TransformRT> X_WL);
  void reset_target_link_transforms(ActorHandle articulation, std::span<const TransformRT> X_WL);
  void set_target_velocity(ActorHandle articulation, const VecX& velocity);
  VecX target_pose(ActorHandle articulation) const;
  std::vector<Transform> target_link_transforms(ActorHandle articulation) const;
  /// The generalized force (N or N m per DOF) the controller's constraints applied in the last
  /// step. Needs an ArticulatedControllerForce query registered before that step.
  VecX controller_force(ActorHandle articulation) const;

  // Articulations (articulated_actor_api.cpp).
  std::vector<ArticulatedJointFrictionParams> joint_friction_params(ActorHandle articulation) const;
  void set_joint_friction_params(ActorHandle articulation, const std::vector<ArticulatedJointFrictionParams>& friction);
  /// Armature (kg or kg m^2) per joint.
  std::vector<real> joint_inertia_params(ActorHandle articulation) const;
  void set_joint_inertia_params(ActorHandle articulation, std::span<const real> inertia);
  /// [min, max] per DOF (m or rad; +-infinity where unlimited).
  std::vector<Real2> dof_limits(ActorHandle articulation) const;
  /// Poses the articulation from world-from-link transforms (projected onto its joints).
  void set_pose_from_links(ActorHandle articulation, std::span<const TransformRT> X_WL);
  /// pose (+) delta: joint-aware (rotation vectors composed as rotations).
  VecX add_delta_to_pose(ActorHandle articulation, const VecX& pose, const VecX& delta) const;
  /// The delta with add_delta_to_pose(base, delta) = target.
  VecX pose_delta(ActorHandle articulation, const VecX& base, const VecX& target) const;
  /// Per joint: translation distance (m) and rotation angle (rad) between two poses.
  void pose_distance(ActorHandle articulation, const VecX& a, const VecX& b, VecX& translation, VecX& rotation) const;

  /// Contact layers: each actor has one, named ("" by default); contact between a colliding actor
  /// of layer a and a collider of layer b is enabled unless switched off (two actors touch when
  /// either order is enabled). At most 64 layers per scene; names are registered on first use.
  void enable_layer_contact_asymmetric(const std::string& layer_a, const std::string& layer_b, bool enable);
  void enable_layer_contact_symmetric(const std::string& layer_a, const std::string& layer_b, bool enable);
  bool is_layer_contact_enabled(const std::string& layer_a, const std::string& layer_b) const;
  int num_contact_layers() const;
  std::vector<std::string> contact_layer_names() const;
  /// The contact layer of an actor (of each link, for an articulation's link actor).
  std::string contact_layer(ActorHandle actor) const;
  void set_contact_layer(ActorHandle actor, const std::string& layer);
  /// Enables or disables contact of the colliding actor with the collider (asymmetric), or both
  /// ways. With IncludeNestedActors::Yes the rule covers an articulation's links too; a rule for
  /// two links of one articulation overrides its default (joined links do not touch).
  void enable_actor_contact_asymmetric(ActorHandle colliding, ActorHandle collider, bool enable, IncludeNestedActors nested);
  void enable_actor_contact_symmetric(ActorHandle a, ActorHandle b, bool enable, IncludeNestedActors nested);
  /// The actor contact rules set so far, ordered by (colliding, collider) handle; the latest rule
  /// of a pair replaces the earlier ones. Rules naming a destroyed actor are left out.
  std::vector<ActorContactRule> actor_contact_rules() const;

  // Creation parameters read back (actor_readback.cpp): what would create the actor again as it
  // is now, for exporting scenes (prefab::export_scene). Positions are the current ones, in the
  // world frame W; values changed by setters since creation (contact params, layers, masses,
  // joint friction and armature, soft materials) are the current ones.
  /// A rigid actor (not a link): world_from_local is its current pose X_WL; the shape is a new
  /// reference to the one it was made from (release it after use); mass, center_of_mass and
  /// moment_of_inertia are set (kg, m in frame L, kg m^2 about the centre of mass) for a dynamic
  /// actor, density the one in use; linear and angular velocity are the current ones (m/s, rad/s,
  /// world) when not zero. The sdf and boundary fields keep their defaults (not recorded).
  RigidActorParams rigid_actor_params(ActorHandle rigid) const;
  /// A soft actor: world_from_local is its current actor frame X_WL and the shape a new reference
  /// to its rest tetrahedral mesh (in frame L; the current deformation is not part of it), the
  /// material the actor-wide one (soft_material_params).
  SoftActorParams soft_actor_params(ActorHandle soft) const;
  /// The nodes of a soft actor pinned at creation (indices into its tet mesh, ascending).
  std::vector<int> soft_fixed_nodes(ActorHandle soft) const;
  /// The vibration modes of a reduced soft actor; 0 for the full finite-element model.
  int soft_reduced_modes(ActorHandle soft) const;
  /// An articulation as the description it was built from (articulation_desc.h), with the
  /// current values of what setters change. world_from_root places the root joint's parent frame
  /// so that the root link is where it is now with the root joint at its zero position; the other
  /// joints' positions and all velocities are not part of it (default_pose is the one given at
  /// creation). Per link: `shape` is the geometry the link was given (in frame S, before
  /// shape_scale, placed at link_from_shape X_LS in the link frame L; for a BOX or SPHERE collider
  /// fitted around another shape, that box or sphere), mass, center_of_mass and
  /// moment_of_inertia the ones in use (kg, m in L, kg m^2 about the centre of mass, L's axes),
  /// layer its index in the scene (contact_layer() names it), collider_type as given. Shape files
  /// (shape_file, render_model) are not kept: links carry their geometry inline.
  ArticulationDesc articulation_desc(ActorHandle articulation) const;
  /// Whether gravity acts on the actor (a rigid actor, a link or a soft actor; an articulation:
  /// on any of its links).
  bool has_gravity(ActorHandle actor) const;

  /// The priority of callbacks registered without one.
  static constexpr int kDefaultCallbackPriority = 100;
  /// Registers a callback run at the start of every step (pre) or after it (post), on the
  /// stepping thread, in increasing priority and then registration order. `debug_name` names it
  /// in messages. An exception thrown by a pre-step callback aborts the step before anything
  /// changed. Callbacks may register and cancel callbacks; the change applies from the next step.
  CallbackHandle register_pre_step_callback(const std::string& debug_name, StepCallback fn, int priority = kDefaultCallbackPriority);
  CallbackHandle register_post_step_callback(const std::string& debug_name, StepCallback fn, int priority = kDefaultCallbackPriority);
  /// Removes a callback; no effect for an invalid or already cancelled handle.
  void cancel_callback(CallbackHandle handle);
  /// The number of registered pre- and post-step callbacks.
  std::size_t num_step_callbacks() const;

  /// Adds a source of named signals shown by the debugger and written to recordings (frames
  /// already carry joint velocities and efforts and contact forces); returns its id.
  int add_signal_source(SignalSource source);
  /// Removes a signal source; no effect for an unknown id.
  void remove_signal_source(int id);

  /// Captured states: capture_state() keeps a copy of the scene's evolving state (time, every
  /// body's positions, velocities and held forces) under a handle; restore_state() replays from it
  /// bitwise identically in this scene (the same actors).
  StateHandle capture_state();
  /// Throws superdex::Error for an unknown or released handle; releases it when `release`.
  void restore_state(StateHandle state, bool release);
  void release_state(StateHandle state);
  void release_all_states();
  /// Both handles valid and their states identical.
  bool is_equal_state(StateHandle a, StateHandle b) const;
  /// The state as bytes (appended to `out`), and restored from them.
  void capture_state_to_bytes(std::vector<std::uint8_t>& out) const;
  void restore_state_from_bytes(std::span<const std::uint8_t> bytes);
  /// A JSON snapshot of the state for inspection.
  void capture_state_to_file(const std::string& path) const;

  /// Records this scene to an HDF5 file (created or replaced; layout: docs/recording_format.md,
  /// "Scene recordings"): its actors when first seen, then a frame after every step with what
  /// `params` selects. Stops a recording already running. Throws superdex::Error naming the
  /// file when it cannot be created. A later failure to write a frame logs a warning and the
  /// recording goes on.
  void start_recording(const std::string& file_path, const RecordingParams& params);
  /// Closes the file; no effect when no recording runs.
  void stop_recording();
  bool is_recording() const;

  /// Solve every dynamic body in one island (a debugging aid; slower).
  void set_force_single_island(bool force);
  bool force_single_island() const;
  /// Every actor, links and nested actors included, in creation order.
  std::vector<ActorHandle> all_actors() const;

  /// The scene's debug drawing (debug_draw.h): contacts, bounds, frames and bodies as line
  /// segments and spheres for the client to render. Off until DebugDraw::enable(true).
  DebugDraw debug_draw() const { return DebugDraw(handle_); }

 private:
  // the physics of one step (between the callbacks)
  void step_dynamics(real dt);
  SceneHandle handle_;
};

struct StepInfo {
  Scene scene;
  double time_step_sec = 0;
};

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

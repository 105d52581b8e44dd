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
#include <vector>

#include "superdex/physics/articulation_desc.h"
#include "superdex/physics/handles.h"
#include "superdex/physics/real.h"
#include "superdex/physics/shape.h"
#include "superdex/physics/transform.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

enum class ActorType { Rigid, Soft, Articulated, Link };

/// Results an actor can ask the step to report (register before reading; valid after the next step).
enum class QueryType {
  TotalContactForce,
  ContactPoints,
  NodePositions,
  NodeContactForces,
  ConstraintForce,
  ArticulatedControllerForce,
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

/// One contact of the last step seen from actor a.
struct ContactPointInfo {
  ActorHandle actor_a = 0, actor_b = 0;  ///< link or rigid actors
  Vec3 position = Vec3::Zero();          ///< world (m)
  Vec3 normal = Vec3::Zero();            ///< unit, from b towards a
  real distance = 0;                     ///< signed gap at the start of the step (m), negative when penetrating
  Vec3 force = Vec3::Zero();             ///< force applied to a (N), world
};

/// Parameters of the implicit solve.
struct SolverParams {
  int max_newton_iterations = 50;
  /// Stop when the scaled momentum residual is below abs + rel * scale.
  real absolute_tolerance = real(1e-10);
  real relative_tolerance = kUsesDoublePrecision ? real(1e-8) : real(1e-5);
  int max_line_search_iterations = 40;
  /// Near-rigid regularisation of limits: constraint compliance = beta^2 / (4 pi^2) * w.
  real near_rigid_beta = 1;
  /// Regularisation of friction rows relative to their effective compliance w.
  real friction_sigma = real(1e-3);
  /// Pairs of shapes closer than this (m) produce contact candidates (speculative contact).
  real contact_margin = real(0.01);
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
  /// Soft bodies: a Newton iteration after the first recomputes the Hessian only of the elements
  /// whose deformation gradient changed by more than this (in any entry, dimensionless) since
  /// the start of the step; the others keep their Hessian there. The problem and its tolerance
  /// are unchanged (the gradient is always exact); only the Newton direction is approximate.
  /// 0 recomputes every element that moved.
  real soft_hessian_reuse_strain = real(1e-3);
};

/// What the last step did.
struct SolverStats {
  int newton_iterations = 0;      ///< largest number of Newton iterations over islands
  int total_newton_iterations = 0;
  real residual = 0;              ///< largest final scaled residual over islands
  bool converged = true;
  int num_islands = 0;
  int num_constraints = 0;        ///< active constraint rows (limits, friction)
  int num_contacts = 0;
  int soft_element_hessians = 0;  ///< element Hessians of soft bodies computed (see SolverParams::soft_hessian_reuse_strain)
  /// Sparse factorizations of soft bodies' Newton matrices. A Newton iteration after the first
  /// of a solve is solved by conjugate gradients preconditioned by the last factorization, and
  /// factors its matrix only when they do not converge in a few iterations.
  int soft_factorizations = 0;
  double time_kinematics = 0;     ///< seconds in kinematics and dynamics terms
  double time_collision = 0;      ///< seconds in collision detection
  double time_solve = 0;          ///< seconds in the implicit solves
  double time_total = 0;
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

/// One joint's slice of the generalized coordinates.
struct DofInfo {
  int offset = 0;      ///< first DOF index of the joint
  int trans_size = 0;  ///< translational DOFs
  int rot_size = 0;    ///< rotational DOFs
  int size() const { return trans_size + rot_size; }
};

/// The structure of an articulation, in link order.
struct ArticulatedShapeInfo {
  std::vector<std::string> link_names, joint_names;
  std::vector<int> parents;            ///< -1 for the root
  std::vector<JointType> joint_types;
  std::vector<Vec3> joint_axes;        ///< unit axis in the joint frame
  std::vector<DofInfo> dof_info;
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

class Scene;
/// Called before (pre) or after (post) each step with the scene and the step's dt (s).
using StepCallback = std::function<void(Scene& scene, real dt)>;

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
  void step(real dt);
  /// Sets what step() does on a numerical fault (default Raise). Not thread-safe: call it while
  /// no thread steps this scene.
  void set_numerical_fault_policy(NumericalFaultPolicy policy);
  NumericalFaultPolicy numerical_fault_policy() const;
  /// The faults the last step clamped under WarnAndClamp; empty after a clean step.
  std::vector<NumericalFault> last_numerical_faults() const;
  /// Seconds simulated since creation.
  double total_simulation_time() const;
  void set_solver_params(const SolverParams& params);
  SolverParams solver_params() const;
  SolverStats solver_stats() const;

  /// A rigid body carrying `shape`: static (welded) or dynamic (a Free one-link articulation).
  /// Mass from `mass`, else from `density` (kg/m^3, default 1000) and the shape's volume.
  /// Its surface has the contact parameters `contact`, collision `layer` (0..63), and no
  /// collider when `collider_type` is None.
  ActorHandle create_rigid_actor(const std::string& name, const ShapeHandle& shape, bool is_static, const Transform& X_WL,
                                 std::optional<real> density, std::optional<real> mass,
                                 const ContactMaterial& contact = {}, int layer = 0,
                                 ColliderType collider_type = ColliderType::Auto);
  /// A soft body from a tet-mesh shape (create_tet_mesh_shape) placed at X_WL, with pinned
  /// nodes (indices into the mesh). Throws superdex::Error naming the defect.
  ActorHandle create_soft_actor(const std::string& name, const ShapeHandle& tet_mesh, const SoftMaterial& material,
                                const Transform& X_WL, const std::vector<int>& fixed_nodes);
  /// Node positions of a soft actor, world frame (N x 3, row-major).
  std::vector<Vec3> node_positions(ActorHandle soft) const;
  /// Contact force on each node of a soft actor in the last step (N, world). Needs NODE_CONTACT_FORCES.
  std::vector<Vec3> node_contact_forces(ActorHandle soft) const;
  /// Elastic energy of a soft actor at its current positions (J).
  real elastic_energy(ActorHandle soft) const;
  /// Pins nodes of a soft actor at world positions (m); the next step moves them there (a moving
  /// boundary condition: call again each step to drive them along a path). Throws on bad indices.
  void set_boundary_nodes(ActorHandle soft, const std::vector<int>& nodes, const std::vector<Vec3>& positions_W);
  /// Releases pinned nodes: they move freely from the next step.
  void release_boundary_nodes(ActorHandle soft, const std::vector<int>& nodes);
  /// The pinned nodes of a soft actor (a prefab's fixedNodes / fixedRegion, set_boundary_nodes),
  /// in increasing order.
  std::vector<int> boundary_nodes(ActorHandle soft) const;
  /// An articulation from its description; `source` names it in error messages (a file).
  /// Creates one link actor per link.
  ActorHandle create_articulated_actor(const ArticulationDesc& desc, const std::string& source);
  /// Destroys an actor (an articulation with its links). Link actors cannot be destroyed alone.
  void destroy_actor(ActorHandle actor);
  bool has_actor(ActorHandle actor) const;
  /// Top-level actors (rigid and articulated), in creation order.
  std::vector<ActorHandle> actors() const;

  ActorType actor_type(ActorHandle actor) const;
  std::string actor_name(ActorHandle actor) const;
  /// World-from-actor: a rigid body's pose, an articulation's root link, a link's pose.
  Transform root_transform(ActorHandle actor) const;
  /// Moves a rigid body or an articulation's root (its base frame if welded).
  void set_root_transform(ActorHandle actor, const Transform& X_WL);
  /// Sets the velocity of a free body's origin (m/s) and its angular velocity (rad/s), world frame.
  void set_velocity(ActorHandle actor, const Vec3& v_W, const Vec3& w_W);
  /// (linear, angular) velocity of the actor's origin in world frame.
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

  /// Registers a query on an actor; returns its handle. Results are valid after the next step.
  std::int64_t register_query(ActorHandle actor, QueryType type);
  void cancel_query(ActorHandle actor, std::int64_t query);
  /// Total contact force applied TO the actor by everything touching it (N, world). For an
  /// articulation: all its links; for a link: its own contacts. Needs TotalContactForce.
  Vec3 contact_force(ActorHandle actor) const;
  /// Total contact torque about the actor's origin (N m, world). Needs TotalContactForce.
  Vec3 contact_torque(ActorHandle actor) const;
  /// Contact force applied to `actor` by `other` (N, world). Needs TotalContactForce.
  Vec3 contact_force_from(ActorHandle actor, ActorHandle other) const;
  /// The actor's contacts of the last step, each seen from the actor. Needs ContactPoints.
  std::vector<ContactPointInfo> contact_points(ActorHandle actor) const;

  /// Enables or disables contact between two actors (rigid, articulated or link actors).
  void enable_actor_contact(ActorHandle a, ActorHandle b, bool enable);
  /// Enables or disables contact between collision layers (0..63).
  void enable_layer_contact(int layer_a, int layer_b, bool enable);

  /// Registers a callback run at the start of every step (pre) or after it (post), in order of
  /// `priority` (lower first), then name. A name already registered is replaced. An exception
  /// thrown by a pre-step callback aborts the step before anything changed.
  void register_pre_step_callback(const std::string& name, StepCallback fn, int priority = 100);
  void register_post_step_callback(const std::string& name, StepCallback fn, int priority = 100);
  /// Removes a callback; throws if no callback has that name.
  void cancel_callback(const std::string& name);

  /// Adds a source of named signals shown by the debugger and written to recordings (frames
  /// already carry joint velocities and efforts and contact forces); returns its id.
  int add_signal_source(SignalSource source);
  /// Removes a signal source; no effect for an unknown id.
  void remove_signal_source(int id);

  /// The scene's evolving state (time, every body's positions, velocities and held forces) as
  /// bytes; restoring it into a scene with the same actors replays bitwise identically.
  std::vector<std::uint8_t> capture_state() const;
  void restore_state(const std::vector<std::uint8_t>& state);

 private:
  // the physics of one step (between the callbacks)
  void step_dynamics(real dt);
  SceneHandle handle_;
};

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

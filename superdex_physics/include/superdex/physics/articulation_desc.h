#pragma once
/// @file articulation_desc.h
/// The static description of an articulated body: links, joints and their parameters,
/// with the fields of the `.superdex_bot` format (FORMATS.md). A description is what users
/// write and edit; the engine validates it and builds an immutable model from it.

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "superdex/physics/params/actor_params.h"
#include "superdex/physics/real.h"
#include "superdex/physics/shape.h"
#include "superdex/physics/transform.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

/// How a link moves relative to its parent (actor_params.h): Hard, Free (root only; velocity of
/// the link origin in the parent (world-aligned) frame, then angular velocity in the link frame),
/// Revolute (rad), Prismatic (m), Spherical (angular velocity in the child link frame).
using JointType = ArticulatedJointType;

/// Returns "Hard", "Free", ... as written in files.
const char* joint_type_name(JointType type);
/// Generalized velocity size of a joint type.
int joint_num_dofs(JointType type);

/// An implicit spring-damper on one DOF, solved inside the step: effort
/// tau = stiffness (target_position - q+) + damping (target_velocity - v+) at the END of the step
/// (so any stiffness is stable), clamped to |tau| <= max_effort when max_effort >= 0.
struct JointDrive {
  real stiffness = 0;        ///< N m/rad (N/m)
  real damping = 0;          ///< N m s/rad (N s/m)
  real target_position = 0;  ///< rad (m)
  real target_velocity = 0;  ///< rad/s (m/s)
  real max_effort = -1;      ///< N m (N); < 0: unbounded
  bool active() const { return stiffness > 0 || damping > 0; }
};

/// An implicit spring-damper pulling a link towards a world pose, solved inside the step: force
/// K_lin (p* - p+) + D_lin (v* - v+) on the link origin and torque K_ang r(R* R+^T) + D_ang
/// (w* - w+) (r: rotation vector), world frame, each axis clamped to max_force / max_torque
/// when those are >= 0. A zero stiffness and damping leaves that part out.
struct LinkDrive {
  Transform target;                          ///< world-from-link target pose
  Vec3 target_linear_velocity = Vec3::Zero();   ///< m/s, world
  Vec3 target_angular_velocity = Vec3::Zero();  ///< rad/s, world
  real linear_stiffness = 0, linear_damping = 0;    ///< N/m, N s/m
  real angular_stiffness = 0, angular_damping = 0;  ///< N m/rad, N m s/rad
  real max_force = -1, max_torque = -1;             ///< per axis; < 0: unbounded
  bool active() const { return linear_stiffness > 0 || linear_damping > 0 || angular_stiffness > 0 || angular_damping > 0; }
};

/// One joint: connects link i to its parent link (or the world for the root).
struct JointDesc {
  std::string name;
  JointType type = JointType::Revolute;
  /// Joint axis in the joint frame (revolute, prismatic); normalised by the engine.
  Vec3 axis = Vec3::UnitZ();
  /// X_PJ: the joint frame in the parent link frame. The child link frame coincides with
  /// the joint frame at zero joint position.
  Transform parent_link_from_joint;
  /// Position limits as vectors along the axis (limit value = axis . vector); absent: unlimited.
  std::optional<Vec3> min_limit;
  std::optional<Vec3> max_limit;
  /// < 0 unbounded, 0 not actuated, > 0 limit in N or N m (advisory: the physics does not clamp).
  real effort_limit = -1;
  /// Coulomb friction force or torque bound (N or N m), >= 0.
  real coulomb_friction = 0;
  /// Viscous friction coefficient (N s/m or N m s/rad), >= 0; integrated implicitly.
  real viscous_friction = 0;
  /// Armature (rotor inertia, kg m^2 or kg) added to each DOF's diagonal of the mass matrix.
  real armature = 0;
  /// Limit stiffness (N/m or N m/rad); 0 means rigid (the solver's near-rigid regularisation).
  real limit_stiffness = 0;
  /// Limit damping (N s/m or N m s/rad), used with a finite limit stiffness.
  real limit_damping = 0;
};

/// A further collision shape of a link (compound collision), posed in the link frame.
struct LinkShapeDesc {
  ShapeGeometry shape;
  Transform link_from_shape;
  /// The file the shape was loaded from, for messages and viewers (empty for primitives).
  std::string shape_file;
};

/// One link (rigid body) of an articulation.
struct LinkDesc {
  std::string name;
  /// Index of the parent link; -1 for the root (link 0).
  int parent_link = -1;
  /// Mass in kg; when absent it is computed from `density` and the shape.
  std::optional<real> mass;
  /// Centre of mass in the link frame (m); when absent and the mass comes from the shape,
  /// the shape's centre of mass.
  std::optional<Vec3> center_of_mass;
  /// Rotational inertia about the COM in the link frame: Ixx, Ixy, Ixz, Iyy, Iyz, Izz (kg m^2).
  std::optional<std::array<real, 6>> moment_of_inertia;
  /// Density in kg/m^3, used when `mass` is absent.
  std::optional<real> density;
  /// Shape carried by the link, in the link frame (inline primitive); absent: no geometry.
  std::optional<ShapeGeometry> shape;
  /// Shape file path as written in the file (meshes, `.mochi.h5`), resolved by loaders.
  std::string shape_file;
  Vec3 shape_scale = Vec3::Ones();
  std::string collider_type = "Auto";
  std::string render_model;
  Vec3 render_model_scale = Vec3::Ones();
  /// Pose of the shape in the link frame (inline primitives: their "center" and "rotation").
  Transform link_from_shape;
  /// Origin of this link's frame in its joint's frame (m), which rotates with the joint: the
  /// link frame is the joint frame moved by this (no rotation). Zero: the frames coincide.
  Vec3 joint_from_link = Vec3::Zero();
  /// Further collision shapes of the link beside `shape` (a URDF link's later <collision>
  /// elements, a body's several geoms): all of them move and collide as one body, with the
  /// link's contact parameters and layer, and never touch each other. They add no mass: the
  /// mass comes from `mass` (and `moment_of_inertia`), or from `shape` alone.
  std::vector<LinkShapeDesc> extra_shapes;
  /// Contact parameters of the link's surface.
  ContactParams contact;
  /// Collision layer, 0..63 (see Scene::enable_layer_contact).
  int layer = 0;
  bool has_gravity = true;
};

/// Enables or disables contact between two links of the same articulation, by name.
struct ContactOverride {
  std::string link_a, link_b;
  bool enable = false;
};

/// A joint that follows another of the same articulation: q_joint = ratio q_leader + offset (a URDF
/// <mimic>, a linear transmission, an MJCF joint equality). Both are revolute or prismatic; the
/// step holds the relation as a near-rigid constraint (position errors closed within a step).
struct JointCoupling {
  std::string joint;   ///< the follower
  std::string leader;  ///< the joint it follows
  real ratio = 1;      ///< (rad or m) per (rad or m)
  real offset = 0;     ///< rad or m
};

/// SuperDex's linear transmission: sum_k c_k q_k driven towards target_displacement by a spring
/// (`.superdex_bot` "linearTransmissions"). One of two joints is held as a rigid coupling,
/// c_0 q_0 + c_1 q_1 = target_displacement (the second joint follows the first by -c_0 / c_1, as
/// the mimic fingers of the Revo2 hands do); its spring and damper are not modelled yet and
/// transmissions of more joints are not built (the bot file's reader names both in warnings).
struct LinearTransmission {
  std::string name;
  std::vector<int> joint_indices;        ///< indices into ArticulationDesc::joints
  std::vector<real> joint_coefficients;  ///< c_k, per joint (m per joint unit, or dimensionless)
  std::vector<real> joint_axis_disps;    ///< attachment offsets along each joint's axis (m)
  real target_displacement = 0;          ///< m (or the joints' unit for a gearbox)
  real stiffness = 0;                    ///< N/m
  real damping = 0;                      ///< N s/m
  bool allow_compressive_force = true;
  bool operator==(const LinearTransmission&) const = default;
};

/// A fixed tendon (MuJoCo's <tendon><fixed>): a length L = sum_k c_k q_k over revolute and prismatic
/// joints of one articulation, kept within [lower, upper] where limited and pulled towards
/// rest_length by a linear spring and damper (implicit in the step, like joint damping).
struct FixedTendon {
  std::string name;
  std::vector<std::string> joints;  ///< joint names, one per coefficient
  std::vector<real> coefficients;   ///< c_k: m (or rad) of length per unit of joint k's motion
  bool has_lower = false, has_upper = false;
  real lower = 0, upper = 0;        ///< length range (m or rad), where limited
  real stiffness = 0;               ///< N/m (or N m/rad) along the length
  real damping = 0;                 ///< N s/m (or N m s/rad) along the length
  real rest_length = 0;             ///< length at which the spring is relaxed
  bool operator==(const FixedTendon&) const = default;
};

/// A whole articulation: links[i] is attached to its parent by joints[i].
struct ArticulationDesc {
  std::string name;
  std::vector<LinkDesc> links;
  std::vector<JointDesc> joints;
  /// Generalized positions in DOF order, excluding the root joint's DOFs; empty: all zero.
  std::vector<real> default_pose;
  /// Pose of the root joint's parent frame in the world.
  Transform world_from_root;
  /// Link pairs whose contact differs from the default (joined links off, others on).
  std::vector<ContactOverride> contact_overrides;
  /// Joints that follow others.
  std::vector<JointCoupling> couplings;
  /// Linear transmissions between joints; two-joint ones are held as couplings.
  std::vector<LinearTransmission> linear_transmissions;
  /// Fixed tendons (length limits and springs on linear combinations of joints).
  std::vector<FixedTendon> fixed_tendons;
};

/// A link's inline primitive scaled by its shapeScale `s` per axis (a sphere needs a uniform
/// scale, a capsule x == y; meshes come baked and are returned as they are). Throws
/// superdex::Error "<where>: ..." for a non-positive or non-finite scale or one the shape cannot take.
ShapeGeometry scaled_shape(const ShapeGeometry& shape, const Vec3& s, const std::string& where);

/// The coupling a two-joint linear transmission holds: joint 1 follows joint 0 by -c_0 / c_1,
/// offset target / c_1. Throws superdex::Error naming `where` for indices out of range, a
/// transmission of another number of joints, or a zero c_1.
JointCoupling coupling_of(const LinearTransmission& t, const std::vector<JointDesc>& joints, const std::string& where);

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

#pragma once
/// @file actor_params.h
/// What creates actors (SuperDex's names and defaults): RigidActorParams, SoftActorParams and
/// ArticulatedActorParams with its links and joints, and the settings they share. Frames: W the
/// world, L an actor's local frame (a link's frame for links); lengths in m, masses in kg.

#include <optional>
#include <string>
#include <vector>

#include "superdex/physics/handles.h"
#include "superdex/physics/params/contact_params.h"
#include "superdex/physics/params/material_params.h"
#include "superdex/physics/types.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

/// The kind of an actor. A link of an articulation is a Rigid actor nested in its Articulated one.
/// Shell is SuperDex's name for thin shells, which this engine does not create yet.
enum class ActorType { None, Rigid, Soft, Articulated, Shell, Rod };
const char* actor_type_name(ActorType type);

/// Quadrature of surface integrals (PxQy: order x, y points per triangle).
enum class ActorBoundaryElementType { P1Q1, P1Q3, P1Q6, ExperimentalP1Q7, ExperimentalP1Q12, ExperimentalP1Q16, Default = P1Q3 };
enum class BoundarySubsamplingStrategy { UniformProbability, AreaProportional };

/// Subsampling of surface integrals such as contact: the share of sample points kept, in [0, 1].
struct BoundarySubsamplingParams {
  real subsampling_density = 1;
  BoundarySubsamplingStrategy strategy = BoundarySubsamplingStrategy::UniformProbability;
  bool operator==(const BoundarySubsamplingParams&) const = default;
};

/// The reference length that GridSdfParams::resolution_delta scales into the largest voxel size.
enum class GridSdfResolutionMode { LargestAxis, SmallestAxis, MeanAxis, LargestEdge, SmallestEdge, MeanEdge, Explicit };

/// Resolution of signed-distance grids computed for mesh colliders.
struct GridSdfParams {
  GridSdfResolutionMode resolution_mode = GridSdfResolutionMode::MeanEdge;
  /// Largest voxel size as a multiple of the reference length (per axis; metres when Explicit).
  Real3 resolution_delta = Real3::Constant(real(0.25));
  real boundary_padding_dist = real(0.005);  ///< m, >= 0: grow the mesh's box by this
  Int3 min_grid_resolution = Int3::Constant(6);  ///< voxels per axis, >= 1
  bool operator==(const GridSdfParams&) const = default;
};
/// GridSdfParams::boundary_padding_dist's default (m).
inline constexpr real kGridSdfDefaultBoundaryPadding = real(0.005);

/// A soft actor's frame following the body ("recentering"): after each step whose rigid motion
/// of the nodes exceeds the thresholds, the actor's root transform takes that motion and its
/// displacements keep only the deformation.
struct RecenteringParams {
  bool use_recentering = true;
  real rotation_epsilon_deg = 0;  ///< degrees, >= 0
  real translation_epsilon = 0;   ///< m, >= 0
  bool operator==(const RecenteringParams&) const = default;
};

/// Density of actors given neither mass nor density (kg/m^3).
inline constexpr real kDefaultDensity = 1000;

/// A rigid body: static, or dynamic (6 DOFs).
struct RigidActorParams {
  std::string name;
  std::string layer;              ///< contact layer (Scene::enable_layer_contact_*); "" is a layer too
  ShapeHandle shape;
  TransformRT world_from_local;   ///< X_WL at creation
  ColliderType collider_type = ColliderType::Auto;
  bool is_static = false;
  ContactParams contact;
  GridSdfParams sdf;              ///< for a Sdf collider made from a mesh without one
  bool has_gravity = true;
  std::optional<real> density;    ///< kg/m^3; `mass` takes precedence; neither: kDefaultDensity
  std::optional<real> mass;       ///< kg
  std::optional<Real3> center_of_mass;     ///< m, frame L; default: the shape's centroid
  /// kg m^2 about the centre of mass, frame L's axes: [ixx, ixy, ixz, iyy, iyz, izz] with the
  /// off-diagonal entries negative products of inertia (the tensor's own entries, as URDF).
  std::optional<Real6> moment_of_inertia;
  ActorBoundaryElementType boundary_element_type = ActorBoundaryElementType::Default;
  std::optional<BoundarySubsamplingParams> boundary_subsampling;
  std::optional<Real3> linear_velocity;   ///< m/s, world, of the centre of mass
  std::optional<Real3> angular_velocity;  ///< rad/s, world
  bool operator==(const RigidActorParams&) const = default;
};

/// A soft (tetrahedral finite-element) body.
struct SoftActorParams {
  std::string name;
  std::string layer;
  TransformRT world_from_local;
  ShapeHandle shape;              ///< a tetrahedral mesh
  SoftMaterialParams material;    ///< the shape's per-element material, when it has one, overrides it
  ContactParams contact;
  bool has_gravity = true;
  bool has_inertia = true;        ///< false: quasi-static
  bool has_stress = true;         ///< false: no elastic forces
  ActorBoundaryElementType boundary_element_type = ActorBoundaryElementType::Default;
  bool operator==(const SoftActorParams&) const = default;
};

/// An elastic rod's material, per unit of rest length (SuperDex's names and defaults). For a
/// homogeneous circular rod of radius r: linear_density rho A, linear_rotational_inertia rho J,
/// axial_stiffness E A, torsional_stiffness G J, flexural_stiffness E I (both), with A = pi r^2,
/// I = pi r^4 / 4, J = pi r^4 / 2.
struct RodMaterialParams {
  real linear_density = real(0.1);               ///< kg/m, > 0
  real linear_rotational_inertia = real(1e-6);   ///< about the centreline, kg m, >= 0
  real axial_stiffness = 100;                    ///< N, > 0
  real torsional_stiffness = real(5e-4);         ///< N m^2, >= 0 (> 0 when the rotational inertia is 0)
  /// N m^2, >= 0: bending about the element's frame axis (element_frame_axes), then about the
  /// axis normal to it and to the rod
  Real2 flexural_stiffness{real(5e-4), real(5e-4)};
  real mass_damping_coefficient = 0;             ///< 1/s, >= 0
  real stiffness_damping_coefficient = 0;        ///< s, >= 0
  bool operator==(const RodMaterialParams&) const = default;
};

/// Quadrature of integrals along a rod's segments (PxQy: order x, y points per segment).
enum class ActorSegmentElementType { P1Q1, P1Q2, P1Q3, Default = P1Q3 };

/// What creates a rod actor. `shape`: a model whose mesh is a polyline (2 nodes per element, the
/// elements in order along the rod; the last one may close the loop back to the first node) with
/// element_frame_axes, as made by generate_tubular_rod_model_data or loaded from a model file; its
/// nodes are placed at world_from_local. Rods do not touch other actors yet: contact,
/// contact_element_type and use_contact_skin are kept, a contact skin is refused.
struct RodActorParams {
  std::string name;
  std::string layer;
  TransformRT world_from_local;
  ShapeHandle shape;
  ContactParams contact;
  ActorSegmentElementType contact_element_type = ActorSegmentElementType::Default;
  RodMaterialParams material;
  bool has_gravity = true;
  bool use_contact_skin = false;
  ActorBoundaryElementType contact_skin_element_type = ActorBoundaryElementType::Default;
  bool operator==(const RodActorParams&) const = default;
};

/// How a link moves relative to its parent.
enum class ArticulatedJointType {
  Free,       ///< 6 DOFs (root only): translation, then rotation as a rotation vector
  Prismatic,  ///< 1 DOF: translation along the axis (m)
  Revolute,   ///< 1 DOF: rotation about the axis (rad)
  Spherical,  ///< 3 DOFs: rotation vector (rad)
  Hard,       ///< 0 DOFs: welded
  Cycle,      ///< closes a kinematic loop (ArticulatedCycleJointParams)
  Invalid,    ///< not set
};
const char* articulated_joint_type_name(ArticulatedJointType type);

/// Friction of a joint: viscous + dry (Coulomb, regularised below falloff_vel).
struct ArticulatedJointFrictionParams {
  real viscous = 0;         ///< N s/m or N m s/rad, >= 0
  real coulomb = 0;         ///< N or N m, >= 0
  real falloff_vel = real(1e-3);  ///< m/s or rad/s, > 0
  real stiction_extra = 0;  ///< N or N m, >= 0: extra dry friction at rest, fading with stribeck_vel
  real stribeck_vel = 0;    ///< m/s or rad/s, >= 0
  bool operator==(const ArticulatedJointFrictionParams&) const = default;
};

/// joints[i] connects links[i] to its parent.
struct ArticulatedJointParams {
  std::string name;               ///< unique in the actor; empty: "joint_<i>"
  ArticulatedJointType type = ArticulatedJointType::Invalid;
  TransformRT parent_link_from_joint;  ///< X_PJ
  Real3 axis = Real3::Zero();     ///< joint frame; Prismatic and Revolute; normalised
  ArticulatedJointFrictionParams friction;
  std::optional<real> inertia;    ///< armature (kg or kg m^2) added to each of its DOFs
  std::optional<Real3> min_limit; ///< m or rad; 1-DOF joints: value * axis
  std::optional<Real3> max_limit;
  real limit_stiffness = 100;     ///< N/m or N m/rad
  real limit_damping = 0;         ///< N s/m or N m s/rad
  bool operator==(const ArticulatedJointParams&) const = default;
};

/// One rigid link.
struct ArticulatedLinkParams {
  std::string name;               ///< unique in the actor, no '/'; empty: "link_<i>"
  int parent_link = -1;           ///< index of the parent in `links` (parents first); -1 for the root
  TransformRT parent_joint_from_link;  ///< X_JL; its rotation must be the identity
  ShapeHandle shape;
  std::string layer;
  ColliderType collider_type = ColliderType::Auto;
  ContactParams contact;
  bool has_gravity = true;
  std::optional<real> density;
  std::optional<real> mass;
  std::optional<Real3> center_of_mass;
  std::optional<Real6> moment_of_inertia;  ///< as RigidActorParams::moment_of_inertia
  ActorBoundaryElementType boundary_element_type = ActorBoundaryElementType::Default;
  std::optional<BoundarySubsamplingParams> boundary_subsampling;
  bool operator==(const ArticulatedLinkParams&) const = default;
};

/// A spring joint closing a kinematic loop between two links (N/m).
struct ArticulatedCycleJointParams {
  int parent_link = -1;
  int child_link = -1;
  TransformRT joint_from_child_link;  ///< translation: the pivot in the child link frame
  real stiffness = 50000;
  bool operator==(const ArticulatedCycleJointParams&) const = default;
};

/// A skin: one triangle surface bound to an articulation's links by linear-blend skinning. Its
/// shape is a triangle mesh whose nodes carry skinning data (weights over link indices; the
/// model's mesh.skinning), authored in the root joint's parent frame with every joint at zero.
/// Each node then sits at sum_k w_k X_WL_k X_LR_k p_R, X_LR_k the link's rest pose inverted. The
/// skin is colliding only: its nodes probe the colliders of other actors (it is no collider
/// itself), and a contact pushes on the links by their weights.
struct ArticulatedSkinParams {
  ShapeHandle shape;
  std::string layer;
  ContactParams contact;
  ActorBoundaryElementType boundary_element_type = ActorBoundaryElementType::Default;  ///< kept; this engine probes the nodes
  std::optional<BoundarySubsamplingParams> boundary_subsampling;
  bool operator==(const ArticulatedSkinParams&) const = default;
};

/// An articulation: a tree of links and joints.
struct ArticulatedActorParams {
  std::string name;               ///< its links are named "<name>/<link name>"
  TransformRT world_from_root;    ///< X_W of the root joint's parent frame
  std::vector<ArticulatedCycleJointParams> cycles;
  std::vector<ArticulatedJointParams> joints;  ///< one per link
  std::vector<ArticulatedLinkParams> links;    ///< at least one, parents first
  std::optional<ArticulatedSkinParams> skin;   ///< a surface skinned to the links
  std::optional<std::vector<real>> joint_velocities;  ///< initial, one per DOF (m/s, rad/s)
  bool operator==(const ArticulatedActorParams&) const = default;
};

/// A skeleton (an articulation) carrying soft bodies. Each soft body is authored, like the
/// skeleton, in the root joint's parent frame at the rest pose; its shape's constrained nodes are
/// tied to a link: soft_attach_links[i] for soft_params[i] (one name for all when there is one),
/// or, without names, the link of each node's largest skinning weight. Contact between a soft
/// body and its link is off. The soft bodies simulate in the world with gravity, inertia and
/// elastic stress where either their own params or these flags ask for them.
struct SoftSkinnedActorParams {
  ArticulatedActorParams skeleton_params;
  std::vector<SoftActorParams> soft_params;
  std::vector<std::string> soft_attach_links;
  bool enable_colliding_links = false;  ///< false: the links touch nothing (the soft bodies wrap them)
  bool has_gravity = false;
  bool has_inertia = false;
  bool has_stress = false;
};

/// One joint's slice of the generalized coordinates.
struct ArticulatedDofInfo {
  int offset = -1;
  int trans_size = 0;
  int rot_size = 0;
  int trans_offset() const { return offset; }
  int rot_offset() const { return offset + trans_size; }
  int size() const { return trans_size + rot_size; }
  bool operator==(const ArticulatedDofInfo&) const = default;
};

/// A loop-closing joint of an articulation's structure.
struct ArticulatedCycleJoint {
  int child = 0;
  int parent = 0;
  bool operator==(const ArticulatedCycleJoint&) const = default;
};

/// The structure of an articulation (never changes after creation), per link and per joint
/// (joints[i] moves link i; cycles follow the links).
struct ArticulatedShapeInfo {
  std::vector<TransformRT> root_from_links_at_rest;
  std::vector<std::string> link_names;
  std::vector<int> parents;                      ///< -1 for the root
  std::vector<ArticulatedJointType> joint_types;
  std::vector<ArticulatedCycleJoint> cycles;
  std::vector<Real3> joint_axes;                 ///< joint frame
  std::vector<ArticulatedDofInfo> dof_info;
  std::vector<TransformRT> joint_from_child_link;
  std::vector<TransformRT> parent_link_from_joint;
  std::vector<Real3> joint_min_limits;           ///< -infinity where unlimited
  std::vector<Real3> joint_max_limits;           ///< +infinity where unlimited
  std::vector<std::string> joint_names;
};

/// Throw superdex::Error naming `where`.field for an invalid value.
void validate(const RigidActorParams& params, const std::string& where);
void validate(const SoftActorParams& params, const std::string& where);
void validate(const ArticulatedActorParams& params, const std::string& where);
void validate(const SoftSkinnedActorParams& params, const std::string& where);
void validate(const RodActorParams& params, const std::string& where);
void validate(const GridSdfParams& params, const std::string& where);
void validate(const RecenteringParams& params, const std::string& where);
void validate(const ArticulatedJointFrictionParams& params, const std::string& where);

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

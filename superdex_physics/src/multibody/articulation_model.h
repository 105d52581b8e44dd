#pragma once
// The immutable model of one articulation, built and validated from an ArticulationDesc,
// and the evolving state that capture/restore copies. Derived per-step quantities live
// in ArticulationKinematics, recomputed from the state.

#include <map>
#include <string>
#include <vector>

#include "collision/collision_geometry.h"
#include "core/spatial.h"
#include "superdex/physics/articulation_desc.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

struct JointModel {
  JointType type = JointType::Hard;
  Vec3 axis = Vec3::UnitZ();   // unit axis in the joint frame (revolute, prismatic)
  SpatialTransform X_PJ;       // joint frame in the parent link frame (in the base frame for the root)
  Vec3 p_JL = Vec3::Zero();    // child link origin in the moving joint frame (same axes); Hard joints fold it into X_PJ
  int q_offset = 0, nq = 0;    // position coordinates: 1 (revolute, prismatic), 4 (spherical quat xyzw), 7 (free: p, quat)
  int v_offset = 0, nv = 0;    // velocity coordinates (DOFs)
  Mat6 S = Mat6::Zero();       // motion subspace in the child link frame, first nv columns used
                               // (Free joints: configuration-dependent, see ArticulationKinematics::S)
  bool has_lower = false, has_upper = false;
  real lower = 0, upper = 0;   // position limits along the axis (rad or m)
  real coulomb = 0, viscous = 0, armature = 0;
  real limit_stiffness = 0, limit_damping = 0;  // 0 stiffness: near-rigid limits
  real effort_limit = -1;
};

// A collision shape carried by a link.
struct LinkCollider {
  int link = 0;
  ShapeGeometry shape;
  SpatialTransform X_LS;           // shape frame in the link frame
  ContactMaterial material;
  int layer = 0;
  std::vector<Vec3> samples_S;     // surface samples in the shape frame
  Bounds aabb_S;                     // bounds in the shape frame
};

struct ArticulationModel {
  std::string name;
  int num_links = 0;
  int nq = 0;                          // position coordinates
  int nv = 0;                          // generalized velocities (DOFs)
  int root_nv = 0;                     // DOFs of the root joint (0 Hard, 6 Free)
  std::vector<int> parent;             // parent link index, -1 for the root (num_links)
  // per DOF: the DOF it moves with, -1 for none (the previous DOF of its joint, or the last DOF
  // of the nearest ancestor link's joint that has DOFs) (nv)
  std::vector<int> dof_parent;
  std::vector<int> order;              // links in topological order, parents first (num_links)
  std::vector<JointModel> joints;      // joint i attaches link i (num_links)
  std::vector<SpatialInertia> inertia; // spatial inertia of each link about its origin (num_links)
  std::vector<char> has_gravity;       // per link (num_links)
  // What the dynamics (mass matrix, inverse dynamics) visit: a link welded (Hard joint) to its
  // parent, with only welded links below it and the same gravity flag, moves as part of the
  // parent, so its inertia is added to the parent's and the dynamics skip it.
  std::vector<int> dynamics_order;               // the other links, parents first
  std::vector<SpatialInertia> dynamics_inertia;  // per link: its own plus the welded ones it carries (num_links)
  // per link: the first link of the rigid body it belongs to (itself, unless welded by a Hard
  // joint to its parent, then its parent's) (num_links)
  std::vector<int> rigid_body;
  std::vector<std::string> link_names, joint_names;
  std::vector<LinkCollider> colliders; // collision shapes, in link order
  std::map<std::pair<int, int>, bool> contact_overrides;  // (link a < link b) -> enabled
  // joint couplings (ArticulationDesc::couplings): q[q] = ratio q[leader_q] + offset, on DOFs
  struct Coupling {
    int dof = 0, leader_dof = 0, q = 0, leader_q = 0;
    real ratio = 1, offset = 0;
  };
  std::vector<Coupling> couplings;
  // fixed tendons (ArticulationDesc::fixed_tendons): length sum_k coefficients[k] q[q[k]], its
  // rate the same sum over v[dofs[k]]
  struct Tendon {
    std::vector<int> dofs, q;
    std::vector<real> coefficients;
    bool has_lower = false, has_upper = false;
    real lower = 0, upper = 0, stiffness = 0, damping = 0, rest_length = 0;
    real length(const VecX& positions) const {
      real L = 0;
      for (size_t k = 0; k < q.size(); ++k) L += coefficients[k] * positions[q[k]];
      return L;
    }
    // dL/dv over the articulation's nv DOFs (a joint listed twice adds its coefficients)
    VecX jacobian(int nv) const {
      VecX J = VecX::Zero(nv);
      for (size_t k = 0; k < dofs.size(); ++k) J[dofs[k]] += coefficients[k];
      return J;
    }
  };
  std::vector<Tendon> tendons;
  // transmissions added at run time (Scene::add_linear_transmission, add_spatial_tendon): the
  // same sums, plus for a spatial tendon the lengths of its segments between waypoints on links
  // (their rest length taken off, rest_length); no range or spring of their own; their
  // actuators are state (ArticulationState)
  struct Waypoint {
    int link = 0;
    Vec3 p_L = Vec3::Zero();  // in the link frame (m)
    bool to_next = false;     // a segment joins it to the next waypoint
  };
  struct Transmission : Tendon {
    std::vector<Waypoint> waypoints;
  };
  std::vector<Transmission> transmissions;
  ArticulationDesc desc;               // the validated description it was built from
};

// The actuator of a transmission (Scene::attach_*_actuator): its kind, its one state variable
// (the target displacement or the force) and its constants.
struct TransmissionActuator {
  enum class Kind { None, DisplacementControl, ForceControl, McKibben };
  Kind kind = Kind::None;
  real value = 0;                   // the state variable: target, force, pressure
  real stiffness = 0, damping = 0;  // DisplacementControl; McKibben: the deflated stiffness
  bool allow_compressive_force = false;
  // McKibben (McKibbenActuatorParams)
  real minimum_pressure = 0, thread_length = 0, wraps = 0, deflated_length = 0;
};

// Evolving state: what capture_state copies.
struct ArticulationState {
  std::vector<JointDrive> drives;      // per DOF (nv); inactive when stiffness and damping are 0
  std::vector<TransmissionActuator> transmission_actuators;  // per ArticulationModel::transmissions
  std::vector<LinkDrive> link_drives;  // per link; inactive when all gains are 0
  VecX q;                          // generalized positions (nq)
  VecX v;                          // generalized velocities (nv)
  VecX tau_external;               // user generalized forces held until replaced (nv)
  SpatialTransform X_W_base;       // pose of the root joint's parent frame in the world
};

// Quantities derived from the state by forward kinematics.
struct ArticulationKinematics {
  std::vector<SpatialTransform> X_PL;  // parent-from-link (world-from-base composed for the root)
  std::vector<SpatialTransform> X_WL;  // world-from-link
  std::vector<Vec6> V_L;               // link spatial velocity in its own frame
  std::vector<Mat6> S;                 // each joint's motion subspace in its child link frame at q
};

// Validates `desc` and builds the model; errors name `source` and the field path.
ArticulationModel build_articulation_model(const ArticulationDesc& desc, const std::string& source);

// Whether any joint between the world and this link has DOFs (a link welded to the world, like a
// fixed robot's base, cannot take part in a contact with another immovable one).
bool link_moves(const ArticulationModel& model, int link);

// Default contact between two links of one articulation. Links of one rigid body never touch.
// Links of two rigid bodies joined by a joint (one body's first link hangs on a link of the
// other: MuJoCo's parent-child filter, links welded to either counted in) are off unless an
// override enables them; the others are on unless an override disables them.
enum class LinkPairContact { Never, OffByDefault, OnByDefault };
LinkPairContact link_pair_contact(const ArticulationModel& model, int link_a, int link_b);

// Zero-pose state for `model` with the description's default pose and world_from_root applied.
ArticulationState initial_state(const ArticulationModel& model);

// Converts a DOF-sized pose (rotation vectors for spherical and free joints) to positions q.
// `pose` covers all DOFs when full, or all but the root joint's when `skip_root`.
void q_from_pose(const ArticulationModel& model, const real* pose, bool skip_root, VecX& q);
// Inverse of q_from_pose over all DOFs.
void pose_from_q(const ArticulationModel& model, const VecX& q, real* pose);

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

// Constraint rows and deviations (constraint_terms.h).

#include "constraint/constraint_terms.h"

#include <cmath>
#include <limits>
#include <numbers>

#include "core/spatial.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

std::vector<int> constraint_dof_indices(const ConstraintRecord& c, int index) {
  const auto node = [](int n) { return std::vector<int>{3 * n, 3 * n + 1, 3 * n + 2}; };
  switch (c.type) {
    case ConstraintType::DeformableNodePosition:
      return node(c.node_a);
    case ConstraintType::DeformableNodeToRigid:
      return index == 0 ? std::vector<int>{0, 1, 2, 3, 4, 5} : node(c.node_b);
    case ConstraintType::DeformableNodeToDeformableNode:
      return node(index == 0 ? c.node_a : c.node_b);
    case ConstraintType::RigidPivotRotation:
    case ConstraintType::JointRotationRange:
    case ConstraintType::JointRotationTracking:
    case ConstraintType::RodElementRotationToRigid:
      return {3, 4, 5};
    case ConstraintType::RigidPrismaticJoint:
      // B's origin is held on a line fixed in A: B's rotation is free
      return index == 0 ? std::vector<int>{0, 1, 2, 3, 4, 5} : std::vector<int>{0, 1, 2};
    case ConstraintType::ArticulatedSingleDofTarget:
    case ConstraintType::ArticulatedSingleDofRange:
      return {c.dof};
    case ConstraintType::Articulated3dRotationTarget:
      return {c.dof, c.dof + 1, c.dof + 2};
    default:
      return {0, 1, 2, 3, 4, 5};
  }
}

void settle_constraint_targets(ConstraintRecord& c) {
  c.old_target_position = c.target_position;
  c.old_target_rotation = c.target_rotation;
  c.old_target_transform = c.target_transform;
  c.old_target_value = c.target_value;
}

namespace {

// The row of a direction d (world) at the point p_W of a side: the point's velocity along d is
// d . v + (p - o) x d . w.
Vec6 point_row(const Vec3& d, const Vec3& p_W, const Transform& X_WL) {
  Vec6 g;
  g << d, (p_W - X_WL.translation).cross(d);
  return g;
}

// The row of a direction d (world) on a node's velocity.
Vec6 node_row(const Vec3& d) {
  Vec6 g;
  g << d, Vec3::Zero();
  return g;
}

// The row of DOF i of a joint side (its coefficient on velocity dof + i).
Vec6 dof_row(int i) {
  return Vec6::Unit(i);
}

// A 3-D joint's rotation error: the rotation taking it to the target, in its child link frame
// (where its velocity lives).
Vec3 joint_rotation_error(const ConstraintRecord& c, const ConstraintSide& a) {
  return quat_log(a.R_joint.conjugate() * c.target_rotation);
}

Vec6 angular_row(const Vec3& d) {
  Vec6 g;
  g << Vec3::Zero(), d;
  return g;
}

// Two unit vectors that complete `axis` (unit) to an orthonormal frame.
void perpendiculars(const Vec3& axis, Vec3& u1, Vec3& u2) {
  u1 = (std::abs(axis.x()) < real(0.9) ? Vec3::UnitX() : Vec3::UnitY()).cross(axis).normalized();
  u2 = axis.cross(u1);
}

// Appends the rows of one step's spring-damper: equalities (error e, target minus current, which
// the row's rate reduces; u the target's rate along the row) and limits (C >= 0, the row's rate
// being dC/dt).
struct RowWriter {
  ConstraintTerms& t;
  real K, D, dt, per_velocity, R, bound;

  RowWriter(const ConstraintRecord& c, real step_dt, ConstraintTerms& terms)
      : t(terms), K(c.stiffness), D(c.damping), dt(step_dt) {
    // force = K e(q+) + D (u - rate+) with e(q+) = e - dt rate+ (e measured to the target of the
    // step's end): the impulse dt force is (vhat - rate+) / R with R = 1 / (dt (dt K + D)),
    // vhat = (K e + D u) / (dt K + D)
    per_velocity = dt * K + D;
    R = 1 / (dt * per_velocity);
    bound = c.saturation > 0 ? dt * c.saturation : std::numeric_limits<real>::infinity();
  }
  void equality(const Vec6& g_a, const Vec6& g_b, real e, real u) {
    ConstraintRow row{g_a, g_b, {}};
    row.block.kind = BlockKind::Bounded;
    row.block.R = R;
    row.block.vhat = (K * e + D * u) / per_velocity;
    row.block.bound = bound;
    t.rows.push_back(row);
  }
  void limit(const Vec6& g_a, const Vec6& g_b, real C) {
    ConstraintRow row{g_a, g_b, {}};
    row.block.kind = BlockKind::Unilateral;
    row.block.R = R;
    row.block.vhat = -K * C / per_velocity;
    t.rows.push_back(row);
  }
};

// The relative rotation of the joint frames (constraint_record.h), as a rotation vector in A's
// joint axes, and those axes (world).
Vec3 joint_rotation(const ConstraintRecord& c, const Transform& X_WA, const Transform& X_WB, Mat3& F_A) {
  const Quat F_a = X_WA.rotation * c.J_A, F_b = X_WB.rotation * c.J_B;
  F_A = F_a.toRotationMatrix();
  return quat_log(F_a.conjugate() * F_b);
}

// Prismatic: B's origin relative to its creation offset, frame A.
Vec3 prismatic_offset(const ConstraintRecord& c, const Transform& X_WA, const Transform& X_WB) {
  return X_WA.rotation.conjugate() * (X_WB.translation - X_WA.translation) - c.offset_A;
}

}  // namespace

void constraint_terms(const ConstraintRecord& c, real dt, ConstraintTerms& t) {
  t.rows.clear();
  if (c.stiffness <= 0 && c.damping <= 0) return;
  RowWriter w(c, dt, t);
  const Transform& X_WA = t.a.X_WL;
  const Transform& X_WB = t.b.X_WL;
  const Vec6 none = Vec6::Zero();
  switch (c.type) {
    case ConstraintType::RigidPivotPosition:
    case ConstraintType::RigidPivotToRigidTarget: {
      const bool transform = c.type == ConstraintType::RigidPivotToRigidTarget;
      const Vec3 target = transform ? Vec3(c.target_transform * c.p_A) : c.target_position;
      const Vec3 old = transform ? Vec3(c.old_target_transform * c.p_A) : c.old_target_position;
      const Vec3 p = X_WA * c.p_A;
      for (int i = 0; i < 3; ++i)
        w.equality(point_row(Vec3::Unit(i), p, X_WA), none, target[i] - p[i], (target[i] - old[i]) / dt);
      break;
    }
    case ConstraintType::RigidPivotRotation: {
      const Vec3 error = quat_log(c.target_rotation * (X_WA.rotation * c.local_rotation).conjugate());
      const Vec3 rate = quat_log(c.target_rotation * c.old_target_rotation.conjugate()) / dt;
      for (int i = 0; i < 3; ++i) w.equality(angular_row(Vec3::Unit(i)), none, error[i], rate[i]);
      break;
    }
    case ConstraintType::RigidSphericalJoint: {
      const Vec3 p_a = X_WA * c.p_A, p_b = X_WB * c.p_B;
      for (int i = 0; i < 3; ++i) {
        const Vec3 d = Vec3::Unit(i);
        w.equality(point_row(d, p_a, X_WA), -point_row(d, p_b, X_WB), p_b[i] - p_a[i], 0);
      }
      break;
    }
    case ConstraintType::RigidPrismaticJoint: {
      // B's origin on the line through A's origin plus the creation offset along the axis (both
      // fixed in A); rates at B's origin, moving with B and with A
      const Vec3 offset = prismatic_offset(c, X_WA, X_WB);
      const auto row_a = [&](const Vec3& d) { return Vec6(-point_row(d, X_WB.translation, X_WA)); };
      const auto row_b = [&](const Vec3& d) { return point_row(d, X_WB.translation, X_WB); };
      Vec3 u1, u2;
      perpendiculars(c.axis_A, u1, u2);
      for (const Vec3& u : {u1, u2}) {
        const Vec3 d = X_WA.rotation * u;
        w.equality(row_a(d), row_b(d), -u.dot(offset), 0);
      }
      const Vec3 d = X_WA.rotation * c.axis_A;
      const real s = c.axis_A.dot(offset);
      if (c.min) w.limit(row_a(d), row_b(d), s - *c.min);
      if (c.max) w.limit(-row_a(d), -row_b(d), *c.max - s);
      break;
    }
    case ConstraintType::JointRotationTracking:
    case ConstraintType::RodElementRotationToRigid: {
      // the rotation that takes B to R_A T (world), and the target's own turning (in A)
      const Vec3 error = quat_log(X_WA.rotation * c.target_rotation * X_WB.rotation.conjugate());
      const Vec3 rate = X_WA.rotation * quat_log(c.target_rotation * c.old_target_rotation.conjugate()) / dt;
      for (int i = 0; i < 3; ++i) {
        const Vec3 d = Vec3::Unit(i);
        w.equality(-angular_row(d), angular_row(d), error[i], rate[i]);
      }
      break;
    }
    case ConstraintType::DeformableNodePosition: {
      const Vec3& x = t.a.node_W;
      for (int i = 0; i < 3; ++i)
        w.equality(node_row(Vec3::Unit(i)), none, c.target_position[i] - x[i], (c.target_position[i] - c.old_target_position[i]) / dt);
      break;
    }
    case ConstraintType::DeformableNodeToRigid: {
      // the node (B) onto the rigid actor's point (A)
      const Vec3 p = X_WA * c.p_A;
      const Vec3& x = t.b.node_W;
      for (int i = 0; i < 3; ++i) {
        const Vec3 d = Vec3::Unit(i);
        w.equality(-point_row(d, p, X_WA), node_row(d), p[i] - x[i], 0);
      }
      break;
    }
    case ConstraintType::DeformableNodeToDeformableNode: {
      // B's node onto A's
      const Vec3 gap = t.a.node_W - t.b.node_W;
      for (int i = 0; i < 3; ++i) {
        const Vec3 d = Vec3::Unit(i);
        w.equality(-node_row(d), node_row(d), gap[i], 0);
      }
      break;
    }
    case ConstraintType::ArticulatedSingleDofTarget:
      w.equality(dof_row(0), none, c.target_value - t.a.q_dof, (c.target_value - c.old_target_value) / dt);
      break;
    case ConstraintType::Articulated3dRotationTarget: {
      // the target's own turning, in its frame (first order, as the error's rate)
      const Vec3 error = joint_rotation_error(c, t.a);
      const Vec3 rate = quat_log(c.old_target_rotation.conjugate() * c.target_rotation) / dt;
      for (int i = 0; i < 3; ++i) w.equality(dof_row(i), none, error[i], rate[i]);
      break;
    }
    case ConstraintType::ArticulatedSingleDofRange:
      // the articulation's own joint-limit rows act (articulation_step.cpp)
      break;
    case ConstraintType::JointRotationRange: {
      Mat3 F_A;
      const Vec3 phi = joint_rotation(c, X_WA, X_WB, F_A);
      constexpr real pi = std::numbers::pi_v<real>;
      for (int i = 0; i < 3; ++i) {
        // the rotation vector's component i changes at about (w_B - w_A) . (F_A e_i)
        const Vec3 d = F_A.col(i);
        if (c.lower[i] > -pi) w.limit(-angular_row(d), angular_row(d), phi[i] - c.lower[i]);
        if (c.upper[i] < pi) w.limit(angular_row(d), -angular_row(d), c.upper[i] - phi[i]);
      }
      break;
    }
  }
}

std::vector<real> constraint_deviation(const ConstraintRecord& c, const ConstraintSide& a, const ConstraintSide& b) {
  const Transform& X_WA = a.X_WL;
  const Transform& X_WB = b.X_WL;
  auto out = [](const Vec3& v) { return std::vector<real>{v.x(), v.y(), v.z()}; };
  switch (c.type) {
    case ConstraintType::RigidPivotPosition:
      return out(c.target_position - X_WA * c.p_A);
    case ConstraintType::RigidPivotToRigidTarget:
      return out(c.target_transform * c.p_A - X_WA * c.p_A);
    case ConstraintType::RigidPivotRotation:
      return out(quat_log(c.target_rotation * (X_WA.rotation * c.local_rotation).conjugate()));
    case ConstraintType::RigidSphericalJoint:
      return out(X_WB * c.p_B - X_WA * c.p_A);
    case ConstraintType::RigidPrismaticJoint: {
      // off the line (along two axes perpendicular to it, frame A), then beyond the bounds
      const Vec3 offset = prismatic_offset(c, X_WA, X_WB);
      Vec3 u1, u2;
      perpendiculars(c.axis_A, u1, u2);
      const real s = c.axis_A.dot(offset);
      const real beyond = c.min && s < *c.min ? *c.min - s : c.max && s > *c.max ? *c.max - s : 0;
      return {-u1.dot(offset), -u2.dot(offset), beyond};
    }
    case ConstraintType::RodElementRotationToRigid:
    case ConstraintType::JointRotationTracking: {
      const Quat F_a = X_WA.rotation * c.J_A;
      return out(F_a.conjugate() * quat_log(X_WA.rotation * c.target_rotation * X_WB.rotation.conjugate()));
    }
    case ConstraintType::JointRotationRange: {
      Mat3 F_A;
      const Vec3 phi = joint_rotation(c, X_WA, X_WB, F_A);
      Vec3 beyond = Vec3::Zero();
      for (int i = 0; i < 3; ++i) beyond[i] = phi[i] < c.lower[i] ? c.lower[i] - phi[i] : phi[i] > c.upper[i] ? c.upper[i] - phi[i] : 0;
      return out(beyond);
    }
    case ConstraintType::DeformableNodePosition:
      return out(c.target_position - a.node_W);
    case ConstraintType::DeformableNodeToRigid:
      return out(X_WA * c.p_A - b.node_W);
    case ConstraintType::DeformableNodeToDeformableNode:
      return out(a.node_W - b.node_W);
    case ConstraintType::ArticulatedSingleDofTarget:
      return {c.target_value - a.q_dof};
    case ConstraintType::Articulated3dRotationTarget:
      return out(joint_rotation_error(c, a));
    case ConstraintType::ArticulatedSingleDofRange:
      return {c.min && a.q_dof < *c.min ? *c.min - a.q_dof : c.max && a.q_dof > *c.max ? *c.max - a.q_dof : real(0)};
  }
  return {};
}

void constraint_anchor_points(const ConstraintRecord& c, const ConstraintSide& a, const ConstraintSide& b, Vec3& p_a, Vec3& p_b) {
  const Transform& X_WA = a.X_WL;
  const Transform& X_WB = b.X_WL;
  switch (c.type) {
    case ConstraintType::RigidPivotPosition:
      p_a = X_WA * c.p_A, p_b = c.target_position;
      return;
    case ConstraintType::RigidPivotToRigidTarget:
      p_a = X_WA * c.p_A, p_b = c.target_transform * c.p_A;
      return;
    case ConstraintType::RigidSphericalJoint:
      p_a = X_WA * c.p_A, p_b = X_WB * c.p_B;
      return;
    case ConstraintType::DeformableNodePosition:
      p_a = a.node_W, p_b = c.target_position;
      return;
    case ConstraintType::DeformableNodeToRigid:
      p_a = X_WA * c.p_A, p_b = b.node_W;
      return;
    case ConstraintType::DeformableNodeToDeformableNode:
      p_a = a.node_W, p_b = b.node_W;
      return;
    case ConstraintType::RigidPivotRotation:
    case ConstraintType::ArticulatedSingleDofTarget:
    case ConstraintType::Articulated3dRotationTarget:
    case ConstraintType::ArticulatedSingleDofRange:
      p_a = p_b = X_WA.translation;
      return;
    default:
      p_a = X_WA.translation, p_b = X_WB.translation;
  }
}

void side_generalized_force(const ConstraintSide& side, const Vec6& F_origin, const std::vector<int>& dofs, std::vector<real>& out) {
  const Vec3 f = F_origin.head<3>();
  // a rod's element: the torque on it (world)
  if (side.soft >= 0 && side.element >= 0) {
    for (int k : dofs) out.push_back(F_origin[k]);
    return;
  }
  // a node: the force on it, by the node's DOFs (3 n + 0-2)
  if (side.soft >= 0) {
    for (int k : dofs) out.push_back(f[k % 3]);
    return;
  }
  // joint DOFs: the generalized forces on them
  if (side.dof >= 0) {
    for (int k : dofs) out.push_back(F_origin[k - side.dof]);
    return;
  }
  // torque about the centre of mass: tau_o + (o - c) x f
  const Vec3 tau = F_origin.tail<3>() + (side.X_WL.translation - side.com_W).cross(f);
  for (int k : dofs) out.push_back(k < 3 ? f[k] : tau[k - 3]);
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

// Forward kinematics, world-frame link Jacobians and integration of joint positions.

#include "multibody/kinematics.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace {
Quat quat_at(const real* q) { return Quat(q[3], q[0], q[1], q[2]); }  // stored x, y, z, w
}  // namespace

SpatialTransform joint_transform(const JointModel& j, const real* q) {
  switch (j.type) {
    case JointType::Hard:
    default: return {};
    case JointType::Revolute: return {Eigen::AngleAxis<real>(q[0], j.axis).toRotationMatrix(), Vec3::Zero()};
    case JointType::Prismatic: return {Mat3::Identity(), j.axis * q[0]};
    case JointType::Spherical: return {quat_at(q).normalized().toRotationMatrix(), Vec3::Zero()};
    case JointType::Free: return {quat_at(q + 3).normalized().toRotationMatrix(), Vec3(q[0], q[1], q[2])};
  }
  return {};
}

void update_kinematics(const ArticulationModel& model, const ArticulationState& state, ArticulationKinematics& kin) {
  update_kinematics(model, state.q, state.v, state.X_W_base, kin);
}

void update_kinematics(const ArticulationModel& model, const VecX& q, const VecX& v, const SpatialTransform& X_W_base,
                       ArticulationKinematics& kin) {
  const int n = model.num_links;
  kin.X_PL.resize(n);
  kin.X_WL.resize(n);
  kin.V_L.resize(n);
  kin.S.resize(n);
  for (int i : model.order) {
    const JointModel& j = model.joints[i];
    const int p = model.parent[i];
    const SpatialTransform X_J = joint_transform(j, q.data() + j.q_offset);
    kin.X_PL[i] = j.X_PJ * X_J * SpatialTransform{Mat3::Identity(), j.p_JL};
    kin.S[i] = j.S;
    // a Free joint's linear velocity is in the joint (parent) frame: rotate it into the link frame
    if (j.type == JointType::Free) kin.S[i].topLeftCorner<3, 3>() = X_J.R.transpose();
    // joint velocity, column by column (a fixed-size loop: nv is at most 6)
    Vec6 vJ = Vec6::Zero();
    for (int c = 0; c < j.nv; ++c) vJ += kin.S[i].col(c) * v[j.v_offset + c];
    if (p < 0) {
      kin.X_PL[i] = X_W_base * kin.X_PL[i];
      kin.X_WL[i] = kin.X_PL[i];
      kin.V_L[i] = vJ;
    } else {
      kin.X_WL[i] = kin.X_WL[p] * kin.X_PL[i];
      kin.V_L[i] = kin.X_PL[i].apply_motion_inverse(kin.V_L[p]) + vJ;
    }
  }
}

void link_jacobian_world(const ArticulationModel& model, const ArticulationKinematics& kin, int link, MatXR& J_WL) {
  J_WL.setZero(6, model.nv);
  const Vec3& p_WL = kin.X_WL[link].p;
  // walk from the link to the root; each joint's columns are its motion subspace in world
  // axes, shifted from the joint's child-link origin to this link's origin
  for (int k = link; k >= 0; k = model.parent[k]) {
    const JointModel& j = model.joints[k];
    const Mat3& R_WK = kin.X_WL[k].R;
    const Vec3 r = p_WL - kin.X_WL[k].p;
    for (int c = 0; c < j.nv; ++c) {
      const Vec3 w = R_WK * kin.S[k].col(c).tail<3>();
      const Vec3 v = R_WK * kin.S[k].col(c).head<3>() + w.cross(r);
      J_WL.block<3, 1>(0, j.v_offset + c) = v;
      J_WL.block<3, 1>(3, j.v_offset + c) = w;
    }
  }
}

void integrate_positions(const ArticulationModel& model, VecX& q, const VecX& v, real dt) {
  for (const JointModel& j : model.joints) {
    real* qj = q.data() + j.q_offset;
    const real* vj = v.data() + j.v_offset;
    switch (j.type) {
      case JointType::Hard:
      default: break;
      case JointType::Revolute:
      case JointType::Prismatic: qj[0] += dt * vj[0]; break;
      case JointType::Spherical: {
        const Quat next = (quat_at(qj) * quat_exp(dt * Vec3(vj[0], vj[1], vj[2]))).normalized();
        map4(qj) = next.coeffs();
        break;
      }
      case JointType::Free: {
        // linear velocity is in the parent frame, angular velocity in the body frame
        const Quat rot = quat_at(qj + 3).normalized();
        map3(qj) += dt * Vec3(vj[0], vj[1], vj[2]);
        const Quat next = (rot * quat_exp(dt * Vec3(vj[3], vj[4], vj[5]))).normalized();
        map4(qj + 3) = next.coeffs();
        break;
      }
    }
  }
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

// Recursive Newton-Euler inverse dynamics and the composite rigid body mass matrix.

#include "dynamics.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

VecX inverse_dynamics(const ArticulationModel& model, const ArticulationState& state,
                      const ArticulationKinematics& kin, const VecX& a, const Vec3& g_W) {
  const int n = model.num_links;
  std::vector<Vec6> A(n), F(n);
  // forward pass: link accelerations
  for (int i : model.order) {
    const JointModel& j = model.joints[i];
    const int p = model.parent[i];
    const auto S = kin.S[i].leftCols(j.nv);
    const Vec6 vJ = S * state.v.segment(j.v_offset, j.nv);
    Vec6 A_i = S * a.segment(j.v_offset, j.nv) + cross_motion(kin.V_L[i], vJ);
    // a Free joint's S changes with its rotation: Sdot qdot = (-w x (R^T v), 0)
    if (j.type == JointType::Free) A_i.head<3>() -= vJ.tail<3>().cross(vJ.head<3>());
    if (p >= 0) A_i += kin.X_PL[i].apply_motion_inverse(A[p]);
    A[i] = A_i;
    const SpatialInertia& I = model.inertia[i];
    Vec6 A_net = A_i;
    if (model.has_gravity[i]) A_net.head<3>() -= kin.X_WL[i].R.transpose() * g_W;
    F[i] = I.apply(A_net) + cross_force(kin.V_L[i], I.apply(kin.V_L[i]));
  }
  // backward pass: project onto joint axes and accumulate into parents
  VecX tau(model.nv);
  for (auto it = model.order.rbegin(); it != model.order.rend(); ++it) {
    const int i = *it;
    const JointModel& j = model.joints[i];
    // armature (rotor inertia) acts on the joint acceleration directly, as in mass_matrix()
    tau.segment(j.v_offset, j.nv) = kin.S[i].leftCols(j.nv).transpose() * F[i] + j.armature * a.segment(j.v_offset, j.nv);
    const int p = model.parent[i];
    if (p >= 0) F[p] += kin.X_PL[i].apply_force(F[i]);
  }
  return tau;
}

VecX bias_forces(const ArticulationModel& model, const ArticulationState& state, const ArticulationKinematics& kin,
                 const Vec3& g_W) {
  return inverse_dynamics(model, state, kin, VecX::Zero(model.nv), g_W);
}

MatX mass_matrix(const ArticulationModel& model, const ArticulationKinematics& kin) {
  const int n = model.num_links;
  std::vector<Mat6> Ic(n);
  for (int i = 0; i < n; ++i) Ic[i] = model.inertia[i].matrix();
  // composite inertias, leaves first, each expressed in its own link frame
  for (auto it = model.order.rbegin(); it != model.order.rend(); ++it) {
    const int i = *it, p = model.parent[i];
    if (p >= 0) Ic[p] += kin.X_PL[i].force_matrix() * Ic[i] * kin.X_PL[i].inverse().motion_matrix();
  }
  MatX M = MatX::Zero(model.nv, model.nv);
  for (int i = 0; i < n; ++i) {
    const JointModel& ji = model.joints[i];
    if (ji.nv == 0) continue;
    Eigen::Matrix<real, 6, Eigen::Dynamic, 0, 6, 6> F = Ic[i] * kin.S[i].leftCols(ji.nv);
    M.block(ji.v_offset, ji.v_offset, ji.nv, ji.nv) = kin.S[i].leftCols(ji.nv).transpose() * F;
    // off-diagonal blocks with every ancestor joint
    for (int k = i; model.parent[k] >= 0;) {
      F = kin.X_PL[k].force_matrix() * F;
      k = model.parent[k];
      const JointModel& jk = model.joints[k];
      if (jk.nv == 0) continue;
      auto block = (kin.S[k].leftCols(jk.nv).transpose() * F).eval();
      M.block(jk.v_offset, ji.v_offset, jk.nv, ji.nv) = block;
      M.block(ji.v_offset, jk.v_offset, ji.nv, jk.nv) = block.transpose();
    }
    for (int c = 0; c < ji.nv; ++c) M(ji.v_offset + c, ji.v_offset + c) += ji.armature;
  }
  return M;
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

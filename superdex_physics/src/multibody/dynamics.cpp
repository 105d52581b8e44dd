// Recursive Newton-Euler inverse dynamics and the composite rigid body mass matrix.

#include "multibody/dynamics.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace {

// Recursive Newton-Euler into tau (resized); a null `a` is zero acceleration. The link
// accelerations and forces are kept per thread, so that repeated calls do not allocate.
void rnea(const ArticulationModel& model, const ArticulationState& state, const ArticulationKinematics& kin, const VecX* a,
          const Vec3& g_W, VecX& tau) {
  const int n = model.num_links;
  thread_local std::vector<Vec6> A, F;
  A.resize(n);
  F.resize(n);
  auto accel = [&](int k) { return a ? (*a)[k] : real(0); };
  // forward pass: link accelerations (welded links move with their parents: dynamics_order)
  for (int i : model.dynamics_order) {
    const JointModel& j = model.joints[i];
    const int p = model.parent[i];
    // joint velocity and acceleration, column by column (nv is at most 6); no acceleration for
    // the bias forces
    Vec6 vJ = Vec6::Zero(), aJ = Vec6::Zero();
    for (int c = 0; c < j.nv; ++c) vJ += kin.S[i].col(c) * state.v[j.v_offset + c];
    if (a)
      for (int c = 0; c < j.nv; ++c) aJ += kin.S[i].col(c) * (*a)[j.v_offset + c];
    Vec6 A_i = aJ + cross_motion(kin.V_L[i], vJ);
    // a Free joint's S changes with its rotation: Sdot qdot = (-w x (R^T v), 0)
    if (j.type == JointType::Free) A_i.head<3>() -= vJ.tail<3>().cross(vJ.head<3>());
    if (p >= 0) A_i += kin.X_PL[i].apply_motion_inverse(A[p]);
    A[i] = A_i;
    const SpatialInertia& I = model.dynamics_inertia[i];
    Vec6 A_net = A_i;
    if (model.has_gravity[i]) A_net.head<3>() -= kin.X_WL[i].R.transpose() * g_W;
    F[i] = I.apply(A_net) + cross_force(kin.V_L[i], I.apply(kin.V_L[i]));
  }
  // backward pass: project onto joint axes and accumulate into parents
  tau.resize(model.nv);
  for (auto it = model.dynamics_order.rbegin(); it != model.dynamics_order.rend(); ++it) {
    const int i = *it;
    const JointModel& j = model.joints[i];
    // armature (rotor inertia) acts on the joint acceleration directly, as in mass_matrix()
    for (int c = 0; c < j.nv; ++c) tau[j.v_offset + c] = kin.S[i].col(c).dot(F[i]) + j.armature * accel(j.v_offset + c);
    const int p = model.parent[i];
    if (p >= 0) F[p] += kin.X_PL[i].apply_force(F[i]);
  }
}

}  // namespace

VecX inverse_dynamics(const ArticulationModel& model, const ArticulationState& state,
                      const ArticulationKinematics& kin, const VecX& a, const Vec3& g_W) {
  VecX tau;
  rnea(model, state, kin, &a, g_W, tau);
  return tau;
}

VecX bias_forces(const ArticulationModel& model, const ArticulationState& state, const ArticulationKinematics& kin,
                 const Vec3& g_W) {
  VecX c;
  bias_forces(model, state, kin, g_W, c);
  return c;
}

void bias_forces(const ArticulationModel& model, const ArticulationState& state, const ArticulationKinematics& kin,
                 const Vec3& g_W, VecX& c) {
  rnea(model, state, kin, nullptr, g_W, c);
}

namespace {

// A body's spatial inertia about its frame's origin: mass m, first moment h = m c and rotational
// inertia I_o about the origin. Inertias of bodies in one frame add up in this form.
struct OriginInertia {
  real m = 0;
  Vec3 h = Vec3::Zero();
  Mat3 I = Mat3::Zero();

  static OriginInertia of(const SpatialInertia& b) {
    const Vec3 c = b.com;
    return {b.mass, b.mass * c, b.inertia_com + b.mass * (c.squaredNorm() * Mat3::Identity() - c * c.transpose())};
  }
  // The same inertia expressed in frame A, given X_AB (this one in B).
  OriginInertia in_parent(const SpatialTransform& X_AB) const {
    const Vec3& p = X_AB.p;
    const Vec3 h_A = X_AB.R * h;
    // -[p + y]x^2 summed over the body: R I_o R^T + m (|p|^2 - p p^T) - ([p]x [h_A]x + [h_A]x [p]x)
    const Mat3 cross_terms = p.dot(h_A) * Mat3::Identity() * 2 - p * h_A.transpose() - h_A * p.transpose();
    return {m, h_A + m * p,
            X_AB.R * I * X_AB.R.transpose() + m * (p.squaredNorm() * Mat3::Identity() - p * p.transpose()) + cross_terms};
  }
  OriginInertia& operator+=(const OriginInertia& o) {
    m += o.m, h += o.h, I += o.I;
    return *this;
  }
  // Momentum of motion V = (v, w): (m v - h x w, h x v + I w).
  Vec6 apply(const Vec6& V) const {
    const auto v = V.head<3>(), w = V.tail<3>();
    Vec6 F;
    F.head<3>() = m * v - h.cross(w);
    F.tail<3>() = h.cross(v) + I * w;
    return F;
  }
};

}  // namespace

MatX mass_matrix(const ArticulationModel& model, const ArticulationKinematics& kin) {
  MatX M;
  mass_matrix(model, kin, M);
  return M;
}

void mass_matrix(const ArticulationModel& model, const ArticulationKinematics& kin, MatX& M) {
  const int n = model.num_links;
  // a single free body (its welded links merged): M = S^T Ic S in closed form, with S =
  // diag(R^T, 1) (linear velocity in the parent frame, angular velocity in the body's):
  // [m 1, -R [h]x; [h]x R^T, I_o]
  if (model.dynamics_order.size() == 1 && model.joints[model.dynamics_order[0]].type == JointType::Free) {
    const int i = model.dynamics_order[0];
    const OriginInertia I = OriginInertia::of(model.dynamics_inertia[i]);
    const Mat3 R = kin.S[i].topLeftCorner<3, 3>().transpose();
    const Mat3 M_la = -R * skew(I.h);
    M.resize(6, 6);
    M.topLeftCorner<3, 3>() = I.m * Mat3::Identity();
    M.topRightCorner<3, 3>() = M_la;
    M.bottomLeftCorner<3, 3>() = M_la.transpose();
    M.bottomRightCorner<3, 3>() = I.I;
    M.diagonal().array() += model.joints[i].armature;
    return;
  }
  // composite inertias, leaves first, each expressed in its own link frame (kept per thread)
  thread_local std::vector<OriginInertia> Ic;
  Ic.resize(n);
  for (int i : model.dynamics_order) Ic[i] = OriginInertia::of(model.dynamics_inertia[i]);
  for (auto it = model.dynamics_order.rbegin(); it != model.dynamics_order.rend(); ++it) {
    const int i = *it, p = model.parent[i];
    if (p >= 0) Ic[p] += Ic[i].in_parent(kin.X_PL[i]);
  }
  // column by column: the force that a unit motion of DOF (i, c) needs, carried up the tree and
  // projected onto each ancestor joint's motion subspace
  M.setZero(model.nv, model.nv);
  for (int i : model.dynamics_order) {
    const JointModel& ji = model.joints[i];
    for (int c = 0; c < ji.nv; ++c) {
      const int col = ji.v_offset + c;
      Vec6 F = Ic[i].apply(kin.S[i].col(c));
      for (int r = 0; r < ji.nv; ++r) M(ji.v_offset + r, col) = kin.S[i].col(r).dot(F);
      for (int k = i; model.parent[k] >= 0;) {
        F = kin.X_PL[k].apply_force(F);
        k = model.parent[k];
        const JointModel& jk = model.joints[k];
        for (int r = 0; r < jk.nv; ++r) M(col, jk.v_offset + r) = M(jk.v_offset + r, col) = kin.S[k].col(r).dot(F);
      }
      M(col, col) += ji.armature;
    }
  }
}

void merge_welded_links(ArticulationModel& model) {
  const int n = model.num_links;
  // a link merges when welded below a parent, with the same gravity flag, and every child merges
  std::vector<char> merged(n, 0), has_unmerged_child(n, 0);
  std::vector<OriginInertia> carried(n);
  for (int i = 0; i < n; ++i) carried[i] = OriginInertia::of(model.inertia[i]);
  for (auto it = model.order.rbegin(); it != model.order.rend(); ++it) {
    const int i = *it, p = model.parent[i];
    if (p < 0) continue;
    merged[i] = model.joints[i].type == JointType::Hard && !has_unmerged_child[i] && model.has_gravity[i] == model.has_gravity[p];
    if (!merged[i]) {
      has_unmerged_child[p] = 1;
      continue;
    }
    // a welded joint's transform is its joint frame's (joint_transform of a Hard joint is identity)
    carried[p] += carried[i].in_parent(model.joints[i].X_PJ);
  }
  model.dynamics_order.clear();
  for (int i : model.order)
    if (!merged[i]) model.dynamics_order.push_back(i);
  // back to a spatial inertia about the centre of mass: I_com = I_o - m (|c|^2 1 - c c^T)
  model.dynamics_inertia = model.inertia;
  for (int i : model.dynamics_order) {
    const OriginInertia& o = carried[i];
    SpatialInertia& I = model.dynamics_inertia[i];
    I.mass = o.m;
    I.com = o.m > 0 ? Vec3(o.h / o.m) : Vec3::Zero();
    I.inertia_com = o.I - o.m * (I.com.squaredNorm() * Mat3::Identity() - I.com * I.com.transpose());
  }
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

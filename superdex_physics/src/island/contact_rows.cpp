// An island solve's contact rows (contact_rows.h).

#include "island/contact_rows.h"

#include "island/contact_block.h"
#include "island/link_jacobians.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

ContactRows::ContactRows(const IslandInputs& in, IslandWorkspace& w, IslandJacobian& J)
    : in_(in), w_(w), J_(J) {
  w.frames.clear();
}

void ContactRows::add_rigid() {
  for (int j : w_.solved_contacts) {
    const Contact& c = in_.contacts[in_.island.contacts[j]];
    const Mat3 R_C = contact_frame(c.n_W);
    w_.frames.push_back(R_C);
    Vec3 W_diag = Vec3::Zero();
    real vn_free = 0;
    J_.begin_block(3);
    if (c.skin_node >= 0) {
      add_skin_side(c, R_C, W_diag, vn_free);
    } else {
      add_link_side(c.body_a, c.link_a, c.p_W, R_C, 1, W_diag, vn_free);
    }
    add_link_side(c.body_b, c.link_b, c.p_W, R_C, -1, W_diag, vn_free);
    push_contact_block(c.material, c.phi, W_diag, vn_free);
  }
}

void ContactRows::add_soft() {
  for (int j : w_.solved_soft_contacts) {
    const SoftContact& c = in_.soft_contacts[in_.island.soft_contacts[j]];
    const Mat3 R_C = contact_frame(c.n_W);
    w_.frames.push_back(R_C);
    Vec3 W_diag = Vec3::Zero();
    real vn_free = 0;
    J_.begin_block(3);
    if (w_.reduced_of[c.soft] >= 0) {
      add_reduced_side(w_.reduced[w_.reduced_of[c.soft]], c, R_C, W_diag, vn_free);
    } else {
      add_node_side(c, R_C, W_diag, vn_free);
    }
    add_link_side(c.body, c.link, c.p_W, R_C, -1, W_diag, vn_free);
    push_contact_block(c.material, c.phi, W_diag, vn_free);
  }
}

// adds the rows of one side (an articulation link) of a contact in frame R_C, scaled by `scale`
// (+1 side a, -1 side b, a skin weight), with the diagonal of its Delassus block (the only part
// the contact block reads) and free-motion normal velocity
void ContactRows::add_link_side(int body, int link, const Vec3& p_W, const Mat3& R_C, real scale, Vec3& W_diag, real& vn_free) {
  const SceneData& s = in_.s;
  const int nb = s.articulations[body]->model.nv;
  if (nb == 0) return;
  const IslandWorkspace::LinkJacobian& lj = link_compliance(s, body, link, in_.terms[body].A_factor, w_);
  const MatXR& J = lj.J_WL;
  const Vec3 r = p_W - s.articulations[body]->kin.X_WL[link].p;
  const Mat3 R = scale * R_C.transpose();
  const int o = w_.body_offset[body];
  // on the sparse path the side's rows on all its body's DOFs (zeros included: the structure
  // is the contact's bodies), adding to the other side's when both are on one body
  real* P = J_.form() == IslandJacobian::Form::Bodies ? J_.piece(w_.island_position[body]) : nullptr;
  for (int k = 0; k < nb; ++k) {
    // velocity of point p_W per unit velocity of DOF k, in the contact frame
    const Vec3 v = R * (J.block<3, 1>(0, k) + J.block<3, 1>(3, k).cross(r));
    if (P) {
      for (int i = 0; i < 3; ++i) P[3 * k + i] += v[i];
    } else {
      J_.add_column(o + k, v.data());
    }
    vn_free += v[2] * w_.v_start[o + k];
  }
  // the point's compliance in the contact frame, R S W_L S^T R^T with S = [I, -[r]x] (the
  // point's velocity from the link origin's and the angular one): per contact, a 3 x 6 product
  // whatever the body's DOFs
  Eigen::Matrix<real, 3, 6> RS;
  RS.leftCols<3>() = R;
  RS.rightCols<3>().noalias() = -R * skew(r);
  W_diag += (RS * lj.W_L).cwiseProduct(RS).rowwise().sum();
}

// a skin node (side a) moves with its links by their weights: the rows of each link's point,
// weighted; the Delassus diagonal of the weighted sum is bounded by (sum_k w_k sqrt(W_k))^2
// (Cauchy-Schwarz over the links' coupled compliances)
void ContactRows::add_skin_side(const Contact& c, const Mat3& R_C, Vec3& W_diag, real& vn_free) {
  const Articulation& a = *in_.s.articulations[c.body_a];
  const ArticulationSkin& skin = *a.skin;
  Vec3 root_sum = Vec3::Zero();
  for (int j = skin.first[c.skin_node]; j < skin.first[c.skin_node + 1]; ++j) {
    const SkinInfluence& f = skin.influences[j];
    const SpatialTransform& X = a.kin.X_WL[f.link];
    Vec3 W_k = Vec3::Zero();
    add_link_side(c.body_a, f.link, X.R * f.p_L + X.p, R_C, f.weight, W_k, vn_free);
    // add_link_side scaled the rows by the weight, so W_k holds w^2 W: its root is w sqrt(W)
    root_sum += W_k.cwiseSqrt();
  }
  W_diag += root_sum.cwiseAbs2();
}

// a contact point on a reduced body moves with its nodes' modal and residual velocities: adds
// its rows (side a), their Delassus diagonal and free-motion normal velocity
void ContactRows::add_reduced_side(const ReducedVariables& rv, const SoftContact& c, const Mat3& R_C, Vec3& W_diag, real& vn_free) {
  const real dt = in_.dt;
  const ReducedSoftModel& model = *in_.s.soft_bodies[c.soft]->reduced;
  const int o = rv.offset, nq = model.num_modes();
  // the contact's nodes (weight non-zero) and their residual columns (-1: pinned)
  bool node[3];
  int col[3];
  for (int j = 0; j < 3; ++j) {
    node[j] = c.nodes[j] >= 0 && c.weights[j] != 0;
    col[j] = node[j] ? rv.column(c.nodes[j], 0) : -1;
  }
  MatX& Jq = w_.Jc;
  Jq.setZero(3, nq);
  for (int j = 0; j < 3; ++j)
    if (node[j]) Jq.noalias() += (c.weights[j] * R_C.transpose()) * model.Phi.middleRows<3>(3 * c.nodes[j]);
  for (int k = 0; k < nq; ++k) J_.add_column(o + k, Jq.col(k).data());
  W_diag += (Jq.array().square().rowwise() / rv.A_q.transpose().array()).rowwise().sum().matrix();
  // the contact's regularization takes the full body's Delassus estimate too (its lumped node
  // masses), so that a reduced body and its full twin press alike
  for (int j = 0; j < 3; ++j)
    if (node[j] && model.free_of_dof[3 * c.nodes[j]] >= 0)
      W_diag.array() += c.weights[j] * c.weights[j] / in_.s.soft_bodies[c.soft]->model.node_mass[c.nodes[j]];
  vn_free += Jq.row(2).dot(rv.r_q.cwiseQuotient(rv.A_q));
  // residual columns: the node's own velocity w, weighted; compliance G / h among them
  for (int j = 0; j < 3; ++j) {
    const int cj = col[j];
    if (cj < 0) continue;
    for (int a = 0; a < 3; ++a) {
      const Vec3 v = c.weights[j] * R_C.row(a).transpose();
      J_.add_column(o + cj + a, v.data());
    }
    vn_free -= c.weights[j] * (dt / rv.h) * R_C.col(2).dot(rv.u_old.segment<3>(cj - nq));
    for (int l = 0; l < 3; ++l) {
      const int cl = col[l];
      if (cl < 0) continue;
      const Mat3 G_jl = R_C.transpose() * rv.G.block<3, 3>(cj - nq, cl - nq) * R_C;
      W_diag += (c.weights[j] * c.weights[l] / rv.h) * G_jl.diagonal();
    }
  }
}

// a contact point on a full soft body moves with its free nodes by their weights: adds its rows
// (side a), their Delassus diagonal (the lumped node masses) and free-motion normal velocity
void ContactRows::add_node_side(const SoftContact& c, const Mat3& R_C, Vec3& W_diag, real& vn_free) {
  const SoftStep& st = *in_.soft_steps[c.soft];
  const int o = w_.soft_offset[c.soft];
  for (int j = 0; j < 3; ++j) {
    if (c.nodes[j] < 0 || c.weights[j] == 0 || st.pattern.free_of_dof[3 * c.nodes[j]] < 0) continue;
    const real w = c.weights[j];
    for (int a = 0; a < 3; ++a) {
      const int f = st.pattern.free_of_dof[3 * c.nodes[j] + a];
      const Vec3 v = w * R_C.row(a).transpose();
      J_.add_column(o + f, v.data());
      vn_free += w * R_C(a, 2) * (st.r[f] / st.mass[f]);
    }
    W_diag.array() += w * w / st.mass[st.pattern.free_of_dof[3 * c.nodes[j]]];
  }
}

// the frictional block of a contact with Delassus diagonal W_diag and free-motion normal
// velocity, closing its three rows
void ContactRows::push_contact_block(const ContactMaterial& material, real phi, const Vec3& W_diag, real vn_free) {
  ConstraintBlock blk = frictional_contact_block(material, phi, W_diag.sum() / 3, W_diag[2], vn_free, in_.dt, in_.params);
  blk.row = J_.row;
  w_.rows.blocks.push_back(blk);
  J_.end_block();
  J_.row += 3;
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

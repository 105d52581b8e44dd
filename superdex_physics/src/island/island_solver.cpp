// Assembly and solution of one island's convex problem.

#include "island/island_solver.h"

#include <algorithm>
#include <cmath>

#include "island/contact_block.h"
#include "multibody/kinematics.h"
#include "solver/row_block_assembler.h"
#include "soft/soft_island_solver.h"
#include "solver/sparse_newton_system.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

bool island_is_sparse(const SceneData& s, const Island& island, const SolverParams& params) {
  if (!island.soft_bodies.empty()) return false;
  int dofs = 0;
  for (int b : island.bodies) dofs += s.articulations[b]->model.nv;
  return dofs > params.dense_island_max_dofs;
}

namespace {

// v <- n copies of `value`, inline (vector::assign calls out to a general routine, a dozen
// times per island)
void fill_to(std::vector<int>& v, size_t n, int value) {
  v.resize(n);
  std::fill(v.begin(), v.end(), value);
}

// A soft contact too far apart to close within the step at the current speeds: it is left out of
// the first solve, and joins a second one only if that solve's velocities would close (half) its
// gap. Most speculative contacts of a soft surface are such.
bool soft_contact_deferred(const SoftContact& c) { return c.phi > c.sweep; }

// The world Jacobian J_WL (6 x nv) of a link of an island's body, computed once per solve of the
// island (w.link_jacobians_used is reset at its start) and kept in `w`.
IslandWorkspace::LinkJacobian& cached_link_jacobian(const SceneData& s, int body, int link, IslandWorkspace& w) {
  // the link's slot, when its body is in the island (w.link_base)
  int* slot = w.link_base[body] >= 0 ? &w.link_slot[w.link_base[body] + link] : nullptr;
  if (slot && *slot >= 0) return w.link_jacobians[*slot];
  if (w.link_jacobians_used == w.link_jacobians.size()) w.link_jacobians.emplace_back();
  if (slot) *slot = static_cast<int>(w.link_jacobians_used);
  IslandWorkspace::LinkJacobian& added = w.link_jacobians[w.link_jacobians_used++];
  added.body = body;
  added.link = link;
  added.has_W_L = false;
  const Articulation& a = *s.articulations[body];
  link_jacobian_world(a.model, a.kin, link, added.J_WL);
  return added;
}

// The same with its compliance W_L = J_WL A^-1 J_WL^T, for the body's factored A.
const IslandWorkspace::LinkJacobian& link_compliance(const SceneData& s, int body, int link, const SmallLLT& A_llt,
                                                     IslandWorkspace& w) {
  IslandWorkspace::LinkJacobian& lj = cached_link_jacobian(s, body, link, w);
  if (!lj.has_W_L) {
    w.L_inv_Jt = lj.J_WL.transpose();
    A_llt.solve_lower_in_place(w.L_inv_Jt);
    lj.W_L.noalias() = w.L_inv_Jt.transpose() * w.L_inv_Jt;
    lj.has_W_L = true;
  }
  return lj;
}

// One solve of the island, with or without the deferred joint-limit rows, and with the deferred
// soft contacts `admitted` flags (per island soft contact).
void solve_island_once(const SceneData& s, const Island& island, const std::vector<ArticulationTerms>& terms,
                       const std::vector<Contact>& contacts, const std::vector<SoftContact>& soft_contacts,
                       const std::vector<std::unique_ptr<SoftStep>>& soft_steps, real dt, const SolverParams& params,
                       bool include_deferred, const std::vector<char>& admitted, IslandWorkspace& w,
                       SparseNewtonSystem* system, IslandSolution& out) {
  // variable offsets: the articulations' DOFs, then each soft body's free DOFs
  std::vector<int>& offset = w.body_offset;
  std::vector<int>& soft_offset = w.soft_offset;
  fill_to(offset, s.articulations.size(), -1);
  fill_to(soft_offset, soft_steps.size(), -1);
  fill_to(w.link_base, s.articulations.size(), -1);
  fill_to(w.island_position, s.articulations.size(), -1);
  int n = 0, links = 0;
  for (size_t j = 0; j < island.bodies.size(); ++j) {
    const int b = island.bodies[j];
    offset[b] = n, n += s.articulations[b]->model.nv;
    w.link_base[b] = links, links += s.articulations[b]->model.num_links;
    w.island_position[b] = static_cast<int>(j);
  }
  // the soft contacts that take part (positions in island.soft_contacts)
  std::vector<int>& solved_soft = w.solved_soft_contacts;
  solved_soft.clear();
  for (size_t j = 0; j < island.soft_contacts.size(); ++j)
    if (admitted[j] || !soft_contact_deferred(soft_contacts[island.soft_contacts[j]])) solved_soft.push_back(static_cast<int>(j));
  // reduced soft bodies: dense variables after the articulations' DOFs, with the residual
  // velocities of the free nodes of the contacts that take part
  std::vector<ReducedVariables>& reduced = w.reduced;
  std::vector<int>& reduced_of = w.reduced_of;
  reduced.resize(0);
  fill_to(reduced_of, soft_steps.size(), -1);
  for (int k : island.soft_bodies) {
    const SoftBody& body = *s.soft_bodies[k];
    if (!body.reduced) continue;
    std::vector<int> nodes;
    for (int j : solved_soft) {
      const SoftContact& c = soft_contacts[island.soft_contacts[j]];
      if (c.soft != k) continue;
      for (int v = 0; v < 3; ++v)
        if (c.nodes[v] >= 0 && c.weights[v] != 0 && body.reduced->free_of_dof[3 * c.nodes[v]] >= 0) nodes.push_back(c.nodes[v]);
    }
    std::sort(nodes.begin(), nodes.end());
    nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
    reduced_of[k] = static_cast<int>(reduced.size());
    reduced.emplace_back();
    reduced_variables(body, k, s.gravity, dt, std::move(nodes), reduced.back());
    reduced.back().offset = soft_offset[k] = n;
    n += reduced.back().size();
  }
  const int n_rigid = n;
  std::vector<SoftStep*>& soft = w.soft;
  soft.clear();
  for (int k : island.soft_bodies) {
    if (reduced_of[k] >= 0) continue;
    soft.push_back(soft_steps[k].get());
    soft_offset[k] = n;
    n += soft.back()->size();
  }

  // the joint rows that take part, in row order: deferred limit rows only when `include_deferred`
  std::vector<IslandWorkspace::JointRowRef>& solved_rows = w.solved_joint_rows;
  solved_rows.clear();
  for (size_t j = 0; j < island.bodies.size(); ++j) {
    const std::vector<JointRow>& body_rows = terms[island.bodies[j]].joint_rows;
    for (size_t i = 0; i < body_rows.size(); ++i)
      if (!body_rows[i].deferred || include_deferred) solved_rows.push_back({static_cast<int>(j), static_cast<int>(i)});
  }
  const int joint_rows = static_cast<int>(solved_rows.size());
  const int num_contacts = static_cast<int>(island.contacts.size() + solved_soft.size());

  // small islands: dense algebra; large ones: sparse, on a pattern kept from step to step
  const bool sparse = island_is_sparse(s, island, params);
  // A as a dense matrix (the sparse path builds its own from the bodies' blocks)
  MatX& A = w.A;
  VecX &r = w.r, &v_start = w.v_start;
  if (!sparse) A.setZero(n_rigid, n_rigid);
  r.resize(n);
  v_start.resize(n);
  for (int b : island.bodies) {
    const int o = offset[b], nb = s.articulations[b]->model.nv;
    if (!sparse) A.block(o, o, nb, nb) = terms[b].A;
    r.segment(o, nb) = terms[b].r;
    // velocities of the free (unconstrained) motion: the start of the Newton iteration, and the
    // reference of the near-rigid target compensation
    v_start.segment(o, nb) = terms[b].v_free;
  }
  // a reduced body: the modal block (diagonal) and the contact nodes' residual stiffness and
  // damping h G^-1; its free motion leaves the modes to themselves and relaxes the residual
  for (const ReducedVariables& rv : reduced) {
    const int o = rv.offset, nq = static_cast<int>(rv.A_q.size()), k3 = rv.size() - nq;
    A.diagonal().segment(o, nq) = rv.A_q;
    r.segment(o, nq) = rv.r_q;
    v_start.segment(o, nq) = rv.r_q.cwiseQuotient(rv.A_q);
    if (k3 == 0) continue;
    A.block(o + nq, o + nq, k3, k3) = rv.h * rv.G_inv;
    r.segment(o + nq, k3).noalias() = -dt * (rv.G_inv * rv.u_old);
    v_start.segment(o + nq, k3) = -(dt / rv.h) * rv.u_old;
  }
  for (int k : island.soft_bodies) {
    if (reduced_of[k] >= 0) continue;
    const SoftStep& st = *soft_steps[k];
    r.segment(soft_offset[k], st.size()) = st.r;
    v_start.segment(soft_offset[k], st.size()) = st.v0;
  }
  // J's form: by bodies on the sparse path; a dense matrix on the dense path (the dense algebra's
  // own); with full soft bodies, compressed rows (rows.J) assembled block by block
  enum class JForm { Bodies, Dense, Rows };
  const JForm form = sparse ? JForm::Bodies : soft.empty() ? JForm::Dense : JForm::Rows;
  ConstraintRows& rows = w.rows;
  RowBlockAssembler& J_rows = w.J_rows;
  BodyJacobian& J_bodies = w.J_bodies;
  MatXR& J_dense = w.J_dense;
  rows.blocks.clear();
  rows.blocks.reserve(joint_rows + num_contacts);
  if (form == JForm::Bodies) {
    std::vector<int>& dofs = w.body_dofs;
    dofs.clear();
    for (int b : island.bodies) dofs.push_back(s.articulations[b]->model.nv);
    J_bodies.reset(dofs);
  } else if (form == JForm::Dense) {
    J_dense.setZero(joint_rows + 3 * num_contacts, n);
  } else {
    J_rows.clear();
  }
  int row = 0;         // the open block's first row
  int block_rows = 0;  // and its rows
  auto begin_block = [&](int size) {
    block_rows = size;
    if (form == JForm::Bodies) J_bodies.begin_block(size);
    if (form == JForm::Rows) J_rows.begin_block(size);
  };
  auto end_block = [&]() {
    if (form == JForm::Bodies) J_bodies.end_block();
    if (form == JForm::Rows) J_rows.end_block();
  };
  // adds the open block's values v[0..block_rows) in column `col` (dense and compressed forms)
  auto add_column = [&](int col, const real* v) {
    if (form == JForm::Dense) {
      for (int i = 0; i < block_rows; ++i) J_dense(row + i, col) += v[i];
    } else {
      J_rows.add(col, v);
    }
  };
  for (const auto [j, i] : solved_rows) {
    const int b = island.bodies[j];
    const JointRow& jr = terms[b].joint_rows[i];
    begin_block(1);
    if (form == JForm::Bodies) {
      real* P = J_bodies.piece(j);
      if (jr.J.size() > 0) {
        std::copy(jr.J.data(), jr.J.data() + jr.J.size(), P);
      } else {
        P[jr.dof] = jr.sign;
      }
    } else if (jr.J.size() > 0) {
      for (Eigen::Index c = 0; c < jr.J.size(); ++c) add_column(offset[b] + static_cast<int>(c), &jr.J[c]);
    } else {
      add_column(offset[b] + jr.dof, &jr.sign);
    }
    end_block();
    ConstraintBlock blk = jr.block;
    if (jr.deferred) blk.R = deferred_compliance(terms[b], jr, params);
    blk.row = row++;
    rows.blocks.push_back(blk);
  }

  // contact blocks: rows R_C^T (J_a(p) - J_b(p)), regularised by the Delassus estimate w
  w.link_jacobians_used = 0;
  fill_to(w.link_slot, links, -1);
  // adds the rows of one side (an articulation link) of a contact in frame R_C, with the
  // diagonal of its Delassus block (the only part the contact block reads) and free-motion
  // normal velocity
  auto add_link_side = [&](int body, int link, const Vec3& p_W, const Mat3& R_C, real sign, Vec3& W_diag, real& vn_free) {
    const int nb = s.articulations[body]->model.nv;
    if (nb == 0) return;
    const IslandWorkspace::LinkJacobian& lj = link_compliance(s, body, link, terms[body].A_llt, w);
    const MatXR& J = lj.J_WL;
    const Vec3 r = p_W - s.articulations[body]->kin.X_WL[link].p;
    const Mat3 R = sign * R_C.transpose();
    const int o = offset[body];
    // on the sparse path the side's rows on all its body's DOFs (zeros included: the structure
    // is the contact's bodies), adding to the other side's when both are on one body
    real* P = form == JForm::Bodies ? J_bodies.piece(w.island_position[body]) : nullptr;
    for (int k = 0; k < nb; ++k) {
      // velocity of point p_W per unit velocity of DOF k, in the contact frame
      const Vec3 v = R * (J.block<3, 1>(0, k) + J.block<3, 1>(3, k).cross(r));
      if (P) {
        for (int i = 0; i < 3; ++i) P[3 * k + i] += v[i];
      } else {
        add_column(o + k, v.data());
      }
      vn_free += v[2] * v_start[o + k];
    }
    // the point's compliance in the contact frame, R S W_L S^T R^T with S = [I, -[r]x] (the
    // point's velocity from the link origin's and the angular one): per contact, a 3 x 6 product
    // whatever the body's DOFs
    Eigen::Matrix<real, 3, 6> RS;
    RS.leftCols<3>() = R;
    RS.rightCols<3>().noalias() = -R * skew(r);
    W_diag += (RS * lj.W_L).cwiseProduct(RS).rowwise().sum();
  };
  std::vector<Mat3>& frames = w.frames;
  frames.clear();
  // the frictional block of a contact with Delassus diagonal W_diag and free-motion normal velocity
  auto push_contact_block = [&](const ContactMaterial& material, real phi, const Vec3& W_diag, real vn_free) {
    ConstraintBlock blk = frictional_contact_block(material, phi, W_diag.sum() / 3, W_diag[2], vn_free, dt, params);
    blk.row = row;
    rows.blocks.push_back(blk);
    end_block();
    row += 3;
  };
  for (int ci : island.contacts) {
    const Contact& c = contacts[ci];
    const Mat3 R_C = contact_frame(c.n_W);
    frames.push_back(R_C);
    Vec3 W_diag = Vec3::Zero();
    real vn_free = 0;
    begin_block(3);
    add_link_side(c.body_a, c.link_a, c.p_W, R_C, 1, W_diag, vn_free);
    add_link_side(c.body_b, c.link_b, c.p_W, R_C, -1, W_diag, vn_free);
    push_contact_block(c.material, c.phi, W_diag, vn_free);
  }
  // a contact point on a reduced body moves with its nodes' modal and residual velocities: adds
  // its rows (side a), their Delassus diagonal and free-motion normal velocity
  auto add_reduced_side = [&](const ReducedVariables& rv, const SoftContact& c, const Mat3& R_C, Vec3& W_diag, real& vn_free) {
    const ReducedSoftModel& model = *s.soft_bodies[c.soft]->reduced;
    const int o = rv.offset, nq = model.num_modes();
    // the contact's nodes (weight non-zero) and their residual columns (-1: pinned)
    bool node[3];
    int col[3];
    for (int j = 0; j < 3; ++j) {
      node[j] = c.nodes[j] >= 0 && c.weights[j] != 0;
      col[j] = node[j] ? rv.column(c.nodes[j], 0) : -1;
    }
    MatX& Jq = w.Jc;
    Jq.setZero(3, nq);
    for (int j = 0; j < 3; ++j)
      if (node[j]) Jq.noalias() += (c.weights[j] * R_C.transpose()) * model.Phi.middleRows<3>(3 * c.nodes[j]);
    for (int k = 0; k < nq; ++k) add_column(o + k, Jq.col(k).data());
    W_diag += (Jq.array().square().rowwise() / rv.A_q.transpose().array()).rowwise().sum().matrix();
    // the contact's regularization takes the full body's Delassus estimate too (its lumped node
    // masses), so that a reduced body and its full twin press alike
    for (int j = 0; j < 3; ++j)
      if (node[j] && model.free_of_dof[3 * c.nodes[j]] >= 0)
        W_diag.array() += c.weights[j] * c.weights[j] / s.soft_bodies[c.soft]->model.node_mass[c.nodes[j]];
    vn_free += Jq.row(2).dot(rv.r_q.cwiseQuotient(rv.A_q));
    // residual columns: the node's own velocity w, weighted; compliance G / h among them
    for (int j = 0; j < 3; ++j) {
      const int cj = col[j];
      if (cj < 0) continue;
      for (int a = 0; a < 3; ++a) {
        const Vec3 v = c.weights[j] * R_C.row(a).transpose();
        add_column(o + cj + a, v.data());
      }
      vn_free -= c.weights[j] * (dt / rv.h) * R_C.col(2).dot(rv.u_old.segment<3>(cj - nq));
      for (int l = 0; l < 3; ++l) {
        const int cl = col[l];
        if (cl < 0) continue;
        const Mat3 G_jl = R_C.transpose() * rv.G.block<3, 3>(cj - nq, cl - nq) * R_C;
        W_diag += (c.weights[j] * c.weights[l] / rv.h) * G_jl.diagonal();
      }
    }
  };
  // soft contacts: a point moving with up to three nodes by barycentric weights (side a, the
  // compliance of the lumped node masses) against a link (side b)
  for (int j : solved_soft) {
    const SoftContact& c = soft_contacts[island.soft_contacts[j]];
    const Mat3 R_C = contact_frame(c.n_W);
    frames.push_back(R_C);
    Vec3 W_diag = Vec3::Zero();
    real vn_free = 0;
    begin_block(3);
    if (reduced_of[c.soft] >= 0) {
      add_reduced_side(reduced[reduced_of[c.soft]], c, R_C, W_diag, vn_free);
      add_link_side(c.body, c.link, c.p_W, R_C, -1, W_diag, vn_free);
      push_contact_block(c.material, c.phi, W_diag, vn_free);
      continue;
    }
    const SoftStep& st = *soft_steps[c.soft];
    const int o = soft_offset[c.soft];
    for (int j = 0; j < 3; ++j) {
      if (c.nodes[j] < 0 || c.weights[j] == 0 || st.pattern.free_of_dof[3 * c.nodes[j]] < 0) continue;
      const real w = c.weights[j];
      for (int a = 0; a < 3; ++a) {
        const int f = st.pattern.free_of_dof[3 * c.nodes[j] + a];
        const Vec3 v = w * R_C.row(a).transpose();
        add_column(o + f, v.data());
        vn_free += w * R_C(a, 2) * (st.r[f] / st.mass[f]);
      }
      W_diag.array() += w * w / st.mass[st.pattern.free_of_dof[3 * c.nodes[j]]];
    }
    add_link_side(c.body, c.link, c.p_W, R_C, -1, W_diag, vn_free);
    push_contact_block(c.material, c.phi, W_diag, vn_free);
  }

  // (same-row entries of a contact with both bodies on one articulation have added up)
  if (form == JForm::Rows) J_rows.finish(n, rows.J);

  // the solve (dense, sparse, or with soft bodies block elimination) starts from the free
  // motion A^-1 r, or, when bodies touch, from their current velocities: resting and pressing
  // contacts change little from one step to the next, and the problem is convex, so any start
  // converges.
  if (num_contacts > 0) {
    for (int b : island.bodies) v_start.segment(offset[b], s.articulations[b]->model.nv) = s.articulations[b]->state.v;
    // a reduced body: its modes' velocities, and contact nodes that keep their residual
    for (const ReducedVariables& rv : reduced) {
      v_start.segment(rv.offset, rv.A_q.size()) = s.soft_bodies[rv.soft]->state.qd;
      v_start.segment(rv.offset + rv.A_q.size(), rv.size() - rv.A_q.size()).setZero();
    }
  }
  if (sparse) {
    w.A_blocks.clear();
    for (int b : island.bodies) w.A_blocks.push_back(&terms[b].A);
  }
  // every path leaves its result in w.newton.result
  ConvexResult& sol = !soft.empty() ? solve_convex_with_soft(A, r, rows, soft, v_start, params, w.newton)
                      : sparse      ? solve_convex(w.A_blocks, r, J_bodies, rows.blocks, params, v_start, *system, w.newton)
                                    : solve_convex(A, r, J_dense, rows.blocks, params, v_start, w.newton);
  out.iterations = sol.iterations;
  out.residual = sol.residual;
  out.converged = sol.converged;
  out.active_rows = 0;
  for (int i = 0; i < joint_rows; ++i) out.active_rows += sol.gamma[i] != 0;
  // the result vectors keep their storage from the last step (the same island, mostly)
  out.v.resize(island.bodies.size());
  out.drive_efforts.resize(island.bodies.size());
  for (size_t j = 0; j < island.bodies.size(); ++j) {
    const int b = island.bodies[j], nb = s.articulations[b]->model.nv;
    out.v[j] = sol.v.segment(offset[b], nb);
    out.drive_efforts[j].setZero(nb);
  }
  // joint drive impulses back to efforts
  for (int k = 0; k < joint_rows; ++k) {
    const auto [j, i] = solved_rows[k];
    const JointRow& jr = terms[island.bodies[j]].joint_rows[i];
    if (jr.drive) out.drive_efforts[j][jr.dof] += jr.sign * sol.gamma[k] / dt;
  }
  out.soft_v.resize(island.soft_bodies.size());
  out.soft_reduced.resize(island.soft_bodies.size());
  for (size_t j = 0; j < island.soft_bodies.size(); ++j) {
    const int k = island.soft_bodies[j];
    if (reduced_of[k] >= 0) {
      const ReducedVariables& rv = reduced[reduced_of[k]];
      reduced_next_state(*s.soft_bodies[k], rv, sol.v.segment(rv.offset, rv.size()), s.gravity, dt, out.soft_reduced[j]);
      out.soft_v[j] = out.soft_reduced[j].v;
    } else {
      out.soft_reduced[j].q.resize(0);
      out.soft_v[j] = soft_steps[k]->full_velocity(sol.v.segment(soft_offset[k], soft_steps[k]->size()));
    }
  }
  out.contact_force.clear();
  out.soft_contact_force.clear();
  for (size_t k = 0; k < island.contacts.size(); ++k)
    out.contact_force.push_back(frames[k] * sol.gamma.segment<3>(joint_rows + 3 * k) / dt);
  out.soft_contact_force.assign(island.soft_contacts.size(), Vec3::Zero());
  for (size_t k = island.contacts.size(); k < frames.size(); ++k)
    out.soft_contact_force[solved_soft[k - island.contacts.size()]] = frames[k] * sol.gamma.segment<3>(joint_rows + 3 * k) / dt;
}

// Whether the island's solution `v` (per body) would make a deferred joint-limit row act.
bool violates_deferred_rows(const Island& island, const std::vector<ArticulationTerms>& terms, const std::vector<VecX>& v) {
  for (size_t j = 0; j < island.bodies.size(); ++j)
    for (const JointRow& row : terms[island.bodies[j]].joint_rows)
      if (row.deferred && row.sign * v[j][row.dof] < row.block.vhat) return true;
  return false;
}

// Admits the deferred soft contacts not yet `admitted` whose gap the island's solution would close
// by more than half (half the gap its contact block would let close before acting); returns how
// many.
int admit_closing_soft_contacts(const SceneData& s, const Island& island, const std::vector<SoftContact>& soft_contacts, real dt,
                                const IslandSolution& out, IslandWorkspace& w, std::vector<char>& admitted) {
  int count = 0;
  // velocity of point p_W of a link at the solution (world), by the link Jacobians of the solve
  auto point_velocity = [&](int body, int link, const Vec3& p_W) -> Vec3 {
    const Articulation& a = *s.articulations[body];
    if (a.model.nv == 0) return Vec3::Zero();
    const int j = static_cast<int>(std::find(island.bodies.begin(), island.bodies.end(), body) - island.bodies.begin());
    const Vec6 V = cached_link_jacobian(s, body, link, w).J_WL * out.v[j];
    return V.head<3>() + V.tail<3>().cross(p_W - a.kin.X_WL[link].p);
  };
  for (size_t j = 0; j < island.soft_contacts.size(); ++j) {
    const SoftContact& c = soft_contacts[island.soft_contacts[j]];
    if (admitted[j] || !soft_contact_deferred(c)) continue;
    const VecX& v_soft = out.soft_v[std::find(island.soft_bodies.begin(), island.soft_bodies.end(), c.soft) - island.soft_bodies.begin()];
    Vec3 v_point = Vec3::Zero();
    for (int k = 0; k < 3; ++k)
      if (c.nodes[k] >= 0) v_point += c.weights[k] * v_soft.segment<3>(3 * c.nodes[k]);
    const real vn = c.n_W.dot(v_point - point_velocity(c.body, c.link, c.p_W));
    const real allowed = c.material.stiffness > 0 ? c.phi / (dt + std::max<real>(c.material.dissipation_time, 0)) : c.phi / dt;
    if (vn < -allowed / 2) admitted[j] = 1, ++count;
  }
  return count;
}

}  // namespace

void solve_island(const SceneData& s, const Island& island, const std::vector<ArticulationTerms>& terms,
                  const std::vector<Contact>& contacts, const std::vector<SoftContact>& soft_contacts,
                  const std::vector<std::unique_ptr<SoftStep>>& soft_steps, real dt, const SolverParams& params,
                  IslandWorkspace& w, SparseNewtonSystem* system, IslandSolution& out) {
  const Ticks t0 = ticks_now();
  std::vector<char>& admitted = w.admitted_soft_contacts;
  admitted.assign(island.soft_contacts.size(), 0);
  solve_island_once(s, island, terms, contacts, soft_contacts, soft_steps, dt, params, false, admitted, w, system, out);
  // a deferred limit row or soft contact is inactive at the solution unless it says otherwise:
  // then the same problem with every limit row and the soft contacts the solution would close,
  // until no other would (rare: the free motion kept them far from acting)
  constexpr int kLastRound = 3;  // after which every deferred contact joins
  bool all_rows = false;
  for (int round = 0;; ++round) {
    const bool rows = !all_rows && violates_deferred_rows(island, terms, out.v);
    const int closing = admit_closing_soft_contacts(s, island, soft_contacts, dt, out, w, admitted);
    if (!rows && closing == 0) break;
    all_rows = all_rows || rows;
    if (round == kLastRound) std::fill(admitted.begin(), admitted.end(), 1), all_rows = true;
    const int iterations = out.iterations;
    solve_island_once(s, island, terms, contacts, soft_contacts, soft_steps, dt, params, all_rows, admitted, w, system, out);
    out.iterations += iterations;
    if (round == kLastRound) break;
  }
  out.ticks = ticks_now() - t0;
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

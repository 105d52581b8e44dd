// Assembly and solution of one island's convex problem.

#include "island_solver.h"

#include <chrono>
#include <map>

#include "contact_block.h"
#include "kinematics.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace {

}  // namespace

IslandSolution solve_island(const SceneData& s, const Island& island, const std::vector<ArticulationTerms>& terms,
                            const std::vector<Contact>& contacts, real dt, const SolverParams& params) {
  const auto t0 = std::chrono::steady_clock::now();
  IslandSolution out;
  // DOF offsets of the island's bodies
  std::map<int, int> offset;
  int n = 0;
  for (int b : island.bodies) offset[b] = n, n += s.articulations[b]->model.nv;

  int m = 0;
  for (int b : island.bodies) m += static_cast<int>(terms[b].joint_rows.size());
  const int joint_rows = m;
  m += 3 * static_cast<int>(island.contacts.size());

  MatX A = MatX::Zero(n, n);
  VecX r(n);
  for (int b : island.bodies) {
    const int o = offset[b], nb = s.articulations[b]->model.nv;
    A.block(o, o, nb, nb) = terms[b].A;
    r.segment(o, nb) = terms[b].r;
  }
  ConstraintRows rows;
  std::vector<Eigen::Triplet<real>> J_entries;
  rows.blocks.reserve(joint_rows + island.contacts.size());
  int row = 0;
  for (int b : island.bodies)
    for (const JointRow& jr : terms[b].joint_rows) {
      if (jr.J.size() > 0) {
        for (Eigen::Index c = 0; c < jr.J.size(); ++c)
          if (jr.J[c] != 0) J_entries.emplace_back(row, offset[b] + static_cast<int>(c), jr.J[c]);
      } else {
        J_entries.emplace_back(row, offset[b] + jr.dof, jr.sign);
      }
      ConstraintBlock blk = jr.block;
      blk.row = row++;
      rows.blocks.push_back(blk);
    }

  // contact blocks: rows R_C^T (J_a(p) - J_b(p)), regularised by the Delassus estimate w
  std::map<std::pair<int, int>, MatXR> link_jacobians;
  auto point_jacobian = [&](int body, int link, const Vec3& p_W) {
    const Articulation& a = *s.articulations[body];
    auto it = link_jacobians.find({body, link});
    if (it == link_jacobians.end()) {
      MatXR J;
      link_jacobian_world(a.model, a.kin, link, J);
      it = link_jacobians.emplace(std::make_pair(body, link), std::move(J)).first;
    }
    const MatXR& J = it->second;
    return MatX(J.topRows<3>() - skew(p_W - a.kin.X_WL[link].p) * J.bottomRows<3>());
  };
  // velocities of the free (unconstrained) motion, for the near-rigid target compensation
  VecX v_free(n);
  for (int b : island.bodies) v_free.segment(offset[b], s.articulations[b]->model.nv) = terms[b].A_llt.solve(terms[b].r);
  std::vector<Mat3> frames;
  std::vector<real> contact_mu;
  for (int ci : island.contacts) {
    const Contact& c = contacts[ci];
    const Mat3 R_C = contact_frame(c.n_W);
    frames.push_back(R_C);
    Mat3 W = Mat3::Zero();
    real vn_free = 0;
    for (int side = 0; side < 2; ++side) {
      const int body = side == 0 ? c.body_a : c.body_b;
      const int link = side == 0 ? c.link_a : c.link_b;
      const int nb = s.articulations[body]->model.nv;
      if (nb == 0) continue;
      const MatX Jc = (side == 0 ? real(1) : real(-1)) * R_C.transpose() * point_jacobian(body, link, c.p_W);
      const int o = offset.at(body);
      for (int i = 0; i < 3; ++i)
        for (int k = 0; k < nb; ++k)
          if (Jc(i, k) != 0) J_entries.emplace_back(row + i, o + k, Jc(i, k));
      W += Jc * terms[body].A_llt.solve(Jc.transpose());
      vn_free += Jc.row(2).dot(v_free.segment(o, nb));
    }
    ConstraintBlock blk = frictional_contact_block(c.material, c.phi, W.trace() / 3, W(2, 2), vn_free, dt, params);
    blk.row = row;
    contact_mu.push_back(c.material.friction);
    rows.blocks.push_back(blk);
    row += 3;
  }

  // same-row entries of a contact with both bodies on one articulation add up
  rows.J.resize(m, n);
  rows.J.setFromTriplets(J_entries.begin(), J_entries.end());

  // small islands: dense algebra (A's factor reused for one body); large ones: sparse
  Eigen::LLT<MatX> A_llt;
  const Eigen::LLT<MatX>* llt = &terms[island.bodies[0]].A_llt;
  SparseMat A_sparse;
  const bool sparse = n > params.dense_island_max_dofs;
  if (sparse) {
    A_sparse = A.sparseView();
  } else if (island.bodies.size() > 1) {
    A_llt.compute(A);
    llt = &A_llt;
  }
  auto solve = [&] { return sparse ? solve_convex(A_sparse, r, rows, params) : solve_convex(A, *llt, r, rows, params); };
  ConvexResult sol = solve();
  // the cone model lets sliding contacts drift apart at mu |v_t|; refine with the normal row
  // apart and friction bounded by mu gamma_n of the previous solve, to a fixed point
  const int first_contact = static_cast<int>(rows.blocks.size() - island.contacts.size());
  for (int pass = 0; pass < params.max_friction_passes && !island.contacts.empty(); ++pass) {
    real change = 0, scale = 0;
    for (size_t k = first_contact; k < rows.blocks.size(); ++k) {
      ConstraintBlock& blk = rows.blocks[k];
      const real mu = blk.kind == BlockKind::FrictionalContact ? blk.bound : contact_mu[k - first_contact];
      const real bound = mu * sol.gamma[blk.row + 2];
      change = std::max(change, std::abs(bound - (blk.kind == BlockKind::ContactFixedFriction ? blk.bound : real(-1))));
      scale = std::max(scale, bound);
      blk.kind = BlockKind::ContactFixedFriction;
      blk.bound = bound;
    }
    if (pass > 0 && change <= params.friction_pass_tolerance * scale) break;
    const int previous = sol.iterations;
    sol = solve();
    sol.iterations += previous;
  }
  out.iterations = sol.iterations;
  out.residual = sol.residual;
  out.converged = sol.converged;
  for (int i = 0; i < joint_rows; ++i) out.active_rows += sol.gamma[i] != 0;
  for (int b : island.bodies) out.v.push_back(sol.v.segment(offset[b], s.articulations[b]->model.nv));
  // joint drive impulses back to efforts, per body
  int jr = 0;
  for (int b : island.bodies) {
    VecX efforts = VecX::Zero(s.articulations[b]->model.nv);
    for (const JointRow& row : terms[b].joint_rows) {
      if (row.drive) efforts[row.dof] += row.sign * sol.gamma[jr] / dt;
      ++jr;
    }
    out.drive_efforts.push_back(std::move(efforts));
  }
  for (size_t k = 0; k < island.contacts.size(); ++k)
    out.contact_force.push_back(frames[k] * sol.gamma.segment<3>(joint_rows + 3 * k) / dt);
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

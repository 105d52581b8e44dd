// Soft bodies: building from a tet mesh, and the implicit Newton step (soft_body.h).

#include "soft_body.h"

#include <Eigen/Sparse>
#include <cmath>

#include "articulation_step.h"
#include "collision_detection.h"
#include "contact_block.h"
#include "newton_solver.h"
#include "superdex/physics/error.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace {

using SparseMat = Eigen::SparseMatrix<real>;

// Positions of the four nodes of tetrahedron t.
void gather(const std::array<int, 4>& tet, const VecX& x, Vec3* out) {
  for (int k = 0; k < 4; ++k) out[k] = x.segment<3>(3 * tet[k]);
}

// Per-tetrahedron fixed rotations: the polar rotation at x0 for the corotated model.
std::vector<Mat3> rotations(const SoftBody& b, const VecX& x0) {
  std::vector<Mat3> R(b.model.tets.size(), Mat3::Identity());
  for (size_t t = 0; t < b.model.tets.size(); ++t) {
    if (b.model.material[t].model != MaterialModel::Corotated) continue;
    Vec3 xs[4];
    gather(b.model.tets[t], x0, xs);
    R[t] = polar_rotation(deformation_gradient(b.model.rest[t], xs));
  }
  return R;
}

// Elastic energy, and optionally its gradient and (projected) Hessian triplets scaled by `h_scale`.
real elastic(const SoftBody& b, const VecX& x, const std::vector<Mat3>& R, VecX* grad,
             std::vector<Eigen::Triplet<real>>* hess, real h_scale) {
  real energy = 0;
  if (grad) grad->setZero(x.size());
  for (size_t t = 0; t < b.model.tets.size(); ++t) {
    const auto& tet = b.model.tets[t];
    Vec3 xs[4];
    gather(tet, x, xs);
    Vec12 g;
    Mat12 H;
    energy += tet_energy(b.model.material[t], b.model.rest[t], xs, R[t], grad ? &g : nullptr, hess ? &H : nullptr, true);
    for (int i = 0; i < 4; ++i) {
      if (grad) grad->segment<3>(3 * tet[i]) += g.segment<3>(3 * i);
      if (hess)
        for (int j = 0; j < 4; ++j)
          for (int a = 0; a < 3; ++a)
            for (int c = 0; c < 3; ++c) hess->emplace_back(3 * tet[i] + a, 3 * tet[j] + c, h_scale * H(3 * i + a, 3 * j + c));
    }
  }
  return energy;
}

}  // namespace

std::unique_ptr<SoftBody> build_soft_body(const std::string& name, std::shared_ptr<const TetMesh> mesh,
                                          const SoftMaterial& material, const Transform& X_WL,
                                          const std::vector<int>& fixed_nodes, const std::string& where) {
  auto body = std::make_unique<SoftBody>();
  SoftModel& m = body->model;
  m.name = name;
  m.mesh = mesh;
  m.tets = mesh->tets;
  const int n = static_cast<int>(mesh->nodes.size());
  if (!std::isfinite(material.density) || material.density <= 0) throw Error(where + ": material.density must be positive");
  if (!(material.damping_alpha >= 0) || !(material.damping_beta >= 0))
    throw Error(where + ": material damping must be >= 0");
  m.alpha = material.damping_alpha;
  m.beta = material.damping_beta;
  const ElasticMaterial elastic_material = ElasticMaterial::from_young_poisson(
      material_model_from_name(material.type, where + ": material.type"), material.youngs_modulus, material.poisson_ratio,
      where + ": material");
  // world rest positions, rest data and lumped masses
  body->state.x.resize(3 * n);
  for (int i = 0; i < n; ++i) body->state.x.segment<3>(3 * i) = X_WL * mesh->nodes[i];
  body->state.v = VecX::Zero(3 * n);
  body->state.tau_external = VecX::Zero(3 * n);
  m.node_mass = VecX::Zero(n);
  for (size_t t = 0; t < m.tets.size(); ++t) {
    Vec3 xs[4];
    gather(m.tets[t], body->state.x, xs);
    m.rest.push_back(make_tet_rest(xs[0], xs[1], xs[2], xs[3], 0, where + ": tetrahedron " + std::to_string(t)));
    m.material.push_back(elastic_material);
    for (int k = 0; k < 4; ++k) m.node_mass[m.tets[t][k]] += material.density * m.rest.back().volume / 4;
  }
  for (int i = 0; i < n; ++i)
    if (m.node_mass[i] <= 0) throw Error(where + ": node " + std::to_string(i) + " belongs to no tetrahedron");
  m.total_mass = m.node_mass.sum();
  m.pinned.assign(n, 0);
  for (size_t k = 0; k < fixed_nodes.size(); ++k) {
    if (fixed_nodes[k] < 0 || fixed_nodes[k] >= n)
      throw Error(where + ": fixed_nodes[" + std::to_string(k) + "] = " + std::to_string(fixed_nodes[k]) + " is out of range (" +
                  std::to_string(n) + " nodes)");
    m.pinned[fixed_nodes[k]] = 1;
  }
  return body;
}

real soft_elastic_energy(const SoftBody& b, const VecX& x) {
  return elastic(b, x, rotations(b, b.state.x), nullptr, nullptr, 0);
}

SoftState step_soft_body(SoftBody& b, const Vec3& g_W, real dt, const SolverParams& params,
                         const std::vector<StaticSurface>& surfaces) {
  const SoftModel& m = b.model;
  const int n = static_cast<int>(b.state.x.size());
  const VecX& x0 = b.state.x;
  VecX v0 = b.state.v;
  VecX M(n), free(n);
  for (int i = 0; i < n / 3; ++i) {
    M.segment<3>(3 * i).setConstant(m.node_mass[i]);
    free.segment<3>(3 * i).setConstant(m.pinned[i] ? 0 : 1);
  }
  v0 = v0.cwiseProduct(free);
  // external impulse: gravity and user forces
  VecX f_ext(n);
  for (int i = 0; i < n / 3; ++i) f_ext.segment<3>(3 * i) = m.node_mass[i] * g_W;
  f_ext += b.state.tau_external;
  const std::vector<Mat3> R = rotations(b, x0);
  // Rayleigh damping D = alpha M + beta K(x0), fixed over the step
  std::vector<Eigen::Triplet<real>> damping;
  if (m.beta > 0) elastic(b, x0, R, nullptr, &damping, m.beta);
  for (int i = 0; i < n; ++i) damping.emplace_back(i, i, m.alpha * M[i]);
  SparseMat D(n, n);
  D.setFromTriplets(damping.begin(), damping.end());

  // contacts of free nodes with static surfaces, detected at the start of the step
  struct NodeContact {
    int node;
    Mat3 R_C;  // contact frame [t1 t2 n], n out of the surface
    ConstraintBlock block;
  };
  std::vector<NodeContact> contacts;
  for (int i = 0; i < n / 3; ++i) {
    if (m.pinned[i]) continue;
    const Vec3 p = x0.segment<3>(3 * i);
    const real reach = params.contact_margin + dt * (v0.segment<3>(3 * i).norm() + dt * g_W.norm());
    for (const StaticSurface& surface : surfaces) {
      Vec3 g_S;
      const real phi = shape_signed_distance(*surface.shape, surface.X_WS.R.transpose() * (p - surface.X_WS.p), &g_S);
      if (phi >= reach) continue;
      const Vec3 nrm = surface.X_WS.R * g_S;
      NodeContact c;
      c.node = i;
      c.R_C = contact_frame(nrm);
      // the node's compliance 1/m for the regularisation, as an isolated contact
      const real w = 1 / m.node_mass[i];
      const real vn_free = nrm.dot(v0.segment<3>(3 * i) + dt * (g_W + b.state.tau_external.segment<3>(3 * i) / m.node_mass[i]));
      c.block = frictional_contact_block(combine_materials(b.model.contact, surface.material), phi, w, w, vn_free, dt, params);
      contacts.push_back(c);
    }
  }
  // impulses (3 per contact, contact frame) and Hessian blocks at velocities v
  auto contact_response = [&](const VecX& v, VecX& gamma, std::vector<Mat3>* G) {
    gamma.resize(3 * contacts.size());
    if (G) G->resize(contacts.size());
    for (size_t k = 0; k < contacts.size(); ++k) {
      const Vec3 vc = contacts[k].R_C.transpose() * v.segment<3>(3 * contacts[k].node);
      Mat3 Gk;
      block_response(contacts[k].block, vc.data(), gamma.data() + 3 * k, Gk.data());
      if (G) (*G)[k] = Gk;
    }
  };

  // gradient of the objective (pinned DOFs masked); its Hessian triplets when `hess` is given
  auto gradient = [&](const VecX& v, std::vector<Eigen::Triplet<real>>* hess, VecX* grad_psi_out) {
    VecX grad_psi;
    elastic(b, x0 + dt * v, R, &grad_psi, hess, dt * dt);
    VecX g = M.cwiseProduct(v - v0) - dt * f_ext + dt * grad_psi + dt * (D * v);
    if (!contacts.empty()) {
      VecX gamma;
      std::vector<Mat3> G;
      contact_response(v, gamma, hess ? &G : nullptr);
      for (size_t k = 0; k < contacts.size(); ++k) {
        const int i = contacts[k].node;
        g.segment<3>(3 * i) -= contacts[k].R_C * gamma.segment<3>(3 * k);
        if (hess) {
          const Mat3 Hk = contacts[k].R_C * G[k] * contacts[k].R_C.transpose();
          for (int a = 0; a < 3; ++a)
            for (int c = 0; c < 3; ++c) hess->emplace_back(3 * i + a, 3 * i + c, Hk(a, c));
        }
      }
    }
    g = g.cwiseProduct(free);
    if (grad_psi_out) *grad_psi_out = std::move(grad_psi);
    return g;
  };

  VecX v = v0;
  const VecX scale = M.cwiseSqrt().cwiseInverse();
  const real ref = std::max({(scale.asDiagonal() * M.cwiseProduct(v0)).norm(), (scale.asDiagonal() * (dt * f_ext)).norm(), real(1e-30)});
  Eigen::SimplicialLDLT<SparseMat> ldlt;
  int it = 0;
  real residual = 0;
  real best = std::numeric_limits<real>::infinity();
  int stalled = 0;
  for (; it < params.max_newton_iterations; ++it) {
    VecX grad_psi;
    std::vector<Eigen::Triplet<real>> hess;
    const VecX grad = gradient(v, &hess, &grad_psi);
    residual = (scale.asDiagonal() * grad).norm();
    if (residual <= params.absolute_tolerance + params.relative_tolerance * std::max(ref, (scale.asDiagonal() * (dt * grad_psi)).norm()))
      break;
    // no progress over three iterations: converged as far as this precision allows
    stalled = residual < real(0.99) * best ? 0 : stalled + 1;
    best = std::min(best, residual);
    if (stalled >= 3) break;
    // H = M + dt^2 K + dt D, with pinned DOFs kept at their velocity (identity rows and columns)
    for (int i = 0; i < n; ++i) hess.emplace_back(i, i, M[i]);
    SparseMat H(n, n);
    H.setFromTriplets(hess.begin(), hess.end());
    H += dt * D;
    H.prune([&](const Eigen::Index& r, const Eigen::Index& c, const real&) { return free[r] != 0 && free[c] != 0; });
    for (int i = 0; i < n; ++i)
      if (free[i] == 0) H.coeffRef(i, i) = 1;
    ldlt.compute(H);
    if (ldlt.info() != Eigen::Success) throw Error("soft actor '" + m.name + "': the Newton system could not be factored");
    const VecX dv = -ldlt.solve(grad);
    // line search on the directional derivative (gradients stay accurate in float where energy
    // differences at small strain do not): halve until it stops overshooting the minimum
    const real slope = grad.dot(dv);
    real alpha = 1;
    for (int ls = 0; ls < 12; ++ls) {
      const real d = gradient(v + alpha * dv, nullptr, nullptr).dot(dv);
      if (d <= real(0.5) * std::abs(slope)) break;
      alpha /= 2;
    }
    v += alpha * dv;
  }
  // contact forces of the solution, per node (N), world
  b.node_contact_forces = VecX::Zero(n);
  if (!contacts.empty()) {
    VecX gamma;
    contact_response(v, gamma, nullptr);
    for (size_t k = 0; k < contacts.size(); ++k)
      b.node_contact_forces.segment<3>(3 * contacts[k].node) += contacts[k].R_C * gamma.segment<3>(3 * k) / dt;
  }
  b.last_iterations = it;
  b.last_residual = residual;
  SoftState next{x0 + dt * v, v, b.state.tau_external};
  if (!next.x.allFinite() || !next.v.allFinite())
    throw Error("step: soft actor '" + m.name + "': positions or velocities became non-finite; the scene keeps its last good state");
  return next;
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

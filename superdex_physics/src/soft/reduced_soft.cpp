// Reduced soft bodies: their modes, residual compliances and step (reduced_soft.h).

#include "soft/reduced_soft.h"
#include "linalg/sparse_cholesky.h"

#include <Spectra/SymEigsSolver.h>
#include <algorithm>
#include <cmath>

#include "superdex/physics/error.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

// K on the free DOFs, its solves in double precision whatever `real` is.
struct ReducedSoftModel::Stiffness {
  SparseCholesky llt;
};

namespace {

// The operator y = M^1/2 K^-1 M^1/2 x for Spectra: its largest eigenvalues are 1 / the smallest
// of K y = lambda M y, with eigenvectors M^1/2 y.
class InverseStiffnessOp {
 public:
  using Scalar = double;
  InverseStiffnessOp(const SparseCholesky& K, const Eigen::VectorXd& sqrt_mass) : K_(K), s_(sqrt_mass), y_(sqrt_mass.size(), 1) {}
  Eigen::Index rows() const { return s_.size(); }
  Eigen::Index cols() const { return s_.size(); }
  void perform_op(const double* x_in, double* y_out) const {
    Eigen::Map<const Eigen::VectorXd> x(x_in, s_.size());
    Eigen::Map<Eigen::VectorXd> y(y_out, s_.size());
    y_.col(0) = s_.cwiseProduct(x);
    K_.solve_in_place(y_);
    y = s_.cwiseProduct(y_.col(0));
  }

 private:
  const SparseCholesky& K_;
  const Eigen::VectorXd& s_;
  mutable Eigen::MatrixXd y_;
};

}  // namespace

std::shared_ptr<ReducedSoftModel> build_reduced_model(const SoftModel& m, const VecX& x_rest, int modes, const std::string& where) {
  auto model = std::make_shared<ReducedSoftModel>();
  const int n = static_cast<int>(x_rest.size());
  model->x_rest = x_rest;
  model->free_of_dof.assign(n, -1);
  for (int d = 0; d < n; ++d)
    if (!m.pinned[d / 3]) model->free_of_dof[d] = static_cast<int>(model->dof_of_free.size()), model->dof_of_free.push_back(d);
  const int nf = static_cast<int>(model->dof_of_free.size());
  if (nf == n)
    throw Error(where + ": material.reducedModes needs pinned nodes (fixedNodes or fixedRegion): a reduced soft body is linear about "
                        "its rest shape and cannot move as a whole");
  if (modes < 1 || modes >= nf)
    throw Error(where + ": material.reducedModes must be between 1 and " + std::to_string(nf - 1) + " (the free DOFs less one), got " +
                std::to_string(modes));
  // the rest stiffness: every element's Hessian at F = I, on the free DOFs
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(144 * m.tets.size());
  for (size_t t = 0; t < m.tets.size(); ++t) {
    Mat12 H;
    tet_derivatives_at(m.material[t], m.rest[t], Mat3::Identity(), Mat3::Identity(), nullptr, &H, false);
    for (int i = 0; i < 12; ++i)
      for (int j = 0; j < 12; ++j) {
        const int r = model->free_of_dof[3 * m.tets[t][i / 3] + i % 3], c = model->free_of_dof[3 * m.tets[t][j / 3] + j % 3];
        if (r >= 0 && c >= 0) entries.emplace_back(r, c, static_cast<double>(H(i, j)));
      }
  }
  Eigen::SparseMatrix<double> K(nf, nf);
  K.setFromTriplets(entries.begin(), entries.end());
  auto stiffness = std::make_shared<ReducedSoftModel::Stiffness>();
  // (rounded to `real`: the float build's stiffness to 1e-7)
  if (!stiffness->llt.compute(K.cast<real>()))
    throw Error(where + ": the rest stiffness with the pinned nodes held is not positive definite (a part of the body is not held)");
  Eigen::VectorXd sqrt_mass(nf);
  for (int f = 0; f < nf; ++f) sqrt_mass[f] = std::sqrt(static_cast<double>(m.node_mass[model->dof_of_free[f] / 3]));
  // the largest eigenvalues of M^1/2 K^-1 M^1/2, by Spectra's implicitly restarted Lanczos
  InverseStiffnessOp op(stiffness->llt, sqrt_mass);
  const Eigen::Index ncv = std::min<Eigen::Index>(nf, std::max(2 * modes + 1, modes + 20));
  Spectra::SymEigsSolver<InverseStiffnessOp> eigs(op, modes, ncv);
  eigs.init();
  eigs.compute(Spectra::SortRule::LargestAlge, 1000, 1e-10);
  if (eigs.info() != Spectra::CompInfo::Successful)
    throw Error(where + ": the " + std::to_string(modes) + " lowest vibration modes did not converge");
  // descending 1/lambda: ascending lambda
  const Eigen::VectorXd mu = eigs.eigenvalues();
  const Eigen::MatrixXd Y = eigs.eigenvectors();
  model->lambda.resize(modes);
  model->Phi = MatX::Zero(n, modes);
  for (int k = 0; k < modes; ++k) {
    model->lambda[k] = static_cast<real>(1 / mu[k]);
    for (int f = 0; f < nf; ++f) model->Phi(model->dof_of_free[f], k) = static_cast<real>(Y(f, k) / sqrt_mass[f]);
  }
  model->K = std::move(stiffness);
  return model;
}

void ReducedSoftModel::prepare_residuals(const std::vector<int>& nodes) const {
  std::vector<int> missing;
  for (int node : nodes)
    if (!residual_columns.count(node)) missing.push_back(node);
  if (missing.empty()) return;
  // K^-1 of the missing nodes' unit loads, in one solve
  const int nf = static_cast<int>(dof_of_free.size()), m = static_cast<int>(missing.size());
  Eigen::MatrixXd C = Eigen::MatrixXd::Zero(nf, 3 * m);
  for (int j = 0; j < m; ++j)
    for (int a = 0; a < 3; ++a) C(free_of_dof[3 * missing[j] + a], 3 * j + a) = 1;
  K->llt.solve_in_place(C);
  // less the modes' static part Phi Lambda^-1 Phi_S^T of them all
  MatX Phi_S(3 * m, num_modes());
  for (int j = 0; j < m; ++j) Phi_S.middleRows<3>(3 * j) = Phi.middleRows<3>(3 * missing[j]);
  MatX columns = -Phi * (lambda.cwiseInverse().asDiagonal() * Phi_S.transpose());
  for (int j = 0; j < m; ++j) {
    for (int f = 0; f < nf; ++f) columns.block<1, 3>(dof_of_free[f], 3 * j) += C.block<1, 3>(f, 3 * j).cast<real>();
    residual_columns.emplace(missing[j], columns.middleCols<3>(3 * j));
  }
}

const MatX& ReducedSoftModel::residual(int node) const {
  auto it = residual_columns.find(node);
  if (it != residual_columns.end()) return it->second;
  prepare_residuals({node});
  return residual_columns.at(node);
}

const ReducedSoftModel::Gravity& ReducedSoftModel::gravity(const VecX& node_mass, const Vec3& g_W) const {
  Gravity& out = gravity_response;
  if (g_W == out.g_W) return out;
  const int nf = static_cast<int>(dof_of_free.size());
  Eigen::MatrixXd f(nf, 1);
  for (int k = 0; k < nf; ++k) f(k, 0) = static_cast<double>(node_mass[dof_of_free[k] / 3] * g_W[dof_of_free[k] % 3]);
  Eigen::MatrixXd u = f;
  K->llt.solve_in_place(u);
  out.u_g = VecX::Zero(free_of_dof.size());
  VecX f_full = VecX::Zero(free_of_dof.size());
  for (int k = 0; k < nf; ++k) out.u_g[dof_of_free[k]] = static_cast<real>(u(k, 0)), f_full[dof_of_free[k]] = static_cast<real>(f(k, 0));
  out.modal_force = Phi.transpose() * f_full;
  out.u_g.noalias() -= Phi * (lambda.cwiseInverse().asDiagonal() * out.modal_force);
  out.g_W = g_W;
  return out;
}

int ReducedVariables::column(int node, int axis) const {
  auto it = std::lower_bound(nodes.begin(), nodes.end(), node);
  if (it == nodes.end() || *it != node) return -1;
  return static_cast<int>(A_q.size() + 3 * (it - nodes.begin()) + axis);
}

void reduced_variables(const SoftBody& b, int soft, const Vec3& g_W, real dt, std::vector<int> nodes, ReducedVariables& out) {
  const ReducedSoftModel& model = *b.reduced;
  const SoftModel& m = b.model;
  const SoftState& st = b.state;
  out.soft = soft;
  out.nodes = std::move(nodes);
  // modal block: implicit Euler of q'' + (alpha + beta Lambda) q' + Lambda q = Phi^T f
  const VecX& lambda = model.lambda;
  out.A_q = VecX::Ones(lambda.size()) + dt * (m.alpha * VecX::Ones(lambda.size()) + m.beta * lambda) + dt * dt * lambda;
  out.r_q = st.qd + dt * model.gravity(m.node_mass, g_W).modal_force - dt * lambda.cwiseProduct(st.q);
  if ((st.tau_external.array() != 0).any()) out.r_q.noalias() += dt * (model.Phi.transpose() * st.tau_external);
  // residual block of the contact nodes
  out.h = dt * (dt + m.beta);
  const int k3 = 3 * static_cast<int>(out.nodes.size());
  out.G.resize(k3, k3);
  out.u_old.resize(k3);
  model.prepare_residuals(out.nodes);
  for (size_t j = 0; j < out.nodes.size(); ++j) {
    const MatX& C = model.residual(out.nodes[j]);
    for (size_t i = 0; i < out.nodes.size(); ++i) out.G.block<3, 3>(3 * i, 3 * j) = C.middleRows<3>(3 * out.nodes[i]);
    out.u_old.segment<3>(3 * j) = st.u_c.segment<3>(3 * out.nodes[j]);
  }
  if (k3 > 0) {
    // symmetric up to round-off; the inverse by Cholesky
    const MatX G_sym = (out.G + out.G.transpose()) / 2;
    out.G = G_sym;
    Eigen::LLT<MatX> llt(out.G);
    if (llt.info() != Eigen::Success) throw Error("soft actor '" + m.name + "': the residual compliance of its contact nodes is not positive definite");
    out.G_inv = llt.solve(MatX::Identity(k3, k3));
  } else {
    out.G_inv.resize(0, 0);
  }
}

void reduced_next_state(const SoftBody& b, const ReducedVariables& vars, const Eigen::Ref<const VecX>& y, const Vec3& g_W, real dt,
                        SoftState& next) {
  const ReducedSoftModel& model = *b.reduced;
  const SoftState& st = b.state;
  const int r = model.num_modes();
  next.tau_external = st.tau_external;
  next.qd = y.head(r);
  next.q = st.q + dt * next.qd;
  // the contact nodes' residual displacements, their forces, and the residual field they make
  next.u_c = VecX::Zero(st.x.size());
  if (!vars.nodes.empty()) {
    const VecX u_new = vars.u_old + dt * y.tail(3 * vars.nodes.size());
    const VecX f = vars.G_inv * u_new;
    for (size_t j = 0; j < vars.nodes.size(); ++j) next.u_c.noalias() += model.residual(vars.nodes[j]) * f.segment<3>(3 * j);
  }
  next.x = model.x_rest + model.gravity(b.model.node_mass, g_W).u_g + next.u_c;
  next.x.noalias() += model.Phi * next.q;
  next.v = (next.x - st.x) / dt;
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

// Hyperelastic energies, stresses and stiffness of linear tetrahedra (fem_elasticity.h).

#include "soft/fem_elasticity.h"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/SVD>
#include <cmath>

#include "core/spatial.h"
#include "superdex/physics/error.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

MaterialModel material_model_from_name(const std::string& name, const std::string& where) {
  if (name == "NeoHookean") return MaterialModel::NeoHookean;
  if (name == "StVK") return MaterialModel::StVK;
  if (name == "Corotated") return MaterialModel::Corotated;
  if (name == "Linear") return MaterialModel::Linear;
  throw Error(where + ": unknown material type '" + name + "' (expected NeoHookean, StVK, Corotated or Linear)");
}

ElasticMaterial ElasticMaterial::from_young_poisson(MaterialModel model, real E, real nu, const std::string& where) {
  if (!std::isfinite(E) || E <= 0) throw Error(where + ": Young's modulus must be positive, got " + std::to_string(E));
  if (!std::isfinite(nu) || nu <= -1 || nu >= real(0.5))
    throw Error(where + ": Poisson's ratio must be in (-1, 0.5), got " + std::to_string(nu));
  ElasticMaterial m;
  m.model = model;
  m.mu = E / (2 * (1 + nu));
  m.lambda = E * nu / ((1 + nu) * (1 - 2 * nu));
  return m;
}

TetRest make_tet_rest(const Vec3& X0, const Vec3& X1, const Vec3& X2, const Vec3& X3, real min_volume, const std::string& where) {
  Mat3 Dm;
  Dm << X1 - X0, X2 - X0, X3 - X0;
  const real volume = Dm.determinant() / 6;
  if (!std::isfinite(volume)) throw Error(where + ": non-finite node coordinates");
  if (volume < 0) throw Error(where + ": inverted tetrahedron (negative volume " + std::to_string(volume) + " m^3)");
  if (volume <= min_volume) throw Error(where + ": degenerate tetrahedron (volume " + std::to_string(volume) + " m^3)");
  return {Dm.inverse(), volume};
}

Mat3 deformation_gradient(const TetRest& rest, const Vec3* x) {
  Mat3 Ds;
  Ds << x[1] - x[0], x[2] - x[0], x[3] - x[0];
  return Ds * rest.Dm_inv;
}

namespace {

Vec9 vec(const Mat3& A) { return Eigen::Map<const Vec9>(A.data()); }
Mat3 unvec(const Vec9& v) { return Eigen::Map<const Mat3>(v.data()); }

Mat3 cofactor(const Mat3& F) {
  Mat3 C;
  C.col(0) = F.col(1).cross(F.col(2));
  C.col(1) = F.col(2).cross(F.col(0));
  C.col(2) = F.col(0).cross(F.col(1));
  return C;
}

// d2J/dF2 on column-stacked vec(F) (the "cross-product" Hessian of the determinant).
Mat9 determinant_hessian(const Mat3& F) {
  Mat9 H = Mat9::Zero();
  const Mat3 f0 = skew(F.col(0)), f1 = skew(F.col(1)), f2 = skew(F.col(2));
  H.block<3, 3>(0, 3) = -f2, H.block<3, 3>(0, 6) = f1;
  H.block<3, 3>(3, 0) = f2, H.block<3, 3>(3, 6) = -f0;
  H.block<3, 3>(6, 0) = -f1, H.block<3, 3>(6, 3) = f0;
  return H;
}

// The stable Neo-Hookean volume coefficient: lambda + mu, so that the model linearizes to
// linear elasticity with Lame parameters (mu, lambda) (Smith et al. 2018, section 3.4).
real neo_hookean_lambda(const ElasticMaterial& m) { return m.lambda + m.mu; }

// The linear material's stress of a (small-strain) gradient G.
Mat3 linear_stress(real mu, real lambda, const Mat3& G) {
  const Mat3 eps = (G + G.transpose()) / 2 - Mat3::Identity();
  return 2 * mu * eps + lambda * eps.trace() * Mat3::Identity();
}

// d(linear stress)/dG on vec: mu (I + T) + lambda vec(I) vec(I)^T, T the transpose permutation.
Mat9 linear_stress_derivative(real mu, real lambda) {
  Mat9 H = mu * Mat9::Identity();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) H(i + 3 * j, j + 3 * i) += mu;
  const Vec9 I = vec(Mat3::Identity());
  H += lambda * I * I.transpose();
  return H;
}

}  // namespace

Mat3 polar_rotation(const Mat3& F) {
  Eigen::JacobiSVD<Mat3> svd(F, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Mat3 U = svd.matrixU(), V = svd.matrixV();
  // keep a proper rotation: flip the axis of the smallest singular value when F is inverted
  if ((U * V.transpose()).determinant() < 0) U.col(2) = -U.col(2);
  return U * V.transpose();
}

real energy_density(const ElasticMaterial& m, const Mat3& F, const Mat3& R) {
  switch (m.model) {
    case MaterialModel::NeoHookean: {
      const real J = F.determinant(), lam = neo_hookean_lambda(m);
      return m.mu / 2 * (F.squaredNorm() - 3) - m.mu * (J - 1) + lam / 2 * (J - 1) * (J - 1);
    }
    case MaterialModel::StVK: {
      const Mat3 E = (F.transpose() * F - Mat3::Identity()) / 2;
      return m.mu * E.squaredNorm() + m.lambda / 2 * E.trace() * E.trace();
    }
    case MaterialModel::Corotated:
    case MaterialModel::Linear: {
      const Mat3 G = m.model == MaterialModel::Corotated ? Mat3(R.transpose() * F) : F;
      const Mat3 eps = (G + G.transpose()) / 2 - Mat3::Identity();
      return m.mu * eps.squaredNorm() + m.lambda / 2 * eps.trace() * eps.trace();
    }
  }
  return 0;
}

Mat3 first_piola(const ElasticMaterial& m, const Mat3& F, const Mat3& R) {
  switch (m.model) {
    case MaterialModel::NeoHookean: {
      const real J = F.determinant(), lam = neo_hookean_lambda(m);
      return m.mu * F + (lam * (J - 1) - m.mu) * cofactor(F);
    }
    case MaterialModel::StVK: {
      const Mat3 E = (F.transpose() * F - Mat3::Identity()) / 2;
      return F * (2 * m.mu * E + m.lambda * E.trace() * Mat3::Identity());
    }
    case MaterialModel::Corotated: return R * linear_stress(m.mu, m.lambda, R.transpose() * F);
    case MaterialModel::Linear: return linear_stress(m.mu, m.lambda, F);
  }
  return Mat3::Zero();
}

Mat9 stress_derivative(const ElasticMaterial& m, const Mat3& F, const Mat3& R) {
  switch (m.model) {
    case MaterialModel::NeoHookean: {
      const real J = F.determinant(), lam = neo_hookean_lambda(m);
      const Vec9 g = vec(cofactor(F));
      return m.mu * Mat9::Identity() + lam * g * g.transpose() + (lam * (J - 1) - m.mu) * determinant_hessian(F);
    }
    case MaterialModel::StVK: {
      // columns: dP = dF S + F (2 mu dE + lambda tr(dE) I), dE = sym(F^T dF), for each basis dF
      const Mat3 E = (F.transpose() * F - Mat3::Identity()) / 2;
      const Mat3 S = 2 * m.mu * E + m.lambda * E.trace() * Mat3::Identity();
      Mat9 H;
      for (int k = 0; k < 9; ++k) {
        Vec9 e = Vec9::Zero();
        e[k] = 1;
        const Mat3 dF = unvec(e);
        const Mat3 dE = (F.transpose() * dF + dF.transpose() * F) / 2;
        H.col(k) = vec(dF * S + F * (2 * m.mu * dE + m.lambda * dE.trace() * Mat3::Identity()));
      }
      return H;
    }
    case MaterialModel::Corotated: {
      // P(F) = R L(R^T F): dP = R L'(R^T dF), i.e. the linear operator conjugated by R
      Eigen::Matrix<real, 9, 9> Rk = Mat9::Zero();
      for (int j = 0; j < 3; ++j) Rk.block<3, 3>(3 * j, 3 * j) = R;  // vec(R A) = (I kron R) vec(A)
      return Rk * linear_stress_derivative(m.mu, m.lambda) * Rk.transpose();
    }
    case MaterialModel::Linear: return linear_stress_derivative(m.mu, m.lambda);
  }
  return Mat9::Zero();
}

Mat9 neo_hookean_projected_stress_derivative(const ElasticMaterial& m, const Mat3& F) {
  // rotation-variant SVD: U and V proper rotations, the sign of det F on the last singular value
  Eigen::JacobiSVD<Mat3> svd(F, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Mat3 U = svd.matrixU(), V = svd.matrixV();
  Vec3 sigma = svd.singularValues();
  if (U.determinant() < 0) U.col(2) = -U.col(2), sigma[2] = -sigma[2];
  if (V.determinant() < 0) V.col(2) = -V.col(2), sigma[2] = -sigma[2];
  const real J = sigma.prod(), lam = neo_hookean_lambda(m);
  // Hessian = mu I + lam g g^T + c H_J, with H_J the Hessian of det F
  const real c = lam * (J - 1) - m.mu;
  Mat9 H = Mat9::Zero();
  auto add_mode = [&](real eigenvalue, const Mat3& Q_sigma) {
    if (eigenvalue <= 0) return;
    const Vec9 q = vec(U * Q_sigma * V.transpose());
    H.noalias() += eigenvalue * q * q.transpose();
  };
  // scaling modes: the 3 x 3 Hessian with respect to the singular values
  const Vec3 dJ(sigma[1] * sigma[2], sigma[0] * sigma[2], sigma[0] * sigma[1]);
  Mat3 A = m.mu * Mat3::Identity() + lam * dJ * dJ.transpose();
  A(0, 1) += c * sigma[2], A(1, 0) += c * sigma[2];
  A(0, 2) += c * sigma[1], A(2, 0) += c * sigma[1];
  A(1, 2) += c * sigma[0], A(2, 1) += c * sigma[0];
  Eigen::SelfAdjointEigenSolver<Mat3> eig(A);
  for (int i = 0; i < 3; ++i) add_mode(eig.eigenvalues()[i], eig.eigenvectors().col(i).asDiagonal());
  // twist and flip modes of each pair (i, j), k the third axis: mu + c sigma_k and mu - c sigma_k
  const real r = 1 / std::sqrt(real(2));
  for (int k = 0; k < 3; ++k) {
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    Mat3 T = Mat3::Zero(), L = Mat3::Zero();
    T(i, j) = -r, T(j, i) = r;
    L(i, j) = r, L(j, i) = r;
    add_mode(m.mu + c * sigma[k], T);
    add_mode(m.mu - c * sigma[k], L);
  }
  return H;
}

void tet_derivatives_at(const ElasticMaterial& m, const TetRest& rest, const Mat3& F, const Mat3& R, Vec12* gradient,
                        Mat12* hessian, bool project_spd) {
  if (!gradient && !hessian) return;
  // F = Ds Dm^-1 is linear in the node positions: dF(i, j)/dx_a(c) = delta_ic D(a, j), with D's
  // rows those of Dm^-1 for nodes 1-3 and minus their sum for node 0
  Eigen::Matrix<real, 4, 3> D;
  D.bottomRows<3>() = rest.Dm_inv;
  D.row(0) = -rest.Dm_inv.colwise().sum();
  if (gradient) {
    const Mat3 P = rest.volume * first_piola(m, F, R);
    for (int a = 0; a < 4; ++a) gradient->segment<3>(3 * a) = P * D.row(a).transpose();
  }
  if (hessian) {
    Mat9 H = project_spd && m.model == MaterialModel::NeoHookean ? neo_hookean_projected_stress_derivative(m, F)
                                                                    : stress_derivative(m, F, R);
    // linear and corotated stress derivatives are positive semi-definite already; others are
    // projected only when a Cholesky factorization shows they are indefinite (most elements
    // at moderate strain are not)
    const bool psd = m.model != MaterialModel::StVK;
    if (project_spd && !psd && Eigen::LLT<Mat9>((H + H.transpose()) / 2).info() != Eigen::Success) {
      // clamp negative eigenvalues of the symmetric stress derivative
      Eigen::SelfAdjointEigenSolver<Mat9> eig((H + H.transpose()) / 2);
      const Vec9 l = eig.eigenvalues().cwiseMax(real(0));
      H = eig.eigenvectors() * l.asDiagonal() * eig.eigenvectors().transpose();
    }
    // block (a, b) of dF/dx^T H dF/dx: sum over columns j, l of F of D(a, j) D(b, l) H_jl, with
    // H_jl the 3 x 3 block of H coupling column j with column l
    Mat3 T[4][3];
    for (int a = 0; a < 4; ++a)
      for (int l = 0; l < 3; ++l)
        T[a][l] = D(a, 0) * H.block<3, 3>(0, 3 * l) + D(a, 1) * H.block<3, 3>(3, 3 * l) + D(a, 2) * H.block<3, 3>(6, 3 * l);
    for (int a = 0; a < 4; ++a)
      for (int b = a; b < 4; ++b) {
        const Mat3 block = rest.volume * (D(b, 0) * T[a][0] + D(b, 1) * T[a][1] + D(b, 2) * T[a][2]);
        hessian->block<3, 3>(3 * a, 3 * b) = block;
        if (b != a) hessian->block<3, 3>(3 * b, 3 * a) = block.transpose();
      }
  }
}

real tet_energy(const ElasticMaterial& m, const TetRest& rest, const Vec3* x, const Mat3& R, Vec12* gradient,
                Mat12* hessian, bool project_spd) {
  const Mat3 F = deformation_gradient(rest, x);
  tet_derivatives_at(m, rest, F, R, gradient, hessian, project_spd);
  return rest.volume * energy_density(m, F, R);
}

void tet_derivatives(const ElasticMaterial& m, const TetRest& rest, const Vec3* x, const Mat3& R, Vec12* gradient,
                     Mat12* hessian, bool project_spd) {
  tet_derivatives_at(m, rest, deformation_gradient(rest, x), R, gradient, hessian, project_spd);
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

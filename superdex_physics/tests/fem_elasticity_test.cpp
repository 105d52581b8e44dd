/// @file fem_elasticity_test.cpp
/// The tetrahedral element library against independent checks: stresses are the derivative of
/// the energy and stiffnesses the derivative of the stress (central finite differences), the
/// rest state is stress free, hyperelastic energies are invariant under rotation, all models
/// agree with linear elasticity for small strains, a uniaxial stretch gives the analytic stress,
/// and inverted or degenerate rest tetrahedra are refused.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <random>

#include "soft/fem_elasticity.h"
#include "superdex/physics/error.h"

namespace superdex::physics {
namespace {

const MaterialModel kModels[] = {MaterialModel::NeoHookean, MaterialModel::StVK, MaterialModel::Corotated, MaterialModel::Linear};

ElasticMaterial material(MaterialModel model) {
  return ElasticMaterial::from_young_poisson(model, 1e5, 0.3, "test");
}

Mat3 random_near_identity(std::mt19937& rng, double scale) {
  std::uniform_real_distribution<double> u(-scale, scale);
  Mat3 F = Mat3::Identity();
  for (int i = 0; i < 9; ++i) F.data()[i] += u(rng);
  return F;
}

Mat3 rotation(double angle, Vec3 axis) { return Eigen::AngleAxis<double>(angle, axis.normalized()).toRotationMatrix(); }

// The closed-form projection of the Neo-Hookean Hessian equals clamping the eigenvalues of the
// dense stress derivative, at rest, stretched, compressed, sheared and inverted.
TEST(FemElasticity, NeoHookeanAnalyticProjectionMatchesTheEigenDecomposition) {
  std::mt19937 rng(7);
  const ElasticMaterial m = ElasticMaterial::from_young_poisson(MaterialModel::NeoHookean, 1e5, 0.45, "test");
  std::vector<Mat3> cases = {Mat3::Identity(), Vec3(1.2, 0.9, 1.0).asDiagonal(), Vec3(0.7, 0.7, 0.7).asDiagonal(),
                             Vec3(1.0, 1.0, -0.5).asDiagonal(), rotation(0.7, Vec3(1, 2, 3)) * Vec3(1.1, 0.8, 0.95).asDiagonal()};
  for (int trial = 0; trial < 40; ++trial) cases.push_back(random_near_identity(rng, trial < 20 ? 0.05 : 0.6));
  for (const Mat3& F : cases) {
    const Mat9 H = stress_derivative(m, F, Mat3::Identity());
    Eigen::SelfAdjointEigenSolver<Mat9> eig((H + H.transpose()) / 2);
    const Mat9 expected = eig.eigenvectors() * eig.eigenvalues().cwiseMax(0).asDiagonal() * eig.eigenvectors().transpose();
    const Mat9 analytic = neo_hookean_projected_stress_derivative(m, F);
    EXPECT_LT((analytic - expected).norm(), 1e-8 * expected.norm()) << "F =\n" << F;
  }
}

TEST(FemElasticity, StressIsTheDerivativeOfTheEnergy) {
  std::mt19937 rng(1);
  for (MaterialModel model : kModels) {
    const ElasticMaterial m = material(model);
    for (int trial = 0; trial < 10; ++trial) {
      const Mat3 F = random_near_identity(rng, 0.3);
      const Mat3 R = polar_rotation(F);
      const Mat3 P = first_piola(m, F, R);
      Mat3 fd;
      const double h = 1e-6;
      for (int k = 0; k < 9; ++k) {
        Mat3 Fp = F, Fm = F;
        Fp.data()[k] += h, Fm.data()[k] -= h;
        // the corotated model keeps R fixed: differentiate with the same R
        fd.data()[k] = (energy_density(m, Fp, R) - energy_density(m, Fm, R)) / (2 * h);
      }
      EXPECT_LT((P - fd).norm(), 1e-5 * (1 + P.norm())) << "model " << static_cast<int>(model);
    }
  }
}

TEST(FemElasticity, StressDerivativeMatchesFiniteDifferences) {
  std::mt19937 rng(2);
  for (MaterialModel model : kModels) {
    const ElasticMaterial m = material(model);
    for (int trial = 0; trial < 5; ++trial) {
      const Mat3 F = random_near_identity(rng, 0.4);
      const Mat3 R = polar_rotation(F);
      const Mat9 H = stress_derivative(m, F, R);
      Mat9 fd;
      const double h = 1e-6;
      for (int k = 0; k < 9; ++k) {
        Mat3 Fp = F, Fm = F;
        Fp.data()[k] += h, Fm.data()[k] -= h;
        const Mat3 dP = (first_piola(m, Fp, R) - first_piola(m, Fm, R)) / (2 * h);
        fd.col(k) = Eigen::Map<const Vec9>(dP.data());
      }
      EXPECT_LT((H - fd).norm(), 1e-4 * (1 + H.norm())) << "model " << static_cast<int>(model);
    }
  }
}

TEST(FemElasticity, ElementGradientAndHessianMatchFiniteDifferences) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-0.01, 0.01);
  const Vec3 X[4] = {Vec3(0, 0, 0), Vec3(0.1, 0, 0), Vec3(0.02, 0.09, 0), Vec3(0.03, 0.02, 0.11)};
  const TetRest rest = make_tet_rest(X[0], X[1], X[2], X[3], 1e-12, "tet");
  for (MaterialModel model : kModels) {
    const ElasticMaterial m = material(model);
    Vec3 x[4];
    for (int i = 0; i < 4; ++i) x[i] = rotation(0.3, Vec3(1, 2, 3)) * X[i] + Vec3(u(rng), u(rng), u(rng));
    const Mat3 R = polar_rotation(deformation_gradient(rest, x));
    Vec12 g;
    Mat12 H;
    tet_energy(m, rest, x, R, &g, &H, false);
    Vec12 g_fd;
    Mat12 H_fd;
    const double h = 1e-7;
    for (int k = 0; k < 12; ++k) {
      Vec3 xp[4], xm[4];
      for (int i = 0; i < 4; ++i) xp[i] = xm[i] = x[i];
      xp[k / 3][k % 3] += h, xm[k / 3][k % 3] -= h;
      Vec12 gp, gm;
      g_fd[k] = (tet_energy(m, rest, xp, R, &gp, nullptr, false) - tet_energy(m, rest, xm, R, &gm, nullptr, false)) / (2 * h);
      H_fd.col(k) = (gp - gm) / (2 * h);
    }
    EXPECT_LT((g - g_fd).norm(), 1e-5 * (1 + g.norm())) << "model " << static_cast<int>(model);
    EXPECT_LT((H - H_fd).norm(), 1e-4 * (1 + H.norm())) << "model " << static_cast<int>(model);
    // forces on the element sum to zero (translation invariance)
    EXPECT_LT((g.segment<3>(0) + g.segment<3>(3) + g.segment<3>(6) + g.segment<3>(9)).norm(), 1e-9 * (1 + g.norm()));
  }
}

TEST(FemElasticity, RestStateIsStressFreeAndAllModelsLinearizeToLinearElasticity) {
  const Mat9 linear = stress_derivative(material(MaterialModel::Linear), Mat3::Identity(), Mat3::Identity());
  for (MaterialModel model : kModels) {
    const ElasticMaterial m = material(model);
    EXPECT_NEAR(energy_density(m, Mat3::Identity(), Mat3::Identity()), 0, 1e-12);
    EXPECT_LT(first_piola(m, Mat3::Identity(), Mat3::Identity()).norm(), 1e-9);
    EXPECT_LT((stress_derivative(m, Mat3::Identity(), Mat3::Identity()) - linear).norm(), 1e-6 * linear.norm())
        << "model " << static_cast<int>(model);
  }
}

TEST(FemElasticity, HyperelasticEnergiesAreRotationInvariant) {
  std::mt19937 rng(4);
  for (MaterialModel model : {MaterialModel::NeoHookean, MaterialModel::StVK, MaterialModel::Corotated}) {
    const ElasticMaterial m = material(model);
    const Mat3 F = random_near_identity(rng, 0.3);
    const Mat3 Q = rotation(1.1, Vec3(0.3, -1, 0.5));
    // the corotated model's R follows the deformation
    EXPECT_NEAR(energy_density(m, Q * F, polar_rotation(Q * F)), energy_density(m, F, polar_rotation(F)),
                1e-9 * (1 + energy_density(m, F, polar_rotation(F))));
  }
}

TEST(FemElasticity, UniaxialStretchGivesTheAnalyticStress) {
  // F = diag(1 + e, 1, 1): linear P11 = (lambda + 2 mu) e, P22 = P33 = lambda e
  const ElasticMaterial m = material(MaterialModel::Linear);
  const double e = 0.01;
  const Mat3 P = first_piola(m, Vec3(1 + e, 1, 1).asDiagonal(), Mat3::Identity());
  EXPECT_NEAR(P(0, 0), (m.lambda + 2 * m.mu) * e, 1e-9 * m.mu);
  EXPECT_NEAR(P(1, 1), m.lambda * e, 1e-9 * m.mu);
  // StVK exactly: S11 = (lambda + 2 mu) E11 with E11 = ((1+e)^2 - 1)/2, P11 = (1 + e) S11
  const ElasticMaterial s = material(MaterialModel::StVK);
  const double E11 = ((1 + e) * (1 + e) - 1) / 2;
  EXPECT_NEAR(first_piola(s, Vec3(1 + e, 1, 1).asDiagonal(), Mat3::Identity())(0, 0), (1 + e) * (s.lambda + 2 * s.mu) * E11, 1e-6);
}

TEST(FemElasticity, NeoHookeanResistsInversion) {
  // an inverted element (J < 0) has finite, positive energy and a stress pushing it back
  const ElasticMaterial m = material(MaterialModel::NeoHookean);
  const Mat3 F = Vec3(1, 1, -0.2).asDiagonal();
  EXPECT_GT(energy_density(m, F, Mat3::Identity()), energy_density(m, Vec3(1, 1, 0.2).asDiagonal(), Mat3::Identity()));
  EXPECT_LT(first_piola(m, F, Mat3::Identity())(2, 2), 0) << "the stress drives the third axis back towards +1";
}

TEST(FemElasticity, ProjectedHessianIsPositiveSemidefinite) {
  const ElasticMaterial m = material(MaterialModel::NeoHookean);
  const Vec3 X[4] = {Vec3(0, 0, 0), Vec3(0.1, 0, 0), Vec3(0, 0.1, 0), Vec3(0, 0, 0.1)};
  const TetRest rest = make_tet_rest(X[0], X[1], X[2], X[3], 1e-12, "tet");
  // strongly compressed: the raw Hessian is indefinite
  const Vec3 x[4] = {X[0], X[1] * 0.3, X[2] * 1.5, X[3] * 0.2};
  Mat12 raw, projected;
  tet_energy(m, rest, x, Mat3::Identity(), nullptr, &raw, false);
  tet_energy(m, rest, x, Mat3::Identity(), nullptr, &projected, true);
  Eigen::SelfAdjointEigenSolver<Mat12> eig_raw(raw), eig_proj(projected);
  EXPECT_LT(eig_raw.eigenvalues().minCoeff(), 0);
  EXPECT_GT(eig_proj.eigenvalues().minCoeff(), -1e-9 * eig_proj.eigenvalues().maxCoeff());
}

TEST(FemElasticity, BadRestTetrahedraAndMaterialsAreRefused) {
  using ::testing::HasSubstr;
  try {
    make_tet_rest(Vec3(0, 0, 0), Vec3(0, 1, 0), Vec3(1, 0, 0), Vec3(0, 0, 1), 1e-12, "duck.mochi.h5: mesh/connectivity[7]");
    FAIL();
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("duck.mochi.h5: mesh/connectivity[7]: inverted tetrahedron"));
  }
  try {
    make_tet_rest(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0), Vec3(0, 0, 1), 1e-12, "t");
    FAIL();
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("degenerate tetrahedron"));
  }
  EXPECT_THROW(ElasticMaterial::from_young_poisson(MaterialModel::Linear, 1e5, 0.5, "m"), Error);
  EXPECT_THROW(ElasticMaterial::from_young_poisson(MaterialModel::Linear, -1, 0.3, "m"), Error);
  try {
    material_model_from_name("Rubber", "prefab.json: actors.soft[0].material.type");
    FAIL();
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("unknown material type 'Rubber'"));
  }
  const ElasticMaterial m = ElasticMaterial::from_young_poisson(MaterialModel::Linear, 2.6e5, 0.3, "m");
  EXPECT_NEAR(m.mu, 1e5, 1e-6);
  EXPECT_NEAR(m.lambda, 2.6e5 * 0.3 / (1.3 * 0.4), 1e-6);
}

}  // namespace
}  // namespace superdex::physics

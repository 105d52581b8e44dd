#pragma once
// Hyperelastic tetrahedral elements: energy density Psi(F), first Piola-Kirchhoff stress
// P = dPsi/dF and its differential, and per-tetrahedron energy, gradient and Hessian with
// respect to the four node positions. F = Ds Dm^-1 with Ds, Dm the edge matrices
// [x1 - x0, x2 - x0, x3 - x0] of the deformed and rest tetrahedra. Units: Pa for mu, lambda
// and P; J for energies; N for gradients.

#include <string>

#include "superdex/physics/real.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

using Vec9 = Eigen::Matrix<real, 9, 1>;
using Mat9 = Eigen::Matrix<real, 9, 9>;
using Vec12 = Eigen::Matrix<real, 12, 1>;
using Mat12 = Eigen::Matrix<real, 12, 12>;

enum class MaterialModel {
  NeoHookean,  // stable Neo-Hookean (Smith et al. 2018): mu/2 (I_C - 3) - mu (J - 1) + (lambda + mu)/2 (J - 1)^2,
               // linearizing to Lame (mu, lambda); well defined when inverted
  StVK,        // St. Venant-Kirchhoff: mu E:E + lambda/2 tr(E)^2, E = (F^T F - I)/2
  Corotated,   // corotated linear: linear elasticity of R^T F with the rotation R of F held fixed (set per step)
  Linear,      // linear: mu eps:eps + lambda/2 tr(eps)^2, eps = sym(F) - I
};

/// Parses "NeoHookean", "StVK", "Corotated", "Linear"; throws superdex::Error naming `where`.
MaterialModel material_model_from_name(const std::string& name, const std::string& where);

struct ElasticMaterial {
  MaterialModel model = MaterialModel::NeoHookean;
  real mu = 0;      // shear modulus (Pa)
  real lambda = 0;  // first Lame parameter (Pa)

  /// From Young's modulus E (Pa) and Poisson's ratio nu (-1 < nu < 0.5); throws naming `where`.
  static ElasticMaterial from_young_poisson(MaterialModel model, real E, real nu, const std::string& where);
};

/// Rest data of a tetrahedron.
struct TetRest {
  Mat3 Dm_inv;  // inverse rest edge matrix
  real volume;  // rest volume (m^3), positive
};

/// Rest data from the four rest positions; throws superdex::Error naming `where` for an
/// inverted (negative volume) or degenerate (volume below `min_volume`) tetrahedron.
TetRest make_tet_rest(const Vec3& X0, const Vec3& X1, const Vec3& X2, const Vec3& X3, real min_volume, const std::string& where);

/// Deformation gradient of a tetrahedron at positions x.
Mat3 deformation_gradient(const TetRest& rest, const Vec3* x);

/// Energy density Psi(F) (J/m^3). For Corotated, R is the fixed rotation (ignored otherwise).
real energy_density(const ElasticMaterial& m, const Mat3& F, const Mat3& R);
/// First Piola-Kirchhoff stress P = dPsi/dF (Pa).
Mat3 first_piola(const ElasticMaterial& m, const Mat3& F, const Mat3& R);
/// d2Psi/dF2 as a 9 x 9 matrix on column-stacked vec(F).
Mat9 stress_derivative(const ElasticMaterial& m, const Mat3& F, const Mat3& R);

/// The Neo-Hookean stress derivative projected to the nearest positive semi-definite matrix, in
/// closed form from the SVD of F (the Hessian's nine eigenpairs: three scaling modes from a 3 x 3
/// matrix, three twists and three flips; Smith, de Goes and Kim 2019, "Analytic Eigensystems for
/// Isotropic Distortion Energies"). Equals clamping the eigenvalues of stress_derivative().
Mat9 neo_hookean_projected_stress_derivative(const ElasticMaterial& m, const Mat3& F);

/// Rotation of the polar decomposition F = R S (det R = +1, also for inverted F).
Mat3 polar_rotation(const Mat3& F);

/// Element energy V Psi (J); its gradient with respect to the 12 node coordinates (N) and its
/// Hessian (N/m), projected to the nearest positive semi-definite matrix when `project_spd`.
real tet_energy(const ElasticMaterial& m, const TetRest& rest, const Vec3* x, const Mat3& R, Vec12* gradient,
                Mat12* hessian, bool project_spd);
/// The gradient and Hessian of tet_energy() alone (the energy is not evaluated).
void tet_derivatives(const ElasticMaterial& m, const TetRest& rest, const Vec3* x, const Mat3& R, Vec12* gradient,
                     Mat12* hessian, bool project_spd);
/// The same at a deformation gradient F = deformation_gradient(rest, x) already computed.
void tet_derivatives_at(const ElasticMaterial& m, const TetRest& rest, const Mat3& F, const Mat3& R, Vec12* gradient,
                        Mat12* hessian, bool project_spd);

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

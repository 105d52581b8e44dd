// SoftMaterialParams -> SoftMaterial (material_from_params.h).

#include "soft/material_from_params.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

SoftMaterial soft_material_from_params(const SoftMaterialParams& mp, const TetMesh& mesh) {
  SoftMaterial material;
  material.density = mp.density;
  material.damping_alpha = mp.mass_damping_coefficient;
  material.damping_beta = mp.stiffness_damping_coefficient;
  real E = 0, nu = 0;
  switch (mp.type) {
    case SoftMaterialType::NeoHookean: material.type = "NeoHookean", E = mp.neo_hookean.youngs_modulus, nu = mp.neo_hookean.poisson_ratio; break;
    case SoftMaterialType::StVenantKirchhoff:
      material.type = "StVK", E = mp.st_venant_kirchhoff.youngs_modulus, nu = mp.st_venant_kirchhoff.poisson_ratio;
      break;
    case SoftMaterialType::LinearElastic: material.type = "Linear", E = mp.linear_elastic.youngs_modulus, nu = mp.linear_elastic.poisson_ratio; break;
    default: break;
  }
  // the shape's per-element values, when it has them, take precedence
  if (mesh.youngs_modulus.empty()) material.youngs_modulus = E;
  if (mesh.poisson_ratio.empty()) material.poisson_ratio = nu;
  return material;
}

SoftMaterialParams soft_material_params_from(const SoftMaterial& m, const TetMesh& mesh, bool* corotated) {
  SoftMaterialParams p;
  p.density = m.density;
  p.mass_damping_coefficient = m.damping_alpha;
  p.stiffness_damping_coefficient = m.damping_beta;
  if (corotated) *corotated = m.type == "Corotated";
  real *E = &p.neo_hookean.youngs_modulus, *nu = &p.neo_hookean.poisson_ratio;
  if (m.type == "StVK" || m.type == "StVenantKirchhoff") {
    p.type = SoftMaterialType::StVenantKirchhoff, E = &p.st_venant_kirchhoff.youngs_modulus, nu = &p.st_venant_kirchhoff.poisson_ratio;
  } else if (m.type == "Linear" || m.type == "LinearElastic") {
    p.type = SoftMaterialType::LinearElastic, E = &p.linear_elastic.youngs_modulus, nu = &p.linear_elastic.poisson_ratio;
  }
  // soft_body.cpp's fallbacks when neither the material nor the mesh gives a value
  *E = m.youngs_modulus ? *m.youngs_modulus : mesh.youngs_modulus.empty() ? real(1e5) : mesh.youngs_modulus[0];
  *nu = m.poisson_ratio ? *m.poisson_ratio : mesh.poisson_ratio.empty() ? real(0.3) : mesh.poisson_ratio[0];
  return p;
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

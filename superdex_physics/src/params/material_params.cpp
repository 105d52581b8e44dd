// Soft materials: names, fibre angles and validation (material_params.h).

#include "superdex/physics/params/material_params.h"

#include <cmath>

#include "params/check.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

const char* soft_material_type_name(SoftMaterialType type) {
  switch (type) {
    case SoftMaterialType::NeoHookean: return "NeoHookean";
    case SoftMaterialType::StVenantKirchhoff: return "StVenantKirchhoff";
    case SoftMaterialType::LinearElastic: return "LinearElastic";
    case SoftMaterialType::ActiveNeoHookean: return "ActiveNeoHookean";
    case SoftMaterialType::ActiveShapeTargetingArap: return "ActiveShapeTargetingArap";
    case SoftMaterialType::Arap: return "Arap";
  }
  return "?";
}

real ActiveAnisoArapMaterialParams::theta() const { return std::atan2(aniso_dir[2], aniso_dir[0]); }
real ActiveAnisoArapMaterialParams::phi() const { return std::asin(std::clamp(aniso_dir[1], real(-1), real(1))); }
Real3 ActiveAnisoArapMaterialParams::fiber_direction(real theta, real phi) {
  return Real3(std::cos(phi) * std::cos(theta), std::sin(phi), std::cos(phi) * std::sin(theta));
}

int PerElementSoftMaterialData::num_elements() const {
  const bool arap = type == SoftMaterialType::Arap || type == SoftMaterialType::ActiveShapeTargetingArap;
  return static_cast<int>(arap ? arap_stiffness.size() : poisson_ratio.size());
}

namespace {

// The Young's modulus and Poisson's ratio of an isotropic material.
template <class P>
void check_lame(const FieldCheck& c, const P& p) {
  c.positive("youngs_modulus", p.youngs_modulus);
  if (!(std::isfinite(p.poisson_ratio) && p.poisson_ratio > -1 && p.poisson_ratio < real(0.5)))
    c.fail("poisson_ratio", "must be in (-1, 0.5), got " + value_text(p.poisson_ratio));
}

// This engine's element Hessians are projected to positive semi-definite matrices (its Newton
// solve factors an SPD matrix): the strategies that do that are the material's default and Projection.
void check_psd(const FieldCheck& c, MaterialPsdStrategy s) {
  if (s != MaterialPsdStrategy::MaterialDefault && s != MaterialPsdStrategy::Projection)
    c.fail("psd_strategy",
           "only MATERIAL_DEFAULT or PROJECTION is available: this engine projects each element's Hessian to the nearest "
           "positive semi-definite matrix, got " + std::to_string(static_cast<int>(s)));
}

}  // namespace

void validate(const SoftMaterialParams& p, const std::string& where) {
  const FieldCheck c(where);
  c.positive("density", p.density);
  c.non_negative("mass_damping_coefficient", p.mass_damping_coefficient);
  c.non_negative("stiffness_damping_coefficient", p.stiffness_damping_coefficient);
  switch (p.type) {
    case SoftMaterialType::NeoHookean:
      check_lame(c.nested("neo_hookean"), p.neo_hookean);
      check_psd(c.nested("neo_hookean"), p.neo_hookean.psd_strategy);
      break;
    case SoftMaterialType::StVenantKirchhoff:
      check_lame(c.nested("st_venant_kirchhoff"), p.st_venant_kirchhoff);
      check_psd(c.nested("st_venant_kirchhoff"), p.st_venant_kirchhoff.psd_strategy);
      break;
    case SoftMaterialType::LinearElastic:
      check_lame(c.nested("linear_elastic"), p.linear_elastic);
      break;
    default:
      c.fail("type", std::string(soft_material_type_name(p.type)) +
                         " is not available yet: this engine simulates NEO_HOOKEAN, ST_VENANT_KIRCHHOFF and LINEAR_ELASTIC soft bodies");
  }
}

void validate(const PerElementSoftMaterialData& d, int num_elements, const std::string& where) {
  const FieldCheck c(where);
  auto sized = [&](const char* field, const std::vector<real>& v, size_t per_element) {
    if (v.size() != per_element * static_cast<size_t>(num_elements))
      c.fail(field, "must have " + std::to_string(per_element * num_elements) + " values (" + std::to_string(per_element) +
                        " per element), got " + std::to_string(v.size()));
  };
  if (d.psd_strategy != MaterialPsdStrategy::MaterialDefault) check_psd(c, d.psd_strategy);
  switch (d.type) {
    case SoftMaterialType::NeoHookean:
    case SoftMaterialType::StVenantKirchhoff:
    case SoftMaterialType::LinearElastic:
      sized("youngs_modulus", d.youngs_modulus, 1);
      sized("poisson_ratio", d.poisson_ratio, 1);
      for (size_t e = 0; e < d.youngs_modulus.size(); ++e) {
        c.positive("youngs_modulus[" + std::to_string(e) + "]", d.youngs_modulus[e]);
        const real nu = d.poisson_ratio[e];
        if (!(std::isfinite(nu) && nu > -1 && nu < real(0.5)))
          c.fail("poisson_ratio[" + std::to_string(e) + "]", "must be in (-1, 0.5), got " + value_text(nu));
      }
      break;
    default:
      c.fail("type", std::string(soft_material_type_name(d.type)) + " is not available yet for per-element materials");
  }
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

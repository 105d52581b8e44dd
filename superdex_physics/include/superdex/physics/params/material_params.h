#pragma once
/// @file material_params.h
/// Soft materials (SuperDex's names and defaults). Moduli in Pa, densities in kg/m^3, Poisson's
/// ratios in (-1, 0.5).

#include <string>
#include <vector>

#include "superdex/physics/types.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

/// Constitutive models of soft bodies.
enum class SoftMaterialType {
  NeoHookean,              ///< stable Neo-Hookean (large deformations)
  StVenantKirchhoff,       ///< St. Venant-Kirchhoff (unstable under large compression)
  LinearElastic,           ///< Hookean: small deformations only
  ActiveNeoHookean,        ///< Neo-Hookean plus an active anisotropic fibre
  ActiveShapeTargetingArap,  ///< as-rigid-as-possible towards a target shape tensor
  Arap,                    ///< as-rigid-as-possible
};
const char* soft_material_type_name(SoftMaterialType type);

/// How a material keeps its Hessian positive semi-definite.
enum class MaterialPsdStrategy { MaterialDefault, None, Projection, Fast, AbsEigenProjection, PerTermProjection };

struct LinearElasticMaterialParams {
  real youngs_modulus = real(1e5);
  real poisson_ratio = real(0.45);
  bool operator==(const LinearElasticMaterialParams&) const = default;
};
struct StVenantKirchhoffMaterialParams {
  real youngs_modulus = real(1e5);
  real poisson_ratio = real(0.45);
  MaterialPsdStrategy psd_strategy = MaterialPsdStrategy::Projection;
  bool operator==(const StVenantKirchhoffMaterialParams&) const = default;
};
struct NeoHookeanMaterialParams {
  real youngs_modulus = real(1e5);
  real poisson_ratio = real(0.45);
  MaterialPsdStrategy psd_strategy = MaterialPsdStrategy::Projection;
  bool operator==(const NeoHookeanMaterialParams&) const = default;
};
/// The active fibre of ActiveNeoHookean: stiffness `alpha` (Pa, >= 0) along `aniso_dir` (unit,
/// (cos(phi) cos(theta), sin(phi), cos(phi) sin(theta))) towards the reference `length` (>= 0).
struct ActiveAnisoArapMaterialParams {
  real alpha = 1000;
  real length = 1;
  Real3 aniso_dir = Real3::UnitX();
  MaterialPsdStrategy psd_strategy = MaterialPsdStrategy::Projection;
  real theta() const;  ///< rad
  real phi() const;    ///< rad
  static Real3 fiber_direction(real theta, real phi);
  bool operator==(const ActiveAnisoArapMaterialParams&) const = default;
};
struct ActiveNeoHookeanMaterialParams {
  NeoHookeanMaterialParams passive_isotropic;
  ActiveAnisoArapMaterialParams active_anisotropic;
  bool operator==(const ActiveNeoHookeanMaterialParams&) const = default;
};
struct ArapMaterialParams {
  real stiffness = 1000;  ///< mu, Pa, > 0
  MaterialPsdStrategy psd_strategy = MaterialPsdStrategy::Projection;
  bool operator==(const ArapMaterialParams&) const = default;
};
/// S_t = I + [[s0, s1, s2], [s1, s3, s4], [s2, s4, s5]] for shape_target_tensor (s0..s5).
struct ActiveShapeTargetingArapMaterialParams {
  real stiffness = 1000;
  Real6 shape_target_tensor = Real6::Zero();
  MaterialPsdStrategy psd_strategy = MaterialPsdStrategy::Projection;
  bool operator==(const ActiveShapeTargetingArapMaterialParams&) const = default;
};

/// A homogeneous soft material: `type` selects which of the model structs applies.
struct SoftMaterialParams {
  SoftMaterialType type = SoftMaterialType::NeoHookean;
  NeoHookeanMaterialParams neo_hookean;
  StVenantKirchhoffMaterialParams st_venant_kirchhoff;
  LinearElasticMaterialParams linear_elastic;
  ActiveNeoHookeanMaterialParams active_neo_hookean;
  ActiveShapeTargetingArapMaterialParams active_shape_targeting_arap;
  ArapMaterialParams arap;
  real density = 1000;                       ///< kg/m^3, > 0
  real mass_damping_coefficient = 0;         ///< 1/s, >= 0: force alpha M v
  real stiffness_damping_coefficient = 0;    ///< s, >= 0: Kelvin-Voigt viscosity beta C : dE/dt
  bool stiffness_damping_include_geometric_term = false;
  bool operator==(const SoftMaterialParams&) const = default;
};

/// Per-element material values (one per element; shape_target_tensor six per element).
struct PerElementSoftMaterialData {
  SoftMaterialType type = SoftMaterialType::NeoHookean;
  MaterialPsdStrategy psd_strategy = MaterialPsdStrategy::MaterialDefault;
  std::vector<real> youngs_modulus, poisson_ratio, aniso_alpha, aniso_length, aniso_theta, aniso_phi, arap_stiffness,
      shape_target_tensor;
  /// arap_stiffness' size for the ARAP types, poisson_ratio's otherwise.
  int num_elements() const;
  bool operator==(const PerElementSoftMaterialData&) const = default;
};

/// Throws superdex::Error naming `where`.field for an invalid value or a material this engine
/// cannot simulate (see soft_material_supported).
void validate(const SoftMaterialParams& params, const std::string& where);
/// Throws superdex::Error naming `where`.field when the arrays do not match `num_elements` or hold
/// invalid values.
void validate(const PerElementSoftMaterialData& data, int num_elements, const std::string& where);

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

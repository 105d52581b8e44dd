#pragma once
// SuperDex's SoftMaterialParams as this engine's soft-body material (SoftMaterial): the moduli of
// the selected model, the density and the Rayleigh damping coefficients.

#include "superdex/physics/params/material_params.h"
#include "superdex/physics/scene.h"
#include "superdex/physics/shape.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

/// The material `params` give a body of `mesh`. The mesh's own per-element moduli, when it has
/// them, take precedence (the material then leaves them unset). Types this engine does not
/// simulate keep the default model; validate(SoftActorParams) rejects them first.
SoftMaterial soft_material_from_params(const SoftMaterialParams& params, const TetMesh& mesh);

/// The reverse: the SoftMaterialParams of a material given as a SoftMaterial (NeoHookean, StVK,
/// Linear), its moduli those of the mesh's elements when it leaves them to the mesh (the first
/// element's). Corotated has no SoftMaterialParams type: it gives the NeoHookean type with
/// `corotated` set, so that readers of the params can refuse it.
SoftMaterialParams soft_material_params_from(const SoftMaterial& material, const TetMesh& mesh, bool* corotated = nullptr);

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

#pragma once
// What an actor was created with that its simulation model does not keep, returned as given by the
// actor getters (contact params, layer, density, shape, collider type).

#include <memory>
#include <optional>
#include <string>

#include "superdex/physics/params/actor_params.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

struct ShapeData;

// One link of an articulation, or a rigid actor.
struct LinkRecord {
  std::shared_ptr<const ShapeData> shape;  // null for a link without a shape
  ContactParams contact;
  std::string layer;
  real density = 0;  // kg/m^3: as given, or implied by a given mass and the shape's volume
  ColliderType collider_type = ColliderType::Auto;
  // a moment of inertia given that is not physical (kg m^2, [ixx, ixy, ixz, iyy, iyz, izz]): what
  // the getters report, while the dynamics use the nearest physical one
  std::optional<Real6> declared_inertia;
};

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

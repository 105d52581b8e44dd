// Comparisons of the prefab structs that hold quaternions, primitives or contact overrides
// (prefab/actor_prefabs.h).

#include "superdex/physics/prefab/actor_prefabs.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {
namespace prefab {

namespace {

bool same_primitive(const ShapeGeometry& a, const ShapeGeometry& b) {
  if (a.index() != b.index()) return false;
  if (auto* x = std::get_if<SphereShape>(&a)) return x->center == std::get<SphereShape>(b).center && x->radius == std::get<SphereShape>(b).radius;
  if (auto* x = std::get_if<BoxShape>(&a)) return x->half_extents == std::get<BoxShape>(b).half_extents;
  if (auto* x = std::get_if<CapsuleShape>(&a))
    return x->radius == std::get<CapsuleShape>(b).radius && x->half_length == std::get<CapsuleShape>(b).half_length;
  if (auto* x = std::get_if<PlaneShape>(&a)) return x->normal == std::get<PlaneShape>(b).normal && x->distance == std::get<PlaneShape>(b).distance;
  return false;  // meshes are never inline primitives
}

}  // namespace

bool operator==(const ShapeSource& a, const ShapeSource& b) {
  const bool primitives = a.primitive.has_value() == b.primitive.has_value() && (!a.primitive || same_primitive(*a.primitive, *b.primitive));
  return a.file == b.file && primitives && a.scale == b.scale && a.rotation.coeffs() == b.rotation.coeffs() && a.translation == b.translation;
}

bool ArticulatedActorPrefab::operator==(const ArticulatedActorPrefab& o) const {
  auto same_overrides = [&] {
    if (contact_overrides.size() != o.contact_overrides.size()) return false;
    for (size_t i = 0; i < contact_overrides.size(); ++i) {
      const ContactOverride &x = contact_overrides[i], &y = o.contact_overrides[i];
      if (x.link_a != y.link_a || x.link_b != y.link_b || x.enable != y.enable) return false;
    }
    return true;
  };
  return comment == o.comment && name == o.name && scale == o.scale && rotation.coeffs() == o.rotation.coeffs() &&
         translation == o.translation && cycles == o.cycles && joints == o.joints && links == o.links &&
         joint_velocities == o.joint_velocities && default_pose == o.default_pose && same_overrides() && bot_file == o.bot_file;
}

}  // namespace prefab
}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

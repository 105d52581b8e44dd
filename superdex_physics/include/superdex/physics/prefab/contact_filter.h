#pragma once
/// @file contact_filter.h
/// Contact rules that a prefab applies once all its actors exist (SuperDex's ContactFilter):
/// between named actors and between contact layers, one-way (asymmetric: the first named collides
/// with the second) or both ways.

#include <optional>
#include <string>
#include <vector>

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {
namespace prefab {

/// Contact between two actors of the prefab, named as in it ("box", or "nested/box" for an actor
/// of a nested prefab); the same name twice is self-contact.
struct ActorContactEntry {
  bool enable = true;  ///< false: the entry disables contact
  std::vector<std::string> actors;    ///< exactly 2
  bool include_nested_actors = true;  ///< an articulation's name covers its links
  bool operator==(const ActorContactEntry&) const = default;
};

/// Contact between two contact layers (by name).
struct LayerContactEntry {
  bool enable = true;  ///< false: the entry disables contact
  std::vector<std::string> layers;  ///< exactly 2
  bool operator==(const LayerContactEntry&) const = default;
};

/// The rules, applied in this order: layer_contact_asymmetric, layer_contact_symmetric,
/// actor_contact_asymmetric, actor_contact_symmetric, each in list order; a nested prefab's
/// rules before its parent's.
struct ContactFilter {
  std::optional<std::string> comment;
  std::optional<std::vector<ActorContactEntry>> actor_contact_asymmetric;
  std::optional<std::vector<ActorContactEntry>> actor_contact_symmetric;
  std::optional<std::vector<LayerContactEntry>> layer_contact_asymmetric;
  std::optional<std::vector<LayerContactEntry>> layer_contact_symmetric;
  bool operator==(const ContactFilter&) const = default;
};

}  // namespace prefab
}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

#pragma once
// Islands: bodies coupled by contacts or constraints solve together; bodies without DOFs never
// join.

#include <array>
#include <vector>

#include "collision/collision_detection.h"
#include "soft/soft_contact.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

struct Island {
  std::vector<int> bodies;         // articulation indices, ascending
  std::vector<int> contacts;       // indices into the contact list, ascending
  std::vector<int> soft_bodies;    // soft body indices, ascending
  std::vector<int> soft_contacts;  // indices into the soft contact list, ascending
  std::vector<int> constraints;    // indices into the constraint list, ascending
};

// Groups the articulations with DOFs (num_dofs[b] > 0) and the soft bodies with free DOFs
// (soft_free_dofs[k] > 0) into islands connected by contacts and by constraints (the two nodes
// each joins: an articulation index, or the number of articulations plus a soft body index; -1
// for none).
std::vector<Island> build_islands(const std::vector<int>& num_dofs, const std::vector<Contact>& contacts,
                                  const std::vector<int>& soft_free_dofs = {},
                                  const std::vector<SoftContact>& soft_contacts = {},
                                  const std::vector<std::array<int, 2>>& constraints = {});

// Working storage of build_islands.
struct IslandScratch {
  std::vector<int> dofs, parent, index_of_root;
};
// The same into `islands`, whose elements keep their lists' storage across calls.
void build_islands(const std::vector<int>& num_dofs, const std::vector<Contact>& contacts, const std::vector<int>& soft_free_dofs,
                   const std::vector<SoftContact>& soft_contacts, const std::vector<std::array<int, 2>>& constraints,
                   std::vector<Island>& islands, IslandScratch& scratch);

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

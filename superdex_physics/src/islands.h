#pragma once
// Islands: bodies coupled by contacts solve together; bodies without DOFs never join.

#include <vector>

#include "collision_detection.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

struct Island {
  std::vector<int> bodies;    // articulation indices, ascending
  std::vector<int> contacts;  // indices into the contact list, ascending
};

// Groups the bodies with DOFs (num_dofs[b] > 0) into islands connected by contacts.
std::vector<Island> build_islands(const std::vector<int>& num_dofs, const std::vector<Contact>& contacts);

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

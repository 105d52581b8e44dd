#pragma once
// A rod drawn as a tube: rings of vertices around its polyline nodes, turned with its elements'
// material frames, for the debugger and recordings.

#include <array>
#include <vector>

#include "soft/soft_body.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

inline constexpr int kRodDisplaySegments = 8;  // vertices per ring

/// The tube's vertices now (world, 3 per vertex): a ring per polyline node, then for an open rod
/// its two end centres. Its radius is the rod's cross-section's, r = sqrt(2 J / (rho A)) from its
/// rotational inertia and linear density (a solid circular section's).
void rod_display_vertices(const SoftBody& b, VecX& out);

/// The tube's triangles (counter-clockwise seen from outside), indexing rod_display_vertices.
std::vector<std::array<int, 3>> rod_display_faces(const SoftBody& b);

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

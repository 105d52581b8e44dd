#pragma once
// The world Jacobians J_WL of the links an island solve's contacts touch, computed once per link
// and solve and kept in the island's workspace (IslandWorkspace::link_jacobians), with their
// compliances W_L when asked for.

#include "island/island_solver.h"
#include "linalg/small_llt.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

// Forgets the links' Jacobians of the last solve; `links`: the island's links (island_stages.h).
void reset_link_jacobians(int links, IslandWorkspace& w);

// The world Jacobian J_WL (6 x nv) of a link of an island's body, computed once per solve of the
// island (reset_link_jacobians at its start) and kept in `w`.
IslandWorkspace::LinkJacobian& cached_link_jacobian(const SceneData& s, int body, int link, IslandWorkspace& w);

// The same with its compliance W_L = J_WL A^-1 J_WL^T, for the body's factored A.
const IslandWorkspace::LinkJacobian& link_compliance(const SceneData& s, int body, int link, const SmallLLT& A_llt,
                                                     IslandWorkspace& w);

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

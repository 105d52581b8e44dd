#pragma once
// The world Jacobians J_WL of the links an island solve's contacts touch, computed once per link
// and solve and kept in the island's workspace (IslandWorkspace::link_jacobians), with their
// compliances W_L when asked for.

#include "island/island_solver.h"
#include "linalg/tree_ldlt.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

// Forgets the links' Jacobians of the last island solved in `w` and numbers the links of
// `island`'s bodies (IslandWorkspace::link_base). Once per island and step: the Jacobians and
// compliances stay valid for every solve of the island within the step.
void reset_link_jacobians(const SceneData& s, const Island& island, IslandWorkspace& w);

// The world Jacobian J_WL (6 x nv) of a link of an island's body, computed once per solve of the
// island (reset_link_jacobians at its start) and kept in `w`.
IslandWorkspace::LinkJacobian& cached_link_jacobian(const SceneData& s, int body, int link, IslandWorkspace& w);

// The same with its compliance W_L = J_WL A^-1 J_WL^T, for the body's factored A.
const IslandWorkspace::LinkJacobian& link_compliance(const SceneData& s, int body, int link, const TreeLDLT& A_factor,
                                                     IslandWorkspace& w);

// The motions of an island's bodies at which link velocities are asked for: their current
// velocities, their free motion (ArticulationTerms::v_free) and the last solve's result.
enum class LinkMotion { Current = 0, Free = 1, Solution = 2 };

// Velocity (m/s, world) of the material point at p_W (m, world) of a link of an island's body
// when the body's DOFs move at v_body (nv), the body's velocities at `motion`. The link's spatial
// velocity is kept for each motion (forget_link_velocities).
Vec3 link_point_velocity(const SceneData& s, int body, int link, const Vec3& p_W, LinkMotion motion, const VecX& v_body,
                         IslandWorkspace& w);
// Velocity (m/s, world) of side a's point of a rigid contact: a link's material point, or a skin
// node moving with its links by their weights (articulation_skin.h).
Vec3 contact_point_velocity_a(const SceneData& s, const Contact& c, LinkMotion motion, const VecX& v_body, IslandWorkspace& w);
// Forgets the links' velocities at `motion` (the solution, once solved again).
void forget_link_velocities(LinkMotion motion, IslandWorkspace& w);

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

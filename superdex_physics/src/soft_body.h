#pragma once
// Soft bodies: tetrahedral finite elements with lumped masses, hyperelastic materials
// (fem_elasticity.h), Rayleigh damping and pinned nodes. Each step solves the implicit
// (backward Euler) problem in the next node velocities v by Newton's method:
//
//   min_v  1/2 (v - v0)^T M (v - v0) - dt (M g)^T v + Psi(x0 + dt v) + dt/2 v^T D v
//
// with Psi the elastic energy, D = alpha M + beta K(x0) the Rayleigh damping, projected element
// Hessians, a sparse LDL^T per iteration and a line search on the directional derivative (energy
// differences at small strain are round-off in float), iterated to a tolerance (not a single
// linearisation). Pinned nodes keep their velocity (zero).
// Contact with other bodies is not coupled yet (issue 5): soft bodies are their own islands.

#include <memory>
#include <string>
#include <vector>

#include "collision_geometry.h"
#include "fem_elasticity.h"
#include "spatial.h"
#include "superdex/physics/handles.h"
#include "superdex/physics/scene.h"
#include "superdex/physics/shape.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

struct SoftModel {
  std::string name;
  std::shared_ptr<const TetMesh> mesh;   // rest mesh in the actor frame
  std::vector<std::array<int, 4>> tets;  // (M)
  std::vector<TetRest> rest;             // rest data in the world placement (M)
  std::vector<ElasticMaterial> material; // per tetrahedron (M)
  VecX node_mass;                        // lumped masses (N)
  std::vector<char> pinned;              // per node (N)
  real alpha = 0, beta = 0;              // Rayleigh damping: mass (1/s) and stiffness (s) proportional
  real total_mass = 0;
  ContactMaterial contact;               // surface contact parameters
};

struct SoftState {
  VecX x;             // node positions, world (3N)
  VecX v;             // node velocities, world (3N)
  VecX tau_external;  // user forces on the nodes (N), world (3N)
};

struct SoftBody {
  ActorHandle handle = 0;
  SoftModel model;
  SoftState state;
  VecX node_contact_forces;  // results of the last step: contact force on each node (N), world (3N)
  int last_iterations = 0;
  real last_residual = 0;
};

// Builds a soft body from a registered tet mesh placed at X_WL; throws naming `where`.
std::unique_ptr<SoftBody> build_soft_body(const std::string& name, std::shared_ptr<const TetMesh> mesh,
                                          const SoftMaterial& material, const Transform& X_WL,
                                          const std::vector<int>& fixed_nodes, const std::string& where);

// A static surface soft nodes can touch (a collider of an immovable body), posed in the world.
struct StaticSurface {
  const ShapeGeometry* shape;
  SpatialTransform X_WS;
  ContactMaterial material;
};

// One implicit step; returns the next state (not committed). Nodes closer than the margin to a
// static surface get frictional contact blocks (SAP cone, near-rigid, as for rigid bodies) in the
// same Newton solve; their impulses are returned as node contact forces. Throws on non-finite results.
SoftState step_soft_body(SoftBody& body, const Vec3& g_W, real dt, const SolverParams& params,
                         const std::vector<StaticSurface>& surfaces);

// Total elastic energy at positions x (J).
real soft_elastic_energy(const SoftBody& body, const VecX& x);

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

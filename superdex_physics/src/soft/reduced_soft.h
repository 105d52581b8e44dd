#pragma once
// Reduced soft bodies (SoftMaterial::reduced_modes = r > 0): linear elasticity about the rest
// shape, in the body's r lowest vibration modes plus a static correction. Node positions are
//
//   x = X + Phi q + u_g + u_c
//
// X the rest positions (world), Phi the mass-normalized modes of the pinned rest stiffness K and
// lumped mass M (K Phi = M Phi Lambda, Phi^T M Phi = I), q their amplitudes (m sqrt(kg)), and u_g,
// u_c the parts of the static responses to gravity and to the contact forces that the modes leave
// out, (K^-1 - Phi Lambda^-1 Phi^T) f. The static response to gravity and contact loads is thus the
// full linear finite-element one, whatever r; the dynamics are the modes'.
//
// In a step, the amplitudes follow the same implicit Euler as full soft bodies, projected onto the
// modes: A_q = I + dt (alpha I + beta Lambda) + dt^2 Lambda (diagonal). The residual displacements
// of the nodes in contact are further unknowns of the island's problem: u_c = u_c0 + dt w at those
// nodes, with the energy 1/2 u_c^T G^-1 u_c of the residual compliance G among them and the
// stiffness damping beta G^-1 w (as full bodies damp beta K v): their block is h G^-1 with
// h = dt (dt + beta). Node forces from set_external_forces act through the modes only.

#include <limits>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "soft/soft_body.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

struct ReducedSoftModel {
  std::vector<int> free_of_dof;  // (3N) index among the free DOFs, -1 when pinned
  std::vector<int> dof_of_free;  // (num_free)
  MatX Phi;                      // (3N x r) mass-normalized modes (1/sqrt(kg)), zero rows on pinned DOFs
  VecX lambda;                   // (r) squared angular frequencies (1/s^2), ascending
  VecX x_rest;                   // (3N) rest positions, world (m)
  struct Stiffness;              // the factored rest stiffness on the free DOFs
  std::shared_ptr<const Stiffness> K;
  // per node: the residual compliance columns (K^-1 - Phi Lambda^-1 Phi^T) of its three DOFs
  // (3N x 3, m/N), computed when the node first touches something
  mutable std::map<int, MatX> residual_columns;
  // the body's response to one gravity g_W (world, m/s^2)
  struct Gravity {
    Vec3 g_W = Vec3::Constant(std::numeric_limits<real>::quiet_NaN());
    VecX u_g;          // (3N) the residual static response (m)
    VecX modal_force;  // (r) Phi^T M g (sqrt(kg) m / s^2)
  };
  mutable Gravity gravity_response;

  int num_modes() const { return static_cast<int>(lambda.size()); }
  // Residual compliance columns of a free node (computed and kept on first use).
  const MatX& residual(int node) const;
  // Computes the residual columns of those free `nodes` that have none yet, together.
  void prepare_residuals(const std::vector<int>& nodes) const;
  // The response to gravity g_W (recomputed when g_W changes).
  const Gravity& gravity(const VecX& node_mass, const Vec3& g_W) const;
};

// The r lowest modes of a soft body's rest stiffness (every element's material linearized at
// rest) with its pinned nodes held; throws superdex::Error naming `where` (no pinned node, r out
// of range, a stiffness that is not positive definite, modes that do not converge).
std::shared_ptr<ReducedSoftModel> build_reduced_model(const SoftModel& m, const VecX& x_rest, int modes, const std::string& where);

// One reduced body's unknowns in an island's problem: its modal velocities (r), then the
// residual velocities w (m/s) of its contact nodes (3 per node).
struct ReducedVariables {
  int soft = -1;                // soft body index in the scene
  int offset = 0;               // first variable in the island
  std::vector<int> nodes;       // free contact nodes, ascending
  VecX A_q, r_q;                // the modal block (diagonal, 1) and its right side (m sqrt(kg) / s)
  MatX G;                       // (3k x 3k) residual compliance among the contact nodes (m/N)
  MatX G_inv;                   // its inverse (N/m)
  real h = 0;                   // dt (dt + beta) (s^2): the residual block is h G^-1
  VecX u_old;                   // (3k) residual displacements of the contact nodes now (m)

  int size() const { return static_cast<int>(A_q.size() + 3 * nodes.size()); }
  // Column of node DOF (node, axis) among the variables (relative to offset), -1 when not one.
  int column(int node, int axis) const;
};

// The variables of body `b` (index `soft`) for a step of dt under gravity g_W, with `nodes` the
// free nodes its island's contacts touch (ascending).
void reduced_variables(const SoftBody& b, int soft, const Vec3& g_W, real dt, std::vector<int> nodes, ReducedVariables& out);

// The next state of the body (positions, velocities and reduced state) from its variables' values
// y at the solution.
void reduced_next_state(const SoftBody& b, const ReducedVariables& vars, const Eigen::Ref<const VecX>& y, const Vec3& g_W,
                        real dt, SoftState& next);

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

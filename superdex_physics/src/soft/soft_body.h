#pragma once
// Soft bodies: tetrahedral finite elements with lumped masses, hyperelastic materials
// (fem_elasticity.h), Rayleigh damping and pinned nodes. Each step, a soft body contributes to its
// island's convex problem (newton_solver.h), in the velocities v of its free (unpinned) nodes:
//
//   1/2 (v - v0)^T M (v - v0) - dt (M g + f)^T v + dt/2 v^T D v  +  Psi(x0 + dt v)
//
// a quadratic part (A = M + dt D, r = M v0 + dt f_ext) and a smooth convex part, the elastic
// energy Psi, whose gradient and projected Hessian the Newton loop evaluates at each iterate, so
// that nonlinear elasticity is iterated to the tolerance together with contact. D = alpha M +
// beta K(x0) is the Rayleigh damping. Pinned nodes move to their targets within the step (they stay
// put unless a boundary condition moves them); the stiffness damping does not see their motion.

#include <Eigen/Sparse>
#include <memory>
#include <string>
#include <vector>

#include "soft/fem_elasticity.h"
#include "soft/rod_model.h"
#include "linalg/sparse_cholesky.h"
#include "core/spatial.h"
#include "superdex/physics/handles.h"
#include "superdex/physics/scene.h"
#include "superdex/physics/params/actor_params.h"
#include "superdex/physics/shape.h"
#include "solver/step_settings.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

struct ReducedSoftModel;
struct ShapeData;

struct SoftModel {
  std::string name;
  std::shared_ptr<const TetMesh> mesh;   // rest mesh in the actor frame
  std::vector<std::array<int, 4>> tets;  // (M)
  std::vector<TetRest> rest;             // rest data in the world placement (M)
  std::vector<ElasticMaterial> material; // per tetrahedron (M)
  VecX node_mass;                        // lumped masses (N)
  std::vector<char> pinned;              // per node (N)
  VecX pin_target;                       // where pinned nodes go in the next step (3N), world
  std::vector<int> surface_nodes;        // nodes on boundary faces, ascending
  std::vector<std::array<int, 3>> surface_faces;  // boundary faces, counter-clockwise seen from outside
  real alpha = 0, beta = 0;              // Rayleigh damping: mass (1/s) and stiffness (s) proportional
  real total_mass = 0;
  ContactMaterial contact;               // surface contact parameters
  // a rod's elements and joints (rod_model.h), null for a tetrahedral body: its polyline's nodes
  // come first, then one ghost node per element, which has no weight
  std::shared_ptr<const RodModel> rod;
};

struct SoftState {
  VecX x;             // node positions, world (3N)
  VecX v;             // node velocities, world (3N)
  VecX tau_external;  // user forces on the nodes (N), world (3N)
  // reduced bodies only (reduced_soft.h), empty otherwise: modal amplitudes (m sqrt(kg)), their
  // velocities, and the residual static displacement of the last step's contact forces (3N, m)
  VecX q, qd, u_c;
};

// The fixed sparsity of a soft body's Newton matrix over its free DOFs and its symbolic
// factorization, computed once and reused every step (until the pinned set changes).
struct SoftPattern {
  int num_free = 0;
  std::vector<int> free_of_dof;              // (3N) index among the free DOFs, -1 when pinned
  std::vector<int> dof_of_free;              // (num_free)
  Eigen::SparseMatrix<real> H;               // free x free, full symmetric storage, zero values
  std::vector<int> tet_slots;                // (144 per tet) value index of entry (3i+a, 3j+c), -1 if pinned
  std::vector<int> rod_slots;                // the same for a rod: 81 per element, then 324 per joint
  SparseCholesky cholesky;                   // analysed on H's pattern

  // Value index of entry (row, col) of H, or -1 when it is not in the pattern.
  int slot(int row, int col) const;
};

// Storage of a soft body's steps, kept across steps so that a step does not allocate it: what is
// in it is overwritten by every step, none of it is state.
struct SoftStepStorage {
  std::vector<Mat3> F0;            // per tetrahedron: the deformation gradient at the start of the step
  std::vector<Mat12> H0;           // per tetrahedron: its (projected) Hessian there, unscaled
  std::vector<Mat12> hessians;     // per tetrahedron results of the element loops on worker threads
  std::vector<Vec12> gradients;
  std::vector<int> changed;        // tetrahedra whose Hessian the current iterate recomputes
  std::vector<Mat3> changed_F;     // and their deformation gradients there
  VecX grad;                       // the elastic gradient on all nodes (3N)
};

struct SoftBody {
  ActorHandle handle = 0;
  ActorHandle skeleton;  // the soft-skinned actor it belongs to, if any
  SoftModel model;
  SoftState state;
  // the actor frame (its root transform): where the mesh's rest nodes were placed, then, with
  // recentering, following the body's rigid motion (soft_recentering.h)
  Transform X_WL;
  RecenteringParams recentering;
  bool has_gravity = true;
  // as created (returned by the actor getters)
  ContactParams contact_params;
  SoftMaterialParams material_params;
  // per tetrahedron, once one was given its own (set_soft_material_params_field); empty while all
  // take material_params
  std::vector<SoftMaterialParams> element_params;
  std::string layer;
  int layer_index = 0;  // SceneData::layer_names
  std::shared_ptr<const ShapeData> shape;
  // boundary conditions added by DOF (3 per node: the node's world position), in insertion order:
  // the clearable ones and the permanent ones
  std::vector<int> bc_dofs, bc_permanent_dofs;
  std::vector<real> bc_values, bc_permanent_values;
  // the nodes pinned at creation (a prefab's fixed nodes) and their targets, which the boundary
  // conditions add to
  std::vector<char> base_pinned;
  VecX base_pin_target;
  VecX node_contact_forces;  // results of the last step: contact force on each node (N), world (3N)
  ConvergenceStatus convergence_status = ConvergenceStatus::None;  // of its island's last solve
  std::unique_ptr<SoftPattern> pattern;  // built on first use
  std::shared_ptr<const ReducedSoftModel> reduced;  // the modes of a reduced body (reduced_soft.h), else null
  SoftStepStorage step_storage;

  /// The nodes users address (node indices, constraints, queries): a rod's polyline nodes (its
  /// ghosts follow them and are internal), else every node.
  int user_nodes() const { return model.rod ? model.rod->num_nodes : static_cast<int>(state.x.size() / 3); }
};

// Builds a soft body from a registered tet mesh placed at X_WL; throws naming `where`.
std::unique_ptr<SoftBody> build_soft_body(const std::string& name, std::shared_ptr<const TetMesh> mesh,
                                          const SoftMaterial& material, const Transform& X_WL,
                                          const std::vector<int>& fixed_nodes, const std::string& where);

// One soft body's part of an island's convex problem for one step, in its free DOFs.
class SoftStep {
 public:
  // `reuse_strain`: StepSettings::soft_hessian_reuse_strain.
  SoftStep(SoftBody& body, const Vec3& g_W, real dt, real reuse_strain);

  SoftBody& body;
  const SoftPattern& pattern;
  real dt;
  VecX x0;                   // node positions at the start of the step (3N), world
  VecX v_pinned;             // velocities of the pinned DOFs (3N, zero on free ones): to their targets
  VecX v0;                   // free-DOF velocities at the start of the step
  VecX mass;                 // lumped mass per free DOF (kg)
  Eigen::SparseMatrix<real> A;  // M + dt D on the free DOFs, in the pattern
  VecX r;                    // M v0 + dt f_ext on the free DOFs

  int size() const { return pattern.num_free; }
  // Velocities of all nodes (3N) from the free-DOF velocities and the pinned nodes' motion.
  VecX full_velocity(const VecX& v_free) const;
  // g += dt P^T grad Psi(x0 + dt v) (N s): the elastic part of the gradient.
  void add_gradient(const Eigen::Ref<const VecX>& v_free, Eigen::Ref<VecX> g) const;
  // K = dt^2 P^T hess Psi(x0 + dt v) P, element Hessians projected to be positive semi-definite;
  // K must have the pattern's structure (its values are overwritten). An element whose
  // deformation gradient differs from its value at x0 by no more than the reuse strain in every
  // entry keeps its Hessian at x0: only the Newton direction changes, not the problem solved.
  void hessian(const Eigen::Ref<const VecX>& v_free, Eigen::SparseMatrix<real>& K) const;
  // K at the start of the step, x0 (computed once with the stiffness damping): the Hessian of a
  // first Newton iteration, which starts from v0 and so differs from x0 by dt v0 only.
  void start_hessian(Eigen::SparseMatrix<real>& K) const;
  // Element Hessians computed so far in this step (at x0 and by hessian()).
  int element_hessians() const { return element_hessians_; }
  // Numeric factorizations of this body's Newton matrices so far in this step.
  int factorizations() const { return pattern.cholesky.factorizations() - factorizations_at_start_; }

 private:
  std::vector<Mat3> R_;     // per-tetrahedron rotations of the corotated model, at x0
  std::vector<real> K0_;    // dt^2 P^T hess Psi(x0) P, in the pattern's value order
  std::vector<real> rod_K0_;  // a rod's part of it (kept apart: recomputed at every iterate)
  std::vector<std::pair<int, real>> newton_shift_;  // (value slot, amount) added to the Newton matrix only (float rods)
  real reuse_strain_;       // largest change of an entry of F for which an element keeps its Hessian at x0
  SoftStepStorage& storage_;  // the body's
  mutable int element_hessians_ = 0;
  int factorizations_at_start_;
};

// Total elastic energy at positions x (J).
real soft_elastic_energy(const SoftBody& body, const VecX& x);

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

#pragma once
// One island's implicit solve: assembles the block-diagonal momentum matrix of its bodies,
// their joint rows and the frictional contact blocks (SAP regularisation from each contact's
// effective compliance), adds its soft bodies (soft_body.h), and solves the convex problem.

#include <array>

#include "constraint/constraint_terms.h"
#include "multibody/articulation_step.h"
#include "multibody/body_jacobian.h"
#include "island/islands.h"
#include "soft/reduced_soft.h"
#include "solver/row_block_assembler.h"
#include "soft/soft_body.h"
#include "core/step_ticks.h"
#include "solver/step_settings.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

struct IslandSolution {
  std::vector<VecX> v;              // next velocities, per island body
  std::vector<VecX> drive_efforts;  // joint drive efforts (N m or N), per island body
  std::vector<Vec3> contact_force;  // per island contact: force on body a (N), world
  std::vector<VecX> soft_v;         // next node velocities (3N), per island soft body
  std::vector<SoftState> soft_reduced;  // next states of reduced soft bodies, per island soft body (empty for full ones)
  std::vector<Vec3> soft_contact_force;  // per island soft contact: force on the node (N), world
  // per island constraint: the spatial force (N, and N m about the link origin; world) on its
  // sides a and b
  std::vector<Vec6> constraint_force_a, constraint_force_b;
  int iterations = 0;               // Newton iterations, summed over the solves
  int solves = 0;                   // solves of the island: 1, and 1 more per round of deferred rows or contacts joining
  real residual = 0;
  bool converged = true;
  ConvergenceStatus status = ConvergenceStatus::None;
  int line_search_iterations = 0;
  int active_rows = 0;              // joint rows with a non-zero impulse
  Ticks ticks = 0;                  // time spent solving (step_ticks.h)
};

// Working storage of one island's solve, kept across steps (SceneData::island_workspaces, by
// island index) so that solving an island of the same shape as last step's allocates little, and
// islands solved at the same time never share it. Every member is cleared or resized before use,
// keeping its capacity.
struct IslandWorkspace {
  std::vector<int> body_offset;   // by articulation index: first variable, or -1 when not in the island
  std::vector<int> soft_offset;   // by soft step index: first variable
  std::vector<SoftStep*> soft;
  std::vector<ReducedVariables> reduced;  // the island's reduced soft bodies
  std::vector<int> reduced_of;            // by island soft body: its index in `reduced`, or -1
  // a joint row that takes part in the solve: the body's position in the island, and the row's
  // index in its terms' joint_rows
  struct JointRowRef {
    int body, row;
  };
  std::vector<JointRowRef> solved_joint_rows;  // in the order of their constraint rows
  std::vector<int> solved_contacts;            // the rigid contacts that take part (positions in the island's list)
  std::vector<char> contact_takes_part;        // per island rigid contact: not deferred (deferred_contacts.h), or admitted
  std::vector<int> solved_soft_contacts;       // the soft contacts that take part (positions in the island's list)
  std::vector<char> admitted_soft_contacts;    // per island soft contact: a deferred one that takes part
  MatX A;                          // A on the dense paths
  std::vector<const MatX*> A_blocks;  // A on the sparse path: its bodies' blocks, in island order
  VecX r, v_start;
  ConstraintRows rows;       // the blocks; J itself with full soft bodies
  RowBlockAssembler J_rows;  // rows.J as its blocks are made
  MatXR J_dense;             // J on the dense path
  BodyJacobian J_bodies;     // J on the sparse path
  std::vector<int> body_dofs;  // the island's bodies' DOFs, in island order
  std::vector<int> island_position;  // by articulation index: its position in the island's bodies, or -1
  // world Jacobians of the links touched by contacts, computed once per link
  struct LinkJacobian {
    int body, link;
    MatXR J_WL;
    // J_WL A^-1 J_WL^T (6 x 6; rows and columns: the link origin's linear velocity (m/s), then
    // the link's angular velocity (rad/s), world frame; per unit of impulse): the link's
    // compliance as the body's DOFs and inertia allow it; valid when has_W_L
    Mat6 W_L;
    bool has_W_L = false;
    // the link's spatial velocity J_WL v (its origin's linear velocity, then its angular one;
    // m/s, rad/s, world) at each LinkMotion (link_jacobians.h), valid by the bit 1 << motion
    std::array<Vec6, 3> V;
    unsigned has_V = 0;
  };
  std::vector<LinkJacobian> link_jacobians;
  size_t link_jacobians_used = 0;
  // where a link's entry in link_jacobians is: link_slot[link_base[body] + link] (-1: none
  // yet); link_base by articulation index, -1 for the bodies not in the island
  std::vector<int> link_base, link_slot;
  MatX Jc;   // a reduced body's side of a soft contact (3 x modes)
  MatX H_Jt;  // H J_WL^T of a link (DOFs x 6; H^T H = A^-1), for its W_L
  std::vector<Mat3> frames;
  NewtonScratch newton;
};

// Whether the island is solved on the sparse path: rigid only, with more than
// params.dense_island_max_dofs DOFs. Such islands keep their Newton pattern across steps.
bool island_is_sparse(const SceneData& scene, const Island& island, const StepSettings& params);

// Solves one island into `out`, whose vectors keep their storage across calls.
// `soft_steps` holds one problem per scene soft body (null for those without free DOFs); `w` is
// this island's working storage.
// `system` holds the Newton matrices of a sparse island (island_is_sparse), kept from step to
// step for the island's bodies (it keeps its analysis while their structure allows); null for
// the other islands.
void solve_island(const SceneData& scene, const Island& island, const std::vector<ArticulationTerms>& terms,
                  const std::vector<Contact>& contacts, const std::vector<SoftContact>& soft_contacts,
                  const std::vector<ConstraintTerms>& constraints,
                  const std::vector<std::unique_ptr<SoftStep>>& soft_steps, real dt, const StepSettings& params,
                  IslandWorkspace& w, SparseNewtonSystem* system, IslandSolution& out);

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

#pragma once
// One island's implicit solve: assembles the block-diagonal momentum matrix of its bodies,
// their joint rows and the frictional contact blocks (SAP regularisation from each contact's
// effective compliance), adds its soft bodies (soft_body.h), and solves the convex problem.

#include "articulation_step.h"
#include "islands.h"
#include "soft_body.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

struct IslandSolution {
  std::vector<VecX> v;              // next velocities, per island body
  std::vector<VecX> drive_efforts;  // joint drive efforts (N m or N), per island body
  std::vector<Vec3> contact_force;  // per island contact: force on body a (N), world
  std::vector<VecX> soft_v;         // next node velocities (3N), per island soft body
  std::vector<Vec3> soft_contact_force;  // per island soft contact: force on the node (N), world
  int iterations = 0;
  real residual = 0;
  bool converged = true;
  int active_rows = 0;              // joint rows with a non-zero impulse
  double seconds = 0;
};

// Whether the island is solved on the sparse path: rigid only, with more than
// params.dense_island_max_dofs DOFs. Such islands keep their Newton pattern across steps.
bool island_is_sparse(const SceneData& scene, const Island& island, const SolverParams& params);

// `soft_steps` holds one problem per scene soft body (null for those without free DOFs).
// `sparse_cache` (may be null) holds the sparse Newton pattern of this island's bodies from the
// last step: reused when the structure is unchanged, replaced otherwise.
IslandSolution solve_island(const SceneData& scene, const Island& island, const std::vector<ArticulationTerms>& terms,
                            const std::vector<Contact>& contacts, const std::vector<SoftContact>& soft_contacts,
                            const std::vector<std::unique_ptr<SoftStep>>& soft_steps, real dt, const SolverParams& params,
                            std::shared_ptr<SparseNewtonSystem>* sparse_cache = nullptr);

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

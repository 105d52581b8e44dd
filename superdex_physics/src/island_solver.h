#pragma once
// One island's implicit solve: assembles the block-diagonal momentum matrix of its bodies,
// their joint rows and the frictional contact blocks (SAP regularisation from each contact's
// effective compliance), and solves the convex problem.

#include "articulation_step.h"
#include "islands.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

struct IslandSolution {
  std::vector<VecX> v;              // next velocities, per island body
  std::vector<VecX> drive_efforts;  // joint drive efforts (N m or N), per island body
  std::vector<Vec3> contact_force;  // per island contact: force on body a (N), world
  int iterations = 0;
  real residual = 0;
  bool converged = true;
  int active_rows = 0;              // joint rows with a non-zero impulse
  double seconds = 0;
};

IslandSolution solve_island(const SceneData& scene, const Island& island, const std::vector<ArticulationTerms>& terms,
                            const std::vector<Contact>& contacts, real dt, const SolverParams& params);

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

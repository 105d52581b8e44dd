#pragma once
// One implicit step of a single articulation (its own island while there is no contact):
// assembles the convex problem of newton_solver.h from dynamics, joint damping, joint
// friction and joint limits, solves it and integrates positions.

#include "scene_data.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

struct ArticulationStepResult {
  VecX q, v;              // next positions and velocities (not yet committed)
  int iterations = 0;
  real residual = 0;
  bool converged = true;
  int active_rows = 0;    // constraint rows with a non-zero impulse
  double time_dynamics = 0, time_solve = 0;
};

// Computes the next state of `a` over dt under gravity g_W. Reads a.state and a.kin.
ArticulationStepResult step_articulation(const Articulation& a, const Vec3& g_W, real dt, const SolverParams& params);

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

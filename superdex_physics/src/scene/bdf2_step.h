#pragma once
// The BDF2 integration method (SolverParams::integration_method). BDF2 on (x, v),
//   x+ = 4/3 x - 1/3 x- + 2/3 h v+,   v+ = 4/3 v - 1/3 v- + 2/3 h a(x+, v+),
// is a backward Euler step of 2/3 h from the extrapolated state (4/3 x - 1/3 x-, 4/3 v - 1/3 v-):
// the scene's own implicit step (contacts, constraints, soft bodies and all) taken from there.
// Rotations extrapolate on the sphere, q (q-^-1 q)^(1/3). A step is backward Euler instead when
// there is no history to extrapolate from: the first one, the first after the state was changed
// outside the step (set_pose, a restore, actors created or destroyed) or after a change of the
// time step, and every step of a scene with reduced soft actors.

#include <vector>

#include "superdex/physics/real.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

struct SceneData;

// The states of a scene's bodies at the end of the last two steps.
struct Bdf2History {
  struct Body {
    VecX q_prev, v_prev, q, v;  // articulations: positions and velocities; soft bodies: node positions and velocities (world)
  };
  std::vector<Body> bodies, softs;  // per articulation and per soft body, creation order
  double dt = 0;                    // the time step both were taken with (s)
  bool valid = false;
};

// The bodies' current states (as q and v of `out`).
void bdf2_capture(const SceneData& s, Bdf2History& out);
// Whether the next step of dt can extrapolate from `history`: the same time step, the same
// bodies, none reduced, each still in the state the last step left.
bool bdf2_can_extrapolate(const SceneData& s, const Bdf2History& history, double dt);
// Moves every body to the extrapolated state, and the old targets of moving constraints so that
// their rate over the step of 2/3 dt stays the one over dt.
void bdf2_extrapolate(SceneData& s, const Bdf2History& history);
// Puts the bodies back in the captured state `start` (a step that failed after extrapolating).
void bdf2_restore(SceneData& s, const Bdf2History& start);
// After a step of dt that began in `start`: the history for the next one (the start state moves
// into it; `start` keeps the storage it gets back).
void bdf2_advance(const SceneData& s, double dt, Bdf2History& start, Bdf2History& history);

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

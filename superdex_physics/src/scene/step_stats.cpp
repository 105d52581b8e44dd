// The step's statistics (StepStats): its islands' solves and its wall time by parts.

#include <algorithm>

#include "scene/step_stages.h"
#include "solver/step_settings.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

void step_stats(Step& step, const StepClock& clock) {
  StepStats stats;
  stats.num_islands = static_cast<int>(step.ws.islands.size());
  stats.num_contacts = static_cast<int>(step.ws.contacts.size());
  Ticks solve_ticks = 0;
  for (const auto& st : step.soft_steps)
    if (st) {
      stats.soft_element_hessians += st->element_hessians();
      stats.soft_factorizations += st->factorizations();
    }
  // each actor's status is its island's (NONE when it was in none: static or without DOFs)
  for (auto& a : step.s.articulations) a->convergence_status = ConvergenceStatus::None;
  for (auto& b : step.s.soft_bodies) b->convergence_status = ConvergenceStatus::None;
  for (size_t k = 0; k < step.ws.islands.size() && k < step.ws.solutions.size(); ++k) {
    for (int b : step.ws.islands[k].bodies) step.s.articulations[b]->convergence_status = step.ws.solutions[k].status;
    for (int b : step.ws.islands[k].soft_bodies) step.s.soft_bodies[b]->convergence_status = step.ws.solutions[k].status;
  }
  for (const IslandSolution& sol : step.ws.solutions) {
    stats.newton_iterations = std::max(stats.newton_iterations, sol.iterations);
    stats.total_newton_iterations += sol.iterations;
    stats.island_solves += sol.solves;
    stats.residual = std::max(stats.residual, sol.residual);
    stats.converged = stats.converged && sol.converged;
    stats.status = std::max(stats.status, sol.status);
    stats.line_search_iterations = std::max(stats.line_search_iterations, sol.line_search_iterations);
    stats.num_constraints += sol.active_rows;
    solve_ticks += sol.ticks;
  }
  double tick_seconds = 0;
  stats.time_total = clock.seconds(tick_seconds);
  stats.time_kinematics = tick_seconds * static_cast<double>(step.kinematics_ticks);
  stats.time_collision = tick_seconds * static_cast<double>(step.collision_ticks);
  stats.time_solve = tick_seconds * static_cast<double>(solve_ticks);
  step.s.stats = stats;
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

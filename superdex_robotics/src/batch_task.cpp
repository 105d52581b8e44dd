// The C++ tasks of a SceneBatch (batch_task.h): circle tracking with force regulation (the seed's
// task) and goal reaching, their observation columns and rewards.

#include "batch_task.h"

#include <cmath>
#include <string>

#include "superdex/physics/error.h"

namespace superdex::robotics {
inline namespace SUPERDEX_REAL_NAMESPACE {

int batch_task_params_size(BatchTaskKind kind) {
  switch (kind) {
    case BatchTaskKind::CircleTracking: return 1;
    case BatchTaskKind::GoalReach: return 3;
    default: return 0;
  }
}

int batch_task_obs_size(BatchTaskKind kind) { return kind == BatchTaskKind::None ? 0 : 3; }

void check_batch_task(const BatchTask& task) {
  auto fail = [](const std::string& what) { throw Error("SceneBatch: spec.task." + what); };
  if (task.kind != BatchTaskKind::None && task.kind != BatchTaskKind::CircleTracking && task.kind != BatchTaskKind::GoalReach)
    fail("kind is not a BatchTaskKind");
  if (task.kind == BatchTaskKind::None) return;
  if (!std::isfinite(task.force_weight)) fail("force_weight must be finite");
  if (task.kind != BatchTaskKind::CircleTracking) return;
  for (double c : task.center)
    if (!std::isfinite(c)) fail("center must be finite (m)");
  if (!(task.radius > 0) || !std::isfinite(task.radius)) fail("radius must be a positive length (m), got " + std::to_string(task.radius));
  if (!std::isfinite(task.omega)) fail("omega must be finite (rad/s)");
  if (!(task.force_target > 0) || !std::isfinite(task.force_target))
    fail("force_target must be a positive force (N), got " + std::to_string(task.force_target));
}

double write_task_columns_and_reward(const BatchTask& task, const double* params, double t_seconds, int n, real* row) {
  const real* p_WE = row + 2 * n;
  const real* f_C_W = row + 2 * n + 3;
  real* columns = row + 2 * n + 6;
  if (task.kind == BatchTaskKind::CircleTracking) {
    const double theta = task.omega * t_seconds + params[0];
    const double x = task.center[0] + task.radius * std::cos(theta);
    const double z = task.center[2] + task.radius * std::sin(theta);
    columns[0] = static_cast<real>(x);
    columns[1] = static_cast<real>(task.center[1]);
    columns[2] = static_cast<real>(z);
    const double tracking = std::hypot(double(p_WE[0]) - x, double(p_WE[2]) - z) / task.radius;
    const bool touching = f_C_W[0] != 0 || f_C_W[1] != 0 || f_C_W[2] != 0;
    const double force = touching ? std::abs(double(f_C_W[2]) - task.force_target) / task.force_target : 0.0;
    return -tracking - task.force_weight * force;
  }
  if (task.kind == BatchTaskKind::GoalReach) {
    double d2 = 0, f2 = 0;
    for (int k = 0; k < 3; ++k) {
      columns[k] = static_cast<real>(params[k]);
      d2 += (double(p_WE[k]) - params[k]) * (double(p_WE[k]) - params[k]);
      f2 += double(f_C_W[k]) * double(f_C_W[k]);
    }
    return -std::sqrt(d2) - task.force_weight * std::sqrt(f2);
  }
  return 0.0;
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::robotics

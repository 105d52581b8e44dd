#pragma once
// The C++ tasks of a SceneBatch (scene_batch.h, BatchTaskKind): a scene's task columns and
// reward from its observation row, computed on that scene's worker thread.

#include "superdex/robotics/scene_batch.h"

namespace superdex::robotics {
inline namespace SUPERDEX_REAL_NAMESPACE {

/// Writes the task columns of one observation row and returns the reward. `row` is the whole row
/// (n = action columns: p_WE at 2 n, f_C_W at 2 n + 3, the task columns at 2 n + 6 are written);
/// `params` the scene's task parameters; `t_seconds` its task time (s) since its reset.
double write_task_columns_and_reward(const BatchTask& task, const double* params, double t_seconds, int n, real* row);

/// Throws superdex::Error naming the spec field when a task's constants are out of range.
void check_batch_task(const BatchTask& task);

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::robotics

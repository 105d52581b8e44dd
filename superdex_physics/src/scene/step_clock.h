#pragma once
// The wall clock of one scene step (Scene::step_dynamics): time-stamp ticks from its start
// (step_ticks.h), and steady_clock's time too until the ticks' rate is calibrated.

#include <chrono>

#include "core/step_ticks.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

struct StepClock {
  double calibrated_tick_seconds = 0;        // seconds per tick; 0 until calibrated
  std::chrono::steady_clock::time_point t0;  // the start by steady_clock (uncalibrated only)
  Ticks k0 = 0;                              // the start in ticks

  // A clock started now.
  static StepClock start() {
    StepClock c;
    c.calibrated_tick_seconds = calibrated_seconds_per_tick();
    c.t0 = c.calibrated_tick_seconds > 0 ? std::chrono::steady_clock::time_point{} : std::chrono::steady_clock::now();
    c.k0 = ticks_now();
    return c;
  }

  // The wall time since the start (s); sets `tick_seconds` to the seconds per tick that convert
  // the step's parts, counted in ticks.
  double seconds(double& tick_seconds) const {
    const Ticks total_ticks = ticks_now() - k0;
    tick_seconds = calibrated_tick_seconds;
    if (tick_seconds > 0) return tick_seconds * static_cast<double>(total_ticks);
    const double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    tick_seconds = seconds_per_tick(total, total_ticks);
    return total;
  }
};

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

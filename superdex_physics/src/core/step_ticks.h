#pragma once
// Timestamps for the step's timing statistics (StepStats::time_*), taken several times per body,
// contact chunk and island in every step: the processor's time-stamp counter on x86-64 (some
// 10 ns a read, against some 25 ns for steady_clock; constant-rate on the processors of the last
// decade), steady_clock's count elsewhere. A count of ticks becomes seconds by the ratio of one
// steady_clock interval to the ticks it spans (seconds_per_tick), or by the ratio calibrated once
// per process (calibrated_seconds_per_tick).

#include <chrono>
#include <cstdint>

#include "superdex/physics/real.h"
#include "solver/step_settings.h"

#if defined(__x86_64__)
#include <x86intrin.h>
#endif

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

using Ticks = std::int64_t;

inline Ticks ticks_now() {
#if defined(__x86_64__)
  return static_cast<Ticks>(__rdtsc());
#else
  return std::chrono::steady_clock::now().time_since_epoch().count();
#endif
}

// Seconds per tick over an interval of `seconds` that spanned `ticks` (0 when it spanned none).
inline double seconds_per_tick(double seconds, Ticks ticks) { return ticks > 0 ? seconds / static_cast<double>(ticks) : 0.0; }

// Seconds per tick for the whole process, from the steady_clock interval since the first call:
// 0 until that interval reaches kTickCalibrationSeconds, then fixed (on x86-64; elsewhere the
// ticks are steady_clock's and the ratio its period). Until then, callers time their intervals
// with steady_clock themselves.
inline constexpr double kTickCalibrationSeconds = 0.01;
double calibrated_seconds_per_tick();

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

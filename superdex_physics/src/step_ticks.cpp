// The process's time-stamp counter rate, calibrated against steady_clock.

#include "step_ticks.h"

#include <atomic>

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

double calibrated_seconds_per_tick() {
#if defined(__x86_64__)
  static std::atomic<double> fixed{0};
  const double known = fixed.load(std::memory_order_relaxed);
  if (known > 0) return known;
  // the first call's clock and counter (initialised once, thread-safe)
  struct Mark {
    std::chrono::steady_clock::time_point time;
    Ticks ticks;
  };
  static const Mark first{std::chrono::steady_clock::now(), ticks_now()};
  const auto now = std::chrono::steady_clock::now();
  const Ticks ticks = ticks_now();
  const double seconds = std::chrono::duration<double>(now - first.time).count();
  if (seconds < kTickCalibrationSeconds || ticks <= first.ticks) return 0;
  const double ratio = seconds_per_tick(seconds, ticks - first.ticks);
  fixed.store(ratio, std::memory_order_relaxed);
  return ratio;
#else
  return static_cast<double>(std::chrono::steady_clock::period::num) / std::chrono::steady_clock::period::den;
#endif
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

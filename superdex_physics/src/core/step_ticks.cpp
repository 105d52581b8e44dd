// The process's time-stamp counter rate, calibrated against steady_clock.

#include "core/step_ticks.h"

#include <atomic>

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

#if defined(__x86_64__)
namespace {

// A steady_clock reading and the counter at the same moment: the clock read between two counter
// reads, their midpoint. A pair whose counter reads lie far apart (the thread was preempted
// between them) is not taken: kMaxBracket ticks is some 30 us at the processors' rates.
struct Mark {
  std::chrono::steady_clock::time_point time;
  Ticks ticks = 0;
  bool valid = false;
};
constexpr Ticks kMaxBracket = 100000;

Mark mark_now() {
  const Ticks before = ticks_now();
  const auto time = std::chrono::steady_clock::now();
  const Ticks after = ticks_now();
  if (after < before || after - before > kMaxBracket) return {};
  return {time, before + (after - before) / 2, true};
}

}  // namespace
#endif

double calibrated_seconds_per_tick() {
#if defined(__x86_64__)
  static std::atomic<double> fixed{0};
  const double known = fixed.load(std::memory_order_relaxed);
  if (known > 0) return known;
  // the first good mark (a few tries), initialised once (thread-safe)
  static const Mark first = [] {
    Mark m;
    for (int attempt = 0; attempt < 8 && !m.valid; ++attempt) m = mark_now();
    return m;
  }();
  if (!first.valid) return 0;
  const Mark now = mark_now();
  if (!now.valid || now.ticks <= first.ticks) return 0;
  const double seconds = std::chrono::duration<double>(now.time - first.time).count();
  if (seconds < kTickCalibrationSeconds) return 0;
  const double ratio = seconds_per_tick(seconds, now.ticks - first.ticks);
  fixed.store(ratio, std::memory_order_relaxed);
  return ratio;
#else
  return static_cast<double>(std::chrono::steady_clock::period::num) / std::chrono::steady_clock::period::den;
#endif
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

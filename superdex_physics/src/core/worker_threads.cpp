// Running work items on the engine's worker threads (the oneTBB arena of initialize()).

#include <algorithm>
#include <array>
#include <atomic>
#include <cstdint>
#include <numeric>
#include <vector>

#include <oneapi/tbb/parallel_for.h>
#include <oneapi/tbb/task_arena.h>

#include "scene/scene_data.h"
#include "superdex/physics/engine.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace {

// Nesting depth of work items on this thread: a call from inside a work item (a scene's step
// within a batch of scenes) runs in order on its thread, as the outer items keep the threads busy.
thread_local int t_depth = 0;

// The arena to run `count` items on, or null when they run in order on the calling thread.
oneapi::tbb::task_arena* arena_for(std::size_t count) {
  if (count < 2 || t_depth > 0) return nullptr;
  EngineData& e = engine_data();
  std::shared_lock lock(e.mutex);
  oneapi::tbb::task_arena* arena = e.arena.get();
  if (e.single_threaded.load(std::memory_order_relaxed)) return nullptr;
  return arena && arena->max_concurrency() >= 2 ? arena : nullptr;
}

// Runs body(runner) on `runners` threads of the arena, as work items (t_depth raised meanwhile).
template <class Body>
void run_runners(oneapi::tbb::task_arena& arena, int runners, const Body& body) {
  arena.execute([&] {
    oneapi::tbb::parallel_for(0, runners, [&](int runner) {
      ++t_depth;
      try {
        body(runner);
      } catch (...) {
        --t_depth;
        throw;
      }
      --t_depth;
    });
  });
}

// The items not yet taken of one thread's share [front, back), packed in one word (front in the
// low half) so that its owner (from the front) and a helper (from the back) never take the same
// item; on a cache line of its own.
struct alignas(64) Share {
  std::atomic<std::uint64_t> front_back{0};

  void assign(std::size_t front, std::size_t back) { front_back.store(pack(front, back), std::memory_order_relaxed); }
  // The next item from the front (the owner), or false when none is left.
  bool take_front(std::size_t& item) { return take(item, true); }
  // The last item (a helper), or false when none is left.
  bool take_back(std::size_t& item) { return take(item, false); }

 private:
  static std::uint64_t pack(std::uint64_t front, std::uint64_t back) { return front | back << 32; }
  bool take(std::size_t& item, bool from_front) {
    std::uint64_t fb = front_back.load(std::memory_order_relaxed);
    for (;;) {
      const std::uint64_t front = fb & 0xffffffffu, back = fb >> 32;
      if (front >= back) return false;
      const std::uint64_t next = from_front ? pack(front + 1, back) : pack(front, back - 1);
      if (front_back.compare_exchange_weak(fb, next, std::memory_order_acq_rel, std::memory_order_relaxed)) {
        item = from_front ? front : back - 1;
        return true;
      }
    }
  }
};

}  // namespace

void run_on_worker_threads(std::size_t count, const std::function<void(std::size_t)>& work) {
  oneapi::tbb::task_arena* arena = arena_for(count);
  if (!arena) {
    for (std::size_t i = 0; i < count; ++i) work(i);
    return;
  }
  // greedy self-scheduling: each thread takes the next item as it becomes free, so items that
  // differ much in cost (islands, scenes), given largest first, end close together
  std::atomic<std::size_t> next{0};
  const int runners = static_cast<int>(std::min<std::size_t>(count, static_cast<std::size_t>(arena->max_concurrency())));
  run_runners(*arena, runners, [&](int) {
    for (std::size_t i = next.fetch_add(1); i < count; i = next.fetch_add(1)) work(i);
  });
}

namespace {

// Sorts the item indices `order` by decreasing costs[i], ties in the given order (stable). Short
// lists by insertion: std::stable_sort takes a temporary buffer from the heap.
void order_costliest_first(std::span<std::size_t> order, std::span<const double> costs) {
  const auto costlier = [&](std::size_t x, std::size_t y) { return costs[x] > costs[y]; };
  if (order.size() > 32) {
    std::stable_sort(order.begin(), order.end(), costlier);
    return;
  }
  for (std::size_t i = 1; i < order.size(); ++i)
    for (std::size_t j = i; j > 0 && costlier(order[j], order[j - 1]); --j) std::swap(order[j], order[j - 1]);
}

}  // namespace

void run_on_worker_threads_costliest_first(std::span<const double> costs, const std::function<void(std::size_t)>& work) {
  // the order on the stack when it is short (a scene's islands), so that a step does not allocate
  constexpr std::size_t kOnStack = 32;
  std::array<std::size_t, kOnStack> small;
  std::vector<std::size_t> large;
  if (costs.size() > kOnStack) large.resize(costs.size());
  const std::span<std::size_t> order = costs.size() > kOnStack ? std::span<std::size_t>(large) : std::span<std::size_t>(small.data(), costs.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  order_costliest_first(order, costs);
  run_on_worker_threads(order.size(), [&](std::size_t i) { work(order[i]); });
}

void run_on_worker_threads_with_home_threads(std::span<const double> costs, const std::function<void(std::size_t)>& work) {
  const std::size_t count = costs.size();
  oneapi::tbb::task_arena* arena = arena_for(count);
  const int runners = arena ? static_cast<int>(std::min<std::size_t>(count, static_cast<std::size_t>(arena->max_concurrency()))) : 1;
  // share s is the items [count * s / runners, count * (s + 1) / runners), costliest first
  std::vector<std::size_t> order(count);
  std::iota(order.begin(), order.end(), std::size_t{0});
  const auto share_begin = [&](int s) { return count * static_cast<std::size_t>(s) / static_cast<std::size_t>(runners); };
  for (int s = 0; s < runners; ++s)
    order_costliest_first(std::span<std::size_t>(order).subspan(share_begin(s), share_begin(s + 1) - share_begin(s)), costs);
  if (!arena) {
    for (std::size_t i : order) work(i);
    return;
  }
  // thread slot s of the arena (0: the calling thread) owns share s
  std::vector<Share> shares(static_cast<std::size_t>(runners));
  for (int s = 0; s < runners; ++s) shares[s].assign(share_begin(s), share_begin(s + 1));
  run_runners(*arena, runners, [&](int) {
    const int slot = oneapi::tbb::this_task_arena::current_thread_index();
    const int home = slot >= 0 ? slot % runners : 0;
    std::size_t p;
    while (shares[home].take_front(p)) work(order[p]);
    // then help the others from the cheap ends of their shares, nearest share first
    for (int k = 1; k < runners; ++k)
      while (shares[(home + k) % runners].take_back(p)) work(order[p]);
  });
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics

/// @file worker_threads_test.cpp
/// run_on_worker_threads_with_home_threads: every item runs once; each thread runs its own
/// contiguous share of indices (the calling thread the first share) costliest first, then the
/// other's from its cheapest, whatever the timing; one thread runs them in that order; a throwing
/// item's exception reaches the caller; a call from inside an item runs in order on that thread.

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <numeric>
#include <random>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <vector>

#include "superdex/physics/engine.h"

namespace superdex::physics {
namespace {

// The items each thread ran, in the order it ran them.
struct Trace {
  std::mutex mutex;
  std::map<std::thread::id, std::vector<std::size_t>> by_thread;

  void record(std::size_t item) {
    // a little work, so that both threads take part
    volatile double x = 1;
    for (int k = 0; k < 2000; ++k) x = x * 1.0000001 + 1e-9;
    std::lock_guard lock(mutex);
    by_thread[std::this_thread::get_id()].push_back(item);
  }
};

// True when `items` is first = first, first + 1, ... (increasing by one) for `up`, or first,
// first - 1, ... for !up.
bool consecutive(const std::vector<std::size_t>& items, std::size_t begin, std::size_t end, std::size_t first, bool up) {
  for (std::size_t k = begin; k < end; ++k)
    if (items[k] != (up ? first + (k - begin) : first - (k - begin))) return false;
  return true;
}

class WorkerThreads : public ::testing::Test {
 protected:
  void TearDown() override { shutdown(); }
};

// The expected order of the items: each half of the indices by decreasing cost (equal costs in
// index order); `position[i]` is item i's place in it.
std::vector<std::size_t> positions(const std::vector<double>& costs, std::size_t split) {
  std::vector<std::size_t> order(costs.size()), position(costs.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  const auto costlier = [&](std::size_t x, std::size_t y) { return costs[x] > costs[y]; };
  std::stable_sort(order.begin(), order.begin() + split, costlier);
  std::stable_sort(order.begin() + split, order.end(), costlier);
  for (std::size_t p = 0; p < order.size(); ++p) position[order[p]] = p;
  return position;
}

TEST_F(WorkerThreads, HomeSharesCostliestFirstThenTheOthersCheapestFirst) {
  initialize(2);
  ASSERT_EQ(num_worker_threads(), 2);
  std::mt19937 rng(5);
  for (std::size_t count : {2u, 3u, 7u, 64u, 65u}) {
    const std::size_t split = count / 2;  // share 0: [0, split) on the calling thread; share 1: [split, count)
    for (int call = 0; call < 20; ++call) {
      // equal costs (index order) in the first calls, then random ones with ties
      std::vector<double> costs(count, 1.0);
      if (call >= 5)
        for (double& c : costs) c = std::uniform_int_distribution<int>(0, 5)(rng);
      const std::vector<std::size_t> position = positions(costs, split);
      Trace trace;
      run_on_worker_threads_with_home_threads(costs, [&](std::size_t i) { trace.record(i); });
      std::vector<int> runs(count, 0);
      for (const auto& [thread, items] : trace.by_thread)
        for (std::size_t i : items) ++runs[i];
      for (std::size_t i = 0; i < count; ++i) ASSERT_EQ(runs[i], 1) << "item " << i << " of " << count;
      ASSERT_LE(trace.by_thread.size(), 2u);
      for (const auto& [thread, items] : trace.by_thread) {
        const bool caller = thread == std::this_thread::get_id();
        const std::size_t own_begin = caller ? 0 : split, own_end = caller ? split : count;
        const std::size_t other_end = caller ? count : split;
        std::vector<std::size_t> places;
        for (std::size_t i : items) places.push_back(position[i]);
        // its own share's items: a run from the share's costliest
        std::size_t own = 0;
        while (own < items.size() && items[own] >= own_begin && items[own] < own_end) ++own;
        EXPECT_TRUE(consecutive(places, 0, own, own_begin, true)) << "count " << count << ", call " << call << (caller ? ", caller" : ", worker");
        // then the other share's from its cheapest up
        EXPECT_TRUE(consecutive(places, own, places.size(), other_end - 1, false))
            << "count " << count << ", call " << call << (caller ? ", caller" : ", worker");
      }
    }
  }
}

TEST_F(WorkerThreads, OneThreadRunsTheItemsInOrder) {
  initialize(0);
  Trace trace;
  const std::vector<double> costs = {1, 3, 2, 3, 0};
  run_on_worker_threads_with_home_threads(costs, [&](std::size_t i) { trace.record(i); });
  ASSERT_EQ(trace.by_thread.size(), 1u);
  EXPECT_EQ(trace.by_thread.begin()->first, std::this_thread::get_id());
  EXPECT_EQ(trace.by_thread.begin()->second, (std::vector<std::size_t>{1, 3, 2, 0, 4}));
}

TEST_F(WorkerThreads, AnExceptionReachesTheCallerAndNestedCallsRunOnTheItemsThread) {
  initialize(2);
  EXPECT_THROW(run_on_worker_threads_with_home_threads(std::vector<double>(16, 0.0), [](std::size_t i) {
                 if (i == 12) throw std::runtime_error("item 12");
               }),
               std::runtime_error);
  // nested calls run in order on the item's thread; the outer items still spread
  std::mutex mutex;
  std::vector<std::thread::id> nested_threads;
  std::vector<std::size_t> nested_items;
  run_on_worker_threads_with_home_threads(std::vector<double>(2, 0.0), [&](std::size_t outer) {
    const std::thread::id here = std::this_thread::get_id();
    run_on_worker_threads_with_home_threads(std::vector<double>(3, 0.0), [&](std::size_t inner) {
      std::lock_guard lock(mutex);
      nested_threads.push_back(std::this_thread::get_id() == here ? here : std::thread::id());
      nested_items.push_back(outer * 3 + inner);
    });
  });
  ASSERT_EQ(nested_items.size(), 6u);
  for (const std::thread::id& t : nested_threads) EXPECT_NE(t, std::thread::id()) << "a nested item ran on another thread";
}

}  // namespace
}  // namespace superdex::physics

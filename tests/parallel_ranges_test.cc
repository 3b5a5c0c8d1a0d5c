// base/parallel_ranges.h: every element handled exactly once, in contiguous ranges, serially
// below kParallelFrom, on several threads above it; and an element-wise computation gives the
// same bits on any number of threads.
#include "base/parallel_ranges.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstring>
#include <mutex>
#include <set>
#include <thread>
#include <vector>

namespace pqlayout {
namespace {

struct Visit {
  std::vector<int> count;
  std::set<std::thread::id> threads;
  std::mutex mutex;
};

void VisitAll(int n, unsigned threads, Visit* visit) {
  visit->count.assign(n, 0);
  ParallelRanges(n, [&](int begin, int end) {
    ASSERT_LE(begin, end);
    for (int i = begin; i < end; ++i) ++visit->count[i];  // each element by one range only
    std::lock_guard<std::mutex> lock(visit->mutex);
    visit->threads.insert(std::this_thread::get_id());
  }, threads);
}

TEST(ParallelRanges, EveryElementOnceSeriallyBelowTheThreshold) {
  for (const int n : {0, 1, 7, kParallelFrom - 1}) {
    Visit visit;
    VisitAll(n, 4, &visit);
    for (int i = 0; i < n; ++i) ASSERT_EQ(visit.count[i], 1) << "n " << n << " element " << i;
    if (n > 0) {
      EXPECT_EQ(visit.threads.size(), 1u);
      EXPECT_EQ(*visit.threads.begin(), std::this_thread::get_id());
    }
  }
}

TEST(ParallelRanges, EveryElementOnceOnSeveralThreadsAboveIt) {
  for (const unsigned threads : {1u, 2u, 3u, 4u, 9u}) {
    const int n = kParallelFrom + 7;
    Visit visit;
    VisitAll(n, threads, &visit);
    for (int i = 0; i < n; ++i) ASSERT_EQ(visit.count[i], 1) << "threads " << threads << " element " << i;
    EXPECT_EQ(visit.threads.size(), std::min(threads, kMaxRangeThreads)) << "threads " << threads;
  }
}

TEST(ParallelRanges, ElementWiseResultsAreTheSameBitsOnAnyThreadCount) {
  const int n = 3 * kParallelFrom;
  const auto compute = [n](unsigned threads) {
    std::vector<double> out(n);
    ParallelRanges(n, [&](int begin, int end) {
      for (int i = begin; i < end; ++i) out[i] = std::sin(0.001 * i) * std::exp(-1e-6 * i) / (1.0 + i);
    }, threads);
    return out;
  };
  const std::vector<double> one = compute(1);
  for (const unsigned threads : {2u, 3u, 4u}) {
    const std::vector<double> many = compute(threads);
    EXPECT_EQ(std::memcmp(one.data(), many.data(), n * sizeof(double)), 0) << threads << " threads";
  }
}

}  // namespace
}  // namespace pqlayout

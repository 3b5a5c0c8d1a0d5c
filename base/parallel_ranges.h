// Element-wise loops split over a few threads, with the same result as one: body(begin, end)
// handles the elements [begin, end) of [0, n), and must write only those elements' own outputs
// and read nothing another range writes, and must not throw. Each element is then computed by the same code in the
// same order of operations whichever thread runs it, so the output is bit-identical for any
// thread count (unlike a reduction, whose sums would regroup: never use it for one).
// Used where a stage walks every face of a large reference once (principal_directions.cc,
// guidance.cc): below kParallelFrom elements, or on one hardware thread, it runs serially.
#pragma once

#include <algorithm>
#include <thread>
#include <vector>

namespace pqlayout {

inline constexpr int kParallelFrom = 50000;  // below this a thread's start costs more than it saves
inline constexpr unsigned kMaxRangeThreads = 4;

template <typename Body>
void ParallelRanges(int n, Body&& body, unsigned threads = std::thread::hardware_concurrency()) {
  threads = std::clamp(threads, 1u, kMaxRangeThreads);
  if (n < kParallelFrom || threads == 1) {
    if (n > 0) body(0, n);
    return;
  }
  const auto bound = [&](unsigned part) { return static_cast<int>(static_cast<long long>(n) * part / threads); };
  std::vector<std::thread> workers;
  workers.reserve(threads - 1);
  for (unsigned part = 1; part < threads; ++part)
    workers.emplace_back([&body, begin = bound(part), end = bound(part + 1)] { body(begin, end); });
  body(0, bound(1));
  for (std::thread& worker : workers) worker.join();
}

}  // namespace pqlayout

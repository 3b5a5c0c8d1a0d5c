// CostWindow (solver/cost_window.h): when a crawling minimisation is declared stalled.
#include "solver/cost_window.h"

#include <gtest/gtest.h>

#include <cmath>

namespace pqlayout {
namespace {

// The iteration (0-based) at which the window first reports a stall, or -1 within n.
template <typename Cost>
int StallIteration(int window, double gain, int n, Cost cost) {
  CostWindow w(window, gain);
  for (int i = 0; i < n; ++i)
    if (w.AddAndCheckStalled(cost(i))) return i;
  return -1;
}

TEST(CostWindow, NeverStallsBeforeTheWindowIsFull) {
  // A constant cost is a stall, but only from iterate `size` on (iterate 0 is never compared).
  EXPECT_EQ(StallIteration(25, 0.005, 100, [](int) { return 7.0; }), 25);
  EXPECT_EQ(StallIteration(2, 0.005, 100, [](int) { return 7.0; }), 2);
  // Iterate 0 far above a flat rest: still iterate `size`, not earlier or later.
  EXPECT_EQ(StallIteration(5, 0.005, 100, [](int i) { return i == 0 ? 1e9 : 7.0; }), 5);
}

TEST(CostWindow, GeometricDecreaseStallsWhereTheWindowGainFallsBelowTheThreshold) {
  // cost_i = c∞ + r^i; a window of size W spans S = W − 1 steps, whose decrease
  // r^(i−S) − r^i = r^i (r^−S − 1) falls below gain × cost_i = gain (c∞ + r^i) first at
  // i > log(gain c∞ / (r^−S − 1 − gain)) / log r (closed form).
  const double r = 0.9, c_inf = 100.0, gain = 0.005;
  const int W = 25, S = W - 1;
  const auto cost = [&](int i) { return c_inf + std::pow(r, i); };
  const double bound = std::log(gain * c_inf / (std::pow(r, -S) - 1.0 - gain)) / std::log(r);
  const int expected = static_cast<int>(std::floor(bound)) + 1;
  ASSERT_GT(expected, W);  // the known answer is not the trivial first full window
  EXPECT_EQ(StallIteration(W, gain, 1000, cost), expected);
}

TEST(CostWindow, SteadyRelativeProgressNeverStalls) {
  // 1 % per iteration is 22 % per window of 25: never a stall, however long it runs.
  EXPECT_EQ(StallIteration(25, 0.005, 2000, [](int i) { return std::pow(0.99, i); }), -1);
}

TEST(CostWindow, APlateauAfterProgressStallsOneWindowLater) {
  // Fast progress to iterate 40, then flat: the window's oldest cost is iterate i − 24, which
  // reaches the plateau at i = 64 (at 63 it is iterate 39, 20 above: 10 % of 200).
  const auto cost = [](int i) { return i < 40 ? 1000.0 - 20.0 * i : 200.0; };
  EXPECT_EQ(StallIteration(25, 0.005, 200, cost), 64);
}

}  // namespace
}  // namespace pqlayout

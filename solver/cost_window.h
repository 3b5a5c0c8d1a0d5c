// A minimisation's progress over a sliding window of iterations, for ending a solve that
// crawls: Ceres' own function tolerance compares consecutive iterations only (1e-6 of the
// cost), which a Levenberg–Marquardt or L-BFGS run that lowers its cost by 0.01 % per
// iteration never meets. Used by the level-set joint solve (levelset_terms.cc) and stiffen.
#pragma once

#include <deque>

namespace pqlayout {

class CostWindow {
 public:
  // size ≥ 2: the number of latest costs kept; gain: the relative decrease they must span.
  CostWindow(int size, double gain) : window_(size), gain_(gain) {}

  // Adds the cost of the next iterate (the i-th added, from 0). True when i ≥ size and the
  // oldest kept cost, that of iterate i − size + 1, lies less than gain × the newest above it:
  // size − 1 steps that did not lower the cost by that fraction. The first cost added (a
  // run's start, often far above everything after it) is never the reference.
  bool AddAndCheckStalled(double cost) {
    costs_.push_back(cost);
    if (static_cast<int>(costs_.size()) <= window_) return false;
    costs_.pop_front();
    return costs_.front() - costs_.back() < gain_ * costs_.back();
  }
  bool empty() const { return costs_.empty(); }

 private:
  const int window_;
  const double gain_;
  std::deque<double> costs_;
};

}  // namespace pqlayout

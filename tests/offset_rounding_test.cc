// Rounding the seams' offsets to whole levels (problems/levelset_initial.cc, RoundOffsets):
// odd across sign −1 seams, whole across sign +1 seams; with the free fit's offset block
// C = (A⁻¹)_aa, the combination of least energy excess ½ (a − a*)ᵀ C⁻¹ (a − a*).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "problems/levelset.h"
#include "problems/levelset_internal.h"

namespace pqlayout {
namespace {
using levelset_internal::RoundOffsets;

LevelSetSeams Signs(std::vector<int> sign) {
  LevelSetSeams seams;
  seams.sign = std::move(sign);
  return seams;
}

double Excess(const std::vector<double>& a, const std::vector<double>& free, const Eigen::MatrixXd& block) {
  const Eigen::VectorXd d = Eigen::Map<const Eigen::VectorXd>(a.data(), a.size()) -
                            Eigen::Map<const Eigen::VectorXd>(free.data(), free.size());
  return d.dot(block.ldlt().solve(d));
}

TEST(OffsetRounding, EachAloneGoesToTheNearestAllowedLevel) {
  const LevelSetSeams seams = Signs({-1, -1, 1, 1, -1});
  std::vector<double> offsets{10.2, 9.9, 0.4, -2.6, -4.3};
  RoundOffsets(seams, &offsets);
  EXPECT_EQ(offsets, (std::vector<double>{11.0, 9.0, 0.0, -3.0, -5.0}));
  // An uncoupled block (identity) changes nothing.
  std::vector<double> again{10.2, 9.9, 0.4, -2.6, -4.3};
  const Eigen::MatrixXd identity = Eigen::MatrixXd::Identity(5, 5);
  RoundOffsets(seams, &again, &identity);
  EXPECT_EQ(again, offsets);
}

// Two seams whose offsets the fit wants equal (strongly correlated block, as at a pair of
// singularities around one umbilic): rounded one by one they split 11 / 9, which costs
// ~15× the energy of moving both to 11.
TEST(OffsetRounding, CoupledSeamsAreRoundedTogether) {
  const LevelSetSeams seams = Signs({-1, -1});
  Eigen::MatrixXd block(2, 2);
  block << 1.0, 0.99, 0.99, 1.0;
  const std::vector<double> free{10.2, 9.9};
  std::vector<double> alone = free, together = free;
  RoundOffsets(seams, &alone);
  RoundOffsets(seams, &together, &block);
  EXPECT_EQ(alone, (std::vector<double>{11.0, 9.0}));
  EXPECT_EQ(together, (std::vector<double>{11.0, 11.0}));
  EXPECT_NEAR(Excess(together, free, block), 0.1076 / (1.0 - 0.99 * 0.99), 1e-9);
  EXPECT_GT(Excess(alone, free, block), 10.0 * Excess(together, free, block));
}

// Random SPD blocks: the joint choice is allowed (odd / whole), each offset one of its two
// nearest allowed values, never worse than rounding alone, and optimal among all 2^k
// neighbours up to kMaxJointSeams (12); beyond, single flips only, still never worse.
TEST(OffsetRounding, JointChoiceIsNeverWorseThanRoundingAlone) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> uniform(-20.0, 20.0), unit(-1.0, 1.0);
  for (const int k : {3, 6, 12, 15}) {
    for (int trial = 0; trial < 20; ++trial) {
      std::vector<int> sign(k);
      for (int p = 0; p < k; ++p) sign[p] = (p + trial) % 3 == 0 ? 1 : -1;
      const LevelSetSeams seams = Signs(sign);
      Eigen::MatrixXd m(k, k);
      for (int i = 0; i < k; ++i)
        for (int j = 0; j < k; ++j) m(i, j) = unit(rng);
      const Eigen::MatrixXd block = m * m.transpose() + 0.05 * Eigen::MatrixXd::Identity(k, k);
      std::vector<double> free(k);
      for (double& a : free) a = uniform(rng);
      std::vector<double> alone = free, together = free;
      RoundOffsets(seams, &alone);
      RoundOffsets(seams, &together, &block);
      for (int p = 0; p < k; ++p) {
        const double a = together[p];
        EXPECT_EQ(a, std::round(a));
        if (sign[p] < 0) {
          EXPECT_EQ(std::abs(std::fmod(a, 2.0)), 1.0) << "seam " << p;
        }
        EXPECT_LT(std::abs(a - free[p]), sign[p] < 0 ? 2.0 : 1.0) << "seam " << p;
      }
      const double joint = Excess(together, free, block);
      EXPECT_LE(joint, Excess(alone, free, block) * (1.0 + 1e-12));
      if (k > 12) continue;
      for (unsigned mask = 0; mask < (1u << k); ++mask) {
        std::vector<double> a(k);
        for (int p = 0; p < k; ++p) {
          const double step = sign[p] < 0 ? 2.0 : 1.0;
          const double low = sign[p] < 0 ? 2.0 * std::floor((free[p] - 1.0) / 2.0) + 1.0 : std::floor(free[p]);
          a[p] = low + ((mask >> p & 1u) ? step : 0.0);
        }
        ASSERT_GE(Excess(a, free, block), joint * (1.0 - 1e-9)) << "k " << k << " trial " << trial;
      }
    }
  }
}

}  // namespace
}  // namespace pqlayout

// Linear buckling (solver/frame_buckling.h) against Euler's columns, its invariants, and
// member utilisation (solver/member_checks.h) against hand values.
#include <gtest/gtest.h>

#include <cmath>

#include <Eigen/Geometry>

#include "solver/frame_buckling.h"
#include "solver/member_checks.h"

namespace pqlayout {
namespace {

const FrameSection kChs = FrameSection::CircularHollow(0.1143, 0.005);

FrameMaterial Steel() {
  FrameMaterial m;
  m.youngs_modulus = 210e9;
  m.shear_modulus = 210e9 / 2.6;
  return m;
}

// A straight column of `members` equal members from the origin along `axis`, rotated by R,
// axial load −P at the far end (compression for P > 0). Supports per end.
FrameModel Column(int members, double L, double P, const Restraints& first, const Restraints& last,
                  const Eigen::Matrix3d& R = Eigen::Matrix3d::Identity()) {
  FrameModel m;
  for (int i = 0; i <= members; ++i) m.nodes.push_back(R * Eigen::Vector3d(L * i / members, 0.0, 0.0));
  for (int i = 0; i < members; ++i) m.members.push_back({i, i + 1, R * Eigen::Vector3d::UnitZ()});
  m.restraints.assign(m.nodes.size(), Restraints{});
  m.restraints.front() = first, m.restraints.back() = last;
  m.loads.assign(m.nodes.size(), NodeVector::Zero());
  m.loads.back().head<3>() = R * Eigen::Vector3d(-P, 0.0, 0.0);
  m.section = kChs;
  m.material = Steel();
  return m;
}

// Pinned at the origin (translations and the twist held), a roller at the far end.
const Restraints kPin{true, true, true, true, false, false};
const Restraints kRoller{false, true, true, false, false, false};
const Restraints kClamp{true, true, true, true, true, true};
const Restraints kFree{false, false, false, false, false, false};

double Factor(const FrameModel& m, BucklingResult* b = nullptr) {
  FrameResult linear;
  EXPECT_TRUE(SolveFrame(m, &linear).ok());
  BucklingResult own;
  BucklingResult& r = b ? *b : own;
  const Status status = SolveBuckling(m, linear, 3, &r);
  EXPECT_TRUE(status.ok()) << status.message();
  return r.factors.empty() ? -1.0 : r.factors.front();
}

TEST(Buckling, PinnedColumnIsEuler) {
  const double L = 6.0, P = 1e4, EI = 210e9 * kChs.inertia_y;
  const double euler = M_PI * M_PI * EI / (L * L);
  for (const int members : {8, 16}) {
    const double critical = Factor(Column(members, L, P, kPin, kRoller)) * P;
    EXPECT_NEAR(critical, euler, 1e-3 * euler) << members << " members";
  }
  // Convergence of the cubic elements: the error falls at least 8-fold when halved (h⁴: 16).
  const double e8 = std::abs(Factor(Column(4, L, P, kPin, kRoller)) * P - euler);
  const double e16 = std::abs(Factor(Column(8, L, P, kPin, kRoller)) * P - euler);
  EXPECT_LT(e16, e8 / 8.0);
}

TEST(Buckling, CantileverIsEulerOverFour) {
  const double L = 4.0, P = 1e4, EI = 210e9 * kChs.inertia_y;
  const double euler = M_PI * M_PI * EI / (4.0 * L * L);
  EXPECT_NEAR(Factor(Column(8, L, P, kClamp, kFree)) * P, euler, 1e-3 * euler);
}

TEST(Buckling, FactorIsInvariantUnderRigidRotation) {
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.9, Eigen::Vector3d(1, -2, 0.5).normalized()).toRotationMatrix();
  BucklingResult straight, rotated;
  const double a = Factor(Column(8, 5.0, 2e4, kClamp, kFree), &straight);
  // Supports in world axes: the rotated cantilever is clamped at the origin, free at the tip.
  const double b = Factor(Column(8, 5.0, 2e4, kClamp, kFree, R), &rotated);
  EXPECT_NEAR(a, b, 1e-8 * a);
  ASSERT_EQ(straight.modes.size(), rotated.modes.size());
  // The mode is the same shape, rotated: its largest translation sits at the same node.
  EXPECT_NEAR(straight.modes[0].back().head<3>().norm(), 1.0, 1e-12);
  EXPECT_NEAR(rotated.modes[0].back().head<3>().norm(), 1.0, 1e-12);
}

TEST(Buckling, TensionOnlyDoesNotBuckle) {
  FrameResult linear;
  const FrameModel m = Column(8, 4.0, -1e4, kClamp, kFree);  // pulled
  ASSERT_TRUE(SolveFrame(m, &linear).ok());
  BucklingResult r;
  ASSERT_TRUE(SolveBuckling(m, linear, 3, &r).ok());
  EXPECT_FALSE(r.buckles);
  EXPECT_TRUE(r.factors.empty());
}

// More modes: factors ascending, each mode normalised; the second Euler mode of the pinned
// column (n = 2: 4 × the first) is among them (the CHS has two equal bending planes).
TEST(Buckling, HigherModesAscend) {
  BucklingResult r;
  const FrameModel m = Column(16, 6.0, 1e4, kPin, kRoller);
  FrameResult linear;
  ASSERT_TRUE(SolveFrame(m, &linear).ok());
  ASSERT_TRUE(SolveBuckling(m, linear, 6, &r).ok());
  ASSERT_GE(r.factors.size(), 3u);
  for (size_t i = 1; i < r.factors.size(); ++i) EXPECT_LE(r.factors[i - 1], r.factors[i] * (1 + 1e-9));
  bool second = false;
  for (const double f : r.factors) second |= std::abs(f / r.factors[0] - 4.0) < 0.01;
  EXPECT_TRUE(second);
}

// A cantilever under a tip load P across it: at the clamp M = P L, N = 0, so
// η = P L / (W_el f_y) with W_el = I / (D/2).
// The memo returns the kept result only for the very same inputs: the same column again (reused,
// the same factors), then one bit of an axial force, a support or the modes count changed (solved
// anew, and the Euler factor moves with the load).
TEST(Buckling, TheMemoReusesOnlyTheSameInputs) {
  const FrameModel m = Column(8, 6.0, 1e4, kPin, kRoller);
  FrameResult linear;
  ASSERT_TRUE(SolveFrame(m, &linear).ok());
  BucklingMemo memo;
  BucklingResult first, again;
  bool reused = true;
  ASSERT_TRUE(memo.Solve(m, linear, 3, &first, &reused).ok());
  EXPECT_FALSE(reused);
  ASSERT_TRUE(memo.Solve(m, linear, 3, &again, &reused).ok());
  EXPECT_TRUE(reused);
  EXPECT_EQ(again.factors, first.factors);
  EXPECT_EQ(again.operations, first.operations);
  FrameResult doubled = linear;
  for (double& n : doubled.axial_force) n *= 2.0;
  BucklingResult other;
  ASSERT_TRUE(memo.Solve(m, doubled, 3, &other, &reused).ok());
  EXPECT_FALSE(reused);
  EXPECT_NEAR(other.factors.front(), 0.5 * first.factors.front(), 1e-9 * first.factors.front());
  FrameModel clamped = m;
  clamped.restraints.front() = kClamp;
  ASSERT_TRUE(memo.Solve(clamped, doubled, 3, &other, &reused).ok());
  EXPECT_FALSE(reused);
  ASSERT_TRUE(memo.Solve(clamped, doubled, 2, &other, &reused).ok());
  EXPECT_FALSE(reused);
  EXPECT_EQ(other.factors.size(), 2u);
}

TEST(Utilisation, CantileverTipLoadIsTheHandValue) {
  const double L = 3.0, P = 5e3, fy = 355e6;
  FrameModel m = Column(6, L, 0.0, kClamp, kFree);
  m.loads.back()[2] = -P;
  FrameResult linear;
  ASSERT_TRUE(SolveFrame(m, &linear).ok());
  const SectionModuli W = SectionModuli::CircularHollow(0.1143, 0.005);
  const std::vector<double> eta = MemberUtilisation(m, linear, W, fy);
  ASSERT_EQ(eta.size(), 6u);
  const double hand = P * L / (kChs.inertia_y / (0.1143 / 2) * fy);
  EXPECT_NEAR(eta[0], hand, 1e-9 * hand);
  EXPECT_NEAR(eta[5], P * (L / 6) / (kChs.inertia_y / (0.1143 / 2) * fy), 1e-9 * hand);  // at the last member's root
  // Axial only: η = N / (A f_y).
  FrameModel axial = Column(4, L, 1e5, kClamp, kFree);
  ASSERT_TRUE(SolveFrame(axial, &linear).ok());
  for (const double e : MemberUtilisation(axial, linear, W, fy)) EXPECT_NEAR(e, 1e5 / (kChs.area * fy), 1e-9);
}

}  // namespace
}  // namespace pqlayout

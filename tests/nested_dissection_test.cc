// The nested-dissection ordering (solver/nested_dissection.h) and CHOLMOD with a given
// ordering: a permutation, the fill of a 2D mesh's factor growing as nested dissection's
// (flops ~ n^1.5, not a band's n²), the same solution as CHOLMOD's own ordering, and a
// perm that is no permutation refused.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <numeric>

#include "solver/cholmod_solver.h"
#include "solver/nested_dissection.h"

namespace pqlayout {
namespace {

// The 5-point Laplacian (+ a small shift, SPD) of a k × k grid numbered row by row, and the
// grid points, bent into a quarter cylinder so that the coordinates are not the numbering.
struct Grid {
  Eigen::SparseMatrix<double> A;
  std::vector<Eigen::Vector3d> points;
};

Grid MakeGrid(int k) {
  Grid g;
  const int n = k * k;
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < k; ++i)
    for (int j = 0; j < k; ++j) {
      const int v = i * k + j;
      t.emplace_back(v, v, 5.01);
      if (j + 1 < k) t.emplace_back(v, v + 1, -1.0), t.emplace_back(v + 1, v, -1.0);
      if (i + 1 < k) t.emplace_back(v, v + k, -1.0), t.emplace_back(v + k, v, -1.0);
      if (i + 1 < k && j + 1 < k) t.emplace_back(v, v + k + 1, -0.5), t.emplace_back(v + k + 1, v, -0.5);
      const double angle = 0.5 * M_PI * j / (k - 1);
      g.points.emplace_back(std::cos(angle), std::sin(angle), static_cast<double>(i) / (k - 1));
    }
  g.A.resize(n, n);
  g.A.setFromTriplets(t.begin(), t.end());
  return g;
}

struct FactorCost {
  double lnz, flops;
};

FactorCost Cost(const Eigen::SparseMatrix<double>& A, std::vector<int> perm) {
  CholmodSolver solver;
  solver.SetOrdering(std::move(perm));
  EXPECT_TRUE(solver.Factorize(A).ok());
  return {solver.factor_nonzeros(), solver.factor_flops()};
}

TEST(NestedDissection, IsAPermutationAlsoWithCoincidentPoints) {
  Grid g = MakeGrid(23);
  for (bool coincident : {false, true}) {
    if (coincident) std::fill(g.points.begin(), g.points.end(), Eigen::Vector3d(1.0, 2.0, 3.0));
    std::vector<int> perm = NestedDissectionOrdering(g.A, g.points);
    ASSERT_EQ(perm.size(), g.points.size());
    std::sort(perm.begin(), perm.end());
    for (int k = 0; k < static_cast<int>(perm.size()); ++k) ASSERT_EQ(perm[k], k) << "coincident " << coincident;
  }
}

// Nested dissection of a k × k triangulated grid (a lattice mesh's 7-point stencil, as the
// lattice-seeded references have): nnz(L) ~ n log n and flops ~ n^1.5 (George 1973); the
// row-by-row order is a band, flops ~ n² (×15.9 from k = 150 to 300, measured). Doubling k
// multiplies n by 4: nested dissection's flops by ~8. CHOLMOD's AMD needs more flops on
// these lattices, and more so the larger they are (at k = 300: 6.8e8 against 5.1e8).
TEST(NestedDissection, FillOfALatticeGrowsAsNestedDissectionsAndBeatsTheBandAndAmd) {
  FactorCost nd[2], amd[2];
  for (int s = 0; s < 2; ++s) {
    const int k = s == 0 ? 150 : 300;
    const Grid g = MakeGrid(k);
    nd[s] = Cost(g.A, NestedDissectionOrdering(g.A, g.points));
    amd[s] = Cost(g.A, {});
    std::cout << "k " << k << ": nested dissection lnz " << nd[s].lnz << " flops " << nd[s].flops
              << ", CHOLMOD's own " << amd[s].lnz << " / " << amd[s].flops << "\n";
    if (s == 0) {
      std::vector<int> natural(g.points.size());
      std::iota(natural.begin(), natural.end(), 0);
      const FactorCost band = Cost(g.A, natural);
      std::cout << "  band " << band.lnz << " / " << band.flops << "\n";
      EXPECT_LT(nd[s].flops, 0.2 * band.flops);
    }
  }
  EXPECT_LT(nd[1].flops, 0.85 * amd[1].flops);
  EXPECT_LT(nd[1].flops / nd[0].flops, 9.0);  // 8.3 measured
  EXPECT_LT(nd[1].lnz / nd[0].lnz, 5.2);      // 4.9 measured
}

TEST(NestedDissection, GivenOrderingSolvesAsCholmodsOwnAndIsRefusedIfNoPermutation) {
  const Grid g = MakeGrid(60);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(g.A.rows(), -1.0, 2.0);
  CholmodSolver own, given;
  ASSERT_TRUE(own.Factorize(g.A).ok());
  given.SetOrdering(NestedDissectionOrdering(g.A, g.points));
  ASSERT_TRUE(given.Factorize(g.A).ok());
  Eigen::VectorXd x_own, x_given;
  ASSERT_TRUE(own.Solve(b, &x_own).ok());
  ASSERT_TRUE(given.Solve(b, &x_given).ok());
  EXPECT_LT((g.A * x_given - b).norm() / b.norm(), 1e-13);
  EXPECT_LT((x_given - x_own).norm() / x_own.norm(), 1e-13);

  std::vector<int> repeated(g.A.rows(), 0);
  std::iota(repeated.begin(), repeated.end(), 0);
  repeated[7] = 8;
  for (std::vector<int> bad : {repeated, std::vector<int>(10, 0), std::vector<int>(g.A.rows(), -1)}) {
    CholmodSolver solver;
    solver.SetOrdering(bad);
    const Status s = solver.Factorize(g.A);
    EXPECT_EQ(s.code(), StatusCode::kInvalidInput);
    EXPECT_NE(s.message().find("not a permutation"), std::string::npos) << s.message();
  }
}

}  // namespace
}  // namespace pqlayout

// SupernodalCholesky (solver/supernodal_cholesky.h): solutions against dense LLᵀ and CHOLMOD
// under several orderings, fronts wider than a panel, refusals (not positive definite, not
// finite, not a permutation) naming the row.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <limits>
#include <numeric>
#include <random>
#include <vector>

#include <Eigen/Dense>

#include "geometry/differential_operators.h"
#include "solver/cholmod_solver.h"
#include "solver/nested_dissection.h"
#include "solver/supernodal_cholesky.h"
#include "tests/test_meshes.h"

namespace pqlayout {
namespace {

// The 5-point Laplacian of a rows × cols grid plus `shift` on the diagonal (SPD for shift > 0),
// with the grid points for nested dissection.
Eigen::SparseMatrix<double> Grid(int rows, int cols, double shift, std::vector<Eigen::Vector3d>* points) {
  const int n = rows * cols;
  std::vector<Eigen::Triplet<double>> t;
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) {
      const int i = r * cols + c;
      t.emplace_back(i, i, 4.0 + shift);
      if (c + 1 < cols) t.emplace_back(i, i + 1, -1.0), t.emplace_back(i + 1, i, -1.0);
      if (r + 1 < rows) t.emplace_back(i, i + cols, -1.0), t.emplace_back(i + cols, i, -1.0);
      if (points) points->emplace_back(c, r, 0.0);
    }
  Eigen::SparseMatrix<double> A(n, n);
  A.setFromTriplets(t.begin(), t.end());
  return A;
}

Eigen::VectorXd RandomVector(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::VectorXd b(n);
  for (auto& x : b) x = u(rng);
  return b;
}

TEST(SupernodalCholesky, MatchesDenseCholeskyUnderEveryOrdering) {
  std::vector<Eigen::Vector3d> points;
  const Eigen::SparseMatrix<double> A = Grid(23, 17, 0.01, &points);
  const int n = static_cast<int>(A.rows());
  const Eigen::VectorXd b = RandomVector(n, 3);
  const Eigen::VectorXd exact = Eigen::MatrixXd(A).llt().solve(b);
  std::vector<int> natural(n), reversed(n), shuffled(n);
  std::iota(natural.begin(), natural.end(), 0);
  std::reverse_copy(natural.begin(), natural.end(), reversed.begin());
  shuffled = natural;
  std::shuffle(shuffled.begin(), shuffled.end(), std::mt19937(5));
  for (const auto& perm : {natural, reversed, shuffled, NestedDissectionOrdering(A, points)}) {
    SupernodalCholesky factor;
    ASSERT_TRUE(factor.Factorize(A, perm).ok());
    EXPECT_LT(factor.supernodes(), n);  // columns were grouped
    Eigen::VectorXd x;
    ASSERT_TRUE(factor.Solve(b, &x).ok());
    EXPECT_LT((x - exact).norm(), 1e-11 * exact.norm());
    EXPECT_LT((A * x - b).norm(), 1e-12 * b.norm());
  }
}

// A membrane matrix (cotangent stiffness of a dome, its rim held) large enough for fronts wider
// than a panel (kPanel = 32) and for relaxed supernodes, with its interior points.
Eigen::SparseMatrix<double> DomeMembrane(std::vector<Eigen::Vector3d>* points) {
  const SurfaceModel s(testing::GeneratedMesh("dome", 30.0, 30.0, 5.0, 0.25));
  const Eigen::SparseMatrix<double> K = CotanStiffness(s);
  std::vector<int> unknown(s.num_vertices(), -1);
  int n = 0;
  for (int v = 0; v < s.num_vertices(); ++v)
    if (!s.is_boundary(v)) unknown[v] = n++, points->push_back(s.position(v));
  std::vector<Eigen::Triplet<double>> t;
  for (int j = 0; j < K.outerSize(); ++j)
    for (Eigen::SparseMatrix<double>::InnerIterator it(K, j); it; ++it)
      if (unknown[it.row()] >= 0 && unknown[j] >= 0) t.emplace_back(unknown[it.row()], unknown[j], it.value());
  Eigen::SparseMatrix<double> A(n, n);
  A.setFromTriplets(t.begin(), t.end());
  return A;
}

// The same solution as CHOLMOD's.
TEST(SupernodalCholesky, MatchesCholmodOnAMembraneMatrix) {
  std::vector<Eigen::Vector3d> points;
  const Eigen::SparseMatrix<double> A = DomeMembrane(&points);
  const int n = static_cast<int>(A.rows());
  ASSERT_GT(n, 10000);
  const Eigen::VectorXd b = RandomVector(n, 11);
  CholmodSolver cholmod;
  ASSERT_TRUE(cholmod.Factorize(A).ok());
  Eigen::VectorXd reference, x;
  ASSERT_TRUE(cholmod.Solve(b, &reference).ok());
  SupernodalCholesky factor;
  ASSERT_TRUE(factor.Factorize(A, NestedDissectionOrdering(A, points)).ok());
  ASSERT_TRUE(factor.Solve(b, &x).ok());
  EXPECT_LT((x - reference).norm(), 1e-10 * reference.norm());
  EXPECT_LT((A * x - b).norm(), 1e-12 * b.norm());
  EXPECT_LT(factor.supernodes(), n / 4);
  EXPECT_GT(factor.flops(), 0.5 * cholmod.factor_flops());  // explicit zeros add work, never remove it
}

// The halves below the top separator factored on two threads: the same bits as one thread, on
// the dome (nested dissection: the split is the top separator), on two grids side by side (two
// trees: the first factored before the split) and a grid under the natural order (a banded
// tree, its supernodes a chain: nothing split).
TEST(SupernodalCholesky, TwoThreadsGiveTheSameBitsAsOne) {
  std::vector<Eigen::Vector3d> dome_points, grid_points;
  const Eigen::SparseMatrix<double> dome = DomeMembrane(&dome_points);
  const Eigen::SparseMatrix<double> grid = Grid(40, 55, 0.01, &grid_points);
  const int g = static_cast<int>(grid.rows());
  std::vector<Eigen::Triplet<double>> t;  // two copies of the grid, uncoupled
  for (int copy = 0; copy < 2; ++copy)
    for (int j = 0; j < g; ++j)
      for (Eigen::SparseMatrix<double>::InnerIterator it(grid, j); it; ++it)
        t.emplace_back(copy * g + static_cast<int>(it.row()), copy * g + j, it.value());
  Eigen::SparseMatrix<double> forest(2 * g, 2 * g);
  forest.setFromTriplets(t.begin(), t.end());
  std::vector<Eigen::Vector3d> forest_points = grid_points;
  for (const auto& p : grid_points) forest_points.push_back(p + Eigen::Vector3d(100.0, 0.0, 0.0));
  std::vector<int> natural(grid.rows());
  std::iota(natural.begin(), natural.end(), 0);
  const std::vector<std::pair<const Eigen::SparseMatrix<double>*, std::vector<int>>> cases = {
      {&dome, NestedDissectionOrdering(dome, dome_points)},
      {&forest, NestedDissectionOrdering(forest, forest_points)},
      {&grid, natural}};
  for (const auto& [A, perm] : cases) {
    const Eigen::VectorXd b = RandomVector(static_cast<int>(A->rows()), 17);
    Eigen::VectorXd x[2];
    for (const int threads : {1, 2}) {
      SupernodalCholesky factor;
      factor.set_threads(threads);
      ASSERT_TRUE(factor.Factorize(*A, perm).ok());
      ASSERT_TRUE(factor.Solve(b, &x[threads - 1]).ok());
      if (threads == 1 || &perm == &cases.back().second) EXPECT_EQ(factor.second_thread_supernodes(), 0);
      else EXPECT_GT(factor.second_thread_supernodes(), factor.supernodes() / 4) << "n " << A->rows();
    }
    EXPECT_LT((*A * x[1] - b).norm(), 1e-12 * b.norm());
    EXPECT_EQ(std::memcmp(x[0].data(), x[1].data(), sizeof(double) * x[0].size()), 0) << "n " << A->rows();
  }
}

// A row that is not positive definite is named whichever thread's half it lies in.
TEST(SupernodalCholesky, NamesTheFailingRowOnTwoThreads) {
  std::vector<Eigen::Vector3d> points;
  const Eigen::SparseMatrix<double> grid = Grid(60, 70, 0.01, &points);
  const std::vector<int> perm = NestedDissectionOrdering(grid, points);
  for (const int row : {0, 1234, 2100, 4199, perm.back()}) {
    Eigen::SparseMatrix<double> A = grid;
    A.coeffRef(row, row) = -1.0;
    for (const int threads : {1, 2}) {
      SupernodalCholesky factor;
      factor.set_threads(threads);
      EXPECT_EQ(factor.Factorize(A, perm).code(), StatusCode::kInternal);
      EXPECT_EQ(factor.failed_row(), row) << threads << " threads";
    }
  }
}

TEST(SupernodalCholesky, NamesTheRowThatIsNotPositiveDefinite) {
  Eigen::SparseMatrix<double> A = Grid(6, 7, 0.5, nullptr);
  A.coeffRef(17, 17) = -1.0;
  std::vector<int> natural(A.rows());
  std::iota(natural.begin(), natural.end(), 0);
  SupernodalCholesky factor;
  const Status status = factor.Factorize(A, natural);
  EXPECT_EQ(status.code(), StatusCode::kInternal);
  EXPECT_EQ(factor.failed_row(), 17);
  EXPECT_NE(status.message().find("row 17"), std::string::npos) << status.message();
  Eigen::VectorXd x;
  EXPECT_FALSE(factor.Solve(Eigen::VectorXd::Ones(A.rows()), &x).ok());
}

TEST(SupernodalCholesky, RefusesNonFiniteEntriesAndBadOrderings) {
  Eigen::SparseMatrix<double> A = Grid(5, 5, 0.5, nullptr);
  std::vector<int> natural(A.rows());
  std::iota(natural.begin(), natural.end(), 0);
  SupernodalCholesky factor;
  std::vector<int> repeated = natural;
  repeated[3] = 4;
  EXPECT_EQ(factor.Factorize(A, repeated).code(), StatusCode::kInvalidInput);
  EXPECT_EQ(factor.Factorize(A, {0, 1, 2}).code(), StatusCode::kInvalidInput);
  A.coeffRef(9, 9) = std::numeric_limits<double>::quiet_NaN();
  const Status status = factor.Factorize(A, natural);
  EXPECT_EQ(status.code(), StatusCode::kInvalidInput);
  EXPECT_EQ(factor.failed_row(), 9);
}

}  // namespace
}  // namespace pqlayout

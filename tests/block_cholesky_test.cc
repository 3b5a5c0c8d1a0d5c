// BlockCholesky (solver/block_cholesky.h): solutions against Eigen's dense LLᵀ and CHOLMOD on
// a ribbed dome's frame stiffness, the factor kept across a pattern, a matrix that is not
// positive definite named by its node block.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <iostream>
#include <random>

#include <Eigen/Cholesky>

#include "solver/block_cholesky.h"
#include "solver/cholmod_solver.h"
#include "solver/frame_analysis.h"

namespace pqlayout {
namespace {

constexpr int kB = BlockCholesky::kBlock;

// A ribbed dome: `rings` rings of `spokes` nodes round a crown node, 2 m apart, members along
// the rings and the spokes, the outer ring pinned.
FrameModel RibbedDome(int rings, int spokes) {
  FrameModel m;
  m.nodes.emplace_back(0.0, 0.0, 0.3 * 2.0 * rings);
  for (int r = 1; r <= rings; ++r)
    for (int k = 0; k < spokes; ++k) {
      const double radius = 2.0 * r, angle = 2.0 * M_PI * k / spokes;
      m.nodes.emplace_back(radius * std::cos(angle), radius * std::sin(angle), 0.3 * (2.0 * rings - radius * radius / (2.0 * rings)));
    }
  const auto id = [spokes](int r, int k) { return r == 0 ? 0 : 1 + (r - 1) * spokes + (k % spokes); };
  for (int r = 1; r <= rings; ++r)
    for (int k = 0; k < spokes; ++k) {
      m.members.push_back({id(r - 1, k), id(r, k), Eigen::Vector3d::UnitZ()});
      m.members.push_back({id(r, k), id(r, k + 1), Eigen::Vector3d::UnitZ()});
    }
  m.restraints.assign(m.nodes.size(), Restraints{});
  for (int k = 0; k < spokes; ++k) m.restraints[id(rings, k)] = {true, true, true, false, false, false};
  m.section = FrameSection::CircularHollow(0.1143, 0.005);
  return m;
}

// The frame's stiffness over all 6 DOFs of every node: a restrained DOF's row and column are
// the identity scaled to K's largest diagonal entry.
Eigen::SparseMatrix<double> PaddedStiffness(const FrameSystem& s, int nodes) {
  const double scale = s.K.diagonal().cwiseAbs().maxCoeff();
  std::vector<int> dof_of(s.free);
  for (int k = 0; k < kB * nodes; ++k)
    if (s.index[k] >= 0) dof_of[s.index[k]] = k;
  std::vector<Eigen::Triplet<double>> entries;
  for (int c = 0; c < s.K.outerSize(); ++c)
    for (Eigen::SparseMatrix<double>::InnerIterator it(s.K, c); it; ++it)
      entries.emplace_back(dof_of[it.row()], dof_of[c], it.value());
  for (int k = 0; k < kB * nodes; ++k)
    if (s.index[k] < 0) entries.emplace_back(k, k, scale);
  Eigen::SparseMatrix<double> A(kB * nodes, kB * nodes);
  A.setFromTriplets(entries.begin(), entries.end());
  return A;
}

// A random SPD matrix of n × n node blocks on a ring with chords (diagonally dominant).
Eigen::SparseMatrix<double> RandomBlockMatrix(int nodes, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Eigen::Triplet<double>> entries;
  Eigen::VectorXd row_sum = Eigen::VectorXd::Zero(kB * nodes);
  const auto couple = [&](int a, int b) {
    for (int r = 0; r < kB; ++r)
      for (int c = 0; c < kB; ++c) {
        const double v = u(rng);
        entries.emplace_back(kB * a + r, kB * b + c, v);
        entries.emplace_back(kB * b + c, kB * a + r, v);
        row_sum[kB * a + r] += std::abs(v), row_sum[kB * b + c] += std::abs(v);
      }
  };
  for (int a = 0; a < nodes; ++a) couple(a, (a + 1) % nodes), couple(a, (a * 7 + 3) % nodes == a ? (a + 2) % nodes : (a * 7 + 3) % nodes);
  for (int k = 0; k < kB * nodes; ++k) entries.emplace_back(k, k, row_sum[k] + 1.0 + u(rng) * 0.5);
  Eigen::SparseMatrix<double> A(kB * nodes, kB * nodes);
  A.setFromTriplets(entries.begin(), entries.end());
  return A;
}

TEST(BlockCholesky, SolvesLikeADenseFactorAndKeepsItsAnalysis) {
  BlockCholesky solver;
  for (const unsigned seed : {1u, 2u}) {  // the same pattern twice: the analysis is kept
    const Eigen::SparseMatrix<double> A = RandomBlockMatrix(40, 7);
    Eigen::SparseMatrix<double> B = A;
    for (int k = 0; k < B.outerSize(); ++k)
      for (Eigen::SparseMatrix<double>::InnerIterator it(B, k); it; ++it)
        if (it.row() == it.col()) it.valueRef() += seed;
    const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(B.rows(), -1.0, 2.0);
    ASSERT_TRUE(solver.Factorize(B).ok());
    Eigen::VectorXd x;
    ASSERT_TRUE(solver.Solve(b, &x).ok());
    const Eigen::VectorXd dense = Eigen::MatrixXd(B).llt().solve(b);
    EXPECT_LE((x - dense).norm(), 1e-12 * dense.norm()) << "seed " << seed;
    EXPECT_LE((B * x - b).norm(), 1e-12 * b.norm());
    EXPECT_GT(solver.rcond(), 0.0);
    EXPECT_LE(solver.rcond(), 1.0);
  }
}

TEST(BlockCholesky, NamesTheNodeBlockThatIsNotPositiveDefinite) {
  Eigen::SparseMatrix<double> A = RandomBlockMatrix(10, 3);
  A.coeffRef(kB * 4 + 2, kB * 4 + 2) = -50.0;
  BlockCholesky solver;
  EXPECT_FALSE(solver.Factorize(A).ok());
  EXPECT_EQ(solver.failed_row(), kB * 4);
  EXPECT_FALSE(solver.factorized());
  Eigen::VectorXd x;
  EXPECT_FALSE(solver.Solve(Eigen::VectorXd::Ones(A.rows()), &x).ok());
  EXPECT_FALSE(solver.Factorize(Eigen::SparseMatrix<double>(7, 7)).ok());  // not in 6 × 6 blocks
  Eigen::SparseMatrix<double> B = RandomBlockMatrix(10, 3);
  B.coeffRef(13, 13) = std::nan("");
  const Status refused = solver.Factorize(B);
  EXPECT_EQ(refused.code(), StatusCode::kInvalidInput);
  EXPECT_EQ(solver.failed_row(), 13);
}

// A ribbed dome's frame (20 rings of 48 nodes, 5,473 free DOFs): the same displacements as
// CHOLMOD's to 1e-10 relative; the two factorisations' times printed (speed lives in benchmarks/).
TEST(BlockCholesky, AFrameStiffnessSolvesLikeCholmod) {
  const FrameModel m = RibbedDome(20, 48);
  FrameSystem system;
  ASSERT_TRUE(AssembleFrame(m, &system).ok());
  const int nodes = static_cast<int>(m.nodes.size());
  const Eigen::SparseMatrix<double> A = PaddedStiffness(system, nodes);
  Eigen::VectorXd f = Eigen::VectorXd::Zero(system.free);
  for (int k = 0; k < kB * nodes; ++k)
    if (system.index[k] >= 0 && k % kB == 2) f[system.index[k]] = -1e4;
  Eigen::VectorXd f_padded = Eigen::VectorXd::Zero(kB * nodes);
  for (int k = 0; k < kB * nodes; ++k)
    if (system.index[k] >= 0) f_padded[k] = f[system.index[k]];
  CholmodSolver cholmod;
  BlockCholesky block;
  ASSERT_TRUE(cholmod.Factorize(system.K).ok());
  ASSERT_TRUE(block.Factorize(A).ok());
  const auto time = [](const auto& work) {
    const auto t0 = std::chrono::steady_clock::now();
    for (int r = 0; r < 5; ++r) work();
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() / 5;
  };
  const double t_cholmod = time([&] { ASSERT_TRUE(cholmod.Factorize(system.K, true).ok()); });
  const double t_block = time([&] { ASSERT_TRUE(block.Factorize(A).ok()); });
  std::cout << "factor: CHOLMOD " << 1e3 * t_cholmod << " ms, block " << 1e3 * t_block << " ms\n";
  Eigen::VectorXd u_cholmod, u_block;
  ASSERT_TRUE(cholmod.Solve(f, &u_cholmod).ok());
  ASSERT_TRUE(block.Solve(f_padded, &u_block).ok());
  double err = 0.0;
  for (int k = 0; k < kB * nodes; ++k) {
    if (system.index[k] < 0) EXPECT_EQ(u_block[k], 0.0);
    else err = std::max(err, std::abs(u_block[k] - u_cholmod[system.index[k]]));
  }
  EXPECT_LE(err, 1e-10 * u_cholmod.cwiseAbs().maxCoeff());
  EXPECT_NEAR(block.rcond(), cholmod.rcond(), 0.5 * cholmod.rcond());
}

// Subtrees of the elimination tree factored on a second thread (block_cholesky.h): the same
// factor to the bit as one thread (the solutions compared with memcmp), on a ribbed dome of
// 3,841 nodes where the split takes a real share of the columns; and where two node blocks
// are not positive definite, the one that one thread finds first is named.
TEST(BlockCholesky, TwoThreadsGiveTheSameBitsAsOne) {
  const FrameModel m = RibbedDome(40, 96);
  FrameSystem system;
  ASSERT_TRUE(AssembleFrame(m, &system).ok());
  const int nodes = static_cast<int>(m.nodes.size());
  Eigen::SparseMatrix<double> A = PaddedStiffness(system, nodes);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(A.rows(), -1.0, 2.0);
  BlockCholesky one, two;
  one.set_threads(1), two.set_threads(2);
  ASSERT_TRUE(one.Factorize(A).ok());
  ASSERT_TRUE(two.Factorize(A).ok());
  EXPECT_EQ(one.second_thread_columns(), 0);
  EXPECT_GE(two.second_thread_columns(), nodes / 5);
  Eigen::VectorXd x1, x2;
  ASSERT_TRUE(one.Solve(b, &x1).ok());
  ASSERT_TRUE(two.Solve(b, &x2).ok());
  EXPECT_EQ(std::memcmp(x1.data(), x2.data(), sizeof(double) * x1.size()), 0);
  EXPECT_EQ(one.rcond(), two.rcond());
  EXPECT_LE((A * x2 - b).norm(), 1e-9 * b.norm());
  for (const int bad : {nodes - 1, nodes / 3, 7}) {  // wherever a failing block lies
    Eigen::SparseMatrix<double> B = A;
    B.coeffRef(kB * bad + 1, kB * bad + 1) = -1.0;
    B.coeffRef(kB * (nodes / 2) + 1, kB * (nodes / 2) + 1) = -1.0;
    EXPECT_FALSE(one.Factorize(B).ok());
    EXPECT_FALSE(two.Factorize(B).ok());
    EXPECT_EQ(one.failed_row(), two.failed_row()) << "bad node " << bad;
    EXPECT_FALSE(two.factorized());
  }
}

}  // namespace
}  // namespace pqlayout

// The membrane solve against analytic solutions (disk, annulus) with the convergence rate,
// the stiffness matrix's invariants, the CHOLMOD wrapper, and refusal of singular problems.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <iostream>
#include <random>

#include <Eigen/Dense>

#include "geometry/differential_operators.h"
#include "geometry/surface_generators.h"
#include "problems/membrane.h"
#include "solver/cholmod_solver.h"
#include "tests/test_meshes.h"

namespace pqlayout {
namespace {

constexpr double kQ = 1350.0, kLambda = 2.0e4;

SurfaceModel Generate(const std::string& name, double width, double depth, double edge) {
  return SurfaceModel(testing::GeneratedMesh(name, width, depth, 5.0, edge));
}

VertexConditions AllBoundary(const SurfaceModel& s, BoundaryCondition c) {
  VertexConditions conditions(s.num_vertices());
  for (int v = 0; v < s.num_vertices(); ++v)
    if (s.is_boundary(v)) conditions[v] = c;
  return conditions;
}

MembraneSolution Solve(const SurfaceModel& s, const VertexConditions& c, double q = kQ, double lambda = kLambda) {
  MembraneOptions options;
  options.stiffness = lambda;
  MembraneSolution solution;
  const Status st = SolveMembrane(s, c, options, q, &solution);
  EXPECT_TRUE(st.ok()) << st.message();
  return solution;
}

double RadialOf(const SurfaceModel& s, int v) { return s.position(v).head<2>().norm(); }

// Max nodal error against the exact solution, relative to the exact peak |v|.
template <typename Exact>
double MaxRelativeNodalError(const SurfaceModel& s, const MembraneSolution& sol, Exact exact, double peak) {
  double error = 0.0;
  for (int v = 0; v < s.num_vertices(); ++v) error = std::max(error, std::abs(sol.v_z[v] - exact(RadialOf(s, v))));
  return error / peak;
}

TEST(Membrane, DiskMatchesAnalyticSolutionAndConvergesAtSecondOrder) {
  // −λ Δv = −q on the unit disk, v = 0 on r = 1:  v = −q (1 − r²) / (4λ).
  auto exact = [](double r) { return -kQ * (1.0 - r * r) / (4.0 * kLambda); };
  const double peak = kQ / (4.0 * kLambda);
  std::vector<double> errors, sizes;
  for (double h : {0.2, 0.1, 0.05}) {
    const SurfaceModel s = Generate("disk", 2.0, 0.0, h);
    const MembraneSolution sol = Solve(s, AllBoundary(s, BoundaryCondition::kFixed));
    errors.push_back(MaxRelativeNodalError(s, sol, exact, peak));
    sizes.push_back(h);
    std::cout << "disk h=" << h << " vertices=" << s.num_vertices() << " max nodal error/peak=" << errors.back() << "\n";
    EXPECT_LT(sol.relative_residual, 1e-10);
  }
  EXPECT_LE(errors.back(), 0.01) << "max nodal error at h = 0.05";
  for (size_t i = 1; i < errors.size(); ++i) {
    const double order = std::log(errors[i - 1] / errors[i]) / std::log(sizes[i - 1] / sizes[i]);
    std::cout << "observed order " << order << "\n";
    EXPECT_GE(order, 1.8) << "h " << sizes[i - 1] << " → " << sizes[i] << ": errors " << errors[i - 1] << " → " << errors[i];
  }
}

// Above 100k unknowns the factor is ordered by nested dissection (problems/membrane.cc): the
// same analytic solution, to the discretisation's error (second order: ~(h / 0.05)² of the
// error at 0.05 above), and fewer flops than CHOLMOD's own ordering of the same matrix.
TEST(Membrane, LargeDiskIsOrderedByNestedDissectionAndStaysAccurate) {
  auto exact = [](double r) { return -kQ * (1.0 - r * r) / (4.0 * kLambda); };
  const double peak = kQ / (4.0 * kLambda);
  const SurfaceModel s = Generate("disk", 2.0, 0.0, 0.0085);
  const MembraneSolution sol = Solve(s, AllBoundary(s, BoundaryCondition::kFixed));
  ASSERT_GE(sol.n_unknowns, 100000);
  EXPECT_EQ(sol.ordering, "nested dissection");
  EXPECT_LT(sol.relative_residual, 1e-10);
  const double error = MaxRelativeNodalError(s, sol, exact, peak);
  std::cout << "disk h=0.0085 unknowns=" << sol.n_unknowns << " max nodal error/peak=" << error
            << " flops=" << sol.factor_flops << "\n";
  EXPECT_LE(error, 3e-5);  // 1.2e-5 measured
  EXPECT_LT(sol.factor_flops, 1.2e9);  // 8.5e8 measured; CHOLMOD's AMD on the same matrix: 1.6e9
}

TEST(Membrane, AnnulusInnerFixedOuterFreeMatchesRadialSolution) {
  // Δv = q/λ on 1 < r < 2, v(1) = 0, v'(2) = 0:  v = q/(4λ)(r² − 1) − (2q/λ) ln r.
  auto exact = [](double r) { return kQ / (4.0 * kLambda) * (r * r - 1.0) - 2.0 * kQ / kLambda * std::log(r); };
  const SurfaceModel s = Generate("annulus", 4.0, 2.0, 0.05);
  ASSERT_EQ(s.boundary_loops().size(), 2u);
  VertexConditions c(s.num_vertices());
  for (const auto v : s.boundary_loops()[0].vertices) c[v.idx()] = BoundaryCondition::kFree;   // outer, r = 2
  for (const auto v : s.boundary_loops()[1].vertices) c[v.idx()] = BoundaryCondition::kFixed;  // inner, r = 1
  const MembraneSolution sol = Solve(s, c);
  const double peak = std::abs(exact(2.0));
  const double error = MaxRelativeNodalError(s, sol, exact, peak);
  std::cout << "annulus max nodal error/peak=" << error << "\n";
  EXPECT_LE(error, 0.01);
  EXPECT_EQ(sol.n_dirichlet, static_cast<int>(s.boundary_loops()[1].vertices.size()));
}

TEST(Membrane, SolutionIsLinearInLoadAndInverseInStiffness) {
  const SurfaceModel s = Generate("dome", 10.0, 8.0, 1.0);
  const auto c = AllBoundary(s, BoundaryCondition::kFixed);
  const auto a = Solve(s, c, 1000.0, 1e5), b = Solve(s, c, 3000.0, 1e5), d = Solve(s, c, 1000.0, 4e5);
  for (int v = 0; v < s.num_vertices(); ++v) {
    EXPECT_NEAR(b.v_z[v], 3.0 * a.v_z[v], 1e-12 * std::abs(a.v_z[v]) + 1e-18);
    EXPECT_NEAR(d.v_z[v], 0.25 * a.v_z[v], 1e-12 * std::abs(a.v_z[v]) + 1e-18);
    EXPECT_LE(a.v_z[v], 0.0);  // maximum principle: a downward load never lifts the membrane
  }
}

TEST(Membrane, SlidingAndClampedAreDirichletFreeIsNot) {
  const SurfaceModel s = Generate("plane", 4.0, 4.0, 0.5);
  auto c = AllBoundary(s, BoundaryCondition::kSliding);
  EXPECT_EQ(Solve(s, c).n_dirichlet, s.num_boundary_vertices());
  c = AllBoundary(s, BoundaryCondition::kClamped);
  EXPECT_EQ(Solve(s, c).n_dirichlet, s.num_boundary_vertices());
}

TEST(Membrane, UnsupportedSurfaceIsRefused) {
  const SurfaceModel s = Generate("plane", 4.0, 4.0, 1.0);
  MembraneSolution sol;
  const Status st = SolveMembrane(s, AllBoundary(s, BoundaryCondition::kFree), MembraneOptions(), kQ, &sol);
  EXPECT_EQ(st.code(), StatusCode::kInvalidInput);
  EXPECT_NE(st.message().find("has no fixed, clamped or sliding boundary vertex"), std::string::npos) << st.message();
}

TEST(CotanStiffness, SymmetricConstantsInNullSpacePositiveSemidefinite) {
  const SurfaceModel s = Generate("hypar", 6.0, 5.0, 1.0);
  const Eigen::SparseMatrix<double> K = CotanStiffness(s);
  EXPECT_NEAR((Eigen::SparseMatrix<double>(K.transpose()) - K).norm(), 0.0, 1e-12);
  const Eigen::VectorXd ones = Eigen::VectorXd::Ones(s.num_vertices());
  EXPECT_NEAR((K * ones).norm(), 0.0, 1e-10);
  std::mt19937 rng(7);
  std::normal_distribution<double> gauss;
  for (int trial = 0; trial < 5; ++trial) {
    Eigen::VectorXd x(s.num_vertices());
    for (auto& xi : x) xi = gauss(rng);
    EXPECT_GE(x.dot(K * x), 0.0);
  }
  // Dirichlet energy of a linear function u = a·x on a flat plate equals |a|² × area.
  const SurfaceModel plate = Generate("plane", 3.0, 2.0, 0.4);
  const Eigen::SparseMatrix<double> Kp = CotanStiffness(plate);
  Eigen::VectorXd u(plate.num_vertices());
  for (int v = 0; v < plate.num_vertices(); ++v) u[v] = 2.0 * plate.position(v).x() - 0.5 * plate.position(v).y();
  EXPECT_NEAR(u.dot(Kp * u), (4.0 + 0.25) * 6.0, 1e-9);
}

TEST(CotanStiffness, MatchesTheCotangentFormulaOnOneTriangle) {
  PolygonSoup soup;
  soup.points = {{0, 0, 0}, {2, 0, 0}, {0.5, 1.5, 0.3}};
  soup.faces = {{0, 1, 2}};
  const SurfaceModel s(testing::ToMesh(soup));
  const Eigen::MatrixXd K = Eigen::MatrixXd(CotanStiffness(s));
  auto cot_at = [&](int k) {
    const Eigen::Vector3d a = s.position((k + 1) % 3) - s.position(k), b = s.position((k + 2) % 3) - s.position(k);
    return a.dot(b) / a.cross(b).norm();
  };
  // Edge (i, j) is opposite vertex k: K_ij = −½ cot θ_k.
  EXPECT_NEAR(K(0, 1), -0.5 * cot_at(2), 1e-14);
  EXPECT_NEAR(K(1, 2), -0.5 * cot_at(0), 1e-14);
  EXPECT_NEAR(K(0, 2), -0.5 * cot_at(1), 1e-14);
  EXPECT_NEAR(K(0, 0), 0.5 * (cot_at(1) + cot_at(2)), 1e-14);
}

// The direct assembly sums each entry's face terms in face order, as Eigen's setFromTriplets
// does: the same pattern and the same bits (memcmp: a −0 stays −0), on a curved mesh and on a
// flat grid of right triangles, whose right angles give zero off-diagonal terms.
TEST(CotanStiffness, BitIdenticalToTheTripletAssembly) {
  for (const SurfaceModel& s : {Generate("dome", 10.0, 8.0, 0.7), Generate("plane", 3.0, 2.0, 0.5)}) {
    std::vector<Eigen::Triplet<double>> triplets;
    for (int f = 0; f < s.num_faces(); ++f) {
      const auto ids = s.face_vertices(f);
      const auto g = FaceBasisGradients(s, f);
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) triplets.emplace_back(ids[a], ids[b], s.face_area(f) * g[a].dot(g[b]));
    }
    Eigen::SparseMatrix<double> reference(s.num_vertices(), s.num_vertices());
    reference.setFromTriplets(triplets.begin(), triplets.end());
    const Eigen::SparseMatrix<double> K = CotanStiffness(s);
    ASSERT_TRUE(K.isCompressed());
    ASSERT_EQ(K.nonZeros(), reference.nonZeros());
    ASSERT_EQ(std::memcmp(K.outerIndexPtr(), reference.outerIndexPtr(), sizeof(int) * (s.num_vertices() + 1)), 0);
    ASSERT_EQ(std::memcmp(K.innerIndexPtr(), reference.innerIndexPtr(), sizeof(int) * K.nonZeros()), 0);
    EXPECT_EQ(std::memcmp(K.valuePtr(), reference.valuePtr(), sizeof(double) * K.nonZeros()), 0);
  }
}

TEST(FaceGradient, ExactForLinearFunctionsOnCurvedSurfaces) {
  const SurfaceModel s = Generate("dome", 10.0, 10.0, 1.0);
  const Eigen::Vector3d a(0.3, -1.2, 0.7);
  std::vector<double> values(s.num_vertices());
  for (int v = 0; v < s.num_vertices(); ++v) values[v] = a.dot(s.position(v));
  for (int f = 0; f < s.num_faces(); f += 7) {
    const Eigen::Vector3d& n = s.face_normal(f);
    const Eigen::Vector3d tangential = a - n * n.dot(a);  // the surface gradient of a·x
    EXPECT_NEAR((FaceGradient(s, f, values) - tangential).norm(), 0.0, 1e-12);
  }
}

TEST(CholmodSolver, SolvesSpdSystemsAndRefusesBadMatrices) {
  const int n = 40;
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < n; ++i) {
    t.emplace_back(i, i, 4.0);
    if (i + 1 < n) {
      t.emplace_back(i, i + 1, -1.0);
      t.emplace_back(i + 1, i, -1.0);
    }
  }
  Eigen::SparseMatrix<double> A(n, n);
  A.setFromTriplets(t.begin(), t.end());
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(n, -1.0, 2.0);
  CholmodSolver solver;
  ASSERT_TRUE(solver.Factorize(A).ok());
  EXPECT_FALSE(solver.is_supernodal());  // simplicial on purpose: no CPU-dependent BLAS kernel
  Eigen::VectorXd x;
  ASSERT_TRUE(solver.Solve(b, &x).ok());
  EXPECT_NEAR((Eigen::MatrixXd(A).ldlt().solve(b) - x).norm(), 0.0, 1e-12);

  Eigen::SparseMatrix<double> indefinite = A;
  indefinite.coeffRef(5, 5) = -10.0;
  Status s = solver.Factorize(indefinite);
  EXPECT_EQ(s.code(), StatusCode::kInternal);
  EXPECT_NE(s.message().find("not positive definite"), std::string::npos) << s.message();
  EXPECT_FALSE(solver.Solve(b, &x).ok());
  Eigen::SparseMatrix<double> asymmetric = A;
  asymmetric.coeffRef(0, 1) = 3.0;
  s = solver.Factorize(asymmetric);
  EXPECT_EQ(s.code(), StatusCode::kInvalidInput);
  EXPECT_NE(s.message().find("not symmetric"), std::string::npos);
  Eigen::SparseMatrix<double> nonfinite = A;
  nonfinite.coeffRef(2, 2) = NAN;
  EXPECT_NE(solver.Factorize(nonfinite).message().find("non-finite"), std::string::npos);
}

}  // namespace
}  // namespace pqlayout

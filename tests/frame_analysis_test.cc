// The 3D frame solver against beam theory: cantilevers in arbitrary orientation (tip
// deflection PL³/3EI, axial PL/EA, twist TL/GJ), subdivision invariance, equilibrium of a
// curved grid, invariance under rigid rotation, and refusal of mechanisms.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

#include <Eigen/Geometry>

#include "solver/frame_analysis.h"

namespace pqlayout {
namespace {

std::mt19937 rng(42);
Eigen::Vector3d RandomUnit() {
  std::normal_distribution<double> g;
  return Eigen::Vector3d(g(rng), g(rng), g(rng)).normalized();
}
Eigen::Vector3d Perpendicular(const Eigen::Vector3d& d) { return d.cross(RandomUnit()).normalized(); }

const FrameSection kChs = FrameSection::CircularHollow(0.1143, 0.005);
FrameMaterial Steel() {
  FrameMaterial m;
  m.youngs_modulus = 210e9;
  m.shear_modulus = 210e9 / (2.0 * 1.3);
  return m;
}

// A straight cantilever of `segments` members from the origin along d, fixed at node 0.
FrameModel Cantilever(const Eigen::Vector3d& d, double length, int segments, const NodeVector& tip_load) {
  FrameModel m;
  for (int i = 0; i <= segments; ++i) m.nodes.push_back(d * length * i / segments);
  for (int i = 0; i < segments; ++i) m.members.push_back({i, i + 1, Perpendicular(d)});
  m.restraints.assign(m.nodes.size(), Restraints{});
  m.restraints[0].fill(true);
  m.loads.assign(m.nodes.size(), NodeVector::Zero());
  m.loads.back() = tip_load;
  m.section = kChs;
  m.material = Steel();
  return m;
}

TEST(FrameAnalysis, CircularHollowSectionConstants) {
  const double D = 0.1143, d = D - 0.01;
  EXPECT_NEAR(kChs.area, M_PI / 4 * (D * D - d * d), 1e-15);
  EXPECT_NEAR(kChs.inertia_y, M_PI / 64 * (std::pow(D, 4) - std::pow(d, 4)), 1e-18);
  EXPECT_EQ(kChs.torsion, 2 * kChs.inertia_y);
}

TEST(FrameAnalysis, CantileverMatchesBeamTheoryInAnyOrientation) {
  const double L = 3.7, P = 12e3, T = 2.5e3;
  const FrameMaterial steel = Steel();
  for (int trial = 0; trial < 10; ++trial) {
    const Eigen::Vector3d d = RandomUnit(), across = Perpendicular(d);
    for (int segments : {1, 4}) {
      FrameResult r;
      NodeVector load = NodeVector::Zero();
      load.head<3>() = P * across;  // transverse tip load
      ASSERT_TRUE(SolveFrame(Cantilever(d, L, segments, load), &r).ok());
      const double expected = P * L * L * L / (3 * steel.youngs_modulus * kChs.inertia_y);
      EXPECT_NEAR(r.displacement.back().head<3>().dot(across), expected, 1e-9 * expected);
      EXPECT_NEAR(r.displacement.back().head<3>().cross(across).norm(), 0.0, 1e-9 * expected);
      // Tip rotation P L² / 2EI about d × across.
      EXPECT_NEAR(r.displacement.back().tail<3>().dot(d.cross(across)), P * L * L / (2 * steel.youngs_modulus * kChs.inertia_y),
                  1e-9 * P * L * L / (2 * steel.youngs_modulus * kChs.inertia_y));
      // Torque about the axis: twist T L / G J.
      load.setZero();
      load.tail<3>() = T * d;
      ASSERT_TRUE(SolveFrame(Cantilever(d, L, segments, load), &r).ok());
      const double twist = T * L / (steel.shear_modulus * kChs.torsion);
      EXPECT_NEAR(r.displacement.back().tail<3>().dot(d), twist, 1e-9 * twist);
      // Axial pull: P L / E A, tension positive.
      load.setZero();
      load.head<3>() = P * d;
      ASSERT_TRUE(SolveFrame(Cantilever(d, L, segments, load), &r).ok());
      const double stretch = P * L / (steel.youngs_modulus * kChs.area);
      EXPECT_NEAR(r.displacement.back().head<3>().dot(d), stretch, 1e-9 * stretch);
      EXPECT_NEAR(r.axial_force[0], P, 1e-9 * P);
      EXPECT_NEAR(r.compliance, P * stretch, 1e-9 * P * stretch);
    }
  }
}

TEST(FrameAnalysis, RectangularSectionBendsAboutTheRightAxis) {
  // Strong axis along `up` (local z): a load along up engages I_y = b h³ / 12.
  const FrameSection rhs = FrameSection::RectangularHollow(0.06, 0.12, 0.005);
  EXPECT_GT(rhs.inertia_y, rhs.inertia_z);
  FrameModel m = Cantilever(Eigen::Vector3d::UnitX(), 2.0, 1, NodeVector::Zero());
  m.section = rhs;
  m.members[0].up = Eigen::Vector3d::UnitZ();
  m.loads.back()[2] = 1e3;
  FrameResult r;
  ASSERT_TRUE(SolveFrame(m, &r).ok());
  EXPECT_NEAR(r.displacement.back()[2], 1e3 * 8.0 / (3 * 210e9 * rhs.inertia_y), 1e-12);
}

// A 6 × 5 grid of members on a dome z = 2 − 0.05 (x² + y²), edge nodes pinned.
FrameModel CurvedGrid() {
  FrameModel m;
  const int nx = 7, ny = 6;
  auto id = [&](int i, int j) { return j * nx + i; };
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const double x = 2.0 * i - 6.0, y = 2.0 * j - 5.0;
      m.nodes.emplace_back(x, y, 2.0 - 0.05 * (x * x + y * y));
    }
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const Eigen::Vector3d normal = Eigen::Vector3d(0.1 * m.nodes[id(i, j)].x(), 0.1 * m.nodes[id(i, j)].y(), 1).normalized();
      if (i + 1 < nx) m.members.push_back({id(i, j), id(i + 1, j), normal});
      if (j + 1 < ny) m.members.push_back({id(i, j), id(i, j + 1), normal});
    }
  m.restraints.assign(m.nodes.size(), Restraints{});
  m.loads.assign(m.nodes.size(), NodeVector::Zero());
  std::uniform_real_distribution<double> load(-5e3, 5e3);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const bool edge = i == 0 || j == 0 || i == nx - 1 || j == ny - 1;
      if (edge) m.restraints[id(i, j)] = {true, true, true, false, false, false};  // pinned
      m.loads[id(i, j)] << load(rng), load(rng), load(rng) - 1e4, 0, 0, 0;
    }
  m.section = kChs;
  m.material = Steel();
  return m;
}

TEST(FrameAnalysis, ReactionsBalanceTheLoadsOnACurvedGrid) {
  const FrameModel m = CurvedGrid();
  FrameResult r;
  ASSERT_TRUE(SolveFrame(m, &r).ok());
  Eigen::Vector3d force = Eigen::Vector3d::Zero(), moment = Eigen::Vector3d::Zero();
  double scale = 0.0;
  for (size_t i = 0; i < m.nodes.size(); ++i) {
    const Eigen::Vector3d total = m.loads[i].head<3>() + r.reaction[i].head<3>();
    force += total;
    moment += m.nodes[i].cross(total) + m.loads[i].tail<3>() + r.reaction[i].tail<3>();
    scale += m.loads[i].head<3>().norm();
  }
  EXPECT_NEAR(force.norm(), 0.0, 1e-9 * scale);
  EXPECT_NEAR(moment.norm(), 0.0, 1e-9 * scale * 10.0);
  EXPECT_GT(r.compliance, 0.0);
  double nodal = 0.0;
  for (const double c : r.nodal_compliance) nodal += c;
  EXPECT_NEAR(nodal, r.compliance, 1e-9 * r.compliance);  // no moment loads: all in translations
}

// K assembled into a kept pattern equals the triplet assembly to the bit (memcmp: values and
// pattern), over moved nodes of one topology, over both numberings, and after the topology
// changes (a support added: the pattern is made anew); the workspace's solve equals a fresh one.
TEST(FrameAnalysis, AKeptPatternAssemblesTheSameBits) {
  const auto same = [](const Eigen::SparseMatrix<double>& a, const Eigen::SparseMatrix<double>& b) {
    return a.rows() == b.rows() && a.nonZeros() == b.nonZeros() &&
           std::memcmp(a.outerIndexPtr(), b.outerIndexPtr(), sizeof(int) * (a.cols() + 1)) == 0 &&
           std::memcmp(a.innerIndexPtr(), b.innerIndexPtr(), sizeof(int) * a.nonZeros()) == 0 &&
           std::memcmp(a.valuePtr(), b.valuePtr(), sizeof(double) * a.nonZeros()) == 0;
  };
  std::uniform_real_distribution<double> jitter(-0.05, 0.05);
  for (const bool every_dof : {true, false}) {
    FrameModel m = CurvedGrid();
    FramePattern pattern;
    for (int step = 0; step < 4; ++step) {
      if (step == 3) m.restraints[10] = {true, true, true, true, true, true};  // another topology
      FrameSystem kept, fresh;
      ASSERT_TRUE(AssembleFrame(m, &kept, every_dof, &pattern).ok());
      ASSERT_TRUE(AssembleFrame(m, &fresh, every_dof).ok());
      EXPECT_TRUE(same(kept.K, fresh.K)) << "step " << step << ", every_dof " << every_dof;
      for (auto& p : m.nodes) p += Eigen::Vector3d(jitter(rng), jitter(rng), jitter(rng));
    }
  }
  FrameModel m = CurvedGrid();
  FrameWorkspace workspace;
  for (int step = 0; step < 3; ++step) {
    FrameResult kept, fresh;
    ASSERT_TRUE(SolveFrame(m, &kept, &workspace).ok());
    ASSERT_TRUE(SolveFrame(m, &fresh).ok());
    EXPECT_EQ(kept.compliance, fresh.compliance);
    for (auto& p : m.nodes) p.z() += jitter(rng);
  }
}

TEST(FrameAnalysis, ComplianceIsInvariantUnderRigidRotation) {
  const FrameModel m = CurvedGrid();
  FrameResult r;
  ASSERT_TRUE(SolveFrame(m, &r).ok());
  const Eigen::Matrix3d Q = Eigen::AngleAxisd(0.7, RandomUnit()).toRotationMatrix();
  FrameModel rotated = m;
  for (auto& p : rotated.nodes) p = Q * p + Eigen::Vector3d(3, -1, 2);
  for (auto& mb : rotated.members) mb.up = Q * mb.up;
  for (auto& f : rotated.loads) f.head<3>() = Q * f.head<3>();
  // Pinned supports restrain all translations, so they stay the same set in any frame.
  FrameResult q;
  ASSERT_TRUE(SolveFrame(rotated, &q).ok());
  EXPECT_NEAR(q.compliance, r.compliance, 1e-9 * r.compliance);
  for (size_t i = 0; i < m.nodes.size(); ++i)
    EXPECT_NEAR((q.displacement[i].head<3>() - Q * r.displacement[i].head<3>()).norm(), 0.0,
                1e-9 * r.displacement[i].head<3>().norm() + 1e-15);
}

TEST(FrameAnalysis, MechanismsAreRefusedNamingANode) {
  // One member pinned at one end: free to swing and spin.
  FrameModel m = Cantilever(Eigen::Vector3d::UnitX(), 2.0, 1, NodeVector::Zero());
  m.restraints[0] = {true, true, true, false, false, false};
  m.loads.back()[2] = -1e3;
  FrameResult r;
  Status s = SolveFrame(m, &r);
  EXPECT_EQ(s.code(), StatusCode::kInvalidInput);
  EXPECT_NE(s.message().find("the frame is a mechanism"), std::string::npos) << s.message();
  EXPECT_NE(s.message().find("node "), std::string::npos);
  // A free-floating second part.
  FrameModel two = CurvedGrid();
  two.nodes.push_back({50, 50, 0});
  two.nodes.push_back({52, 50, 0});
  two.members.push_back({static_cast<int>(two.nodes.size()) - 2, static_cast<int>(two.nodes.size()) - 1});
  two.restraints.resize(two.nodes.size());
  two.loads.resize(two.nodes.size(), NodeVector::Zero());
  s = SolveFrame(two, &r);
  EXPECT_EQ(s.code(), StatusCode::kInvalidInput);
  EXPECT_TRUE(s.message().find("node 42") != std::string::npos || s.message().find("node 43") != std::string::npos)
      << s.message();
}

}  // namespace
}  // namespace pqlayout

// The CalculiX export (solver/calculix_export.h) and, where `ccx` is installed (Debian
// calculix-ccx), ccx's answer on the exported decks against SolveFrame:
// - U1 decks are the same Euler–Bernoulli model: compliance and displacements agree to the
//   precision of ccx's .dat printout (7 significant digits), asserted to 1e-5 relative;
// - B32R decks (ccx expands them to 20-node bricks of the true tube) converge to the
//   beam answer as members are subdivided; the measured convergence is asserted.
// Without ccx those tests are skipped, visibly, and the deck-structure tests still run.
// The analyze stage's own deck: analyze_stage_test.cc.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include "pipeline/stages.h"
#include "solver/calculix_export.h"
#include "solver/frame_analysis.h"
#include "solver/frame_buckling.h"
#include "tests/calculix_helpers.h"
#include "tests/test_meshes.h"

namespace pqlayout {
namespace {

using testing::Cylinder;
using testing::HaveCcx;
using testing::kPrintoutTolerance;
using testing::Lines;
using testing::Numbers;
using testing::SectionDirections;
using testing::TempDir;
using testing::WriteFile;

const FrameSection kChs = FrameSection::CircularHollow(0.1143, 0.005);
const FrameSection kRhs = FrameSection::RectangularHollow(0.06, 0.12, 0.005);

FrameMaterial Steel() {
  FrameMaterial m;
  m.youngs_modulus = 210e9;
  m.shear_modulus = 210e9 / 2.6;
  return m;
}

CalculixSectionShape ChsShape() {
  CalculixSectionShape s;
  s.diameter = 0.1143, s.thickness = 0.005;
  return s;
}

CalculixSectionShape RhsShape() {
  CalculixSectionShape s;
  s.kind = CalculixSectionShape::kRectangularHollow;
  s.width = 0.06, s.height = 0.12, s.thickness = 0.005;
  return s;
}

// Nodes along a polyline, node 0 clamped, members oriented by `up`.
FrameModel Polyline(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& up, const FrameSection& section) {
  FrameModel m;
  m.nodes = points;
  for (size_t i = 0; i + 1 < points.size(); ++i) m.members.push_back({int(i), int(i) + 1, up});
  m.restraints.assign(points.size(), Restraints{});
  m.restraints[0].fill(true);
  m.loads.assign(points.size(), NodeVector::Zero());
  m.section = section;
  m.material = Steel();
  return m;
}

// The cylinder's grid lines as a frame: boundary nodes pinned, random loads at every node.
FrameModel CurvedGrid() {
  FrameModel m;
  for (int j = 0; j < Cylinder::nj; ++j)
    for (int i = 0; i < Cylinder::ni; ++i) m.nodes.push_back(Cylinder::Point(i, j));
  m.restraints.assign(m.nodes.size(), Restraints{});
  m.loads.assign(m.nodes.size(), NodeVector::Zero());
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> load(-5e3, 5e3);
  for (int j = 0; j < Cylinder::nj; ++j)
    for (int i = 0; i < Cylinder::ni; ++i) {
      const int v = Cylinder::Id(i, j);
      const Eigen::Vector3d radial = Cylinder::Point(i, j).cwiseProduct(Eigen::Vector3d(1, 0, 1)).normalized();
      if (i + 1 < Cylinder::ni) m.members.push_back({v, Cylinder::Id(i + 1, j), radial});
      if (j + 1 < Cylinder::nj) m.members.push_back({v, Cylinder::Id(i, j + 1), radial});
      if (i == 0 || j == 0 || i == Cylinder::ni - 1 || j == Cylinder::nj - 1) m.restraints[v] = {true, true, true, false, false, false};
      m.loads[v] << load(rng), load(rng), load(rng) - 1e4, 0, 0, 0;
    }
  m.section = kChs;
  m.material = Steel();
  return m;
}

std::string Deck(const FrameModel& m, const CalculixExportOptions& o) {
  std::string deck;
  const Status s = WriteCalculixDeck(m, o, &deck);
  EXPECT_TRUE(s.ok()) << s.message();
  return deck;
}

int CountLinesStartingWith(const std::string& deck, const std::string& prefix) {
  int n = 0;
  for (const auto& l : Lines(deck)) n += l.rfind(prefix, 0) == 0;
  return n;
}

TEST(CalculixDeck, HasTheModelsNodesSupportsLoadsAndOrientation) {
  FrameModel m = Polyline({{0, 0, 0}, {3, 0, 0}, {3, 4, 0}}, {0.3, 0.2, 1.0}, kChs);
  m.restraints[2] = {false, false, true, false, false, false};  // sliding
  m.loads[1] << 0, 0, -1500, 0, 0, 0;
  m.loads[2] << 250, 0, 0, 0, 0, 75;
  const std::string deck = Deck(m, {});
  EXPECT_NE(deck.find("*NODE, NSET=NMODEL\n1,0,0,0\n2,3,0,0\n3,3,4,0\n"), std::string::npos) << deck;
  EXPECT_NE(deck.find("*USER ELEMENT, TYPE=U1"), std::string::npos);
  EXPECT_NE(deck.find("*ELEMENT, TYPE=U1, ELSET=M1\n1,1,2\n*ELEMENT, TYPE=U1, ELSET=N1\n2,1,2\n"), std::string::npos);
  EXPECT_NE(deck.find("*ELEMENT, TYPE=U1, ELSET=M2\n3,2,3\n*ELEMENT, TYPE=U1, ELSET=N2\n4,2,3\n"), std::string::npos);
  EXPECT_NE(deck.find("*BOUNDARY\n1,1,6\n3,3,3\n*STEP"), std::string::npos) << deck;
  EXPECT_NE(deck.find("*CLOAD\n2,3,-1500\n3,1,250\n3,6,75\n"), std::string::npos) << deck;
  EXPECT_NE(deck.find("*ELASTIC\n210000000000,0.3\n"), std::string::npos) << deck;
  EXPECT_EQ(deck.find("** U1 twists"), std::string::npos);  // CHS: J = I_y + I_z
  EXPECT_NE(deck.find("*NODE PRINT, NSET=NMODEL\nU\n"), std::string::npos);
  // Orientation: M's 1-direction is the member's local z, i.e. `up` made perpendicular to the
  // member, its twin N's is local y; the sections carry I_y and I_z with them.
  const auto dirs = SectionDirections(deck), twins = SectionDirections(deck, 'N');
  ASSERT_EQ(dirs.size(), 2u);
  ASSERT_EQ(twins.size(), 2u);
  for (int e = 0; e < 2; ++e) {
    const FrameMember& mb = m.members[e];
    const Eigen::Matrix3d R = MemberFrame<double>(m.nodes[mb.a], m.nodes[mb.b], mb.up);
    EXPECT_NEAR((dirs.at(e) - R.row(2).transpose()).norm(), 0.0, 1e-11);
    EXPECT_NEAR((twins.at(e) - R.row(1).transpose()).norm(), 0.0, 1e-11);
    EXPECT_NEAR(dirs.at(e).dot(m.nodes[mb.b] - m.nodes[mb.a]), 0.0, 1e-11);
  }
  std::ostringstream halves;
  halves.precision(12);
  halves << kChs.area / 2 << "," << kChs.inertia_y << ",0,0,1000000000\n";
  EXPECT_NE(deck.find("SECTION=GENERAL\n" + halves.str()), std::string::npos) << halves.str();
}

TEST(CalculixDeck, SubdivisionAddsElementsAndNodesAlongEachMember) {
  const FrameModel m = CurvedGrid();  // 45 nodes, 76 members
  const int members = static_cast<int>(m.members.size());
  for (int k : {1, 3}) {
    CalculixExportOptions o;
    o.subdivisions = k;
    std::string deck = Deck(m, o);
    EXPECT_EQ(CountLinesStartingWith(deck, "*BEAM SECTION"), 2 * members);  // U1 twins
    // The highest element id: 2k per member (none of these numbers is a node id).
    EXPECT_NE(deck.find("\n" + std::to_string(2 * k * members) + ","), std::string::npos);
    EXPECT_EQ(deck.find("\n" + std::to_string(2 * k * members + 1) + ",", deck.find("*USER ELEMENT")), std::string::npos);
    EXPECT_EQ(k == 1, deck.find("NSUB") == std::string::npos);
    o.element = CalculixElement::kB32R;
    o.shape = ChsShape();
    deck = Deck(m, o);
    // B32R: 2k − 1 new nodes per member, so the last node id is 45 + (2k − 1) · 76.
    const int last = 45 + (2 * k - 1) * members;
    EXPECT_NE(deck.find("\n" + std::to_string(last) + ","), std::string::npos);
    EXPECT_NE(deck.find("SECTION=PIPE\n0.05715,0.005\n"), std::string::npos);
    EXPECT_EQ(CountLinesStartingWith(deck, "*BEAM SECTION"), members);
  }
}

TEST(CalculixDeck, RefusesWhatItCannotWrite) {
  FrameModel m = CurvedGrid();
  CalculixExportOptions o;
  std::string deck;
  o.subdivisions = 0;
  EXPECT_EQ(WriteCalculixDeck(m, o, &deck).code(), StatusCode::kInvalidInput);
  o.subdivisions = 1;
  o.element = CalculixElement::kB32R;  // no shape given
  EXPECT_EQ(WriteCalculixDeck(m, o, &deck).code(), StatusCode::kInvalidInput);
  m.members[3].b = 999;
  EXPECT_EQ(WriteCalculixDeck(m, {}, &deck).code(), StatusCode::kInvalidInput);
  CalculixElement e;
  EXPECT_TRUE(CalculixElementFromName("b32r", &e));
  EXPECT_EQ(e, CalculixElement::kB32R);
  EXPECT_FALSE(CalculixElementFromName("b31", &e));
}

TEST(CalculixDat, ReadsTheDisplacementBlockOfBothPrintFormats) {
  const std::string beams =
      "\n displacements (vx,vy,vz) for set NMODEL and time  0.1000000E+01\n\n"
      "         1  0.000000E+00  0.000000E+00  0.000000E+00\n"
      "         3 -9.091035E-17 -1.142948E-12 -1.503554E-02\n\n"
      " stresses (elem, integ.pnt.,sxx,syy,szz,sxy,sxz,syz) for set EALL\n\n         1   1  3.7E-03 1 1 1 1 1\n";
  std::map<int, Eigen::Vector3d> u;
  ASSERT_TRUE(ReadCalculixDisplacements(beams, &u).ok());
  ASSERT_EQ(u.size(), 2u);
  EXPECT_DOUBLE_EQ(u.at(3).z(), -1.503554e-2);
  const std::string u1 =
      "\n displacements (v(i),i=1..ndof) for set NMODEL and time  0.1000000E+01\n\n"
      "         2  0.000000E+00  1.0E+00 -2.471276E-03  1.204747E-03  4.633642E-03  0.000000E+00\n";
  ASSERT_TRUE(ReadCalculixDisplacements(u1, &u).ok());
  ASSERT_EQ(u.size(), 1u);
  EXPECT_EQ(u.at(2), Eigen::Vector3d(0, 1, -2.471276e-3));
  EXPECT_EQ(ReadCalculixDisplacements(" nothing here\n", &u).code(), StatusCode::kInvalidInput);
  EXPECT_EQ(ReadCalculixDisplacements(" displacements\n\n   1 abc\n", &u).code(), StatusCode::kInvalidInput);
}

// The buckling deck: one *BUCKLE step with the same loads instead of *STATIC; U1 refused.
TEST(CalculixDeck, BuckleStepReplacesTheStaticOne) {
  FrameModel m = Polyline({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}, {0, 0, 1}, kChs);
  m.loads[2][0] = -1e4;
  CalculixExportOptions o;
  o.element = CalculixElement::kB32R;
  o.shape = ChsShape();
  o.buckling_modes = 3;
  const std::string deck = Deck(m, o);
  EXPECT_NE(deck.find("*STEP\n*BUCKLE\n3\n*CLOAD\n3,1,"), std::string::npos);
  EXPECT_EQ(deck.find("*STATIC"), std::string::npos);
  o.element = CalculixElement::kU1;
  std::string refused;
  EXPECT_EQ(WriteCalculixDeck(m, o, &refused).code(), StatusCode::kInvalidInput);
}

TEST(CalculixDat, ReadsTheBucklingFactors) {
  const std::string dat =
      "\n     B U C K L I N G   F A C T O R   O U T P U T\n\n MODE NO       BUCKLING\n                FACTOR\n\n"
      "      1   0.1476992E+02\n      2   0.1476992E+02\n      3   0.5901234E+02\n\n displacements (vx,vy,vz) ...\n";
  std::vector<double> factors;
  ASSERT_TRUE(ReadCalculixBucklingFactors(dat, &factors).ok());
  ASSERT_EQ(factors.size(), 3u);
  EXPECT_DOUBLE_EQ(factors[0], 14.76992);
  EXPECT_DOUBLE_EQ(factors[2], 59.01234);
  EXPECT_FALSE(ReadCalculixBucklingFactors("no factors here\n", &factors).ok());
}

// ---- with ccx ----

// Runs ccx on the model's deck in dir; the text of its .dat file.
std::string RunCcxDat(const FrameModel& m, const CalculixExportOptions& o, const std::string& dir) {
  WriteFile(dir, "model.inp", Deck(m, o));
  const std::string command = "cd '" + dir + "' && OMP_NUM_THREADS=1 ccx -i model > ccx.log 2>&1";
  EXPECT_EQ(std::system(command.c_str()), 0) << "ccx failed, see " << dir << "/ccx.log";
  std::ifstream in(dir + "/model.dat");
  std::stringstream dat;
  dat << in.rdbuf();
  return dat.str();
}

// The displacements of the model's nodes (by index) that ccx computes.
std::vector<Eigen::Vector3d> RunCcx(const FrameModel& m, const CalculixExportOptions& o, const std::string& dir) {
  std::map<int, Eigen::Vector3d> by_id;
  const Status s = ReadCalculixDisplacements(RunCcxDat(m, o, dir), &by_id);
  EXPECT_TRUE(s.ok()) << s.message();
  std::vector<Eigen::Vector3d> u(m.nodes.size(), Eigen::Vector3d::Constant(NAN));
  for (size_t i = 0; i < m.nodes.size(); ++i)
    if (by_id.count(int(i) + 1)) u[i] = by_id.at(int(i) + 1);
  return u;
}

// fᵀu over the translations (the test models carry no moment loads).
double Compliance(const FrameModel& m, const std::vector<Eigen::Vector3d>& u) {
  double c = 0.0;
  for (size_t i = 0; i < m.nodes.size(); ++i) c += m.loads[i].head<3>().dot(u[i]);
  return c;
}

FrameResult Solve(const FrameModel& m) {
  FrameResult r;
  const Status s = SolveFrame(m, &r);
  EXPECT_TRUE(s.ok()) << s.message();
  return r;
}


TEST(CalculixCrossCheck, U1CantileverTipDeflectionIsPL3Over3EI) {
  REQUIRE_CCX();
  const std::string dir = TempDir();
  const double L = 3.7, P = 12e3;
  const Eigen::Vector3d d = Eigen::Vector3d(1, -2, 0.7).normalized();
  const Eigen::Vector3d across = d.cross(Eigen::Vector3d(0.3, 0.1, 1)).normalized();
  FrameModel m = Polyline({Eigen::Vector3d(1, 2, 3), Eigen::Vector3d(1, 2, 3) + L * d}, Eigen::Vector3d(0.2, 0.9, 0.4), kChs);
  m.loads[1].head<3>() = P * across;
  const std::vector<Eigen::Vector3d> u = RunCcx(m, {}, dir);
  const double expected = P * L * L * L / (3 * 210e9 * kChs.inertia_y);
  EXPECT_NEAR(u[1].dot(across), expected, kPrintoutTolerance * expected);
  EXPECT_NEAR(u[1].cross(across).norm(), 0.0, kPrintoutTolerance * expected);
  EXPECT_NEAR(Compliance(m, u), Solve(m).compliance, kPrintoutTolerance * P * expected);
}

TEST(CalculixCrossCheck, U1RectangularLFrameHasTheStrongAxisAlongUp) {
  REQUIRE_CCX();
  const std::string dir = TempDir();
  // Two members at a right angle, tilted in space, loaded at the corner and the tip: the first
  // member twists and bends about both axes; `up` is not perpendicular to the members. A
  // two-member frame is also what exposes ccx's U1 bending bug (header), the cantilever not.
  const Eigen::Matrix3d Q = Eigen::AngleAxisd(0.6, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  FrameModel m = Polyline({Q * Eigen::Vector3d(0, 0, 0), Q * Eigen::Vector3d(2.5, 0, 0), Q * Eigen::Vector3d(2.5, 1.8, 0)},
                          Q * Eigen::Vector3d(0.2, 0.3, 1.0), kRhs);
  m.loads[1].head<3>() = Q * Eigen::Vector3d(300, -800, -2000);
  m.loads[2].head<3>() = Q * Eigen::Vector3d(-500, 400, -3000);
  // The deck twists the RHS with G (I_y + I_z) and says so; compare with that model.
  EXPECT_NE(Deck(m, {}).find("** U1 twists with G (I11 + I22)"), std::string::npos);
  FrameModel polar = m;
  polar.section.torsion = m.section.inertia_y + m.section.inertia_z;
  const FrameResult r = Solve(polar);
  const std::vector<Eigen::Vector3d> u = RunCcx(m, {}, dir);
  EXPECT_NEAR(Compliance(m, u), r.compliance, kPrintoutTolerance * r.compliance);
  for (size_t i = 1; i < m.nodes.size(); ++i)
    EXPECT_NEAR((u[i] - r.displacement[i].head<3>()).norm(), 0.0, kPrintoutTolerance * u[i].norm());
  // The comparison can tell the axes apart: the section turned by 90° changes the compliance
  // by far more than the tolerance; so does Bredt's J (what SolveFrame uses for the RHS).
  FrameModel turned = polar;
  std::swap(turned.section.inertia_y, turned.section.inertia_z);
  EXPECT_GT(std::abs(Solve(turned).compliance / r.compliance - 1.0), 0.1);
  EXPECT_GT(std::abs(Solve(m).compliance / r.compliance - 1.0), 100 * kPrintoutTolerance);
}

TEST(CalculixCrossCheck, U1CurvedGridMatchesSolveFrame) {
  REQUIRE_CCX();
  const std::string dir = TempDir();
  const FrameModel m = CurvedGrid();
  const FrameResult r = Solve(m);
  for (int k : {1, 2}) {  // U1 is exact per element: subdividing changes nothing
    CalculixExportOptions o;
    o.subdivisions = k;
    const std::vector<Eigen::Vector3d> u = RunCcx(m, o, dir);
    EXPECT_NEAR(Compliance(m, u), r.compliance, kPrintoutTolerance * r.compliance) << k << " element(s) per member";
    double max_u = 0.0, max_diff = 0.0;
    for (size_t i = 0; i < m.nodes.size(); ++i) {
      max_u = std::max(max_u, r.displacement[i].head<3>().norm());
      max_diff = std::max(max_diff, (u[i] - r.displacement[i].head<3>()).norm());
    }
    EXPECT_LT(max_diff, kPrintoutTolerance * max_u);
  }
}

// ccx 2.20 expands a B32R pipe into 20-node bricks; measured on a 3.7 m CHS 114.3 × 5
// cantilever (tip load) and on the curved grid, ccx/SolveFrame compliance rises towards 1:
// see docs/README_analysis_section.md for the numbers. Asserted: monotone convergence, and
// the measured bands (each with a margin of about 1 % of the remaining gap).
TEST(CalculixCrossCheck, B32RBricksConvergeToTheBeamAnswerAsMembersAreSubdivided) {
  REQUIRE_CCX();
  const std::string dir = TempDir();
  const double L = 3.7, P = 12e3;
  FrameModel m = Polyline({{0, 0, 0}, {L, 0, 0}}, {0, 0, 1}, kChs);
  m.loads[1][2] = -P;
  const double beam = P * P * L * L * L / (3 * 210e9 * kChs.inertia_y);
  EXPECT_NEAR(Solve(m).compliance, beam, 1e-9 * beam);
  CalculixExportOptions o;
  o.element = CalculixElement::kB32R;
  o.shape = ChsShape();
  double previous = 0.0;
  for (int k : {1, 2, 4, 8}) {
    o.subdivisions = k;
    const double ratio = Compliance(m, RunCcx(m, o, dir)) / beam;
    RecordProperty("b32r_cantilever_ratio_k" + std::to_string(k), std::to_string(ratio));
    EXPECT_GT(ratio, previous) << k;
    EXPECT_LT(ratio, 1.0) << k;
    previous = ratio;
  }
  EXPECT_GT(previous, 0.98);  // measured 0.901, 0.944, 0.972, 0.986 for k = 1, 2, 4, 8
  // The curved grid: 4 elements per member.
  const FrameModel grid = CurvedGrid();
  o.subdivisions = 4;
  const double ratio = Compliance(grid, RunCcx(grid, o, dir)) / Solve(grid).compliance;
  RecordProperty("b32r_grid_ratio_k4", std::to_string(ratio));
  EXPECT_GT(ratio, 0.985);  // measured 0.993
  EXPECT_LT(ratio, 1.0);
}

TEST(CalculixCrossCheck, B32RBoxSectionHasItsHeightAlongUp) {
  REQUIRE_CCX();
  const std::string dir = TempDir();
  // Loads along up (strong) and across (weak): the ratio of tip deflections is I_y / I_z, as
  // in the beam model, only if BOX's first dimension is the height.
  const double L = 3.0, P = 1e3;
  FrameModel m = Polyline({{0, 0, 0}, {L, 0, 0}}, {0, 0, 1}, kRhs);
  m.loads[1][2] = -P;
  m.loads[1][1] = P;
  CalculixExportOptions o;
  o.element = CalculixElement::kB32R;
  o.shape = RhsShape();
  o.subdivisions = 8;
  const std::vector<Eigen::Vector3d> u = RunCcx(m, o, dir);
  const double weak_over_strong = u[1].y() / -u[1].z();
  EXPECT_NEAR(weak_over_strong, kRhs.inertia_y / kRhs.inertia_z, 0.05 * kRhs.inertia_y / kRhs.inertia_z);
}

// ---- the analyze stage ----


// The analyze stage on the cylinder (boundary default: fixed → pinned) with export on.
double CcxFirstBucklingFactor(const FrameModel& m, int subdivisions, const std::string& dir) {
  CalculixExportOptions o;
  o.element = CalculixElement::kB32R;
  o.shape = ChsShape();
  o.subdivisions = subdivisions;
  o.buckling_modes = 3;
  std::vector<double> factors;
  const Status s = ReadCalculixBucklingFactors(RunCcxDat(m, o, dir), &factors);
  EXPECT_TRUE(s.ok()) << s.message();
  return factors.empty() ? NAN : factors.front();
}

double OwnFirstBucklingFactor(const FrameModel& m) {
  BucklingResult b;
  const Status s = SolveBuckling(m, Solve(m), 3, &b);
  EXPECT_TRUE(s.ok()) << s.message();
  EXPECT_TRUE(b.buckles);
  return b.factors.empty() ? NAN : b.factors.front();
}

TEST(CalculixCrossCheck, B32RBucklingFactorMatchesSolveBuckling) {
  REQUIRE_CCX();
  const std::string dir = TempDir();
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i <= 8; ++i) points.emplace_back(6.0 * i / 8, 0.0, 0.0);
  FrameModel column = Polyline(points, {0, 0, 1}, kChs);  // clamped at node 0
  column.loads.back()[0] = -1e4;
  const double own = OwnFirstBucklingFactor(column), ccx = CcxFirstBucklingFactor(column, 2, dir);
  const double euler = M_PI * M_PI * 210e9 * kChs.inertia_y / (4 * 36.0) / 1e4;
  RecordProperty("buckling_column_own", std::to_string(own));
  RecordProperty("buckling_column_ccx", std::to_string(ccx));
  EXPECT_NEAR(own, euler, 1e-3 * euler);
  EXPECT_NEAR(ccx, own, 0.01 * own);  // measured +0.45 %
  // The curved grid (pinned edges, random loads with a downward bias).
  const FrameModel grid = CurvedGrid();
  const double grid_own = OwnFirstBucklingFactor(grid), grid_ccx = CcxFirstBucklingFactor(grid, 2, dir);
  RecordProperty("buckling_grid_own", std::to_string(grid_own));
  RecordProperty("buckling_grid_ccx", std::to_string(grid_ccx));
  EXPECT_NEAR(grid_ccx, grid_own, 0.05 * grid_own);  // measured +2.5 %
}

}  // namespace
}  // namespace pqlayout

// The level-set stage on known answers: a flat square with a constant guidance field, and a
// translational surface z = f(x) + g(y), whose parameter lines are conjugate.
#include <gtest/gtest.h>

#include <ceres/ceres.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>

#include "geometry/differential_operators.h"
#include "geometry/surface_generators.h"
#include "pipeline/config.h"
#include "problems/levelset.h"
#include "problems/levelset_internal.h"
#include "pipeline/pipeline.h"
#include "tests/test_guidance.h"
#include "tests/test_meshes.h"

namespace pqlayout {
namespace {

constexpr double kDegrees = 180.0 / M_PI;

TriMesh Plane(double size, double edge) {
  GeneratorParams p;
  p.name = "plane";
  p.width = size;
  p.depth = size;
  p.edge_length = edge;
  TriMesh mesh;
  EXPECT_TRUE(GenerateSurface(p, &mesh).ok());
  return mesh;
}

using testing::UniformGuidance;

TEST(LevelSets, FlatSquareWithConstantGuidanceGivesStraightEvenLines) {
  const SurfaceModel s(Plane(12.0, 0.6));
  const GuidanceField g = UniformGuidance(s, [](const Eigen::Vector3d&) { return Eigen::Vector3d::UnitX(); });
  LevelSetSolution solution;
  ASSERT_TRUE(SolveLevelSets(s, g, LevelsetOptions(), 1.5, &solution).ok());
  const LevelSetMetrics& m = solution.metrics;
  std::cout << "flat square: alignment " << m.alignment_rms_deg << "°, CV φ " << m.spacing_cv_phi << ", CV ψ "
            << m.spacing_cv_psi << ", min crossing " << m.min_crossing_angle_deg << "°\n";
  EXPECT_LE(m.alignment_rms_deg, 0.1);
  EXPECT_LE(m.spacing_cv_phi, 1e-3);
  EXPECT_EQ(m.foldovers, 0);
  // A flat surface has no conjugate direction: ψ falls back to orthogonal, evenly spaced.
  EXPECT_GE(m.min_crossing_angle_deg, 89.0);
  EXPECT_LE(m.spacing_cv_psi, 1e-3);
  // φ = ±y / h + c: one level line every h.
  const Eigen::Vector3d grad = FaceGradient(s, 0, solution.phi);
  EXPECT_NEAR(grad.norm() * 1.5, 1.0, 1e-3);
}

// levelset.tip_cone_radius: round a branch point the spacing term asks for the cone's
// h|∇u| = ρ_f = min(1, (d_f / (R h))^½), and a face's term is w A (h|∇u| − ρ)² / 2. On a plane with
// a tip at the origin: ρ = 1 from R h on, ½ at a quarter of it, ordered by distance; no tips
// or R = 0: no targets (1 everywhere). Then the cost of φ = x / h (h|∇φ| = 1) per face.
TEST(LevelSets, SpacingFollowsTheConeRoundABranchPoint) {
  const SurfaceModel s(Plane(12.0, 0.5));
  const levelset_internal::LevelSetGeometry geo = levelset_internal::Precompute(s);
  const double h = 1.5, radius = 1.5;
  EXPECT_EQ(LevelsetOptions().tip_cone_radius, 1.5);
  EXPECT_TRUE(levelset_internal::ConeSpacingTargets(geo, {}, radius, h).empty());
  EXPECT_TRUE(levelset_internal::ConeSpacingTargets(geo, {Eigen::Vector3d::Zero()}, 0.0, h).empty());
  const std::vector<double> rho = levelset_internal::ConeSpacingTargets(geo, {Eigen::Vector3d::Zero()}, radius, h);
  ASSERT_EQ(static_cast<int>(rho.size()), s.num_faces());
  int inside = 0;
  for (int f = 0; f < s.num_faces(); ++f) {
    const double d = geo.centroid[f].norm();
    if (d >= radius * h) {
      EXPECT_EQ(rho[f], 1.0) << f;
    } else {
      ++inside;
      EXPECT_NEAR(rho[f], std::sqrt(d / (radius * h)), 1e-15) << f;
      EXPECT_GT(rho[f], 0.05) << f;  // the floor is never reached on a mesh
    }
  }
  EXPECT_GT(inside, 20);  // π (2.25 m)² / 0.11 m² a face
  // Two tips: the nearer one counts.
  const std::vector<double> two =
      levelset_internal::ConeSpacingTargets(geo, {Eigen::Vector3d(-4, 0, 0), Eigen::Vector3d(4, 0, 0)}, radius, h);
  for (int f = 0; f < s.num_faces(); ++f) {
    const double d = std::min((geo.centroid[f] - Eigen::Vector3d(-4, 0, 0)).norm(), (geo.centroid[f] - Eigen::Vector3d(4, 0, 0)).norm());
    EXPECT_NEAR(two[f], std::min(1.0, std::sqrt(d / (radius * h))), 1e-15);
  }
  // The term's cost with φ = x / h: ½ w A (1 − ρ)² per face, 0 where ρ = 1.
  std::vector<double> phi(s.num_vertices());
  for (int v = 0; v < s.num_vertices(); ++v) phi[v] = s.position(v).x() / h;
  const levelset_internal::Chart chart{&phi, {}};
  const double w = 5.0;
  levelset_internal::TermProblem terms(false);
  levelset_internal::AddSpacing(s, geo, h, w, chart, rho, &terms);
  double cost = 0.0, expected = 0.0;
  ASSERT_TRUE(terms.problem.Evaluate(ceres::Problem::EvaluateOptions(), &cost, nullptr, nullptr, nullptr));
  for (int f = 0; f < s.num_faces(); ++f) expected += 0.5 * w * s.face_area(f) * (1.0 - rho[f]) * (1.0 - rho[f]);
  EXPECT_GT(expected, 0.01);
  EXPECT_NEAR(cost, expected, 1e-9 * expected);
  // One weight object per distinct weight w ρ², shared by the blocks that have it.
  std::vector<ceres::ResidualBlockId> blocks;
  terms.problem.GetResidualBlocks(&blocks);
  ASSERT_EQ(static_cast<int>(blocks.size()), s.num_faces());
  std::set<const ceres::LossFunction*> losses;
  std::set<double> weights;
  for (int f = 0; f < s.num_faces(); ++f) {
    losses.insert(terms.problem.GetLossFunctionForResidualBlock(blocks[f]));
    weights.insert(w * rho[f] * rho[f]);
  }
  EXPECT_GT(weights.size(), 2u);
  EXPECT_LT(weights.size(), blocks.size());
  EXPECT_EQ(losses.size(), weights.size());
}

// levelset.smoothness_max_guidance: the smoothness term acts on the edges with a face of
// guidance weight ≤ it. Left half of a square unguided (weight 0), right half guided (1): at
// 0.5 the kept edges are exactly those touching the left half, at 1 (the default) every one.
TEST(LevelSets, SmoothnessActsOnlyWhereTheGuidanceIsWeak) {
  const SurfaceModel s(Plane(12.0, 1.0));
  GuidanceField g = UniformGuidance(s, [](const Eigen::Vector3d&) { return Eigen::Vector3d::UnitX(); });
  const levelset_internal::LevelSetGeometry geo = levelset_internal::Precompute(s);
  for (int f = 0; f < s.num_faces(); ++f) g.weight[f] = geo.centroid[f].x() < 0.0 ? 0.0 : 1.0;
  const auto edges = levelset_internal::InteriorEdges(s, geo);
  const auto all = levelset_internal::SmoothedEdges(edges, g, 1.0);
  const auto weak = levelset_internal::SmoothedEdges(edges, g, 0.5);
  EXPECT_EQ(LevelsetOptions().smoothness_max_guidance, 1.0);  // the default smooths every edge
  EXPECT_EQ(all.size(), edges.size());
  int touching_weak = 0;
  for (const auto& e : edges) touching_weak += g.weight[e.f] == 0.0 || g.weight[e.g] == 0.0;
  EXPECT_EQ(static_cast<int>(weak.size()), touching_weak);
  for (const auto& e : weak) EXPECT_TRUE(g.weight[e.f] == 0.0 || g.weight[e.g] == 0.0);
  // Roughly half the edges on either side of the middle.
  EXPECT_GT(weak.size(), edges.size() / 3);
  EXPECT_LT(weak.size(), 2 * edges.size() / 3);
  // The faces of each edge are the ones across it.
  for (const auto& e : edges) {
    const auto f = s.face_vertices(e.f), h = s.face_vertices(e.g);
    EXPECT_NE(std::find(f.begin(), f.end(), e.k), f.end());
    EXPECT_NE(std::find(h.begin(), h.end(), e.l), h.end());
  }
}

// A reference much finer than h/2 is solved on a remeshed working mesh and interpolated back:
// on the flat square the answer (φ linear) must come back exactly at every reference vertex,
// with the working mesh far smaller than the reference.
TEST(LevelSets, FineReferenceIsSolvedOnAWorkingMeshAndInterpolated) {
  const SurfaceModel s(Plane(12.0, 0.15));
  const GuidanceField g = UniformGuidance(s, [](const Eigen::Vector3d&) { return Eigen::Vector3d::UnitX(); });
  LevelSetSolution solution;
  ASSERT_TRUE(SolveLevelSets(s, g, LevelsetOptions(), 1.5, &solution).ok());
  std::cout << "fine square: " << s.num_faces() << " reference triangles, working mesh " << solution.working_faces
            << "\n";
  EXPECT_LT(solution.working_faces, s.num_faces() / 8);
  EXPECT_GT(solution.working_faces, 100);
  EXPECT_LE(solution.metrics.alignment_rms_deg, 0.1);
  EXPECT_LE(solution.metrics.spacing_cv_phi, 1e-3);
  // φ = ±y / h + c and ψ = ±x / h + c' at every reference vertex.
  const Eigen::Vector3d p0 = s.position(0);
  const double sign_phi = FaceGradient(s, 0, solution.phi).y() > 0 ? 1.0 : -1.0;
  const double sign_psi = FaceGradient(s, 0, solution.psi).x() > 0 ? 1.0 : -1.0;
  double worst_phi = 0.0, worst_psi = 0.0;
  for (int v = 0; v < s.num_vertices(); ++v) {
    const Eigen::Vector3d d = s.position(v) - p0;
    worst_phi = std::max(worst_phi, std::abs(solution.phi[v] - solution.phi[0] - sign_phi * d.y() / 1.5));
    worst_psi = std::max(worst_psi, std::abs(solution.psi[v] - solution.psi[0] - sign_psi * d.x() / 1.5));
  }
  EXPECT_LE(worst_phi, 1e-2);  // in units of level lines: 1 % of h over a 12 m square
  EXPECT_LE(worst_psi, 1e-2);
  EXPECT_EQ(solution.working_mesh, "CGAL remeshing (not from the plan: fewer than 200000 triangles)");
}

// A height field of more than 200k triangles gets its working mesh from the plan
// (plan_remesh.h), and φ is as exact.
TEST(LevelSets, LargeHeightFieldIsSolvedOnAWorkingMeshFromItsPlan) {
  const SurfaceModel s(Plane(12.0, 0.035));
  const GuidanceField g = UniformGuidance(s, [](const Eigen::Vector3d&) { return Eigen::Vector3d::UnitX(); });
  LevelSetSolution solution;
  ASSERT_TRUE(SolveLevelSets(s, g, LevelsetOptions(), 1.5, &solution).ok());
  EXPECT_GT(s.num_faces(), 200000);
  EXPECT_EQ(solution.working_mesh, "plan");
  EXPECT_LT(solution.working_faces, 1500);
  EXPECT_LE(solution.metrics.alignment_rms_deg, 0.1);
  EXPECT_LE(solution.metrics.spacing_cv_phi, 1e-3);
}

// The pipeline makes the working mesh ahead, on a thread of its own, while the membrane and
// guidance run: it must be the mesh made in place, to the bit, and give the same level sets.
TEST(LevelSets, AWorkingMeshMadeAheadIsTheOneMadeInPlace) {
  const SurfaceModel s(Plane(12.0, 0.035));
  const LevelsetOptions options;
  const std::shared_future<WorkingMesh> ahead = MakeWorkingMeshInBackground(s, options, 1.5);
  const WorkingMesh here = MakeWorkingMesh(s, options, 1.5);
  const WorkingMesh& made = ahead.get();
  ASSERT_TRUE(made.status.ok() && here.status.ok());
  EXPECT_EQ(made.kind, "plan");
  EXPECT_EQ(made.kind, here.kind);
  EXPECT_EQ(made.edge, 0.4 * 1.5);
  ASSERT_TRUE(made.mesh && here.mesh);
  ASSERT_EQ(made.mesh->num_vertices(), here.mesh->num_vertices());
  ASSERT_EQ(made.mesh->num_faces(), here.mesh->num_faces());
  for (int v = 0; v < made.mesh->num_vertices(); ++v) ASSERT_EQ(made.mesh->position(v), here.mesh->position(v)) << v;
  for (int f = 0; f < made.mesh->num_faces(); ++f) ASSERT_EQ(made.mesh->face_vertices(f), here.mesh->face_vertices(f));
  const GuidanceField g = UniformGuidance(s, [](const Eigen::Vector3d&) { return Eigen::Vector3d::UnitX(); });
  LevelSetSolution with, without;
  ASSERT_TRUE(SolveLevelSets(s, g, options, 1.5, &with, &made).ok());
  ASSERT_TRUE(SolveLevelSets(s, g, options, 1.5, &without).ok());
  EXPECT_EQ(with.working_mesh, "plan");
  EXPECT_EQ(with.phi, without.phi);
  EXPECT_EQ(with.psi, without.psi);
  // A reference no finer than the working edge needs none.
  const SurfaceModel coarse(Plane(12.0, 0.8));
  const WorkingMesh none = MakeWorkingMeshInBackground(coarse, options, 1.5).get();
  EXPECT_FALSE(none.mesh);
  EXPECT_EQ(none.kind, "reference");
}

// The same large square stood up at 85° is no height field (plan_remesh.h declines faces
// steeper than 80°): the working mesh comes from CGAL's remeshing of the reference.
TEST(LevelSets, LargeReferenceThatIsNoHeightFieldIsRemeshedByCgal) {
  TriMesh mesh = Plane(12.0, 0.035);
  const double c = std::cos(85.0 * M_PI / 180.0), sn = std::sin(85.0 * M_PI / 180.0);
  for (const auto v : mesh.vertices()) {
    const auto p = mesh.point(v);
    mesh.set_point(v, TriMesh::Point(c * p[0], p[1], sn * p[0]));
  }
  const SurfaceModel s(std::move(mesh));
  const GuidanceField g = UniformGuidance(s, [&](const Eigen::Vector3d&) { return Eigen::Vector3d(c, 0.0, sn); });
  LevelSetSolution solution;
  ASSERT_TRUE(SolveLevelSets(s, g, LevelsetOptions(), 1.5, &solution).ok());
  EXPECT_EQ(solution.working_mesh.rfind("CGAL remeshing (not from the plan: a face is steeper than 80°", 0), 0u)
      << solution.working_mesh;
  EXPECT_LT(solution.working_faces, s.num_faces() / 8);
  EXPECT_GT(solution.working_faces, 100);
  EXPECT_LE(solution.metrics.alignment_rms_deg, 0.1);
  EXPECT_LE(solution.metrics.spacing_cv_phi, 1e-3);
}

TEST(LevelSets, TranslationalSurfaceGivesTheConjugateParameterLines) {
  // z = f(x) + g(y): the curves x = const and y = const are conjugate (z_xy = 0).
  auto f_prime = [](double x) { return 0.12 * x; };           // f = 0.06 x²
  auto g_prime = [](double y) { return -0.08 * y + 0.1; };    // g = −0.04 y² + 0.1 y
  TriMesh mesh = Plane(12.0, 0.5);
  for (const auto v : mesh.vertices()) {
    auto p = mesh.point(v);
    p[2] = 0.06 * p[0] * p[0] - 0.04 * p[1] * p[1] + 0.1 * p[1];
    mesh.set_point(v, p);
  }
  const SurfaceModel s(std::move(mesh));
  // Guidance along the x-parameter lines (y = const): tangent (1, 0, f'(x)).
  const GuidanceField g =
      UniformGuidance(s, [&](const Eigen::Vector3d& p) { return Eigen::Vector3d(1.0, 0.0, f_prime(p.x())); });
  LevelsetOptions options;
  options.weights.conjugacy = 1.0;
  LevelSetSolution solution;
  ASSERT_TRUE(SolveLevelSets(s, g, options, 1.5, &solution).ok());
  double sum = 0.0, area = 0.0;
  for (int f = 0; f < s.num_faces(); ++f) {
    const auto ids = s.face_vertices(f);
    const Eigen::Vector3d centre = (s.position(ids[0]) + s.position(ids[1]) + s.position(ids[2])) / 3.0;
    const Eigen::Vector3d y_line = Eigen::Vector3d(0.0, 1.0, g_prime(centre.y())).normalized();
    const Eigen::Vector3d psi_line = s.face_normal(f).cross(FaceGradient(s, f, solution.psi)).normalized();
    const double angle = std::acos(std::min(1.0, std::abs(psi_line.dot(y_line)))) * kDegrees;
    sum += s.face_area(f) * angle * angle;
    area += s.face_area(f);
  }
  const double rms = std::sqrt(sum / area);
  std::cout << "translational surface: ψ lines vs y-parameter lines " << rms << "° RMS; φ alignment "
            << solution.metrics.alignment_rms_deg << "°, conjugacy " << solution.metrics.conjugacy_rms << "\n";
  EXPECT_LE(rms, 2.0);
  EXPECT_LE(solution.metrics.alignment_rms_deg, 1.0);
  EXPECT_EQ(solution.metrics.foldovers, 0);
}


// The level sets of a 12 m square under circles round (2, 2) (index +1), h = 1.5 m, with
// options.crossing_rounds 0 (without) and `rounds` (with).
void SolveRingGuidance(LevelsetOptions options, int rounds, LevelSetSolution* without, LevelSetSolution* with) {
  const SurfaceModel s(Plane(12.0, 0.6));
  const GuidanceField g = UniformGuidance(s, [](const Eigen::Vector3d& p) {
    return Eigen::Vector3d(-(p.y() - 2.0), p.x() - 2.0, 0.0).normalized();
  });
  options.crossing_rounds = 0;
  ASSERT_TRUE(SolveLevelSets(s, g, options, 1.5, without).ok());
  options.crossing_rounds = rounds;
  ASSERT_TRUE(SolveLevelSets(s, g, options, 1.5, with).ok());
}

// A guidance field with a singularity (circles around a point inside the square, index +1):
// no single-valued φ follows it, and the joint solve's transversality penalty leaves faces
// crossing below min_angle. The crossing rounds (levelset.crossing_rounds) must lift every
// face to min_angle without fold-overs; without them some face stays below.
TEST(LevelSets, CrossingRoundsLiftEveryFaceToTheMinimumAngle) {
  LevelsetOptions options;
  LevelSetSolution without, with;
  SolveRingGuidance(options, 6, &without, &with);
  ASSERT_FALSE(HasFatalFailure());
  std::cout << "singular guidance: min crossing " << without.metrics.min_crossing_angle_deg << "° ("
            << without.metrics.faces_below_min_angle << " faces below) without rounds, "
            << with.metrics.min_crossing_angle_deg << "° (" << with.metrics.faces_below_min_angle
            << ") with; alignment " << without.metrics.alignment_rms_deg << "° → " << with.metrics.alignment_rms_deg
            << "°, fold-overs " << without.metrics.foldovers << " → " << with.metrics.foldovers << ", spacing CV ψ "
            << without.metrics.spacing_cv_psi << " → " << with.metrics.spacing_cv_psi << "\n";
  // The case needs the rounds (27.6° and 87 faces below 30° without them when written) ...
  EXPECT_LT(without.metrics.min_crossing_angle_deg, options.min_angle);
  // ... and they reach 30° on every face at little cost in alignment and spacing. The
  // problem has several local minima (13.4°–27.7° crossing without rounds on different
  // BLAS kernels before issue 15), so the bounds hold for each of them rather than
  // comparing two solves: alignment 25.7° and ψ's spacing CV 0.16 when written; 26.98° →
  // 27.65° was measured on another minimum.
  EXPECT_GE(with.metrics.min_crossing_angle_deg, options.min_angle);
  EXPECT_EQ(with.metrics.faces_below_min_angle, 0);
  EXPECT_EQ(with.metrics.foldovers, 0);
  EXPECT_LE(with.metrics.alignment_rms_deg, 28.5);
  EXPECT_LE(with.metrics.spacing_cv_psi, 0.25);
  EXPECT_TRUE(with.solver.contains("crossing_round_1"));
}

// The floor rounds (problems/levelset_problem.cc, FloorRounds): where the crossing rounds end
// with a fold-over or a face more than 5° below min_angle, local re-solves with a barrier
// under the worst face, from the joint solve's end. The index +1 guidance of the test above
// with min_angle 50°: 15.2° without any rounds; the crossing rounds leave a face far below
// and the floor rounds' end, 37.3° (46 faces below 50°, none folded), is kept (2026-12-06).
// (Until the joint solve started from the initial guess this test asked for 40°, which the
// layout now reaches with the crossing rounds alone; at 44° and from 48° the floor rounds'
// end is kept too, at 36–46° the crossing rounds' end in some.)
TEST(LevelSets, FloorRoundsLiftTheWorstCrossingWhereTheCrossingRoundsCannot) {
  LevelsetOptions options;
  options.min_angle = 50.0;
  LevelSetSolution without, with;
  SolveRingGuidance(options, 3, &without, &with);
  ASSERT_FALSE(HasFatalFailure());
  std::cout << "min angle 50°: " << without.metrics.min_crossing_angle_deg << "° without rounds, "
            << with.metrics.min_crossing_angle_deg << "° (" << with.metrics.faces_below_min_angle
            << " faces below, " << with.metrics.foldovers << " folded) with, kept: " << with.crossing_rounds_kept << "\n";
  EXPECT_LT(without.metrics.min_crossing_angle_deg, 25.0);
  EXPECT_EQ(with.crossing_rounds_kept, "floor");
  EXPECT_TRUE(with.solver.contains("crossing_round_1"));
  EXPECT_TRUE(with.solver.contains("floor_round_1"));
  EXPECT_GE(with.metrics.min_crossing_angle_deg, 35.0);
  EXPECT_EQ(with.metrics.foldovers, 0);
}

// A crossing angle out of reach (CrossingOutOfReach: more than half the area below it after the
// joint solve): the rounds, which re-solve round the failing faces, are not run at all, so the
// layout is the joint solve's to the bit. (The Great Court at levelset.min_angle 89°: 96 % of
// the area below; the rounds and the cone's retry took 190 s of 203 s and still left 96 %.)
TEST(LevelSets, ACrossingAngleOutOfReachRunsNoRounds) {
  LevelsetOptions options;
  options.min_angle = 89.0;
  LevelSetSolution without, with;
  SolveRingGuidance(options, 3, &without, &with);
  ASSERT_FALSE(HasFatalFailure());
  std::cout << "min angle 89°: " << 100.0 * with.metrics.area_below_min_angle << " % of the area below, min "
            << with.metrics.min_crossing_angle_deg << "°\n";
  EXPECT_TRUE(CrossingOutOfReach(with.metrics));
  EXPECT_FALSE(with.solver.contains("crossing_round_1"));
  EXPECT_FALSE(with.solver.contains("floor_round_1"));
  EXPECT_EQ(with.crossing_rounds_kept, "none");
  EXPECT_EQ(with.phi, without.phi);
  EXPECT_EQ(with.psi, without.psi);
}

}  // namespace
}  // namespace pqlayout

namespace pqlayout {
namespace {

// The level sets with seams (default) and with levelset.seams: false, solved on `s` itself
// (seams are not cut on a remeshed working mesh).
void SolveWithAndWithoutSeams(const SurfaceModel& s, const GuidanceField& g, double h, LevelSetSolution* seamed,
                              LevelSetSolution* single) {
  LevelsetOptions options;
  options.working_edge = 0.3;
  ASSERT_TRUE(SolveLevelSets(s, g, options, h, seamed).ok());
  options.seams = false;
  ASSERT_TRUE(SolveLevelSets(s, g, options, h, single).ok());
}

// Flat annulus (radii 4 and 10 m), guidance radial: φ's level lines must be rays, so φ grows
// by a whole number of levels once round the hole, which only a seam allows. With the seam:
// one translation seam (sign +1) whose offset is the number of rays, and alignment ~0; without
// it (levelset.seams: false) a single-valued φ must cross the rays somewhere.
TEST(LevelSets, AnnulusWithRadialGuidanceNeedsATranslationSeam) {
  const SurfaceModel s(testing::GeneratedMesh("annulus", 20.0, 8.0, 0.0, 0.6));
  const GuidanceField g = UniformGuidance(s, [](const Eigen::Vector3d& c) { return Eigen::Vector3d(c.x(), c.y(), 0); });
  const double h = 1.5;
  LevelSetSolution seamed, single;
  SolveWithAndWithoutSeams(s, g, h, &seamed, &single);
  std::cout << "annulus: alignment " << seamed.metrics.alignment_rms_deg << "° with the seam, "
            << single.metrics.alignment_rms_deg << "° without; offset "
            << (seamed.seams.cut ? seamed.seams.phi_offset[0] : 0.0) << "\n";
  ASSERT_TRUE(seamed.seams.cut != nullptr);
  ASSERT_EQ(seamed.seams.cut->num_paths(), 1);
  EXPECT_TRUE(seamed.seams.tips.empty());
  EXPECT_EQ(seamed.seams.sign[0], 1);
  // N rays: |∇φ| = N / (2πr); the best N for ∫ (h|∇φ| − 1)² dA (and for the Poisson guess)
  // is 2π (R − r₀) / (h ln(R / r₀)) = 27.4 for R = 10, r₀ = 4, h = 1.5.
  EXPECT_EQ(std::abs(seamed.seams.phi_offset[0]), std::round(2 * M_PI * 6.0 / (h * std::log(2.5))));
  EXPECT_EQ(seamed.seams.phi_offset[0], std::round(seamed.seams.phi_offset[0]));
  EXPECT_EQ(seamed.seams.psi_offset[0], 0.0);  // ψ (the circles) is single-valued
  EXPECT_LE(seamed.metrics.alignment_rms_deg, 1.0);
  EXPECT_GE(single.metrics.alignment_rms_deg, 5.0);
  EXPECT_EQ(seamed.metrics.foldovers, 0);
  EXPECT_GE(seamed.metrics.min_crossing_angle_deg, 80.0);  // flat: ψ orthogonal to φ
  // The transition holds exactly: every seam vertex's plus copy is its minus copy + offset.
  for (const auto& pair : seamed.seams.cut->copy_pairs())
    EXPECT_NEAR(seamed.phi_cut[pair.plus], seamed.phi_cut[pair.minus] + seamed.seams.phi_offset[0], 1e-9);
}

// The same annulus with a uniform guidance (the x axis): neither family winds round the hole
// (both periods 0), so the hole seam is not cut (uncut_ring_holes) and φ, ψ are the plane's
// coordinates, single-valued.
TEST(LevelSets, AnnulusWithUniformGuidanceGetsNoSeam) {
  const SurfaceModel s(testing::GeneratedMesh("annulus", 20.0, 8.0, 0.0, 0.6));
  const GuidanceField g = UniformGuidance(s, [](const Eigen::Vector3d&) { return Eigen::Vector3d(1, 0, 0); });
  LevelsetOptions options;
  options.working_edge = 0.3;
  LevelSetSolution solution;
  ASSERT_TRUE(SolveLevelSets(s, g, options, 1.5, &solution).ok());
  EXPECT_TRUE(solution.seams.cut == nullptr);
  EXPECT_EQ(solution.seams.ring_holes, 1);
  EXPECT_EQ(solution.seams.ToJson()["uncut_ring_holes"], 1);
  EXPECT_LE(solution.metrics.alignment_rms_deg, 1.0);
  EXPECT_EQ(solution.metrics.foldovers, 0);
}

// Flat disc with a line field of index −½ at the origin (direction angle −θ/2, a trisector
// like the Great Court's umbilics): the field turns by −π once round, so φ must change sign
// across a seam from the singularity to the boundary (sign −1), with a branch point there.
TEST(LevelSets, TrisectorNeedsASignFlipSeamWithABranchPoint) {
  const SurfaceModel s(testing::GeneratedMesh("disk", 24.0, 0.0, 0.0, 0.6));
  const GuidanceField g = UniformGuidance(s, [](const Eigen::Vector3d& c) {
    const double a = -0.5 * std::atan2(c.y(), c.x());
    return Eigen::Vector3d(std::cos(a), std::sin(a), 0);
  });
  const double h = 1.5;
  LevelSetSolution seamed, single;
  SolveWithAndWithoutSeams(s, g, h, &seamed, &single);
  std::cout << "trisector: alignment " << seamed.metrics.alignment_rms_deg << "° with the seam, "
            << single.metrics.alignment_rms_deg << "° without; CV φ " << seamed.metrics.spacing_cv_phi
            << ", min crossing " << seamed.metrics.min_crossing_angle_deg << "°\n";
  ASSERT_TRUE(seamed.seams.cut != nullptr);
  ASSERT_EQ(seamed.seams.cut->num_paths(), 1);
  ASSERT_EQ(seamed.seams.tips.size(), 1u);
  EXPECT_LT(s.position(seamed.seams.tips[0]).norm(), 0.7);  // at the singularity
  EXPECT_EQ(seamed.seams.sign[0], -1);
  EXPECT_LE(seamed.metrics.alignment_rms_deg, 3.0);  // 2.3° measured: spacing gives way near the branch point
  EXPECT_GE(single.metrics.alignment_rms_deg, 2.0 * seamed.metrics.alignment_rms_deg);
  EXPECT_EQ(seamed.metrics.foldovers, 0);
  // u₊ = −u₋ + a on the seam, and a/2 at the branch point.
  const double a = seamed.seams.phi_offset[0];
  for (const auto& pair : seamed.seams.cut->copy_pairs()) {
    if (pair.minus == pair.plus) EXPECT_DOUBLE_EQ(seamed.phi_cut[pair.minus], a / 2);
    else EXPECT_NEAR(seamed.phi_cut[pair.plus], -seamed.phi_cut[pair.minus] + a, 1e-9);
  }
}

}  // namespace
}  // namespace pqlayout

namespace pqlayout {
namespace {

// Seams on a remeshed working mesh, end to end: a fine flat annulus (reference edge 0.25 m,
// solved on the 0.6 m working mesh of h = 1.5 m) with radial guidance read from a file. One
// translation seam is cut on the working mesh, the mesh is extracted on its cut surface and
// moved onto the reference: the ring of rays closes (χ = 0, no seam edge left unmatched).
TEST(LevelSets, SeamsOnTheWorkingMeshCarryThroughExtraction) {
  const std::string dir = testing::TempDir();
  const SurfaceModel s(testing::GeneratedMesh("annulus", 20.0, 8.0, 0.0, 0.25));
  std::ostringstream csv;
  csv << "id,dx,dy,dz\n";
  for (int f = 0; f < s.num_faces(); ++f) {
    const auto ids = s.face_vertices(f);
    const Eigen::Vector3d c = (s.position(ids[0]) + s.position(ids[1]) + s.position(ids[2])) / 3.0;
    csv << f << "," << c.x() << "," << c.y() << ",0\n";
  }
  testing::WriteFile(dir, "radial.csv", csv.str());
  const std::string config_path = testing::WriteFile(
      dir, "annulus.yaml",
      "surface: {generator: annulus, width: 20, depth: 8, rise: 0, edge_length: 0.25}\n"
      "guidance: {source: file, file: radial.csv}\n"
      "layout: {spacing: 1.5}\n");
  Config config;
  const Status loaded = LoadConfig(config_path, {}, &config);
  ASSERT_TRUE(loaded.ok()) << loaded.message();
  RunOptions run;
  run.out_dir = dir + "/out";
  run.until = Stage::kExtract;
  nlohmann::json report;
  const Status status = RunPipeline(config, run, &report);
  ASSERT_TRUE(status.ok()) << status.message();
  const auto& levelset = report["stages"]["levelset"];
  const auto& extract = report["stages"]["extract"];
  std::cout << "working-mesh seams: " << levelset["seams"] << "\nextract: " << extract["quad_fraction"] << " quads, χ "
            << extract["euler_characteristic"] << "\n";
  EXPECT_LT(levelset["working_mesh_triangles"].get<int>(), s.num_faces() / 4);
  EXPECT_TRUE(levelset["seams"]["on_working_mesh"].get<bool>());
  EXPECT_EQ(levelset["seams"]["count"].get<int>(), 1);
  EXPECT_LE(levelset["alignment_rms_deg"].get<double>(), 1.0);
  EXPECT_EQ(extract["unmatched_seam_edges"].get<int>(), 0);
  EXPECT_EQ(extract["euler_characteristic"].get<int>(), 0);
  EXPECT_EQ(extract["boundary_loops"].get<int>(), 2);
  // Every cell off the boundary is a quad (the seam leaves no trace); the boundary cells of
  // this narrow ring are mostly triangles cut off where chords leave the circles.
  EXPECT_TRUE(extract["interior_non_quads"].empty()) << extract["interior_non_quads"];
  EXPECT_LE(extract["boundary_deviation"].get<double>(), 0.01 * 1.5);
}

}  // namespace
}  // namespace pqlayout

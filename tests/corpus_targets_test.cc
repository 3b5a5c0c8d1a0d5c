// The roof corpus (issue 17; examples/corpus, benchmarks/corpus.md): every roof through
// planarisation with both guidance sources, defaults only, each layout target of
// report.json "targets" (pipeline/layout_targets.h) either met or a miss known today, which
// must keep its one-line cause and may not get worse than its bound (the value measured on
// 2026-12-02 with a margin: 25 % for angles, CVs and areas, 0.05 for the quad fraction,
// 1.5× + 1 for counts). A regression on any roof turns this red; a fix lets a miss be struck
// from the list. wavy × curvature (~25 s since the joint solve ends its crawl, 60 s before:
// three bump tops, each a pole since 2026-12-02, the
// level sets solved with and without them) was 9 misses and 23 fold-overs before, now 2.
// The domes with strain guidance got a pole each (problems/levelset_poles.cc; alignment 10.8°
// and 14.8° without); since the curvature fallback the square dome gets two, the circular
// dome none (its crown is a weak zone the blend fills).
// The Great Court at 44k and 112k reference triangles (surface.edge_length 0.8, 0.5; issue 19)
// takes the remeshed working-mesh path the 12k golden run does not: its strain layout once got
// a seam round the Reading Room (18.6°, quad fraction 0.68) and must meet every target, and
// issue 19's stricter ones (ExpectValidAtThisSize).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "pipeline/config.h"
#include "pipeline/pipeline.h"

namespace pqlayout {
namespace {

struct CorpusCase {
  friend void PrintTo(const CorpusCase& c, std::ostream* os) { *os << c.roof << "_" << c.source; }
  std::string roof, source;
  std::map<std::string, double> known_misses;  // target → bound on its value
  // The config: examples/corpus/<roof>.yaml, or this one with these overrides.
  std::string config = "";
  std::vector<std::string> sets = {};
  bool issue19 = true;  // a Great Court case: issue 19's stricter targets too (ExpectValidAtThisSize)
};

const CorpusCase kCases[] = {
    {"barrel", "strain", {}},
    {"barrel", "curvature", {}},
    {"canopy", "strain", {{"quad_fraction", 0.73}}},  // its 8-gon got a centre vertex off the corners' average
    {"canopy", "curvature", {}},
    // A pole since 2026-12-02. With the curvature fallback (guidance.fallback, 2026-12-04) the
    // crown's weak zone follows the dome's near-umbilic curvature lines: spacing CV 0.286 → 0.429,
    // interior non-quads 2 → 0, alignment 0.5° → 5.7° (met).
    {"dome_circular", "strain", {{"spacing_cv", 0.536}, {"interior_non_quads", 3}}},
    {"dome_circular", "curvature", {}},  // quads 0.79 → 0.81 since the joint solve's stall stop
    // A pole. Since 2026-12-04 its cap's rim has no corners (geometry/quad_extraction.h, caps):
    // interior non-quads 3 → 0 here, dome_circular × strain 1 → 2, wavy × curvature 3 → 4.
    // Curvature fallback: the pole's fan loses rays next to the blended field's ±½ pairs:
    // interior non-quads 0 → 4 (three 3-gons and a 5-gon), spacing CV 0.334 → 0.349.
    // The joint solve from the initial guess (levelset.separate_solves false, 2026-12-06): interior
    // non-quads 6 → 10 (the fans of its two poles lose more rays), spacing CV 0.349 → 0.339.
    {"dome_square", "strain", {{"spacing_cv", 0.418}, {"interior_non_quads", 16}}},
    {"dome_square", "curvature", {}},
    // Openings drawn as circles since 2026-12-03 (geometry/roof_generators.cc): the hole's
    // polygon no longer has a kink at every vertex for the panels to follow. Strain: edge_min_h
    // 0.13 → 0.20 h (met), min crossing 25.3° → 27.4°, area below 30° 1.9 % → 0.01 %, no floor
    // rounds; curvature: min crossing 23.8° → 28.0°, area 9.2 % → 0.07 %, alignment 16.9° → 14.0°.
    // Curvature fallback: alignment 14.4° → 7.7° and spacing CV 0.41 → met, but a pole's fan
    // at (-7.7, 0) loses rays: interior non-quads 0 → 6.
    // Strain weights that vanish where e_max swaps by 90° (guidance.shear_switch, 2026-12-05):
    // alignment 7.7° → 5.5°, crossing 26.4° → 28.1°, interior non-quads 6 → 0: all met.
    {"hole_offcentre", "strain", {}},
    // Curved chords cut into the fewest equal pieces (geometry/boundary_refinement.cc) since
    // 2026-12-03, not halved: edge_min_h 0.187 → 0.213 h (met), quads 0.773 → 0.778.
    // Interior valence-2 vertices dropped since 2026-12-04 (DropInteriorValence2Vertices): its
    // triangle + pentagon and triangle + 9-gon on one such vertex each → interior non-quads 4 → 1.
    // The curvature net combed (CombCurvatureNet, 2026-12-05): the major direction swapped from
    // radial to circles across the ring ridge's weak parallel; alignment 14.0° → 4.1°, the
    // 8-gon gone (interior non-quads 1 → 0): met.
    {"hole_offcentre", "curvature", {{"quad_fraction", 0.74}}},
    // The floor rounds: min crossing 10.1° → 27.9° (met), area below 30° 0.3 % → 0.6 %.
    // Curvature fallback: quads 0.781 → 0.842 (met), crossing 27.9° → 30.2°, spacing CV 0.23 → 0.32.
    // guidance.shear_switch (2026-12-05): the hypar's membrane is nearly pure shear, e_max swapped
    // by 90° along lines the solve bent to; alignment 14.5° → 8.0°, spacing CV 0.32 → 0.24: all met.
    // The joint solve from the initial guess (2026-12-06): alignment 7.99° → 8.08°, spacing CV
    // 0.244 → 0.265 (both solve orders end near the same cost; the targets sit on its edge).
    {"hypar", "strain", {{"alignment", 10.1}, {"spacing_cv", 0.33}}},
    {"hypar", "curvature", {}},
    // guidance.shear_switch (2026-12-05): alignment 11.2° → 12.4°, spacing CV 0.25 → 0.28 (0.55 h
    // at the re-entrant corner).
    {"l_shape", "strain", {{"alignment", 13.7}, {"spacing_cv", 0.31}}},
    {"l_shape", "curvature", {}},
    // guidance.shear_switch (2026-12-05): alignment 10.1° → 6.3°, quads 0.73 → 0.82: all met.
    {"saddle_elliptic", "strain", {}},
    {"saddle_elliptic", "curvature", {}},
    // Openings drawn as circles: the smaller (r = 1.1 h) keeps chords within 0.01 h only below
    // 0.29 h, so the chord refinement adds vertices there (quads 0.77 → 0.73 strain, 0.82 →
    // 0.79 curvature; shortest edges 0.15 h and 0.09 h), no interior non-quad, no floor rounds.
    // Chords cut into the fewest equal pieces, not halved: 10 vertices (and triangles) fewer
    // each, quads 0.727 → 0.744 (strain), 0.793 → 0.816 (curvature, met); the shortest edges
    // left are a 0.30 h chord in halves (strain) and a crossing 0.09 h inside the rim.
    // guidance.shear_switch (2026-12-05): alignment 10.4° → 5.4° (met).
    // Short edges judged on the reference, not on the holed working mesh (ExtractQuadMesh's
    // `reference`, 2026-12-05): edge_min_h 0.13 → 0.20 h (met).
    {"two_holes", "strain", {{"quad_fraction", 0.69}}},
    // Since 2026-12-04 the crossing 0.09 h inside the small opening's rim moves onto the chord's
    // new point (MoveOntoBoundary, geometry/boundary_refinement.cc): 0.091 → 0.205 h, all met.
    // The joint solve from the initial guess (2026-12-06): a 0.190 h edge, a pentagon's 0.38 h
    // chord cut in halves. Its ends moved apart first (WidenChord, 2026-12-07): 0.202 h, all met.
    {"two_holes", "curvature", {}},
    // The floor rounds: min crossing 18.8° → 25.3° (met), area below 30° 28 % → 5.4 %
    // (strain); 23.2° → 26.4° (met), 0.3 % → 1.25 % (curvature).
    // Curvature fallback: alignment 18.4° → 10.7°, area below 30° 5.4 % → met, quads 0.78 →
    // 0.87 (met), interior non-quads 1 → 0; spacing CV 0.235 → 0.321.
    // guidance.shear_switch (2026-12-05): alignment 10.7° → 8.5°, spacing CV 0.32 → 0.30.
    {"wavy", "strain", {{"alignment", 9.5}, {"spacing_cv", 0.33}}},
    {"wavy", "curvature", {{"interior_non_quads", 6}}},  // three poles; the area below 30° met since the cone's second solve
    // guidance.shear_switch (2026-12-05) left a 0.190 h edge at the Reading Room's rim: a
    // boundary vertex moved from the working mesh's polygon out onto the ring after the short-edge
    // collapses. Since they judge edges on the reference (ExtractQuadMesh's `reference`): met.
    {"great_court_112k", "strain", {}, "great_court.yaml", {"surface.edge_length=0.5"}},
    // The seams' offsets rounded together (2026-12-06): ψ's CV 0.369 → 0.075, all met.
    {"great_court_112k", "curvature", {}, "great_court.yaml", {"surface.edge_length=0.5"}},
    // 44k (issue 19): the curvature layout's shortest edge was 0.198 h at the Reading Room's rim
    // until short edges were judged on the reference (2026-12-05).
    {"great_court_44k", "strain", {}, "great_court.yaml", {"surface.edge_length=0.8"}},
    {"great_court_44k", "curvature", {}, "great_court.yaml", {"surface.edge_length=0.8"}},
    // Panels 1.25 m wide on the example's 1.5 m triangles (2026-12-07): with the planarisation's
    // anchor fixed, its vertices slid up to 6.8 edge lengths and 473 panels folded (quads 0.95 →
    // 0.67 after the repairs); with the anchor raised as closeness is, 1.3 and 0.87
    // (ExpectPlanarisationKeepsTheGrid). Its 8-gon (1.6 h from a branch point) is a known miss.
    {"great_court_h125", "strain", {{"interior_non_quads", 2}}, "great_court.yaml", {"layout.spacing=1.25"}},
    // The same panels on a reference at 0.5 h, as the surface stage's coarse-reference warning
    // asks (71k triangles): solved on 0.4 h the level sets took 134 s on 71k working triangles;
    // with levelset.working_triangles (2026-12-08) 14.5k triangles of 1.09 m, ~20 s
    // (ExpectWorkingMeshWithinBudget). Its 8-gon is 1.0 h from a branch point; it crosses at
    // 27.0° (0.07 % of the area below 30°; 27.4° on 0.4 h), so not issue 19's 30°.
    {"great_court_h125_fine", "strain", {{"interior_non_quads", 2}}, "great_court.yaml",
     {"layout.spacing=1.25", "surface.edge_length=0.625"}, false},
};

// levelset.working_triangles (default 12,000): a fine reference at a fine spacing is solved on
// a working mesh of the budget's edge, √(4A / (√3 · 12,000)), not of 0.4 h, and CGAL's remesh
// lands within 1.5× the budget's count (14.5k on the Great Court).
void ExpectWorkingMeshWithinBudget(const nlohmann::json& report, double h) {
  const nlohmann::json& levelset = report.at("stages").at("levelset");
  const double area = report.at("stages").at("surface").at("area").get<double>();
  const double budget = std::sqrt(area / (std::sqrt(3.0) / 4.0 * 12000.0));
  EXPECT_GT(budget, 0.4 * h);
  EXPECT_NEAR(levelset.at("working_edge").get<double>(), budget, 1e-9);
  EXPECT_LE(levelset.at("working_mesh_triangles").get<int>(), 18000);
  EXPECT_GE(levelset.at("working_mesh_triangles").get<int>(), 9000);
}

// What the planarisation hands on is the layout's grid made planar, not another grid: most
// quads kept and no vertex far from where the layout put it (the h = 1.25 m case above).
void ExpectPlanarisationKeepsTheGrid(const nlohmann::json& report) {
  const nlohmann::json& planarize = report.at("stages").at("planarize");
  EXPECT_GE(planarize.at("quad_fraction").get<double>(), 0.8);
  EXPECT_LE(planarize.at("max_displacement_edges").get<double>(), 2.0);
}

// Issue 19's targets for the Great Court at every size, stricter than the corpus': alignment
// ≤ 6° where weight > 0.5, spacing CV ≤ 0.2, crossing ≥ 30°, no fold-over, quads ≥ 0.85 as
// extracted, δ ≤ 1e-3 and closeness ≤ 0.02 h after planarisation: met at 44k and 112k for both
// sources since the seams' offsets are rounded together (2026-12-06; the 112k curvature layout's
// ψ spacing CV was 0.369 with them rounded one by one: benchmarks/RESULTS.md, "Diagnosed, not fixed").
void ExpectValidAtThisSize(const CorpusCase& c, const nlohmann::json& report, double h) {
  const nlohmann::json& st = report.at("stages");
  const nlohmann::json& levelset = st.at("levelset");
  const double cv = std::max(levelset.at("spacing_cv_phi").get<double>(), levelset.at("spacing_cv_psi").get<double>());
  EXPECT_LE(levelset.at("alignment_rms_deg_weight_above_half").get<double>(), 6.0);
  EXPECT_LE(cv, 0.2);
  EXPECT_GE(levelset.at("min_crossing_angle_deg").get<double>(), 30.0);
  EXPECT_EQ(levelset.at("foldovers").get<int>(), 0);
  EXPECT_GE(st.at("extract").at("quad_fraction").get<double>(), 0.85);
  EXPECT_LE(st.at("planarize").at("planarity_max").get<double>(), 1e-3);
  EXPECT_LE(st.at("planarize").at("closeness_max").get<double>(), 0.02 * h);
}

// The planarisation's panel repairs (folded panels cut, short edges closed) are a warning
// exactly where they left 0.1 or more of the extracted quad fraction (pipeline/stage_planarize.cc):
// on the corpus the drops run from 0.00 to 0.35 (9 of 22 runs warn), so both sides of the line are exercised.
void ExpectRepairWarningIffQuadsLost(const nlohmann::json& report) {
  const nlohmann::json& st = report.at("stages");
  const double drop = st.at("extract").at("quad_fraction").get<double>() - st.at("planarize").at("quad_fraction").get<double>();
  bool warned = false;
  for (const auto& w : report.at("warnings"))
    warned |= w.get<std::string>().rfind("planarize: the panel repairs left ", 0) == 0;
  EXPECT_EQ(warned, drop >= 0.1) << "quad fraction drop " << drop << ": " << report.at("warnings");
}

class CorpusTargets : public ::testing::TestWithParam<CorpusCase> {};

TEST_P(CorpusTargets, MeetsTheTargetsOrExplainsTheKnownMisses) {
  const CorpusCase& c = GetParam();
  Config config;
  std::vector<std::string> sets = c.sets;
  sets.push_back("guidance.source=" + c.source);
  const std::string path = c.config.empty() ? "/examples/corpus/" + c.roof + ".yaml" : "/examples/" + c.config;
  ASSERT_TRUE(LoadConfig(PQLAYOUT_SOURCE_DIR + path, sets, &config).ok());
  RunOptions run;
  run.out_dir = testing::TempDir() + "/corpus_" + c.roof + "_" + c.source;
  run.until = Stage::kPlanarize;
  run.commit = false;
  nlohmann::json report;
  ASSERT_TRUE(RunPipeline(config, run, &report).ok());
  const nlohmann::json& targets = report.at("targets");
  ASSERT_EQ(targets.at("list").size(), 11u);
  int met = 0;
  for (const auto& t : targets.at("list")) {
    const std::string name = t.at("name");
    met += t.at("met").get<bool>();
    const auto known = c.known_misses.find(name);
    if (known == c.known_misses.end()) {
      EXPECT_TRUE(t.at("met").get<bool>()) << name << " = " << t.at("value") << ": " << t.value("cause", "");
      continue;
    }
    if (t.at("met").get<bool>()) continue;  // fixed: strike it from kCases
    EXPECT_GT(t.at("cause").get<std::string>().size(), 20u) << name;
    const double value = t.at("value").get<double>();
    const bool at_least = name == "min_crossing" || name == "quad_fraction" || name == "edge_min_h";
    if (at_least) EXPECT_GE(value, known->second) << name;
    else EXPECT_LE(value, known->second) << name;
  }
  EXPECT_EQ(met, targets.at("met").get<int>());
  ExpectRepairWarningIffQuadsLost(report);
  if (c.config == "great_court.yaml" && c.issue19) ExpectValidAtThisSize(c, report, config.layout.spacing);
  if (c.roof.rfind("great_court_h125", 0) == 0) ExpectPlanarisationKeepsTheGrid(report);
  if (c.roof == "great_court_h125_fine") ExpectWorkingMeshWithinBudget(report, config.layout.spacing);
  if (c.roof == "dome_circular" && c.source == "strain")  // its triangles sit by the pole's cap
    for (const auto& t : targets.at("list"))
      if (t.at("name") == "interior_non_quads" && !t.at("met").get<bool>())
        EXPECT_NE(t.at("cause").get<std::string>().find("the fan loses a ray"), std::string::npos) << t.at("cause");
  const nlohmann::json& stages = report.at("stages");
  // Poles of the strain layouts since the curvature fallback (2026-12-04): the circular dome's
  // crown is a weak zone the blend fills with near-umbilic curvature lines, no pole kept (it was
  // one); the square dome's blended field has two crowns, two poles.
  const std::map<std::string, size_t> strain_poles{{"dome_circular", 0}, {"dome_square", 2}};
  const bool pole = c.source == "strain" && strain_poles.count(c.roof) > 0;
  if (pole) EXPECT_EQ(stages.at("levelset").at("poles").size(), strain_poles.at(c.roof));
  if (c.roof == "wavy" && c.source == "curvature") EXPECT_EQ(stages.at("levelset").at("poles").size(), 3u);
  if (c.roof == "dome_circular" && c.source == "curvature")  // its joint solve crawls: cut at 100 iterations
    EXPECT_EQ(stages.at("levelset").at("ceres").at("joint").at("termination"), "STALLED");
  if (c.roof == "wavy" && c.source == "strain") {  // after round 4 none reaches a better state: seven run, not ten
    EXPECT_TRUE(stages.at("levelset").at("ceres").contains("crossing_round_7"));
    EXPECT_FALSE(stages.at("levelset").at("ceres").contains("crossing_round_8"));
  }
  // The floor rounds run where the crossing rounds leave a face below min_angle (until
  // 2026-12-05: below min_angle − 5°) and their end is kept where it is the better one.
  // (the openings' roofs took them too until their holes were drawn as circles).
  // With the curvature fallback (2026-12-04) the hypar's and the wavy roof's strain layouts
  // no longer need them (crossing 30.2°, 30.5°) and the off-centre opening's does (26.4°).
  // With guidance.shear_switch (2026-12-05) the opening's strain layout crosses at 28.1° after
  // the crossing rounds and the hypar's and the saddle's take the floor rounds' end (a draw).
  // The off-centre opening's combed curvature net (2026-12-05) takes them too (27.9°).
  // Since the floor way is also tried where the crossing rounds end between 25° and 30°
  // (2026-12-05), the opening's strain layout keeps it (28.1° → 29.9°).
  // Since the cone's second solve (2026-12-06) a layout with branch points that ends below
  // min_angle is solved again with the cone's spacing round them and the better end kept: the
  // wavy roof's curvature layout is the cone's (26.4° floored → 28.3° by the crossing rounds),
  // the off-centre opening's strain layout keeps its first (29.9° against the cone's 25.1°).
  // The retry's solves are named cone_* in report.json (2026-12-06, later).
  // Since the joint solve starts from the initial guess (2026-12-06, seventeenth session) the
  // wavy roof's curvature layout keeps its first (floored, 27.4°) and the Great Court's at 44k
  // (curvature) and 112k (both) take the cone's, which reach 30° with the crossing rounds alone.
  const bool coned = (c.roof == "great_court_112k") || (c.roof == "great_court_44k" && c.source == "curvature") ||
                     c.roof == "great_court_h125_fine";
  const bool cone_tried = coned || (c.source == "strain" && c.roof == "hole_offcentre") ||
                          (c.source == "curvature" && c.roof == "wavy");
  const nlohmann::json& cone = stages.at("levelset").value("tip_cone", nlohmann::json());
  EXPECT_EQ(!cone.is_null(), cone_tried);
  if (cone_tried) EXPECT_EQ(cone.at("kept").get<bool>(), coned);
  if (coned) EXPECT_GT(cone.at("min_crossing_with").get<double>(), cone.at("min_crossing_without").get<double>() + 1.0);
  // With the seams' offsets rounded together (2026-12-06) the 112k Great Court's curvature
  // layout kept the floor rounds' end (30.3°). Since the joint solve starts from the initial
  // guess: the opening's curvature layout, the hypar's, the two openings' and the wavy roof's
  // strain layouts and the wavy roof's curvature layout keep the floor rounds' end; so does the
  // Great Court's at h = 1.25 m on its fine reference, in the cone's retry (27.0° against 25.4°).
  const bool floored = (c.source == "curvature" && (c.roof == "hole_offcentre" || c.roof == "wavy")) ||
                       (c.source == "strain" && (c.roof == "hypar" || c.roof == "two_holes" || c.roof == "wavy" ||
                                                 c.roof == "great_court_h125_fine"));
  const nlohmann::json& ceres = stages.at("levelset").at("ceres");
  const std::string kept_solves = coned ? "cone_" : "";  // the solves whose end the layout is
  EXPECT_EQ(ceres.contains("cone_joint"), cone_tried);
  EXPECT_EQ(stages.at("levelset").at("crossing_rounds_kept") == "floor", floored);
  if (floored) EXPECT_TRUE(ceres.contains(kept_solves + "floor_round_1"));
  // Every layout left with a face below min_angle tried the floor way; one whose crossing
  // rounds reached it did not.
  const double crossing = stages.at("levelset").at("min_crossing_angle_deg").get<double>();
  if (crossing < 30.0) EXPECT_TRUE(ceres.contains(kept_solves + "floor_round_1"));
  if (crossing >= 30.0 && !floored) EXPECT_FALSE(ceres.contains(kept_solves + "floor_round_1"));
  if (pole) EXPECT_EQ(stages.at("extract").at("caps").size(), strain_poles.at(c.roof));
  const bool remeshed = c.roof == "great_court_112k" || c.roof == "great_court_44k";
  if (remeshed) EXPECT_TRUE(stages.at("levelset").at("poles").empty());  // no crown
  if (remeshed) {  // solved on a working mesh, no seam round the ring
    const nlohmann::json& levelset = report.at("stages").at("levelset");
    // ~12k working triangles whatever the reference (11.8k of 44k, 12k of 112k).
    EXPECT_LT(levelset.at("working_mesh_triangles").get<int>(), report.at("stages").at("surface").at("n_faces").get<int>() / 3);
    EXPECT_EQ(levelset.at("working_mesh"), "CGAL remeshing (not from the plan: fewer than 200000 triangles)");
    // Strain with the curvature fallback: the blend has the curvature field's four umbilics,
    // so the layout has the curvature layout's five seams (four branch points, one round the
    // ring); the paper's strain layout had none (no seam worth cutting, the ring's uncut).
    if (c.source == "strain") EXPECT_EQ(levelset.at("seams").at("count"), 5);
    if (c.source == "strain") EXPECT_EQ(levelset.at("seams").at("branch_points"), 4);
  }
  std::cout << c.roof << " × " << c.source << ": " << met << " of 11 targets met\n";
}

// An example's config (path under examples/) with `sets`, run until `until`; its report.
nlohmann::json RunExample(const std::string& path, const std::vector<std::string>& sets, Stage until, const std::string& dir) {
  Config config;
  EXPECT_TRUE(LoadConfig(PQLAYOUT_SOURCE_DIR "/examples/" + path, sets, &config).ok());
  RunOptions run;
  run.out_dir = testing::TempDir() + "/" + dir;
  run.until = until;
  run.commit = false;
  nlohmann::json report;
  EXPECT_TRUE(RunPipeline(config, run, &report).ok());
  return report;
}

nlohmann::json RunBarrel(const std::vector<std::string>& sets, Stage until, const std::string& dir) {
  return RunExample("corpus/barrel.yaml", sets, until, dir);
}

// extract.brace_free_edges = all on the barrel vault (free gables, fixed long sides): the quads
// on the gables are cut (no more than the two gable rows hold), and no interior cell changes.
TEST(FreeEdgeBracing, CutsTheBarrelsGableRowsOnly) {
  const nlohmann::json report = RunBarrel({"extract.brace_free_edges=all"}, Stage::kExtract, "corpus_barrel_braced");
  const nlohmann::json& extract = report.at("stages").at("extract");
  const int braced = extract.at("braced_quads");
  const int triangles = extract.at("face_sides").value("3", 0);
  std::cout << "barrel braced: " << braced << " quads cut, " << triangles << " triangles\n";
  EXPECT_GE(braced, 10);  // two gables, ~13 panels across each (25 measured)
  EXPECT_LE(braced, 30);
  EXPECT_GE(triangles, 2 * braced);
  EXPECT_TRUE(extract.at("interior_non_quads").empty());
}

// The default (extract.brace_free_edges = paying) on the barrel vault: both gables are tried
// and kept (each trial stiffens the shell again; measured after stiffen × 0.54 strain, × 0.63
// curvature on this machine), the long sides are supported, so there are exactly two stretches.
TEST(FreeEdgeBracing, PaysOnTheBarrelsGablesAfterStiffen) {
  Config config;
  ASSERT_TRUE(LoadConfig(PQLAYOUT_SOURCE_DIR "/examples/corpus/barrel.yaml", {}, &config).ok());
  EXPECT_EQ(config.extract.brace_free_edges, "paying");
  const nlohmann::json report = RunBarrel({}, Stage::kStiffen, "corpus_barrel_paying");
  const nlohmann::json& stiffen = report.at("stages").at("stiffen");
  const nlohmann::json& bracing = stiffen.at("bracing");
  std::cout << "barrel paying: " << bracing.dump() << "\n";
  EXPECT_EQ(bracing.at("free_stretches"), 2);
  EXPECT_EQ(bracing.at("trials"), 3);
  EXPECT_EQ(bracing.at("braced_stretches"), 2);
  EXPECT_GE(bracing.at("braced_quads").get<int>(), 10);
  EXPECT_LT(bracing.at("compliance_ratio").get<double>(), 0.8);
  EXPECT_NEAR(stiffen.at("compliance_after").get<double>(),
              bracing.at("compliance_ratio").get<double>() * bracing.at("compliance_unbraced").get<double>(), 1e-6);
  EXPECT_LE(stiffen.at("planarity_max").get<double>(), config.planarize.target_delta);
  EXPECT_LE(stiffen.at("closeness_max").get<double>(), config.stiffen.tolerance);
}

// stiffen when its first line search ends on the start: the Great Court at h = 1.25 m ×
// curvature on a 0.5 h reference found C/C₀ 0.9974 at a z-step of 0.011, reached for 0.11 (its
// retraction failed) and, its four Wolfe steps spent, Ceres handed back the start ("Parameter
// tolerance reached", step 0): the stage ended at C × 1.000. Such a run is run again with 20
// steps (problems/stiffen.cc, kLongLineSearchSteps): × 0.596 at the stage's end, and within ten
// iterations already ≤ 0.9 (measured 2026-12-08).
TEST(StiffenAtFineSpacing, ARunThatDidNotMoveIsRunAgain) {
  const nlohmann::json report =
      RunExample("great_court.yaml",
                 {"layout.spacing=1.25", "surface.edge_length=0.625", "guidance.source=curvature", "stiffen.max_iterations=10"},
                 Stage::kStiffen, "stiffen_h125_fine_curvature");
  const nlohmann::json& stiffen = report.at("stages").at("stiffen");
  std::cout << "h = 1.25 m fine × curvature, stiffen: " << stiffen.at("compliance_ratio") << " in "
            << stiffen.at("iterations") << " iterations\n";
  EXPECT_LE(stiffen.at("compliance_ratio").get<double>(), 0.9);
  EXPECT_LE(stiffen.at("planarity_max").get<double>(), report.at("config").at("planarize").at("target_delta").get<double>());
}

INSTANTIATE_TEST_SUITE_P(Roofs, CorpusTargets, ::testing::ValuesIn(kCases),
                         [](const auto& info) { return info.param.roof + "_" + info.param.source; });

}  // namespace
}  // namespace pqlayout

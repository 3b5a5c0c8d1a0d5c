// Golden metrics of examples/great_court.yaml, the paper's setting (whole boundary fixed,
// h = 3 m), through planarisation, for both guidance sources: the acceptance numbers of
// issues 4–6 as measured, so that a change that loses one of them fails here; and the same
// roof meshed at 1.6 m, where the level sets need the floor rounds.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "pipeline/config.h"
#include "pipeline/pipeline.h"
#include "tests/test_meshes.h"

namespace pqlayout {
namespace {

nlohmann::json GreatCourtStages(const std::string& source, std::vector<std::string> sets = {},
                                Stage until = Stage::kPlanarize) {
  Config config;
  sets.push_back("guidance.source=" + source);
  EXPECT_TRUE(LoadConfig(PQLAYOUT_SOURCE_DIR "/examples/great_court.yaml", sets, &config).ok());
  RunOptions run;
  run.out_dir = testing::TempDir() + "/" + source + std::to_string(sets.size());
  run.until = until;
  nlohmann::json report;
  EXPECT_TRUE(RunPipeline(config, run, &report).ok());
  return report["stages"];
}

// The targets both layouts meet (ExpectCommonTargets): no fold-over and every crossing ≥ 30° (issue 4), quad
// fraction ≥ 0.85, boundary within 0.01 h, no edge below 0.2 h, no panel above seven
// sides (issue 5), δ ≤ 1e-3 with closeness ≤ 0.02 h (issue 6).
void ExpectCommonTargetsExceptCrossing(const nlohmann::json& s, double h) {
  EXPECT_EQ(s["levelset"]["foldovers"].get<int>(), 0);
  EXPECT_GE(s["extract"]["quad_fraction"].get<double>(), 0.85);
  EXPECT_LE(s["extract"]["boundary_deviation"].get<double>(), 0.01 * h);
  EXPECT_GE(s["extract"]["edge_length_min"].get<double>(), 0.2);  // relative to h
  EXPECT_LE(s["planarize"]["planarity_max"].get<double>(), 1e-3);
  EXPECT_LE(s["planarize"]["closeness_max"].get<double>(), 0.02 * h);
  // Planarity bought with panel shape (2026-12-04): before the repair 74 (strain) and 26
  // (curvature) panels folded and edges closed to 0.000 h; the edges planarisation closes
  // are now closed for good, darts and folded panels cut into triangles held the right way
  // round and open (planarize.close_edges, planarize.weights.orientation). Measured: no folded
  // panel, shortest edge 0.113 h and 0.111 h (6 and 2 folded, 0.121 h and 0.102 h before).
  EXPECT_EQ(s["planarize"]["folded_faces"].get<int>(), 0);
  EXPECT_GE(s["planarize"]["edge_length_min"].get<double>(), 0.1);
  // Quads warped beyond δ 0.05 as extracted are cut into two triangles first
  // (planarize.split_warped): both layouts have some (22 strain, 3 curvature when written),
  // and then no vertex moves more than 1.5 edge lengths (1.34 and 0.92; 1.37 and 0.99 before).
  EXPECT_GE(s["planarize"]["warped_split"].get<int>(), 1);
  EXPECT_LE(s["planarize"]["max_displacement_edges"].get<double>(), 1.5);
  // No panel above six sides (measured: 5 on the strain layout, one hexagon on the curvature
  // layout near a branch point).
  for (const auto& [sides, count] : s["extract"]["face_sides"].items()) EXPECT_LE(std::stoi(sides), 6) << count;
}

void ExpectCommonTargets(const nlohmann::json& s, double h) {
  ExpectCommonTargetsExceptCrossing(s, h);
  EXPECT_GE(s["levelset"]["min_crossing_angle_deg"].get<double>(), 30.0);
}

// Issue 4's level-set targets (alignment where weight > 0.5, spacing CV there and overall).
void ExpectLevelsetTargets(const nlohmann::json& l) {
  EXPECT_LE(l["alignment_rms_deg_weight_above_half"].get<double>(), 6.0);
  EXPECT_LE(l["spacing_cv_phi_weight_above_half"].get<double>(), 0.15);
  EXPECT_LE(l["spacing_cv_psi_weight_above_half"].get<double>(), 0.15);
  EXPECT_LE(l["spacing_cv_phi"].get<double>(), 0.2);
  EXPECT_LE(l["spacing_cv_psi"].get<double>(), 0.2);
}

// Strain guidance meets every target, some with thin margins (measured: alignment 5.93°,
// CV 0.149 / 0.131 / 0.088, crossing 30.05°; quad fraction 0.852, boundary 0.00998 h,
// shortest edge 0.205 h; δ 1.5e-4, closeness 0.007 h).
// This is the paper's layout: alignment only where |ε_max| is strong (guidance.fallback = none,
// guidance.shear_switch = paper; the default fills the weak zones with curvature lines and
// takes no weight where e_max swaps by 90°, next test), solved in the paper's order, φ, then ψ,
// then both (levelset.separate_solves; from the initial guess, the default since 2026-12-06,
// this layout aligns to 6.34° and its φ spacing CV is 0.174 where the weight is > 0.5).
TEST(GreatCourt, StrainLayoutMeetsIssues4To6) {
  const nlohmann::json s = GreatCourtStages("strain", {"guidance.fallback=none", "guidance.shear_switch=paper",
                                                       "levelset.separate_solves=true"});
  ExpectCommonTargets(s, 3.0);
  ExpectLevelsetTargets(s["levelset"]);
  // The strain field's singularities lie in the weak bands along the edges: no seam is worth
  // cutting, φ and ψ stay single-valued.
  EXPECT_EQ(s["levelset"]["seams"]["count"].get<int>(), 0);
  // Its crown (a cancelled +½ pair in a weak band) gets no pole: the layout without meets the
  // alignment target, so the pole layout is not solved (it aligned to 6.0°, at twice the
  // stage's time). There were two until pairs in one weak zone had to be closer than 3 h
  // (kCancelInZone, 2026-12-05); the other pair's route is too light to cut, the layout is the same.
  EXPECT_TRUE(s["levelset"]["poles"].empty());
  ASSERT_TRUE(s["levelset"].contains("poles_not_kept"));
  EXPECT_EQ(s["levelset"]["poles_not_kept"]["tried"].get<bool>(), false);
  EXPECT_EQ(s["levelset"]["poles_not_kept"]["crowns"].get<int>(), 1);
  // Two boundary 9-gons are cut into quads and a triangle (SplitLargePolygons).
  EXPECT_GE(s["extract"]["split_boundary_polygons"].get<int>(), 2);
  EXPECT_TRUE(s["extract"]["interior_non_quads"].empty()) << s["extract"]["interior_non_quads"];
  EXPECT_EQ(s["extract"]["n_corner_vertices"].get<int>(), 4);
  // The planarity figure says what was built: its title counts the planarised mesh's quads
  // (quad_fraction × n_faces) and the panels still folded (GreatCourtStages's directory).
  const auto* test = ::testing::UnitTest::GetInstance()->current_test_info();  // TempDir() would wipe it
  std::ifstream svg(std::filesystem::temp_directory_path() /
                    ("pqlayout_test_" + std::string(test->test_suite_name()) + "_" + test->name()) /
                    "strain4/figures/planarity.svg");
  ASSERT_TRUE(svg.good());
  const std::string text((std::istreambuf_iterator<char>(svg)), std::istreambuf_iterator<char>());
  const auto& p = s["planarize"];
  const int quads = static_cast<int>(std::lround(p["quad_fraction"].get<double>() * p["n_faces"].get<int>()));
  EXPECT_NE(text.find("Planarity δ after planarisation: " + std::to_string(quads) + " quads, "), std::string::npos);
  const int folded = p["folded_faces"].get<int>();
  EXPECT_NE(text.find(folded == 0 ? ", none folded" : ", " + std::to_string(folded) + " folded"), std::string::npos);
}

// The default strain layout: where the strain is weak (52 % of the area) the curvature lines
// fill in (guidance.fallback = curvature, β = 0.5). The strain field's 38 singularities in its
// weak zones are gone, the blend keeps the curvature field's four umbilics (index −½); the
// layout aligns to the strain where it is strong far better than the paper's (measured 1.91°
// against 5.93°) and the frame after stiffen is less than half as compliant: 63,961 J against
// 154,794 J here (75,400 J before guidance.shear_switch), ≤ 80,411 J over seven meshes of
// 11k–112k triangles where the paper's layout was ≥ 115,488 J (benchmarks/RESULTS.md,
// 2026-12-04, 2026-12-05). Measured: crossing 30.46°, quads 0.868. Since stiffen's slide no
// longer uses up the tolerance (stiffen.slide 0.1 m instead of 0.01 m, 2026-12-05): 53,257 J
// here, ≤ 65,866 J over the seven meshes; since the planes are measured from their faces
// 52,991 J, ≤ 73,112 J; since the seams' offsets are rounded together (2026-12-06) 55,003 J
// here, ≤ 56,555 J over the seven (benchmarks/ensemble/stiffness_offsets_rounded_together.csv);
// since the joint solve starts from the initial guess (levelset.separate_solves false,
// 2026-12-06) 51,544 J here, ≤ 51,697 J over the seven (benchmarks/ensemble/stiffness_joint_from_initial_guess.csv);
// since the planarisation's anchor rides with closeness (2026-12-07) 51,372 J here, ≤ 51,372 J
// over the seven (benchmarks/ensemble/stiffness_anchor_rides.csv).
TEST(GreatCourt, StrainLayoutWithCurvatureFallbackIsTwiceAsStiff) {
  const nlohmann::json s = GreatCourtStages("strain", {}, Stage::kStiffen);
  ExpectCommonTargetsExceptCrossing(s, 3.0);
  EXPECT_GE(s["levelset"]["min_crossing_angle_deg"].get<double>(), 25.0);  // issue 17's; 28.0–31.0° over the seven
  EXPECT_EQ(s["guidance"]["fallback"].get<std::string>(), "curvature");
  EXPECT_NEAR(s["guidance"]["area_fallback"].get<double>(), 0.525, 0.05);
  EXPECT_EQ(s["guidance"]["singularities"]["by_index"], (nlohmann::json{{"-0.5", 4}}));
  EXPECT_LE(s["levelset"]["alignment_rms_deg_source_above_half"].get<double>(), 3.0);
  EXPECT_LE(s["levelset"]["alignment_rms_deg_weight_above_half"].get<double>(), 3.0);
  EXPECT_EQ(s["planarize"]["folded_faces"].get<int>(), 0);
  EXPECT_LE(s["stiffen"]["compliance_after"].get<double>(), 55000.0);
  EXPECT_LE(s["stiffen"]["closeness_max"].get<double>(), 0.1);  // stiffen.tolerance, with a slide of 0.1 m along it
  EXPECT_LE(s["stiffen"]["planarity_max"].get<double>(), 1e-3);
}

// levelset.draft: the level sets on a working mesh of edge 0.8 h (2,950 triangles instead of
// 12,404; the stage ~5× faster). Still aligned and stiff after stiffen, though a different
// draw: measured alignment 1.84° (source 2.31°), crossing 30.2°, quads 0.855, 72,565 J after
// stiffen; over seven meshes median 72,565 J against 66,827 J without draft, 70 of 77 targets
// (the shortest edge at the hole, 0.14 h, on every mesh) (benchmarks/RESULTS.md, 2026-12-04).
TEST(GreatCourt, DraftLayoutOnAQuarterOfTheTrianglesStillAlignsAndStiffens) {
  const nlohmann::json s = GreatCourtStages("strain", {"levelset.draft=true"}, Stage::kStiffen);
  EXPECT_NEAR(s["levelset"]["working_mesh_triangles"].get<int>(), 2950, 300);
  EXPECT_EQ(s["levelset"]["foldovers"].get<int>(), 0);
  EXPECT_LE(s["levelset"]["alignment_rms_deg_source_above_half"].get<double>(), 3.0);
  EXPECT_GE(s["levelset"]["min_crossing_angle_deg"].get<double>(), 25.0);
  EXPECT_GE(s["extract"]["quad_fraction"].get<double>(), 0.80);
  EXPECT_LE(s["planarize"]["planarity_max"].get<double>(), 1e-3);
  EXPECT_LE(s["planarize"]["closeness_max"].get<double>(), 0.02 * 3.0);
  EXPECT_LE(s["stiffen"]["compliance_after"].get<double>(), 100000.0);
}

// Curvature guidance (the paper's reference layout, Fig. 8b): with seams from the four
// umbilics (index −½, branch points) and from the ring to the outer boundary, every target is
// met (measured 2026-12-06, the layout of the cone's second solve: alignment 2.74°, CV 0.134 /
// 0.053 where weight > 0.5, 0.183 / 0.096 overall, crossing 30.07°; quad fraction 0.885; δ 7.4e-4;
// 2.87°, 30.8° and 0.872 before the cone). Without seams it was 9.34° and CV 0.227.
TEST(GreatCourt, CurvatureLayoutMeetsIssues4To6WithBranchPoints) {
  const nlohmann::json s = GreatCourtStages("curvature");
  ExpectCommonTargets(s, 3.0);
  ExpectLevelsetTargets(s["levelset"]);
  const auto& seams = s["levelset"]["seams"];
  EXPECT_EQ(seams["count"].get<int>(), 5);
  EXPECT_EQ(seams["branch_points"].get<int>(), 4);
  for (const auto& path : seams["paths"]) {
    const bool branch = path["branch_point"].get<bool>();
    EXPECT_EQ(path["sign"].get<int>(), branch ? -1 : 1);
    if (branch) EXPECT_EQ(std::abs(path["phi_offset"].get<int>()) % 2, 1);  // branch point inside a cell
    else EXPECT_GT(std::abs(path["phi_offset"].get<int>()), 40);  // φ's rays once round the ring
  }
  EXPECT_EQ(s["extract"]["unmatched_seam_edges"].get<int>(), 0);
  EXPECT_EQ(s["extract"]["euler_characteristic"].get<int>(), 0);  // still one annulus
  EXPECT_EQ(s["extract"]["n_corner_vertices"].get<int>(), 4);
  EXPECT_LE(s["extract"]["interior_non_quads"].size(), 2u) << s["extract"]["interior_non_quads"];
}

// The example's layout is one draw of the level sets: on the same roof meshed at 1.6 m instead
// of 1.5 m the crossing rounds left the strain layout at 11.2° with a fold-over (2026-12-03,
// benchmarks/ensemble/gc12k_strain.csv). Since the floor rounds the worst crossing there is
// 25.7° with no fold-over (floor_gc12k_strain.csv), and over the five meshes of 1.4–1.6 m
// 25.2–30.0°: on this mesh the floor rounds must run, be kept, and hold issue 17's 25°.
TEST(GreatCourt, StrainLayoutOnTheCoarserMeshHoldsTheFloor) {
  const nlohmann::json l =
      GreatCourtStages("strain", {"surface.edge_length=1.6", "guidance.fallback=none", "guidance.shear_switch=paper"},
                       Stage::kLevelset)["levelset"];
  EXPECT_EQ(l["foldovers"].get<int>(), 0);
  EXPECT_GE(l["min_crossing_angle_deg"].get<double>(), 25.0);
  EXPECT_EQ(l["crossing_rounds_kept"].get<std::string>(), "floor");
  EXPECT_TRUE(l["ceres"].contains("floor_round_1"));
  EXPECT_LE(l["area_fraction_below_min_angle"].get<double>(), 0.03);  // 1.6 % (179 faces) when written
  EXPECT_LE(l["alignment_rms_deg_weight_above_half"].get<double>(), 8.0);  // 7.32°
}

}  // namespace
}  // namespace pqlayout

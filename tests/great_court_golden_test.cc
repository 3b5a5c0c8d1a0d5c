// Golden metrics of examples/great_court.yaml, the paper's setting (whole boundary fixed,
// h = 3 m), through planarisation, for both guidance sources: the acceptance numbers of
// issues 4–6 as measured, so that a change that loses one of them fails here.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "problems/config.h"
#include "problems/pipeline.h"
#include "tests/test_meshes.h"

namespace pqlayout {
namespace {

nlohmann::json GreatCourtStages(const std::string& source) {
  Config config;
  EXPECT_TRUE(LoadConfig(PQLAYOUT_SOURCE_DIR "/examples/great_court.yaml", {"guidance.source=" + source}, &config).ok());
  RunOptions run;
  run.out_dir = testing::TempDir() + "/" + source;
  run.until = Stage::kPlanarize;
  nlohmann::json report;
  EXPECT_TRUE(RunPipeline(config, run, &report).ok());
  return report["stages"];
}

// The targets both layouts meet: no fold-over and every crossing ≥ 30° (issue 4), quad
// fraction ≥ 0.85, boundary within 0.01 h, no edge below 0.2 h, no panel above seven
// sides (issue 5), δ ≤ 1e-3 with closeness ≤ 0.02 h (issue 6).
void ExpectCommonTargets(const nlohmann::json& s, double h) {
  EXPECT_EQ(s["levelset"]["foldovers"].get<int>(), 0);
  EXPECT_GE(s["levelset"]["min_crossing_angle_deg"].get<double>(), 30.0);
  EXPECT_GE(s["extract"]["quad_fraction"].get<double>(), 0.85);
  EXPECT_LE(s["extract"]["boundary_deviation"].get<double>(), 0.01 * h);
  EXPECT_GE(s["extract"]["edge_length_min"].get<double>(), 0.2);  // relative to h
  EXPECT_LE(s["planarize"]["planarity_max"].get<double>(), 1e-3);
  EXPECT_LE(s["planarize"]["closeness_max"].get<double>(), 0.02 * h);
  // Large boundary cells (two 9-gons on the strain layout, a 7- and four 8-gons on the
  // curvature layout) are cut into quads and a triangle where the pieces are well shaped:
  // measured, no panel above 5 sides (strain) and one 7-gon left (curvature).
  EXPECT_GE(s["extract"]["split_boundary_polygons"].get<int>(), 2);
  for (const auto& [sides, count] : s["extract"]["face_sides"].items()) EXPECT_LE(std::stoi(sides), 7) << count;
}

// Strain guidance meets every target, some with thin margins (measured: alignment 5.93°,
// CV 0.149 / 0.131 / 0.088, crossing 30.05°; quad fraction 0.852, boundary 0.00998 h,
// shortest edge 0.205 h; δ 1.5e-4, closeness 0.007 h).
TEST(GreatCourt, StrainLayoutMeetsIssues4To6) {
  const nlohmann::json s = GreatCourtStages("strain");
  ExpectCommonTargets(s, 3.0);
  const auto& l = s["levelset"];
  EXPECT_LE(l["alignment_rms_deg_weight_above_half"].get<double>(), 6.0);
  EXPECT_LE(l["spacing_cv_phi_weight_above_half"].get<double>(), 0.15);
  EXPECT_LE(l["spacing_cv_psi_weight_above_half"].get<double>(), 0.15);
  EXPECT_LE(l["spacing_cv_phi"].get<double>(), 0.2);
  EXPECT_LE(l["spacing_cv_psi"].get<double>(), 0.2);
  EXPECT_TRUE(s["extract"]["interior_non_quads"].empty()) << s["extract"]["interior_non_quads"];
  EXPECT_EQ(s["extract"]["n_corner_vertices"].get<int>(), 4);
}

// Curvature guidance (the reference layout): the crossing angle, extraction and
// planarisation targets are met; alignment and spacing CV are not (measured 9.34° and 0.227
// where the weight is > 0.5, issue 4 asks 6° and 0.15) and are held at what they are.
TEST(GreatCourt, CurvatureLayoutGoldenMetrics) {
  const nlohmann::json s = GreatCourtStages("curvature");
  ExpectCommonTargets(s, 3.0);
  EXPECT_LE(s["levelset"]["alignment_rms_deg_weight_above_half"].get<double>(), 9.5);
  EXPECT_LE(s["levelset"]["spacing_cv_phi_weight_above_half"].get<double>(), 0.24);
}

}  // namespace
}  // namespace pqlayout

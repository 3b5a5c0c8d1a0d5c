// The floor rounds' fixed point (problems/levelset_rounds.cc, FloorRounds): a floor round that
// leaves φ and ψ as they were ends the floor rounds, since every further one would repeat it to
// the bit (its floor, live region and terms are functions of φ and ψ alone). The two-hole roof
// × strain reaches it at its fourth floor round; its level sets must be those of the ten rounds
// run in full (2f8470c, which ran them: the metrics below to the last digits).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "pipeline/config.h"
#include "pipeline/pipeline.h"

namespace pqlayout {
namespace {

TEST(LevelSetRounds, AFloorRoundThatChangesNothingEndsTheFloorRoundsWithTheSameLevelSets) {
  Config config;
  ASSERT_TRUE(LoadConfig(PQLAYOUT_SOURCE_DIR "/examples/corpus/two_holes.yaml", {"guidance.source=strain"}, &config).ok());
  RunOptions run;
  run.out_dir = testing::TempDir() + "/floor_fixed_point";
  run.until = Stage::kLevelset;
  run.commit = false;
  nlohmann::json report;
  ASSERT_TRUE(RunPipeline(config, run, &report).ok());
  const nlohmann::json& stage = report.at("stages").at("levelset");
  const nlohmann::json& ceres = stage.at("ceres");
  EXPECT_EQ(stage.at("crossing_rounds_kept"), "floor");
  ASSERT_TRUE(ceres.contains("floor_round_4"));
  EXPECT_FALSE(ceres.contains("floor_round_5"));  // 2f8470c ran floor_round_5 … 10, each the same
  // φ and ψ as they were: the cost at the end is the cost at the start, to the bit.
  EXPECT_EQ(ceres.at("floor_round_4").at("final_cost").get<double>(),
            ceres.at("floor_round_4").at("initial_cost").get<double>());
  EXPECT_NE(ceres.at("floor_round_3").at("final_cost").get<double>(),
            ceres.at("floor_round_3").at("initial_cost").get<double>());
  const auto expect = [&stage](const char* key, double all_rounds) {
    EXPECT_NEAR(stage.at(key).get<double>(), all_rounds, 1e-9 * all_rounds) << key;
  };
  expect("min_crossing_angle_deg", 30.152228617839032);
  expect("alignment_rms_deg_weight_above_half", 6.058680251805433);
  expect("spacing_cv_phi", 0.15417164561475885);
  expect("spacing_cv_psi", 0.06584784447382887);
  expect("conjugacy_rms", 0.14099275014362841);
  EXPECT_EQ(stage.at("foldovers").get<int>(), 0);
  EXPECT_EQ(stage.at("faces_below_min_angle").get<int>(), 0);
}

}  // namespace
}  // namespace pqlayout

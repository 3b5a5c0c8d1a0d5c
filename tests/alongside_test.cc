// levelset.alongside: the second layouts that may be needed — the cone's retry
// (problems/levelset_problem.cc, TryTipCone) and the layout with poles (levelset_poles.cc,
// ChoosePoles) — started on a second thread beside the first layout's give the same level sets
// as solving them afterwards, on one thread, only once they are needed: every Ceres summary
// (initial and final cost to the last bit, iterations), every metric and the kept end identical.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "pipeline/config.h"
#include "pipeline/pipeline.h"

namespace pqlayout {
namespace {

// report.json's levelset stage without its timings and peak memory (two problems at once hold more).
nlohmann::json WithoutSeconds(nlohmann::json j) {
  if (!j.is_object()) return j;
  nlohmann::json out = nlohmann::json::object();
  for (auto& [key, value] : j.items())
    if (key.find("seconds") == std::string::npos && key != "peak_memory_mb") out[key] = WithoutSeconds(value);
  return out;
}

nlohmann::json LevelsetStage(const std::string& config_file, std::vector<std::string> sets, bool alongside,
                             const std::string& dir) {
  Config config;
  sets.push_back(std::string("levelset.alongside=") + (alongside ? "true" : "false"));
  EXPECT_TRUE(LoadConfig(PQLAYOUT_SOURCE_DIR "/examples/" + config_file, sets, &config).ok());
  RunOptions run;
  run.out_dir = testing::TempDir() + "/" + dir + (alongside ? "_alongside" : "_after");
  run.until = Stage::kLevelset;
  run.commit = false;
  nlohmann::json report;
  EXPECT_TRUE(RunPipeline(config, run, &report).ok());
  return WithoutSeconds(report.at("stages").at("levelset"));
}

// The Great Court's draft curvature layout (four branch points) asked for a 40° crossing that its
// first layout does not reach (38.2°), so the cone's retry runs; two crossing rounds keep it short.
TEST(Alongside, TheConesRetryGivesTheSameLevelSets) {
  const std::vector<std::string> sets{"guidance.source=curvature", "levelset.draft=true", "levelset.min_angle=40",
                                      "levelset.crossing_rounds=2"};
  const nlohmann::json alongside = LevelsetStage("great_court.yaml", sets, true, "cone");
  const nlohmann::json after = LevelsetStage("great_court.yaml", sets, false, "cone");
  ASSERT_TRUE(alongside.contains("tip_cone"));
  EXPECT_TRUE(alongside.at("tip_cone").at("tried").get<bool>());
  EXPECT_TRUE(alongside.at("ceres").contains("cone_joint"));
  EXPECT_TRUE(alongside.at("ceres").contains("cone_crossing_round_1"));
  EXPECT_EQ(alongside.at("ceres").at("cone_joint"), after.at("ceres").at("cone_joint"));
  EXPECT_EQ(alongside, after);  // every summary, metric and the kept end
}

// Draft runs of two corpus roofs with a crown whose layout without poles misaligns (> 8°), so
// the poles are tried: the L-shape × strain rejects them (15.7° with, 14.0° without), the wavy
// roof × curvature keeps its three (4.2° against 39.5°).
TEST(Alongside, ThePolesLayoutGivesTheSameLevelSets) {
  const std::vector<std::string> l_shape{"guidance.source=strain", "levelset.draft=true"};
  const nlohmann::json rejected = LevelsetStage("corpus/l_shape.yaml", l_shape, true, "poles_l_shape");
  ASSERT_TRUE(rejected.contains("poles_not_kept"));
  EXPECT_TRUE(rejected.at("poles_not_kept").at("tried").get<bool>());
  EXPECT_EQ(rejected, LevelsetStage("corpus/l_shape.yaml", l_shape, false, "poles_l_shape"));
  const std::vector<std::string> wavy{"guidance.source=curvature", "levelset.draft=true", "levelset.crossing_rounds=2"};
  const nlohmann::json kept = LevelsetStage("corpus/wavy.yaml", wavy, true, "poles_wavy");
  EXPECT_EQ(kept.at("poles").size(), 3u);
  EXPECT_EQ(kept, LevelsetStage("corpus/wavy.yaml", wavy, false, "poles_wavy"));
}

}  // namespace
}  // namespace pqlayout

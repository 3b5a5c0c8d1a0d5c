// levelset.alongside: the second layouts that may be needed — the cone's retry with its rounds
// (problems/levelset_problem.cc, TryTipCone), the layout with poles (levelset_poles.cc,
// ChoosePoles) and the rounds' floor way (levelset_rounds.cc, Rounds) — started on a second
// thread beside the first layout's give the same level sets as solving them afterwards, on one
// thread, only once they are needed: every Ceres summary (initial and final cost to the last
// bit, iterations), every metric and the kept end identical.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <string>
#include <thread>
#include <vector>

#include <ceres/ceres.h>
#include <nlohmann/json.hpp>

#include "base/interrupt.h"
#include "pipeline/config.h"
#include "pipeline/pipeline.h"
#include "problems/levelset_internal.h"
#include "solver/ceres_options.h"

namespace pqlayout {
namespace {

// report.json's levelset stage without its timings, peak memory (two problems at once hold more)
// and tip_cone.alongside (which thread solved the cone's retry).
nlohmann::json WithoutSeconds(nlohmann::json j) {
  if (!j.is_object()) return j;
  nlohmann::json out = nlohmann::json::object();
  for (auto& [key, value] : j.items())
    if (key.find("seconds") == std::string::npos && key != "peak_memory_mb" && key != "alongside")
      out[key] = WithoutSeconds(value);
  return out;
}

// levelset.alongside = `alongside` ("true", "false", "1"), the run stopped after the level sets.
nlohmann::json LevelsetStage(const std::string& config_file, std::vector<std::string> sets,
                             const std::string& alongside, const std::string& dir, bool keep_alongside_key = false) {
  Config config;
  sets.push_back("levelset.alongside=" + alongside);
  EXPECT_TRUE(LoadConfig(PQLAYOUT_SOURCE_DIR "/examples/" + config_file, sets, &config).ok());
  RunOptions run;
  run.out_dir = testing::TempDir() + "/" + dir + "_" + alongside;
  run.until = Stage::kLevelset;
  run.commit = false;
  nlohmann::json report;
  EXPECT_TRUE(RunPipeline(config, run, &report).ok());
  nlohmann::json stage = report.at("stages").at("levelset");
  return keep_alongside_key ? stage : WithoutSeconds(stage);
}

// The Great Court's draft curvature layout (four branch points) asked for a 45° crossing that its
// first layout does not reach (41.1°), so the cone's retry runs (45.5° after a crossing round:
// at 40° its joint solve alone reached 43.5° and no round of the retry ran); two crossing
// rounds keep it short. Its first layout's crossing rounds fall short too, so their floor way
// runs beside them (Rounds), and the cone's retry runs its own rounds on its thread.
TEST(Alongside, TheConesRetryGivesTheSameLevelSets) {
  const std::vector<std::string> sets{"guidance.source=curvature", "levelset.draft=true", "levelset.min_angle=45",
                                      "levelset.crossing_rounds=2"};
  const nlohmann::json alongside = LevelsetStage("great_court.yaml", sets, "true", "cone");
  const nlohmann::json after = LevelsetStage("great_court.yaml", sets, "false", "cone");
  ASSERT_TRUE(alongside.contains("tip_cone"));
  EXPECT_TRUE(alongside.at("tip_cone").at("tried").get<bool>());
  EXPECT_TRUE(alongside.at("ceres").contains("cone_joint"));
  EXPECT_TRUE(alongside.at("ceres").contains("cone_crossing_round_1"));
  EXPECT_TRUE(alongside.at("ceres").contains("floor_round_1"));
  EXPECT_TRUE(alongside.at("ceres").contains("polish_round_1"));
  EXPECT_EQ(alongside.at("ceres").at("cone_joint"), after.at("ceres").at("cone_joint"));
  EXPECT_EQ(alongside, after);  // every summary, metric and the kept end
}

// Draft runs of two corpus roofs with a crown whose layout without poles misaligns (> 8°), so
// the poles are tried: the L-shape × strain rejects them (15.7° with, 14.0° without), the wavy
// roof × curvature keeps its three (4.2° against 39.5°).
TEST(Alongside, ThePolesLayoutGivesTheSameLevelSets) {
  const std::vector<std::string> l_shape{"guidance.source=strain", "levelset.draft=true"};
  const nlohmann::json rejected = LevelsetStage("corpus/l_shape.yaml", l_shape, "true", "poles_l_shape");
  ASSERT_TRUE(rejected.contains("poles_not_kept"));
  EXPECT_TRUE(rejected.at("poles_not_kept").at("tried").get<bool>());
  EXPECT_EQ(rejected, LevelsetStage("corpus/l_shape.yaml", l_shape, "false", "poles_l_shape"));
  const std::vector<std::string> wavy{"guidance.source=curvature", "levelset.draft=true", "levelset.crossing_rounds=2"};
  const nlohmann::json kept = LevelsetStage("corpus/wavy.yaml", wavy, "true", "poles_wavy");
  EXPECT_EQ(kept.at("poles").size(), 3u);
  EXPECT_EQ(kept, LevelsetStage("corpus/wavy.yaml", wavy, "false", "poles_wavy"));
}

// With one solve alongside at a time (levelset.alongside: 1, auto's schedule on 2 cores), the
// poles' layout takes the second thread from the start, so the kept layout's cone (one branch
// point) cannot start beside it; it starts once the poles' layout has ended, before the first
// layout's rounds, and runs its own rounds there too (SolveOnMesh, StartConeAlongside): the same
// level sets as one thread.
TEST(Alongside, TheConeStartedOnceThePolesLayoutEndedGivesTheSameLevelSets) {
  const std::vector<std::string> wavy{"guidance.source=curvature", "levelset.draft=true", "levelset.crossing_rounds=2"};
  const nlohmann::json one = LevelsetStage("corpus/wavy.yaml", wavy, "1", "late_cone", true);
  EXPECT_EQ(one.at("poles").size(), 3u);
  ASSERT_TRUE(one.contains("tip_cone"));
  EXPECT_TRUE(one.at("tip_cone").at("tried").get<bool>());
  EXPECT_TRUE(one.at("tip_cone").at("alongside").get<bool>());
  EXPECT_TRUE(one.at("ceres").contains("cone_polish_round_1"));
  const nlohmann::json after = LevelsetStage("corpus/wavy.yaml", wavy, "false", "late_cone", true);
  EXPECT_FALSE(after.at("tip_cone").at("alongside").get<bool>());
  EXPECT_EQ(WithoutSeconds(one), WithoutSeconds(after));
  EXPECT_EQ(levelset_internal::AlongsideSolve::Running(), 0);
}

// Both second layouts started and neither needed: the square dome × strain draft has a crown
// (the poles' layout, alongside) and branch points (the cone's retry, alongside too without a
// budget), but aligns to 6.0° and crosses at 30° without them, so both are cancelled while the
// first layout's rounds run or once they end — and the level sets are those of one thread.
TEST(Alongside, SecondLayoutsNotNeededAreCancelledWithTheSameLevelSets) {
  const std::vector<std::string> sets{"guidance.source=strain", "levelset.draft=true"};
  const nlohmann::json alongside = LevelsetStage("corpus/dome_square.yaml", sets, "true", "cancelled");
  ASSERT_TRUE(alongside.contains("poles_not_kept"));
  EXPECT_FALSE(alongside.at("poles_not_kept").at("tried").get<bool>());
  EXPECT_FALSE(alongside.contains("tip_cone"));  // the retry was not needed
  EXPECT_FALSE(alongside.at("ceres").contains("cone_joint"));
  EXPECT_EQ(alongside, LevelsetStage("corpus/dome_square.yaml", sets, "false", "cancelled"));
  EXPECT_EQ(levelset_internal::AlongsideSolve::Running(), 0);  // every thread joined
}

// Waits up to ~20 s for its thread's cancel flag: 1 if it came, 0 if not (never hangs the test).
int WaitForCancel(int max_ms) {
  for (int i = 0; i < max_ms; ++i) {
    if (ThreadCancelled()) return 1;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return 0;
}

// The first layout failed, so the solve alongside is not wanted: leaving the scope without
// Join cancels it (its Ceres solves end within one iteration) instead of waiting for its end.
TEST(Alongside, LeftWithoutJoinTheSolveIsCancelled) {
  std::atomic<int> saw{-1};
  {
    levelset_internal::AlongsideSolve ahead;
    ahead.Start([&saw] {
      saw = WaitForCancel(20000);
      return Status::Ok();
    });
  }  // as PQ_RETURN_IF_ERROR leaves it
  EXPECT_EQ(saw.load(), 1);
  EXPECT_FALSE(ThreadCancelled());  // the flag was the worker's only
}

// The budget counts the solves alongside in the whole process: with a budget of one, a second
// Start while one runs starts nothing (the poles' layout, then the cone's retry inside either
// layout, would otherwise make three threads where AlongsideBudget allows two).
TEST(Alongside, AStartBeyondTheBudgetRunsNothing) {
  const auto waits = [] { return WaitForCancel(20000) == 1 ? Status::Ok() : Status::Internal("not cancelled"); };
  {
    levelset_internal::AlongsideSolve first;
    ASSERT_TRUE(first.Start(waits, 1));
    EXPECT_EQ(levelset_internal::AlongsideSolve::Running(), 1);
    levelset_internal::AlongsideSolve second;
    EXPECT_FALSE(second.Start(waits, 1));
    EXPECT_FALSE(second.started());
    EXPECT_TRUE(second.Join().ok());  // never started: Ok
    levelset_internal::AlongsideSolve unlimited;
    EXPECT_TRUE(unlimited.Start(waits));
    EXPECT_EQ(levelset_internal::AlongsideSolve::Running(), 2);
    levelset_internal::AlongsideSolve none;
    EXPECT_FALSE(none.Start(waits, 0));
  }  // both cancelled and joined
  EXPECT_EQ(levelset_internal::AlongsideSolve::Running(), 0);
  levelset_internal::AlongsideSolve again;
  EXPECT_TRUE(again.Start(waits, 1));  // the budget is free once a solve has ended
}

// "auto" leaves a core to the first layout (one solve alongside on 2 cores); "true" has no
// limit, "false" starts none.
TEST(Alongside, TheBudgetFollowsTheKey) {
  LevelsetOptions options;
  options.alongside = "false";
  EXPECT_EQ(levelset_internal::AlongsideBudget(options), 0);
  options.alongside = "true";
  EXPECT_EQ(levelset_internal::AlongsideBudget(options), levelset_internal::AlongsideSolve::kNoLimit);
  options.alongside = "auto";
  EXPECT_EQ(levelset_internal::AlongsideBudget(options),
            std::max(1, static_cast<int>(std::thread::hardware_concurrency())) - 1);
}

TEST(Alongside, JoinedTheSolveRunsToItsEnd) {
  std::atomic<int> saw{-1};
  std::atomic<bool> tagged{false};  // its log lines say "(alongside)"; the first layout's do not
  levelset_internal::AlongsideSolve ahead;
  ahead.Start([&saw, &tagged] {
    tagged = levelset_internal::AlongsideSolve::OnThisThread();
    saw = WaitForCancel(50);
    return Status::InvalidInput("its own status");
  });
  const Status status = ahead.Join();
  EXPECT_EQ(saw.load(), 0);
  EXPECT_EQ(status.message(), "its own status");
  EXPECT_TRUE(tagged.load());
  EXPECT_FALSE(levelset_internal::AlongsideSolve::OnThisThread());
}

// r = 10 (x − 3): one Gauss–Newton step to x = 3, unless the thread's work is cancelled.
struct Shifted {
  template <typename T>
  bool operator()(const T* x, T* r) const {
    r[0] = T(10.0) * (x[0] - T(3.0));
    return true;
  }
};

TEST(Alongside, ACancelledThreadsCeresSolveEndsAtOnce) {
  for (const bool cancelled : {false, true}) {
    std::atomic<bool> flag{cancelled};
    SetThreadCancelFlag(&flag);
    double x = 0.0;
    ceres::Problem problem;
    problem.AddResidualBlock(new ceres::AutoDiffCostFunction<Shifted, 1, 1>(new Shifted), nullptr, &x);
    ceres::Solver::Summary summary;
    ceres::Solve(SparseCholeskyOptions(50), &problem, &summary);
    SetThreadCancelFlag(nullptr);
    EXPECT_EQ(summary.termination_type, cancelled ? ceres::USER_FAILURE : ceres::CONVERGENCE) << cancelled;
    EXPECT_NEAR(x, cancelled ? 0.0 : 3.0, cancelled ? 0.0 : 1e-6) << cancelled;  // cancelled: not a step taken (LM: 3 − 1e-8)
    EXPECT_EQ(PollInterrupt(), 0);  // no signal recorded: the run carries on
  }
}

}  // namespace
}  // namespace pqlayout

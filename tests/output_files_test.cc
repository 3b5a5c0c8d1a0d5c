// OutputFiles' commit protocol under a kill at every step (report.json is the completion
// marker: never beside another run's files, never counted finished by `sweep` unless the run
// is complete), stale staging folders, and SIGINT/SIGTERM during `pqlayout run`: exit
// 130/143 with one line on stderr, staging removed, the previous output intact.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdlib>
#include <filesystem>

#include "base/interrupt.h"
#include "base/output_files.h"
#include "cli/sweep.h"
#include "tests/run_helpers.h"
#include "tests/test_meshes.h"

namespace pqlayout {
namespace {

namespace fs = std::filesystem;
using testing::Files;
using testing::ReadFile;
using testing::Snapshot;

void WriteFiles(const std::string& dir, const Files& files) {
  for (const auto& [name, content] : files) {
    fs::create_directories((fs::path(dir) / name).parent_path());
    testing::WriteFile(dir, name, content);
  }
}

Files Merge(Files a, const Files& b) {
  a.insert(b.begin(), b.end());
  return a;
}

// A report as sweep reads it: `config` and `run.until`.
std::string Report(const std::string& config) {
  return nlohmann::json{{"config", {{"run", config}}}, {"run", {{"until", "analyze"}}}}.dump();
}

const Files kOld{{"report.json", Report("old")}, {"report.html", "old"}, {"surface.obj", "old"},
                 {"figures/a.svg", "old a"}, {"figures/b.svg", "old b"}, {"analysis/nodes.csv", "old"}};
const Files kNew{{"report.json", Report("new")}, {"report.html", "new"}, {"surface.obj", "new"},
                 {"figures/a.svg", "new a"}, {"fields/faces.csv", "new"}, {"quads.obj", "new"}};
const Files kNotOurs{{"notes.txt", "mine"}, {"run.log", "the sweep's log"}};

// The sweep whose one run `r` lives in dir/runs/r and has the given config.
SweepPlan PlanFor(const std::string& dir, const std::string& config) {
  SweepPlan plan;
  plan.out_dir = dir;
  SweepRun run;
  run.name = "r";
  run.config = {{"run", config}};
  plan.runs.push_back(run);
  return plan;
}

// In a child process: stage kNew into folder and commit with the kill hook at step n.
// Returns the child's wait status.
int CommitInChild(const std::string& folder, int n) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::setenv("PQLAYOUT_TEST_FAIL_COMMIT_AFTER", std::to_string(n).c_str(), 1);
    std::unique_ptr<OutputFiles> out;
    bool ok = OutputFiles::Open(folder, &out).ok();
    for (const auto& [name, content] : kNew) ok = ok && out->WriteText(name, content).ok();
    ok = ok && out->Commit().ok();
    ::_exit(ok ? 0 : 1);
  }
  return testing::WaitFor(pid);
}

TEST(OutputFiles, AKillAtAnyStepOfTheCommitNeverLeavesAReportBesideAnotherRunsFiles) {
  const auto dir = testing::TempDir();
  const std::string folder = dir + "/runs/r";
  const SweepPlan old_plan = PlanFor(dir, "old"), new_plan = PlanFor(dir, "new");
  int kills = 0;
  for (int n = 0; n < 100; ++n) {
    fs::remove_all(dir + "/runs");
    WriteFiles(folder, Merge(kOld, kNotOurs));
    const int status = CommitInChild(folder, n);
    ASSERT_TRUE(WIFEXITED(status)) << n;
    const Files files = Snapshot(folder);
    if (WEXITSTATUS(status) == 0) {  // n is past the last step: the commit completed
      EXPECT_EQ(files, Merge(kNew, kNotOurs));
      EXPECT_EQ(InspectRun(new_plan, new_plan.runs[0]), RunState::kFinished);
      EXPECT_EQ(testing::FindEntry(dir + "/runs", ".r.partial-"), "");
      break;
    }
    ASSERT_EQ(WEXITSTATUS(status), 137) << n;
    ++kills;
    // Files that are not ours are kept; the new report is never there (it moves last), so
    // the new run is never finished; the old report is there only with all its files.
    EXPECT_EQ(files.at("notes.txt"), "mine") << n;
    EXPECT_EQ(files.at("run.log"), "the sweep's log") << n;
    EXPECT_NE(InspectRun(new_plan, new_plan.runs[0]), RunState::kFinished) << n;
    if (files.count("report.json")) {
      EXPECT_EQ(files, Merge(kOld, kNotOurs)) << n;
      EXPECT_EQ(InspectRun(old_plan, old_plan.runs[0]), RunState::kFinished) << n;
    } else {
      EXPECT_NE(InspectRun(old_plan, old_plan.runs[0]), RunState::kFinished) << n;
    }
    // The killed commit left its staging folder; the next run into the folder removes it.
    const std::string staging = testing::FindEntry(dir + "/runs", ".r.partial-");
    ASSERT_NE(staging, "") << n;
    std::unique_ptr<OutputFiles> next;
    ASSERT_TRUE(OutputFiles::Open(folder, &next).ok());
    EXPECT_FALSE(fs::exists(staging)) << n;
  }
  // A kill before each of the 11 steps: unlink the old report; report.html, surface.obj and
  // figures replaced (2 each); fields and quads.obj moved in; analysis removed; the report
  // moved in.
  EXPECT_EQ(kills, 11);
}

TEST(OutputFiles, StagingOfALiveProcessIsKept) {
  const auto dir = testing::TempDir();
  const pid_t dead = ::fork();
  if (dead == 0) ::_exit(0);
  testing::WaitFor(dead);  // reaped: its pid names no process
  const std::vector<std::string> gone{".out.partial-" + std::to_string(dead),
                                      ".out.partial-99999999"};  // above Linux's PID_MAX_LIMIT
  const std::string live = ".out.partial-" + std::to_string(::getppid());
  for (const auto& name : gone) fs::create_directories(dir + "/" + name + "/figures");
  fs::create_directories(dir + "/" + live);
  fs::create_directories(dir + "/.other.partial-1");  // another folder's
  std::unique_ptr<OutputFiles> out;
  ASSERT_TRUE(OutputFiles::Open(dir + "/out", &out).ok());
  for (const auto& name : gone) EXPECT_FALSE(fs::exists(dir + "/" + name)) << name;
  EXPECT_TRUE(fs::exists(dir + "/" + live));
  EXPECT_TRUE(fs::exists(dir + "/.other.partial-1"));
  EXPECT_TRUE(fs::is_directory(out->staging_dir()));
}

TEST(OutputFiles, AnInterruptBeforeTheCommitLeavesThePreviousRun) {
  const auto dir = testing::TempDir();
  WriteFiles(dir + "/out", Merge(kOld, kNotOurs));
  std::unique_ptr<OutputFiles> out;
  ASSERT_TRUE(OutputFiles::Open(dir + "/out", &out).ok());
  for (const auto& [name, content] : kNew) ASSERT_TRUE(out->WriteText(name, content).ok());
  SetInterruptForTesting(SIGTERM);
  const Status status = out->Commit();
  SetInterruptForTesting(0);
  EXPECT_FALSE(status.ok());
  EXPECT_NE(status.message().find("interrupted by signal 15"), std::string::npos) << status.message();
  const std::string staging = out->staging_dir();
  out.reset();
  EXPECT_FALSE(fs::exists(staging));
  EXPECT_EQ(Snapshot(dir + "/out"), Merge(kOld, kNotOurs));
}

// The Great Court at its defaults: after the guidance stage (figures/guidance.svg staged) the
// level-set stage's Ceres solves take seconds, so the signal lands inside one.
TEST(RunInterrupt, SigtermOrSigintStopsTheRunAndKeepsThePreviousOutput) {
  const auto dir = testing::TempDir();
  const std::string config = PQLAYOUT_SOURCE_DIR "/examples/great_court.yaml";
  const std::string previous = "'" PQLAYOUT_BINARY "' run " + config + " --out out --until surface -q";
  ASSERT_EQ(std::system(("cd '" + dir + "' && " + previous).c_str()), 0);
  WriteFiles(dir + "/out", {{"notes.txt", "mine"}});
  const Files before = Snapshot(dir + "/out");
  ASSERT_TRUE(before.count("report.json") && before.count("surface.obj"));
  for (const int signal : {SIGTERM, SIGINT}) {
    const pid_t pid = testing::StartPqlayout(dir, {"run", config, "--out", "out"});
    int status = 0;
    bool exited = false;
    ASSERT_TRUE(testing::WaitUntil([&] {
      exited = testing::Exited(pid, &status);
      const std::string staging = testing::FindEntry(dir, ".out.partial-");
      return exited || (!staging.empty() && fs::exists(staging + "/figures/guidance.svg"));
    }));
    ASSERT_FALSE(exited) << "the run ended before it could be interrupted: " << ReadFile(dir + "/stderr.txt");
    ASSERT_EQ(::kill(pid, signal), 0);
    status = testing::WaitFor(pid);
    ASSERT_TRUE(WIFEXITED(status)) << signal;
    EXPECT_EQ(WEXITSTATUS(status), 128 + signal);
    EXPECT_EQ(ReadFile(dir + "/stderr.txt"), "pqlayout: interrupted\n");
    EXPECT_EQ(testing::FindEntry(dir, ".out.partial-"), "") << "staging folder left behind";
    EXPECT_EQ(Snapshot(dir + "/out"), before) << signal;
  }
}

}  // namespace
}  // namespace pqlayout

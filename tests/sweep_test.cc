// `pqlayout sweep` and `pqlayout collect`: parameter parsing, the cartesian product, resuming
// an interrupted sweep (only the missing runs run), `--list` + `collect` reproducing the
// direct sweep byte for byte, a failed run becoming a row with its error, a run killed while
// committing never counted finished, and SIGTERM stopping the sweep with its runs. Runs on a
// small dome (about 0.5 s per run), the SIGTERM test on the Great Court.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "cli/sweep.h"
#include "report/sweep_figures.h"
#include "tests/run_helpers.h"
#include "tests/test_meshes.h"

namespace pqlayout {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> Values(const std::string& spec) {
  SweepParameter p;
  const Status s = ParseSweepParameter(spec, &p);
  EXPECT_TRUE(s.ok()) << spec << ": " << s.message();
  return p.values;
}

std::string ParseError(const std::string& spec) {
  SweepParameter p;
  const Status s = ParseSweepParameter(spec, &p);
  EXPECT_EQ(s.code(), StatusCode::kInvalidInput) << spec;
  return s.message();
}

using V = std::vector<std::string>;

TEST(SweepParameter, Lists) {
  SweepParameter p;
  ASSERT_TRUE(ParseSweepParameter("levelset.weights.alignment=1,2.50,1e-3,10.0", &p).ok());
  EXPECT_EQ(p.key, "levelset.weights.alignment");
  EXPECT_EQ(p.values, V({"1", "2.5", "0.001", "10"}));  // canonical numbers
  EXPECT_EQ(Values("guidance.source=strain,curvature"), V({"strain", "curvature"}));
  EXPECT_EQ(Values("k=7"), V({"7"}));
  EXPECT_EQ(Values("k=-0.5,0.25"), V({"-0.5", "0.25"}));
}

TEST(SweepParameter, LinearRanges) {
  EXPECT_EQ(Values("k=0:1:5"), V({"0", "0.25", "0.5", "0.75", "1"}));
  EXPECT_EQ(Values("k=0:1:11")[3], "0.3");  // not 0.30000000000000004
  EXPECT_EQ(Values("k=10:-10:3"), V({"10", "0", "-10"}));
  EXPECT_EQ(Values("k=2:2:1"), V({"2"}));
}

TEST(SweepParameter, LogRanges) {
  EXPECT_EQ(Values("k=log:0.01:100:5"), V({"0.01", "0.1", "1", "10", "100"}));
  EXPECT_EQ(Values("k=log:1:8:4"), V({"1", "2", "4", "8"}));
  EXPECT_EQ(Values("k=log:100:1:3"), V({"100", "10", "1"}));
}

TEST(SweepParameter, Errors) {
  EXPECT_NE(ParseError("levelset.weights.alignment").find("expected KEY=v1,v2"), std::string::npos);
  EXPECT_NE(ParseError("=1,2").find("expected KEY="), std::string::npos);
  EXPECT_NE(ParseError("k=1,,2").find("empty value"), std::string::npos);
  EXPECT_NE(ParseError("k=").find("empty value"), std::string::npos);
  EXPECT_NE(ParseError("k=1,1.0").find("value 1 is listed twice"), std::string::npos);
  EXPECT_NE(ParseError("k=0:1").find("bad range '0:1'"), std::string::npos);
  EXPECT_NE(ParseError("k=a:b:c").find("bad range"), std::string::npos);
  EXPECT_NE(ParseError("k=0:1:0").find("count must be an integer"), std::string::npos);
  EXPECT_NE(ParseError("k=0:1:2.5").find("count must be an integer"), std::string::npos);
  EXPECT_NE(ParseError("k=0:1:1").find("count 1 needs start = stop"), std::string::npos);
  EXPECT_NE(ParseError("k=log:0:1:3").find("start and stop > 0"), std::string::npos);
  EXPECT_NE(ParseError("k=log:-1:1:3").find("start and stop > 0"), std::string::npos);
  EXPECT_NE(ParseError("k=log:1:10").find("bad range"), std::string::npos);
  // Every message names the --param it is about.
  EXPECT_EQ(ParseError("k=0:1:0").rfind("--param k=0:1:0: ", 0), 0u);
}

TEST(SweepFigures, NonDominatedIsTheParetoFront) {
  // (1,5) (2,2) (4,1) are the front; (3,3) is dominated by (2,2); (5,5) by everything;
  // (2,2) twice: equal points are both on the front.
  const std::vector<ScatterPoint> points{{1, 5, "a"}, {2, 2, "b"}, {4, 1, "c"}, {3, 3, "d"}, {5, 5, "e"}, {2, 2, "f"}};
  EXPECT_EQ(NonDominated(points), std::vector<bool>({true, true, true, false, false, true}));
  // Same x, larger y: dominated.
  EXPECT_EQ(NonDominated({{1, 1, "a"}, {1, 2, "b"}}), std::vector<bool>({true, false}));
}

// ---- the CLI ----

struct Result {
  int exit_code = -1;
  std::string out, err;
};

std::string ReadAll(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

Result Shell(const std::string& dir, const std::string& command) {
  const std::string line = "cd '" + dir + "' && " + command + " > stdout.txt 2> stderr.txt";
  const int status = std::system(line.c_str());
  Result r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = ReadAll(dir + "/stdout.txt");
  r.err = ReadAll(dir + "/stderr.txt");
  return r;
}

Result Pqlayout(const std::string& dir, const std::string& args) {
  return Shell(dir, "'" PQLAYOUT_BINARY "' " + args);
}

std::vector<std::string> Lines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

// sweep.csv as rows of named fields (no quoted commas in these tests' fields except errors,
// which are checked separately).
struct Csv {
  std::vector<std::string> header;
  std::vector<std::map<std::string, std::string>> rows;
};

std::vector<std::string> SplitCsvLine(const std::string& line) {
  std::vector<std::string> fields(1);
  bool quoted = false;
  for (size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted && c == '"' && i + 1 < line.size() && line[i + 1] == '"') fields.back() += '"', ++i;
    else if (c == '"') quoted = !quoted;
    else if (c == ',' && !quoted) fields.emplace_back();
    else fields.back() += c;
  }
  return fields;
}

Csv ReadCsv(const std::string& path) {
  Csv csv;
  const auto lines = Lines(ReadAll(path));
  if (lines.empty()) return csv;
  csv.header = SplitCsvLine(lines[0]);
  for (size_t i = 1; i < lines.size(); ++i) {
    const auto fields = SplitCsvLine(lines[i]);
    EXPECT_EQ(fields.size(), csv.header.size()) << lines[i];
    std::map<std::string, std::string> row;
    for (size_t c = 0; c < fields.size() && c < csv.header.size(); ++c) row[csv.header[c]] = fields[c];
    csv.rows.push_back(row);
  }
  return csv;
}

const char* kDomeConfig =
    "surface:\n  generator: dome\n  width: 18\n  depth: 15\n  rise: 4\n  edge_length: 1.5\n"
    "layout:\n  spacing: 3.0\n";
const char* kParams = "--param levelset.weights.alignment=1,10 --param planarize.weights.closeness=0.1,10";
const std::vector<std::string> kRuns{"alignment=1_closeness=0.1", "alignment=1_closeness=10",
                                     "alignment=10_closeness=0.1", "alignment=10_closeness=10"};

std::map<std::string, fs::file_time_type> ReportTimes(const std::string& sweep_dir) {
  std::map<std::string, fs::file_time_type> times;
  for (const auto& entry : fs::directory_iterator(sweep_dir + "/runs"))
    if (fs::exists(entry.path() / "report.json"))
      times[entry.path().filename().string()] = fs::last_write_time(entry.path() / "report.json");
  return times;
}

TEST(SweepCli, TwoByTwoGivesFourRowsAndTheParetoFigure) {
  const auto dir = testing::TempDir();
  testing::WriteFile(dir, "dome.yaml", kDomeConfig);
  const Result r = Pqlayout(dir, std::string("sweep dome.yaml ") + kParams + " -j 2 --out sw");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "");
  // One progress line per finished run.
  for (const auto& run : kRuns) EXPECT_NE(r.out.find("] " + run + ": done in"), std::string::npos) << run << r.out;
  const Csv csv = ReadCsv(dir + "/sw/sweep.csv");
  ASSERT_EQ(csv.rows.size(), 4u);
  EXPECT_EQ(std::vector<std::string>(csv.header.begin(), csv.header.begin() + 4),
            std::vector<std::string>({"run", "status", "levelset.weights.alignment", "planarize.weights.closeness"}));
  EXPECT_EQ(csv.header.back(), "error");
  for (const char* metric : {"stages.planarize.planarity_max", "stages.analyze.compliance_node_mean",
                             "stages.levelset.alignment_rms_deg", "stages.planarize.closeness_mean",
                             "stages.extract.n_faces", "stages.membrane.max_displacement"})
    EXPECT_NE(std::find(csv.header.begin(), csv.header.end(), metric), csv.header.end()) << metric;
  for (const auto& column : csv.header) EXPECT_EQ(column.find("seconds"), std::string::npos) << column;
  // Rows in product order (first --param slowest), each matching its run's report.json.
  const std::vector<std::pair<std::string, std::string>> values{{"1", "0.1"}, {"1", "10"}, {"10", "0.1"}, {"10", "10"}};
  for (size_t i = 0; i < 4; ++i) {
    const auto& row = csv.rows[i];
    EXPECT_EQ(row.at("run"), kRuns[i]);
    EXPECT_EQ(row.at("status"), "ok");
    EXPECT_EQ(row.at("error"), "");
    EXPECT_EQ(row.at("levelset.weights.alignment"), values[i].first);
    EXPECT_EQ(row.at("planarize.weights.closeness"), values[i].second);
    const auto report = nlohmann::json::parse(ReadAll(dir + "/sw/runs/" + kRuns[i] + "/report.json"));
    EXPECT_EQ(report["config"]["levelset"]["weights"]["alignment"].get<double>(), std::stod(values[i].first));
    EXPECT_EQ(report["config"]["planarize"]["weights"]["closeness"].get<double>(), std::stod(values[i].second));
    EXPECT_DOUBLE_EQ(std::stod(row.at("stages.analyze.compliance_node_mean")),
                     report["stages"]["analyze"]["compliance_node_mean"].get<double>());
    EXPECT_EQ(std::stoi(row.at("stages.extract.n_faces")), report["stages"]["extract"]["n_faces"].get<int>());
  }
  // The alignment weight acts: stronger alignment, smaller alignment error.
  EXPECT_LT(std::stod(csv.rows[2].at("stages.levelset.alignment_rms_deg")),
            std::stod(csv.rows[0].at("stages.levelset.alignment_rms_deg")));
  // timings.csv: every stage of every run plus its total.
  EXPECT_EQ(Lines(ReadAll(dir + "/sw/timings.csv")).size(), 1u + 4u * 9u);
  // The figure: two panels, 4 points each (+ 2 legend markers).
  const std::string svg = ReadAll(dir + "/sw/figures/pareto.svg");
  EXPECT_EQ(svg.rfind("<svg", 0), 0u);
  EXPECT_NE(svg.find("Planarity vs stiffness"), std::string::npos);
  EXPECT_NE(svg.find("Alignment vs closeness"), std::string::npos);
  size_t circles = 0;
  for (size_t at = svg.find("<circle"); at != std::string::npos; at = svg.find("<circle", at + 1)) ++circles;
  EXPECT_EQ(circles, 2u * 4u + 2u);
}

TEST(SweepCli, ResumeRunsOnlyTheMissingRuns) {
  const auto dir = testing::TempDir();
  testing::WriteFile(dir, "dome.yaml", kDomeConfig);
  // An interrupted sweep: only the alignment=1 half ran.
  Result r = Pqlayout(dir, "sweep dome.yaml --param levelset.weights.alignment=1 "
                           "--param planarize.weights.closeness=0.1,10 --out sw");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto before = ReportTimes(dir + "/sw");
  ASSERT_EQ(before.size(), 2u);
  // ... and one of its runs lost its report (killed while committing, say).
  fs::remove(dir + "/sw/runs/alignment=1_closeness=10/report.json");
  // Its leftover staging; 99999999 is above Linux's PID_MAX_LIMIT, so no process has that id.
  fs::create_directories(dir + "/sw/runs/.alignment=1_closeness=10.partial-99999999/analysis");
  r = Pqlayout(dir, std::string("sweep dome.yaml ") + kParams + " --out sw");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("4 runs, 1 already finished, 3 to run"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("alignment=1_closeness=0.1: done"), std::string::npos) << r.out;
  auto after = ReportTimes(dir + "/sw");
  ASSERT_EQ(after.size(), 4u);
  EXPECT_EQ(after["alignment=1_closeness=0.1"], before["alignment=1_closeness=0.1"]);  // not rewritten
  EXPECT_FALSE(fs::exists(dir + "/sw/runs/.alignment=1_closeness=10.partial-99999999"));
  EXPECT_EQ(ReadCsv(dir + "/sw/sweep.csv").rows.size(), 4u);
  // A complete sweep reruns nothing.
  before = after;
  r = Pqlayout(dir, std::string("sweep dome.yaml ") + kParams + " --out sw");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("4 runs, 4 already finished, 0 to run"), std::string::npos) << r.out;
  EXPECT_EQ(ReportTimes(dir + "/sw"), before);
  // A changed config makes every run stale: all rerun.
  r = Pqlayout(dir, std::string("sweep dome.yaml ") + kParams + " --out sw --set layout.spacing=2.5");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("4 runs, 0 already finished, 4 to run"), std::string::npos) << r.out;
  after = ReportTimes(dir + "/sw");
  for (const auto& run : kRuns) EXPECT_NE(after[run], before[run]) << run;
}

TEST(SweepCli, ListThenCollectReproducesTheDirectSweep) {
  const auto dir = testing::TempDir();
  testing::WriteFile(dir, "dome.yaml", kDomeConfig);
  Result r = Pqlayout(dir, std::string("sweep dome.yaml ") + kParams + " --out direct");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = Pqlayout(dir, std::string("sweep dome.yaml ") + kParams + " --out listed --list");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto commands = Lines(r.out);
  ASSERT_EQ(commands.size(), 4u) << r.out;
  EXPECT_FALSE(fs::exists(dir + "/listed/runs"));  // --list runs nothing
  for (size_t i = 0; i < commands.size(); ++i) {
    EXPECT_NE(commands[i].find(" run dome.yaml "), std::string::npos) << commands[i];
    EXPECT_NE(commands[i].find("--out listed/runs/" + kRuns[i] + " "), std::string::npos) << commands[i];
  }
  // Executed one by one, last first (order does not matter), collecting in between.
  for (size_t i = commands.size(); i-- > 0;) {
    const Result run = Shell(dir, commands[i]);
    ASSERT_EQ(run.exit_code, 0) << commands[i] << "\n" << run.err;
    if (i == 2) {  // two of four done: collect gathers what is there
      const Result partial = Pqlayout(dir, "collect listed");
      ASSERT_EQ(partial.exit_code, 0) << partial.err;
      EXPECT_EQ(ReadCsv(dir + "/listed/sweep.csv").rows.size(), 2u);
      EXPECT_NE(partial.out.find("2 finished, 0 failed, 2 not run"), std::string::npos) << partial.out;
      // And --list now lists only the two runs still missing.
      const Result rest = Pqlayout(dir, std::string("sweep dome.yaml ") + kParams + " --out listed --list");
      EXPECT_EQ(Lines(rest.out), std::vector<std::string>(commands.begin(), commands.begin() + 2));
    }
  }
  r = Pqlayout(dir, "collect listed");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string direct = ReadAll(dir + "/direct/sweep.csv");
  EXPECT_EQ(Lines(direct).size(), 5u);
  EXPECT_EQ(ReadAll(dir + "/listed/sweep.csv"), direct);
}

TEST(SweepCli, AFailedRunIsARowWithItsError) {
  const auto dir = testing::TempDir();
  testing::WriteFile(dir, "dome.yaml", kDomeConfig);
  // A free boundary leaves the membrane problem singular: that run fails, the other runs.
  const std::string params = " --param boundary.default=fixed,free --param levelset.weights.alignment=10";
  Result r = Pqlayout(dir, "sweep dome.yaml" + params + " --out sw -j 2");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(Lines(r.err).size(), 1u) << r.err;
  EXPECT_NE(r.err.find("1 of 2 runs failed"), std::string::npos) << r.err;
  EXPECT_NE(r.out.find("default=free_alignment=10: failed: "), std::string::npos) << r.out;
  const Csv csv = ReadCsv(dir + "/sw/sweep.csv");
  ASSERT_EQ(csv.rows.size(), 2u);
  EXPECT_EQ(csv.rows[0].at("status"), "ok");
  EXPECT_EQ(csv.rows[0].at("error"), "");
  EXPECT_FALSE(csv.rows[0].at("stages.analyze.compliance_node_mean").empty());
  EXPECT_EQ(csv.rows[1].at("run"), "default=free_alignment=10");
  EXPECT_EQ(csv.rows[1].at("status"), "failed");
  EXPECT_EQ(csv.rows[1].at("boundary.default"), "free");
  EXPECT_NE(csv.rows[1].at("error").find("membrane problem is singular"), std::string::npos) << csv.rows[1].at("error");
  EXPECT_EQ(csv.rows[1].at("stages.analyze.compliance_node_mean"), "");
  const std::string error_file = ReadAll(dir + "/sw/runs/default=free_alignment=10/error.txt");
  EXPECT_EQ(error_file, csv.rows[1].at("error") + "\n");
  EXPECT_FALSE(fs::exists(dir + "/sw/runs/default=free_alignment=10/report.json"));
  EXPECT_FALSE(fs::exists(dir + "/sw/runs/default=fixed_alignment=10/error.txt"));
  EXPECT_NE(ReadAll(dir + "/sw/figures/pareto.svg").find("1 failed (not shown)"), std::string::npos);
  // The listed command of the failing run exits 2 and leaves the same error file, so
  // collect gives the same table.
  r = Pqlayout(dir, "sweep dome.yaml" + params + " --out listed --list");
  const auto commands = Lines(r.out);
  ASSERT_EQ(commands.size(), 2u);
  EXPECT_EQ(Shell(dir, commands[0]).exit_code, 0);
  EXPECT_EQ(Shell(dir, commands[1]).exit_code, 2);
  ASSERT_EQ(Pqlayout(dir, "collect listed").exit_code, 0);
  EXPECT_EQ(ReadAll(dir + "/listed/sweep.csv"), ReadAll(dir + "/sw/sweep.csv"));
  // The failed run is retried on resume (failures may be transient); the finished one is not.
  r = Pqlayout(dir, "sweep dome.yaml" + params + " --out sw");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.out.find("2 runs, 1 already finished, 1 to run"), std::string::npos) << r.out;
}

// The run's folder holds a complete earlier run of another config (rise 3); the sweep's run
// (rise 4) is killed before each unlink and rename of its commit in turn
// (PQLAYOUT_TEST_FAIL_COMMIT_AFTER, base/output_files.h). The sweep must never count it as
// finished, and the earlier run must stay complete or lose its report.json.
TEST(SweepCli, ARunKilledWhileCommittingIsNeverCountedFinished) {
  const auto dir = testing::TempDir();
  testing::WriteFile(dir, "dome.yaml", kDomeConfig);
  const std::string folder = dir + "/sw/runs/rise=4";
  ASSERT_EQ(Pqlayout(dir, "run dome.yaml --set surface.rise=3 --until guidance --out sw/runs/rise=4").exit_code, 0);
  const testing::Files old = testing::Snapshot(folder);
  ASSERT_TRUE(old.count("report.json") && old.count("figures/guidance.svg"));
  fs::copy(folder, dir + "/old", fs::copy_options::recursive);
  const auto sweep = [&](int n) {
    return Shell(dir, "PQLAYOUT_TEST_FAIL_COMMIT_AFTER=" + std::to_string(n) + " '" PQLAYOUT_BINARY
                      "' sweep dome.yaml --param surface.rise=4 --until guidance --out sw");
  };
  int kills = 0;
  for (int n = 0; n < 100; ++n) {
    fs::remove_all(folder);
    fs::copy(dir + "/old", folder, fs::copy_options::recursive);
    const Result r = sweep(n);
    const Csv csv = ReadCsv(dir + "/sw/sweep.csv");
    ASSERT_EQ(csv.rows.size(), 1u) << n << r.err;
    testing::Files files = testing::Snapshot(folder);
    files.erase("run.log");
    files.erase("error.txt");
    if (r.exit_code == 0) {  // past the last step: committed
      EXPECT_EQ(csv.rows[0].at("status"), "ok");
      EXPECT_EQ(nlohmann::json::parse(files.at("report.json"))["config"]["surface"]["rise"].get<double>(), 4.0);
      EXPECT_EQ(files.size(), old.size());
      break;
    }
    ++kills;
    EXPECT_EQ(r.exit_code, 1) << n << r.err;
    EXPECT_EQ(csv.rows[0].at("status"), "failed") << n;
    EXPECT_EQ(csv.rows[0].at("error"), "pqlayout run exited with code 137") << n;
    if (files.count("report.json")) EXPECT_EQ(files, old) << n;  // the earlier run, whole
    EXPECT_EQ(Lines(Pqlayout(dir, "sweep dome.yaml --param surface.rise=4 --until guidance --out sw --list").out).size(),
              1u) << n;  // still to run
  }
  // Both runs have the same top-level entries E: unlink the report, replace E − 1 entries
  // (2 steps each), move the report in: 2E steps, a kill before each.
  std::set<std::string> entries;
  for (const auto& [name, content] : old) entries.insert(name.substr(0, name.find('/')));
  EXPECT_EQ(kills, 2 * static_cast<int>(entries.size()));
}

// SIGTERM to `sweep -j 2` while two Great Court runs are in their stages: the sweep forwards
// it, waits for both runs to wind down (each removes its staging folder) and exits 143; no
// run is left running, and none is counted as finished or failed.
TEST(SweepCli, SigtermStopsTheRunsInProgressAndLeavesNoOrphans) {
  const auto dir = testing::TempDir();
  const std::string config = PQLAYOUT_SOURCE_DIR "/examples/great_court.yaml";
  const std::string param = "levelset.weights.alignment=1,10,100";
  const pid_t sweep = testing::StartPqlayout(dir, {"sweep", config, "--param", param, "-j", "2", "--out", "sw"});
  std::vector<pid_t> runs;
  const auto staging_folders = [&] {
    int n = 0;
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(dir + "/sw/runs", ec))
      n += entry.path().filename().string().find(".partial-") != std::string::npos;
    return n;
  };
  int status = 0;
  bool exited = false;
  ASSERT_TRUE(testing::WaitUntil([&] {
    exited = testing::Exited(sweep, &status);
    runs = testing::ChildrenOf(sweep);
    return exited || (runs.size() == 2 && staging_folders() == 2);  // both runs are in their stages
  }));
  ASSERT_FALSE(exited) << testing::ReadFile(dir + "/stderr.txt");
  ASSERT_EQ(::kill(sweep, SIGTERM), 0);
  status = testing::WaitFor(sweep);
  std::vector<pid_t> orphans;
  for (const pid_t run : runs)
    if (testing::ProcessExists(run)) orphans.push_back(run);
  for (const pid_t run : orphans) ::kill(run, SIGKILL);  // do not leave them behind if the test fails
  EXPECT_EQ(orphans, std::vector<pid_t>());
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 143);
  EXPECT_EQ(testing::ReadFile(dir + "/stderr.txt"), "pqlayout: interrupted\n");
  EXPECT_NE(testing::ReadFile(dir + "/stdout.txt").find("sweep: interrupted after 0 of 3 runs"), std::string::npos);
  EXPECT_EQ(staging_folders(), 0);
  for (const char* run : {"alignment=1", "alignment=10", "alignment=100"}) {
    EXPECT_FALSE(fs::exists(dir + "/sw/runs/" + run + "/report.json")) << run;
    EXPECT_FALSE(fs::exists(dir + "/sw/runs/" + run + "/error.txt")) << run;  // not failed: pending
  }
  EXPECT_FALSE(fs::exists(dir + "/sw/sweep.csv"));
  EXPECT_EQ(Lines(Pqlayout(dir, "sweep " + config + " --param " + param + " --out sw --list").out).size(), 3u);
}

TEST(SweepCli, BadParametersStopBeforeAnythingRuns) {
  const auto dir = testing::TempDir();
  testing::WriteFile(dir, "dome.yaml", kDomeConfig);
  const std::vector<std::pair<std::string, std::string>> cases{
      {"--param levelset.weights.alignmnt=1,2", "--param levelset.weights.alignmnt=1,2: levelset.weights.alignmnt: unknown key (did you mean 'levelset.weights.alignment'?)"},
      {"--param levelset.weights.alignment=1,abc", "--param levelset.weights.alignment=1,abc: value abc: expected a number, got 'abc'"},
      {"--param levelset.weights.alignment=1,-1", "--param levelset.weights.alignment=1,-1: value -1: must be >= 0 (got -1)"},
      {"--param levelset.weights.alignment=0:1:0", "--param levelset.weights.alignment=0:1:0: bad range '0:1:0': count must be an integer in [1, 100000]"},
      {"--param layout.spacing=1 --param layout.spacing=2", "--param layout.spacing=2: layout.spacing is swept twice"},
      {"--param guidance.source=strain,magnetic", "--param guidance.source=strain,magnetic: value magnetic: unknown value 'magnetic' (expected strain | curvature | file)"},
  };
  for (const auto& [args, message] : cases) {
    for (const std::string mode : {"", " --list"}) {
      const Result r = Pqlayout(dir, "sweep dome.yaml " + args + " --out sw" + mode);
      EXPECT_EQ(r.exit_code, 2) << args;
      EXPECT_EQ(r.err, "pqlayout: error: " + message + "\n") << args;
      EXPECT_EQ(r.out, "") << args;
      EXPECT_FALSE(fs::exists(dir + "/sw")) << args;
    }
  }
  // No --param at all: CLI11's own one-line error, exit 2.
  const Result r = Pqlayout(dir, "sweep dome.yaml --out sw");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(Lines(r.err).size(), 1u) << r.err;
  // collect on a folder that is not a sweep.
  const Result c = Pqlayout(dir, "collect .");
  EXPECT_EQ(c.exit_code, 2);
  EXPECT_NE(c.err.find("sweep.json: not found"), std::string::npos) << c.err;
}

}  // namespace
}  // namespace pqlayout

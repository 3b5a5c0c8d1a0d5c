// `pqlayout sweep` and `pqlayout collect`: residual-weight experiments (SPEC "Comparison and
// experiments"). A sweep is the cartesian product of `--param KEY=VALUES` over a config; each
// run is an ordinary `pqlayout run` into its own folder DIR/runs/<name>, where <name> is
// derived from the run's parameter values only (`alignment=10_closeness=0.1`), so a sweep
// resumes (finished runs are skipped), and its runs can be listed as shell commands
// (`--list`) and executed anywhere, in any order, then gathered with `collect`.
//
// DIR/sweep.json   the plan: config, overrides, parameters, and every run with its folder,
//                  parameter values and resolved config (written before anything runs)
// DIR/runs/<name>/ report.json (a finished run), error.txt (a failed run), run.log (its
//                  progress output, when run by `sweep`), and the run's other outputs
// DIR/sweep.csv    one row per finished or failed run (see SweepCsv)
// DIR/timings.csv  the per-stage wall times of the finished runs (machine dependent, so kept
//                  out of sweep.csv, which is byte-reproducible across machines)
// DIR/figures/pareto.svg  planarity max vs mean nodal compliance, alignment vs closeness
#pragma once

#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "base/status.h"

namespace pqlayout {

// One `--param KEY=VALUES`: the values as canonical text (numbers in their shortest exact
// form, so that `0.10` and `0.1` name the same run).
struct SweepParameter {
  std::string key;
  std::vector<std::string> values;
};

// Parses KEY=v1,v2,...  |  KEY=start:stop:count  |  KEY=log:start:stop:count (count values,
// both ends included; log: geometric, start and stop > 0). Checks the syntax only; whether KEY
// is a config key and each value is valid for it is checked by PlanSweep.
Status ParseSweepParameter(const std::string& spec, SweepParameter* parameter);

struct SweepRun {
  std::string name;                                              // folder under DIR/runs
  std::vector<std::pair<std::string, std::string>> assignments;  // (key, value) per parameter
  nlohmann::json config;                                         // resolved, as in report.json
};

struct SweepPlan {
  std::string config_path;
  std::vector<std::string> overrides;  // --set KEY=VALUE, applied to every run before the parameters
  std::string until = "analyze";
  std::string out_dir;
  std::vector<SweepParameter> parameters;
  std::vector<SweepRun> runs;  // cartesian product, the first parameter varying slowest
};

struct SweepOptions {
  std::string config_path;
  std::vector<std::string> overrides;
  std::vector<std::string> parameters;  // the --param texts
  std::string until = "analyze";
  std::string out_dir;
};

// Parses the parameters, expands the product and resolves every run's config. Any error
// (syntax, unknown key, a value the config refuses, a repeated key or value) is InvalidInput
// naming the --param, before anything has run.
Status PlanSweep(const SweepOptions& options, SweepPlan* plan);

// DIR/sweep.json.
Status WriteSweepManifest(const SweepPlan& plan);
Status ReadSweepManifest(const std::string& dir, SweepPlan* plan);

enum class RunState { kPending, kFinished, kFailed };
// kFinished: runs/<name>/report.json exists and holds this run's config and `until` (a run
// moves its report.json in last, so a run killed while its outputs were moved in is never
// finished: base/output_files.h); kFailed: otherwise, runs/<name>/error.txt exists
// (*error receives its line); else kPending.
RunState InspectRun(const SweepPlan& plan, const SweepRun& run, std::string* error = nullptr);

std::string RunFolder(const SweepPlan& plan, const SweepRun& run);
// The run as a command line, `EXECUTABLE run CONFIG --set ... --out FOLDER --error-file
// FOLDER/error.txt [--until STAGE]`, with every argument shell-quoted where needed.
std::vector<std::string> RunArguments(const SweepPlan& plan, const SweepRun& run);
std::string RunCommandLine(const std::string& executable, const SweepPlan& plan, const SweepRun& run);

struct SweepSummary {
  int total = 0, skipped = 0, ran = 0, failed = 0;  // failed: of those that ran
};

// Runs every run that is not finished (failed runs are retried), `jobs` at a time, each as
// a child process `executable run ...` whose output goes to runs/<name>/run.log; logs one
// progress line per finished run; then collects (CollectSweep). After SIGINT/SIGTERM
// (base/interrupt.h; the caller installs the handlers) it forwards the signal to the runs
// in progress, starts no more, waits for them and returns the interrupt's status without
// collecting; an interrupted run writes no error.txt (it is left as it was) and runs again
// on resume.
Status RunSweep(const SweepPlan& plan, const std::string& executable, int jobs, SweepSummary* summary);

struct CollectSummary {
  int finished = 0, failed = 0, pending = 0;
};

// Reads DIR/sweep.json and every run's state, writes DIR/sweep.csv, DIR/timings.csv and
// DIR/figures/pareto.svg.
Status CollectSweep(const std::string& dir, CollectSummary* summary);

// sweep.csv: columns `run,status`, then the parameters (in --param order, named by their
// config keys), then every numeric metric of the runs' report.json below `stages`, flattened
// with dotted names (`stages.planarize.planarity_max`), stages in pipeline order and metrics
// in name order within a stage, except the machine-dependent `seconds`; last `error`. Rows
// in the plan's order; pending runs are left out; a failed run has its error and no metrics.
// Numbers are written in their shortest exact form; text is quoted as RFC 4180 requires.
std::string SweepCsv(const SweepPlan& plan, const std::vector<RunState>& states,
                     const std::vector<nlohmann::json>& reports, const std::vector<std::string>& errors);

}  // namespace pqlayout

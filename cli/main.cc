// pqlayout command line: `pqlayout run CONFIG [--set KEY=VALUE]... [--out DIR] [--until STAGE]`,
// `compare`, `sweep`, `collect` and `keys` (the config reference). Exit codes: 0 success,
// 2 bad input or config (one line on stderr naming the file, key or element), 1 internal
// failure (sweep: 1 also when a run failed), 130/143 after SIGINT/SIGTERM (run, compare and
// sweep stop cleanly; see base/interrupt.h). Progress lines with elapsed time go to stdout.
#include <CLI/CLI.hpp>
#include <glog/logging.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <new>

#include "base/allocator.h"
#include "base/atomic_file.h"
#include "base/interrupt.h"
#include "pipeline/build_info.h"
#include "cli/compare.h"
#include "pipeline/config.h"
#include "pipeline/pipeline.h"
#include "cli/sweep.h"

namespace {

using pqlayout::Status;
const auto kProgramStart = std::chrono::steady_clock::now();

// Progress lines read "[   1.2 s] surface: ..." (warnings say so), not glog's default header.
void ProgressPrefix(std::ostream& s, const google::LogMessageInfo& info, void*) {
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - kProgramStart).count();
  char stamp[32];
  std::snprintf(stamp, sizeof(stamp), "[%7.2f s]", elapsed);
  s << stamp;
  if (info.severity[0] == 'W') s << " warning:";
  if (info.severity[0] == 'E' || info.severity[0] == 'F') s << " error:";
}

std::string VersionText() {
  const auto& info = pqlayout::GetBuildInfo();
  std::string text = "pqlayout " + info.version + " (git " + info.git_revision + ")\n";
  for (const auto& [name, version] : info.libraries) text += "  " + name + " " + version + "\n";
  return text + "  malloc: " + pqlayout::AllocatorDescription() + "\n";
}

using pqlayout::OneLine;

// A command stopped by SIGINT/SIGTERM says so in one line and exits with 128 + the signal
// (130, 143), whatever failure the interrupt caused on its way out (base/interrupt.h).
int ExitCode(const Status& status) {
  if (status.ok()) return 0;
  if (const int signal = pqlayout::InterruptSignal()) {
    std::cerr << "pqlayout: interrupted" << std::endl;
    return 128 + signal;
  }
  std::cerr << "pqlayout: error: " << OneLine(status.message()) << std::endl;
  return static_cast<int>(status.code());
}

struct RunArguments {
  std::string config;
  std::vector<std::string> sets;
  std::string out;
  std::string until = "analyze";
  std::string error_file;  // run: on failure the error line is also written here, on success removed
  bool draft = false;      // --draft: WithDraft's --set values
};

// `--draft` (run, compare, sweep): a quick look, the same as `--set levelset.draft=true --set
// stiffen.stop_window=5 --set stiffen.stop_gain=0.01` ahead of the command line's own --set
// values, which win over it.
constexpr const char* kDraftHelp =
    "a quick look: the level sets on a coarser working mesh and stiffen stopped early, ~3x faster in all, a "
    "different and usually somewhat softer layout (same as --set levelset.draft=true --set stiffen.stop_window=5 "
    "--set stiffen.stop_gain=0.01, each overridden by an explicit --set; README \"Draft runs\")";
std::vector<std::string> WithDraft(std::vector<std::string> sets, bool draft) {
  if (draft) sets.insert(sets.begin(), {"levelset.draft=true", "stiffen.stop_window=5", "stiffen.stop_gain=0.01"});
  return sets;
}

// `--error-file`: a failed run leaves its one-line error in a file (sweeps read it). An
// interrupted run did not fail: the file is left as it was, like the output folder.
int RecordError(const std::string& error_file, int code, const Status& status) {
  if (error_file.empty() || (!status.ok() && pqlayout::InterruptSignal())) return code;
  std::error_code ec;
  if (status.ok()) {
    std::filesystem::remove(error_file, ec);
    return code;
  }
  const Status written = pqlayout::WriteTextFileAtomically(error_file, OneLine(status.message()) + "\n");
  if (!written.ok()) std::cerr << "pqlayout: error: " << written.message() << std::endl;
  return code;
}

int Run(const RunArguments& args, const std::string& command_line) {
  pqlayout::InstallInterruptHandlers();
  pqlayout::Config config;
  const Status loaded = pqlayout::LoadConfig(args.config, WithDraft(args.sets, args.draft), &config);
  if (!loaded.ok()) return RecordError(args.error_file, ExitCode(loaded), loaded);
  pqlayout::RunOptions options;
  options.config_path = args.config;
  options.command_line = command_line;
  options.out_dir = args.out.empty() ? "out/" + std::filesystem::path(args.config).stem().string() : args.out;
  options.until = *pqlayout::StageFromName(args.until);  // validated by CLI11
  nlohmann::json report;
  const Status status = pqlayout::RunPipeline(config, options, &report);
  return RecordError(args.error_file, ExitCode(status), status);
}

struct SweepArguments {
  pqlayout::SweepOptions options;
  int jobs = 1;
  bool list = false;
  bool draft = false;  // --draft: WithDraft's --set values in every run
};

// The path printed in --list commands: as invoked if that was a path, else found on PATH.
std::string ExecutableForCommands(const char* argv0) {
  const std::string invoked = argv0;
  if (invoked.find('/') == std::string::npos) return invoked;
  return std::filesystem::absolute(invoked).lexically_normal().string();
}

// The path the sweep starts its runs with: this very binary.
std::string ExecutableForRuns(const char* argv0) {
  std::error_code ec;
  const auto self = std::filesystem::read_symlink("/proc/self/exe", ec);
  return ec ? ExecutableForCommands(argv0) : self.string();
}

int Sweep(SweepArguments args, const char* argv0) {
  if (args.options.out_dir.empty())
    args.options.out_dir = "out/" + std::filesystem::path(args.options.config_path).stem().string() + "-sweep";
  args.options.overrides = WithDraft(args.options.overrides, args.draft);
  pqlayout::SweepPlan plan;
  if (int code = ExitCode(pqlayout::PlanSweep(args.options, &plan))) return code;
  if (args.list) {
    // The plan goes to DIR/sweep.json so that `collect DIR` finds the runs; only runs not
    // yet finished are listed, so the list also resumes a sweep.
    if (int code = ExitCode(pqlayout::WriteSweepManifest(plan))) return code;
    const std::string executable = ExecutableForCommands(argv0);
    for (const auto& run : plan.runs)
      if (pqlayout::InspectRun(plan, run) != pqlayout::RunState::kFinished)
        std::cout << pqlayout::RunCommandLine(executable, plan, run) << "\n";
    return 0;
  }
  pqlayout::SweepSummary summary;
  pqlayout::InstallInterruptHandlers();  // RunSweep forwards them to its runs
  if (int code = ExitCode(pqlayout::RunSweep(plan, ExecutableForRuns(argv0), args.jobs, &summary))) return code;
  if (summary.failed == 0) return 0;
  std::cerr << "pqlayout: error: " << summary.failed << " of " << summary.total
            << " runs failed (their errors are in " << plan.out_dir << "/sweep.csv)" << std::endl;
  return 1;
}

// `pqlayout run CONFIG`: its options.
CLI::App* AddRunCommand(CLI::App* app, RunArguments* args) {
  CLI::App* run = app->add_subcommand("run", "run the pipeline on a YAML config file");
  run->add_option("CONFIG", args->config, "YAML config file (see examples/great_court.yaml)")->required();
  run->add_option("--set", args->sets, "override a config key, KEY=VALUE (VALUE is YAML); repeatable")
      ->type_size(1)->allow_extra_args(false)->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  run->add_option("--out", args->out, "output folder (default: out/<config name>)");
  run->add_option("--until", args->until, "last stage to run")
      ->check(CLI::IsMember(pqlayout::StageNames()))->capture_default_str();
  run->add_flag("--draft", args->draft, kDraftHelp)->disable_flag_override();
  run->add_option("--error-file", args->error_file,
                  "on failure also write the error line to this file (removed on success); used by sweeps");
  return run;
}

// `pqlayout compare CONFIG`: its options.
CLI::App* AddCompareCommand(CLI::App* app, RunArguments* args) {
  CLI::App* compare = app->add_subcommand(
      "compare", "run CONFIG with strain and with curvature guidance and compare the two grid shells");
  compare->add_option("CONFIG", args->config, "YAML config file")->required();
  compare->add_option("--set", args->sets, "override a config key in both runs, KEY=VALUE; repeatable")
      ->type_size(1)->allow_extra_args(false)->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  compare->add_option("--out", args->out, "output folder (default: out/<config name>-compare)");
  compare->add_flag("--draft", args->draft, kDraftHelp)->disable_flag_override();
  return compare;
}

// `pqlayout sweep CONFIG --param ...`: its options.
CLI::App* AddSweepCommand(CLI::App* app, SweepArguments* args) {
  CLI::App* sweep = app->add_subcommand(
      "sweep",
      "run CONFIG for every combination of parameter values (cartesian product), each run in DIR/runs/<name>; "
      "finished runs are skipped, so a sweep resumes. Writes DIR/sweep.csv, DIR/timings.csv and "
      "DIR/figures/pareto.svg. Exit 0 if every run finished, 1 if a run failed (its error is in sweep.csv), "
      "2 on bad input before anything ran");
  sweep->add_option("CONFIG", args->options.config_path, "YAML config file")->required();
  sweep->add_option("--param", args->options.parameters,
                    "KEY=v1,v2,... | KEY=start:stop:count | KEY=log:start:stop:count (count values, ends "
                    "included); repeatable, the first --param varies slowest")
      ->type_size(1)->allow_extra_args(false)->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)->required();
  sweep->add_option("--set", args->options.overrides, "override a config key in every run, KEY=VALUE; repeatable")
      ->type_size(1)->allow_extra_args(false)->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  sweep->add_option("-j,--jobs", args->jobs,
                    "runs at a time, each its own process (each on `threads` threads, default 1; with 4 or more "
                    "hardware threads a second one for the second layouts a run may need: levelset.alongside): -j = "
                    "cores, with --set levelset.alongside=false to keep each run on one")
      ->check(CLI::Range(1, 256))->capture_default_str();
  sweep->add_option("--out", args->options.out_dir, "sweep folder (default: out/<config name>-sweep)");
  sweep->add_option("--until", args->options.until, "last stage of every run")
      ->check(CLI::IsMember(pqlayout::StageNames()))->capture_default_str();
  sweep->add_flag("--draft", args->draft, kDraftHelp)->disable_flag_override();
  sweep->add_flag("--list", args->list,
                  "write DIR/sweep.json and print one `pqlayout run ...` command per run not yet finished "
                  "(for GNU parallel or a job array) instead of running; then `pqlayout collect DIR`");
  return sweep;
}

int Compare(const RunArguments& args, const std::string& command_line) {
  pqlayout::CompareOptions options;
  options.config_path = args.config;
  options.overrides = WithDraft(args.sets, args.draft);
  options.command_line = command_line;
  options.out_dir = args.out.empty() ? "out/" + std::filesystem::path(args.config).stem().string() + "-compare"
                                     : args.out;
  nlohmann::json comparison;
  pqlayout::InstallInterruptHandlers();
  return ExitCode(pqlayout::RunCompare(options, &comparison));
}

int Main(int argc, char** argv) {
  CLI::App app{"pqlayout: lays out planar quadrilateral grid shells on freeform roofs so that the "
               "grid follows the flow of force (Schiftner & Balzer, statics-sensitive layout)."};
  app.set_version_flag("--version", VersionText());
  app.require_subcommand(1);
  app.fallthrough();  // -q and -v also after the subcommand
  bool quiet = false;
  int verbose = 0;
  app.add_flag("-q,--quiet", quiet, "only warnings and errors");
  app.add_flag("-v,--verbose", verbose, "more detail (repeat for more)");

  RunArguments run_args;
  AddRunCommand(&app, &run_args);
  CLI::App* keys = app.add_subcommand("keys", "print the config reference (every key, default, meaning)");
  RunArguments compare_args;
  CLI::App* compare = AddCompareCommand(&app, &compare_args);
  SweepArguments sweep_args;
  CLI::App* sweep = AddSweepCommand(&app, &sweep_args);
  std::string collect_dir;
  CLI::App* collect = app.add_subcommand(
      "collect", "gather the finished runs of a sweep folder into DIR/sweep.csv, DIR/timings.csv and "
                 "DIR/figures/pareto.svg");
  collect->add_option("DIR", collect_dir, "sweep folder (holds sweep.json)")->required();

  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {
    return app.exit(e);  // --help, --version
  } catch (const CLI::ParseError& e) {
    std::cerr << "pqlayout: error: " << e.what() << " (see pqlayout --help)" << std::endl;
    return 2;
  }

  // Progress and warnings go to stdout; stderr carries only the one-line error of a failed run.
  FLAGS_logtostdout = true;
  FLAGS_colorlogtostdout = false;
  FLAGS_minloglevel = quiet ? google::GLOG_WARNING : google::GLOG_INFO;
  FLAGS_v = verbose;
  google::InitGoogleLogging(argv[0], &ProgressPrefix, nullptr);

  if (keys->parsed()) {
    std::cout << pqlayout::ConfigReferenceMarkdown();
    return 0;
  }
  std::string command_line;
  for (int i = 0; i < argc; ++i) command_line += (i ? " " : "") + std::string(argv[i]);
  if (sweep->parsed()) return Sweep(sweep_args, argv[0]);
  if (collect->parsed()) {
    pqlayout::CollectSummary summary;
    return ExitCode(pqlayout::CollectSweep(collect_dir, &summary));
  }
  if (compare->parsed()) return Compare(compare_args, command_line);
  return Run(run_args, command_line);
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return Main(argc, argv);
  } catch (const std::bad_alloc&) {
    std::cerr << "pqlayout: error: out of memory" << std::endl;
  } catch (const std::exception& e) {
    std::cerr << "pqlayout: internal error: " << OneLine(e.what()) << std::endl;
  } catch (...) {
    std::cerr << "pqlayout: internal error: unknown exception" << std::endl;
  }
  return 1;
}

// pqlayout command line: `pqlayout run CONFIG [--set KEY=VALUE]... [--out DIR] [--until STAGE]`
// and `pqlayout keys` (the config reference). Exit codes: 0 success, 2 bad input or config
// (one line on stderr naming the file, key or element), 1 internal failure. Progress lines
// with elapsed time go to stdout.
#include <CLI/CLI.hpp>
#include <glog/logging.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <new>

#include "problems/build_info.h"
#include "problems/compare.h"
#include "problems/config.h"
#include "problems/pipeline.h"

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
  return text;
}

int ExitCode(const Status& status) {
  if (status.ok()) return 0;
  std::cerr << "pqlayout: error: " << status.message() << std::endl;
  return static_cast<int>(status.code());
}

struct RunArguments {
  std::string config;
  std::vector<std::string> sets;
  std::string out;
  std::string until = "analyze";
};

int Run(const RunArguments& args, const std::string& command_line) {
  pqlayout::Config config;
  if (int code = ExitCode(pqlayout::LoadConfig(args.config, args.sets, &config))) return code;
  pqlayout::RunOptions options;
  options.config_path = args.config;
  options.command_line = command_line;
  options.out_dir = args.out.empty() ? "out/" + std::filesystem::path(args.config).stem().string() : args.out;
  options.until = *pqlayout::StageFromName(args.until);  // validated by CLI11
  nlohmann::json report;
  return ExitCode(pqlayout::RunPipeline(config, options, &report));
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
  CLI::App* run = app.add_subcommand("run", "run the pipeline on a YAML config file");
  run->add_option("CONFIG", run_args.config, "YAML config file (see examples/great_court.yaml)")->required();
  run->add_option("--set", run_args.sets, "override a config key, KEY=VALUE (VALUE is YAML); repeatable")
      ->type_size(1)->allow_extra_args(false)->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  run->add_option("--out", run_args.out, "output folder (default: out/<config name>)");
  run->add_option("--until", run_args.until, "last stage to run")
      ->check(CLI::IsMember(pqlayout::StageNames()))->capture_default_str();
  CLI::App* keys = app.add_subcommand("keys", "print the config reference (every key, default, meaning)");
  RunArguments compare_args;
  CLI::App* compare = app.add_subcommand(
      "compare", "run CONFIG with strain and with curvature guidance and compare the two grid shells");
  compare->add_option("CONFIG", compare_args.config, "YAML config file")->required();
  compare->add_option("--set", compare_args.sets, "override a config key in both runs, KEY=VALUE; repeatable")
      ->type_size(1)->allow_extra_args(false)->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  compare->add_option("--out", compare_args.out, "output folder (default: out/<config name>-compare)");

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
  if (compare->parsed()) {
    pqlayout::CompareOptions options;
    options.config_path = compare_args.config;
    options.overrides = compare_args.sets;
    options.command_line = command_line;
    options.out_dir = compare_args.out.empty()
                          ? "out/" + std::filesystem::path(compare_args.config).stem().string() + "-compare"
                          : compare_args.out;
    nlohmann::json comparison;
    return ExitCode(pqlayout::RunCompare(options, &comparison));
  }
  return Run(run_args, command_line);
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return Main(argc, argv);
  } catch (const std::bad_alloc&) {
    std::cerr << "pqlayout: error: out of memory" << std::endl;
  } catch (const std::exception& e) {
    std::cerr << "pqlayout: internal error: " << e.what() << std::endl;
  } catch (...) {
    std::cerr << "pqlayout: internal error: unknown exception" << std::endl;
  }
  return 1;
}

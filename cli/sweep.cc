// `pqlayout sweep`: the plan (parameters, run folders, sweep.json), its runs as commands and as
// child processes (cli/sweep.h). Gathering the finished runs (`collect`): sweep_collect.cc.
#include "cli/sweep.h"

#include <glog/logging.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <mutex>
#include <set>
#include <sstream>
#include <thread>

#include "base/atomic_file.h"
#include "base/interrupt.h"
#include "cli/child_processes.h"
#include "cli/sweep_internal.h"
#include "pipeline/config.h"
#include "pipeline/pipeline.h"

namespace pqlayout {

namespace fs = std::filesystem;
using nlohmann::json;

namespace sweep_internal {

std::string ShortestNumber(double v) {
  char text[40];
  if (v == std::floor(v) && std::abs(v) < 1e15) {  // integers without an exponent: 10, not 1e+01
    std::snprintf(text, sizeof(text), "%.0f", v == 0.0 ? 0.0 : v);
    return text;
  }
  for (int precision = 1; precision <= 17; ++precision) {
    std::snprintf(text, sizeof(text), "%.*g", precision, v);
    if (std::strtod(text, nullptr) == v) break;
  }
  return text;
}

std::string ReadText(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace sweep_internal

using namespace sweep_internal;

namespace {

// ---- parameter values ----

bool ParseNumber(const std::string& text, double* v) {
  if (text.empty() || std::isspace(static_cast<unsigned char>(text[0]))) return false;
  char* end = nullptr;
  *v = std::strtod(text.c_str(), &end);
  return end == text.c_str() + text.size() && std::isfinite(*v);
}

// A value as the user wrote it, numbers in canonical form.
std::string CanonicalValue(const std::string& text) {
  double v;
  return ParseNumber(text, &v) ? ShortestNumber(v) : text;
}

// Range values rounded to 12 significant digits, so 0:1:11 gives 0.3, not 0.30000000000000004.
double RoundRangeValue(double v) {
  char text[40];
  std::snprintf(text, sizeof(text), "%.12g", v);
  return std::strtod(text, nullptr);
}

std::vector<std::string> Split(const std::string& text, char separator) {
  std::vector<std::string> parts;
  size_t start = 0;
  for (size_t at; (at = text.find(separator, start)) != std::string::npos; start = at + 1)
    parts.push_back(text.substr(start, at - start));
  parts.push_back(text.substr(start));
  return parts;
}

Status ParseRange(const std::string& where, const std::string& values, std::vector<std::string>* out) {
  const bool log = values.rfind("log:", 0) == 0;
  const std::string expected =
      log ? "expected log:start:stop:count with start, stop > 0 and an integer count >= 1"
          : "expected start:stop:count with numbers start, stop and an integer count >= 1";
  const std::vector<std::string> parts = Split(log ? values.substr(4) : values, ':');
  double start, stop, count;
  if (parts.size() != 3 || !ParseNumber(parts[0], &start) || !ParseNumber(parts[1], &stop) ||
      !ParseNumber(parts[2], &count))
    return Status::InvalidInput(where + ": bad range '" + values + "' (" + expected + ")");
  if (count < 1 || count != std::floor(count) || count > 100000)
    return Status::InvalidInput(where + ": bad range '" + values + "': count must be an integer in [1, 100000]");
  if (log && (start <= 0 || stop <= 0))
    return Status::InvalidInput(where + ": bad range '" + values + "': a log range needs start and stop > 0");
  if (count == 1 && start != stop)
    return Status::InvalidInput(where + ": bad range '" + values + "': count 1 needs start = stop");
  const int n = static_cast<int>(count);
  for (int i = 0; i < n; ++i) {
    const double t = n == 1 ? 0.0 : double(i) / (n - 1);
    const double v = i == n - 1 ? stop
                     : log      ? std::exp(std::log(start) + t * (std::log(stop) - std::log(start)))
                                : start + t * (stop - start);
    out->push_back(ShortestNumber(RoundRangeValue(v)));
  }
  return Status::Ok();
}

// ---- folder names ----

// For each key the shortest dotted suffix that no other key shares ("alignment" for
// levelset.weights.alignment unless another swept key also ends in ".alignment").
std::vector<std::string> ShortKeys(const std::vector<SweepParameter>& parameters) {
  std::vector<std::string> shorts;
  for (const auto& p : parameters) {
    const std::vector<std::string> parts = Split(p.key, '.');
    std::string suffix;
    for (int i = static_cast<int>(parts.size()) - 1; i >= 0; --i) {
      suffix = suffix.empty() ? parts[i] : parts[i] + "." + suffix;
      bool unique = true;
      for (const auto& other : parameters) {
        if (&other == &p) continue;
        const std::string& k = other.key;
        if (k == suffix || (k.size() > suffix.size() && k.compare(k.size() - suffix.size(), suffix.size(), suffix) == 0 &&
                            k[k.size() - suffix.size() - 1] == '.'))
          unique = false;
      }
      if (unique) break;
    }
    shorts.push_back(suffix);
  }
  return shorts;
}

std::string FolderSafe(const std::string& text) {
  std::string safe;
  for (const char c : text)
    safe += (std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '-' || c == '+') ? c : '_';
  if (safe.empty() || safe[0] == '.') safe = "_" + safe;
  return safe;
}

std::string FirstLine(const std::string& text) {
  std::string line = text.substr(0, text.find('\n'));
  if (!line.empty() && line.back() == '\r') line.pop_back();
  return line;
}

// ---- runs as commands and as child processes ----

std::string ShellQuote(const std::string& arg) {
  const bool plain = !arg.empty() && std::all_of(arg.begin(), arg.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || std::strchr("_./=+:,@%-", c) != nullptr;
  });
  if (plain) return arg;
  std::string quoted = "'";
  for (const char c : arg) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

// Progress lines reach a log file (or a job scheduler's) as each run finishes, even if
// the sweep is killed later.
void FlushProgress() {
  std::cout.flush();
  std::fflush(stdout);
}

double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// One run of the sweep as a child process. Returns kFinished; kFailed with the reason in
// *run_error and in the run's error.txt (*written says whether that could be written); or
// kPending if the sweep was interrupted before the run finished: an interrupted run is left
// as it was, neither finished nor failed, and runs again when the sweep is resumed.
RunState RunOne(const SweepPlan& plan, const SweepRun& run, const std::string& executable,
                ChildProcesses* children, std::string* run_error, Status* written) {
  const fs::path folder = RunFolder(plan, run);
  std::error_code ec;
  fs::create_directories(folder, ec);
  std::string error;
  const int status = children->Run(executable, RunArguments(plan, run), (folder / "run.log").string(), &error);
  RunState state = InspectRun(plan, run, run_error);
  if (state != RunState::kFinished && InterruptSignal() != 0) return RunState::kPending;
  if (status == 0 && state != RunState::kFinished) {
    *run_error = "pqlayout run succeeded but " + (folder / "report.json").string() + " does not hold this run";
    state = RunState::kFailed;
  } else if (status != 0 && state != RunState::kFailed) {
    // No error.txt: the run could not start or was killed; record why.
    *run_error = status < 0 ? error : DescribeExit(status);
    state = RunState::kFailed;
  }
  if (state == RunState::kFailed) *written = WriteTextFileAtomically((folder / "error.txt").string(), *run_error + "\n");
  return state;
}

}  // namespace

Status ParseSweepParameter(const std::string& spec, SweepParameter* parameter) {
  const std::string where = "--param " + spec;
  const size_t eq = spec.find('=');
  if (eq == std::string::npos || eq == 0)
    return Status::InvalidInput(where + ": expected KEY=v1,v2,... or KEY=start:stop:count or KEY=log:start:stop:count");
  parameter->key = spec.substr(0, eq);
  parameter->values.clear();
  const std::string values = spec.substr(eq + 1);
  if (values.rfind("log:", 0) == 0 || (values.find(':') != std::string::npos && values.find(',') == std::string::npos)) {
    PQ_RETURN_IF_ERROR(ParseRange(where, values, &parameter->values));
  } else {
    for (const std::string& v : Split(values, ',')) {
      if (v.empty()) return Status::InvalidInput(where + ": empty value in the list");
      parameter->values.push_back(CanonicalValue(v));
    }
  }
  std::set<std::string> seen;
  for (const auto& v : parameter->values)
    if (!seen.insert(v).second) return Status::InvalidInput(where + ": value " + v + " is listed twice");
  return Status::Ok();
}

Status PlanSweep(const SweepOptions& options, SweepPlan* plan) {
  *plan = SweepPlan();
  plan->config_path = options.config_path;
  plan->overrides = options.overrides;
  plan->until = options.until;
  plan->out_dir = options.out_dir;
  if (options.parameters.empty()) return Status::InvalidInput("sweep: give at least one --param KEY=VALUES");
  Config config;
  PQ_RETURN_IF_ERROR(LoadConfig(options.config_path, options.overrides, &config));
  std::set<std::string> keys;
  for (const std::string& spec : options.parameters) {
    SweepParameter parameter;
    PQ_RETURN_IF_ERROR(ParseSweepParameter(spec, &parameter));
    if (!keys.insert(parameter.key).second)
      return Status::InvalidInput("--param " + spec + ": " + parameter.key + " is swept twice");
    // Each value on its own, so that the error names the --param and the value.
    for (const std::string& value : parameter.values) {
      std::vector<std::string> overrides = options.overrides;
      overrides.push_back(parameter.key + "=" + value);
      const Status status = LoadConfig(options.config_path, overrides, &config);
      if (!status.ok()) {
        // The config says "--set KEY=VALUE: KEY: reason"; say "--param SPEC: value VALUE: reason".
        std::string message = status.message();
        for (const std::string& prefix : {"--set " + overrides.back() + ": ", parameter.key + ": "})
          if (message.rfind(prefix, 0) == 0) message = message.substr(prefix.size());
        if (message.rfind("unknown key", 0) == 0 || message.rfind("is a section", 0) == 0)
          return Status::InvalidInput("--param " + spec + ": " + parameter.key + ": " + message);
        return Status::InvalidInput("--param " + spec + ": value " + value + ": " + message);
      }
    }
    plan->parameters.push_back(parameter);
  }
  size_t total = 1;
  for (const auto& p : plan->parameters) {
    total *= p.values.size();
    if (total > 100000) return Status::InvalidInput("sweep: more than 100000 runs");
  }
  const std::vector<std::string> shorts = ShortKeys(plan->parameters);
  std::map<std::string, size_t> names;
  for (size_t index = 0; index < total; ++index) {
    SweepRun run;
    size_t rest = index;
    std::vector<size_t> digits(plan->parameters.size());
    for (size_t p = plan->parameters.size(); p-- > 0;) {  // the last parameter varies fastest
      digits[p] = rest % plan->parameters[p].values.size();
      rest /= plan->parameters[p].values.size();
    }
    std::vector<std::string> overrides = options.overrides;
    for (size_t p = 0; p < plan->parameters.size(); ++p) {
      const std::string& value = plan->parameters[p].values[digits[p]];
      run.assignments.emplace_back(plan->parameters[p].key, value);
      run.name += (p ? "_" : "") + shorts[p] + "=" + FolderSafe(value);
      overrides.push_back(plan->parameters[p].key + "=" + value);
    }
    const Status status = LoadConfig(options.config_path, overrides, &config);
    if (!status.ok()) return status.WithContext("sweep run " + run.name);
    run.config = ConfigToJson(config);
    if (names.count(run.name))
      return Status::InvalidInput("sweep: two runs would share the folder runs/" + run.name +
                                  " (values that differ only in characters a folder name cannot hold)");
    names[run.name] = index;
    plan->runs.push_back(std::move(run));
  }
  return Status::Ok();
}

Status WriteSweepManifest(const SweepPlan& plan) {
  json parameters = json::array();
  for (const auto& p : plan.parameters) parameters.push_back({{"key", p.key}, {"values", p.values}});
  json runs = json::array();
  for (const auto& r : plan.runs) {
    json assignments = json::array();
    for (const auto& [key, value] : r.assignments) assignments.push_back({key, value});
    runs.push_back({{"name", r.name}, {"parameters", assignments}, {"config", r.config}});
  }
  const json manifest = {{"config_file", plan.config_path}, {"overrides", plan.overrides}, {"until", plan.until},
                         {"parameters", parameters}, {"runs", runs}};
  return WriteTextFileAtomically((fs::path(plan.out_dir) / "sweep.json").string(), manifest.dump(2) + "\n");
}

Status ReadSweepManifest(const std::string& dir, SweepPlan* plan) {
  const fs::path path = fs::path(dir) / "sweep.json";
  std::error_code ec;
  if (!fs::is_regular_file(path, ec))
    return Status::InvalidInput(path.string() + ": not found (is " + dir + " a sweep folder? `pqlayout sweep` "
                                "and `pqlayout sweep --list` write it)");
  *plan = SweepPlan();
  plan->out_dir = dir;
  try {
    const json manifest = json::parse(ReadText(path));
    plan->config_path = manifest.at("config_file").get<std::string>();
    plan->overrides = manifest.at("overrides").get<std::vector<std::string>>();
    plan->until = manifest.at("until").get<std::string>();
    for (const auto& p : manifest.at("parameters"))
      plan->parameters.push_back({p.at("key").get<std::string>(), p.at("values").get<std::vector<std::string>>()});
    for (const auto& r : manifest.at("runs")) {
      SweepRun run;
      run.name = r.at("name").get<std::string>();
      for (const auto& a : r.at("parameters")) run.assignments.emplace_back(a.at(0).get<std::string>(), a.at(1).get<std::string>());
      run.config = r.at("config");
      if (run.assignments.size() != plan->parameters.size())
        return Status::InvalidInput(path.string() + ": run " + run.name + " does not set every parameter");
      plan->runs.push_back(std::move(run));
    }
  } catch (const json::exception& e) {
    return Status::InvalidInput(path.string() + ": not a valid sweep manifest: " + e.what());
  }
  return Status::Ok();
}

std::string RunFolder(const SweepPlan& plan, const SweepRun& run) {
  return (fs::path(plan.out_dir) / "runs" / run.name).string();
}

RunState InspectRun(const SweepPlan& plan, const SweepRun& run, std::string* error) {
  const fs::path folder = RunFolder(plan, run);
  std::error_code ec;
  if (fs::is_regular_file(folder / "report.json", ec)) {
    try {
      const json report = json::parse(ReadText(folder / "report.json"));
      if (report.at("config") == run.config && report.at("run").at("until") == plan.until) return RunState::kFinished;
    } catch (const json::exception&) {
      // not a report of this run: the run is pending (or failed, below)
    }
  }
  if (fs::is_regular_file(folder / "error.txt", ec)) {
    if (error) *error = FirstLine(ReadText(folder / "error.txt"));
    return RunState::kFailed;
  }
  return RunState::kPending;
}

std::vector<std::string> RunArguments(const SweepPlan& plan, const SweepRun& run) {
  std::vector<std::string> args{"run", plan.config_path};
  for (const auto& set : plan.overrides) args.insert(args.end(), {"--set", set});
  for (const auto& [key, value] : run.assignments) args.insert(args.end(), {"--set", key + "=" + value});
  const std::string folder = RunFolder(plan, run);
  args.insert(args.end(), {"--out", folder, "--error-file", (fs::path(folder) / "error.txt").string()});
  if (plan.until != "analyze") args.insert(args.end(), {"--until", plan.until});
  return args;
}

std::string RunCommandLine(const std::string& executable, const SweepPlan& plan, const SweepRun& run) {
  std::string line = ShellQuote(executable);
  for (const auto& arg : RunArguments(plan, run)) line += " " + ShellQuote(arg);
  return line;
}

Status RunSweep(const SweepPlan& plan, const std::string& executable, int jobs, SweepSummary* summary) {
  *summary = SweepSummary();
  summary->total = static_cast<int>(plan.runs.size());
  PQ_RETURN_IF_ERROR(WriteSweepManifest(plan));
  std::vector<size_t> todo;
  for (size_t i = 0; i < plan.runs.size(); ++i)
    if (InspectRun(plan, plan.runs[i]) != RunState::kFinished) todo.push_back(i);
  summary->skipped = summary->total - static_cast<int>(todo.size());
  LOG(INFO) << "sweep: " << summary->total << " runs, " << summary->skipped << " already finished, "
            << todo.size() << " to run, " << std::min<size_t>(std::max(jobs, 1), std::max<size_t>(todo.size(), 1))
            << " at a time";
  FlushProgress();
  std::atomic<size_t> next{0};
  std::mutex mutex;
  Status internal = Status::Ok();
  ChildProcesses children;
  const auto worker = [&] {
    for (size_t k; InterruptSignal() == 0 && (k = next++) < todo.size();) {
      const SweepRun& run = plan.runs[todo[k]];
      const auto start = std::chrono::steady_clock::now();
      std::string run_error;
      Status written = Status::Ok();
      const RunState state = RunOne(plan, run, executable, &children, &run_error, &written);
      std::lock_guard<std::mutex> lock(mutex);
      if (!written.ok() && internal.ok()) internal = written;
      if (state == RunState::kPending) {
        LOG(INFO) << "sweep: " << run.name << ": interrupted";
        FlushProgress();
        continue;
      }
      ++summary->ran;
      char prefix[64];
      std::snprintf(prefix, sizeof(prefix), "sweep: [%d/%zu] ", summary->ran, todo.size());
      if (state == RunState::kFinished) {
        char seconds[32];
        std::snprintf(seconds, sizeof(seconds), "%.1f", SecondsSince(start));
        LOG(INFO) << prefix << run.name << ": done in " << seconds << " s";
      } else {
        ++summary->failed;
        LOG(WARNING) << prefix << run.name << ": failed: " << run_error;
      }
      FlushProgress();
    }
  };
  std::vector<std::thread> threads;
  const int n = std::max(1, std::min<int>(jobs, static_cast<int>(todo.size())));
  std::atomic<int> working{n};
  for (int t = 0; t < n; ++t) threads.emplace_back([&] {
    worker();
    --working;
  });
  // Meanwhile this thread passes SIGINT/SIGTERM on to the runs in progress (the workers are
  // blocked waiting for them), then waits for them to wind down.
  while (working > 0) {
    children.ForwardInterrupt();
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  for (auto& t : threads) t.join();
  if (InterruptSignal() != 0) {
    LOG(INFO) << "sweep: interrupted after " << summary->ran << " of " << todo.size()
              << " runs; run the same command again to resume";
    FlushProgress();
    return CheckInterrupt();
  }
  PQ_RETURN_IF_ERROR(internal);
  CollectSummary collected;
  return CollectSweep(plan.out_dir, &collected);
}

}  // namespace pqlayout

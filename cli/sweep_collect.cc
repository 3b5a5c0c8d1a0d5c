// `pqlayout collect` (and the end of `sweep`): the finished runs of a sweep gathered into
// sweep.csv, timings.csv and figures/pareto.svg (cli/sweep.h). Planning and running: sweep.cc.
#include <glog/logging.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <set>
#include <sstream>

#include "base/atomic_file.h"
#include "cli/sweep.h"
#include "cli/sweep_internal.h"
#include "pipeline/pipeline.h"
#include "report/sweep_figures.h"

namespace pqlayout {

using namespace sweep_internal;

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// ---- CSV ----

std::string CsvField(const std::string& text) {
  if (text.find_first_of(",\"\n\r") == std::string::npos) return text;
  std::string quoted = "\"";
  for (const char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

std::string CsvNumber(const json& v) {
  if (v.is_number_float()) return ShortestNumber(v.get<double>());
  return v.dump();  // integers
}

// Every numeric leaf below `node`, as dotted name → value: objects by key, arrays of numbers
// by index (`bbox_min.0`); booleans count as 0/1. Strings, nulls and lists of records (per
// item detail such as singularities or per-round solver logs, whose length varies from run
// to run) are not metrics of the run and are left out.
void FlattenNumbers(const json& node, const std::string& prefix, std::map<std::string, json>* out) {
  if (node.is_object()) {
    for (const auto& [k, v] : node.items()) FlattenNumbers(v, prefix + "." + k, out);
  } else if (node.is_array()) {
    for (size_t i = 0; i < node.size(); ++i)
      if (node[i].is_number()) (*out)[prefix + "." + std::to_string(i)] = node[i];
  } else if (node.is_number()) {
    (*out)[prefix] = node;
  } else if (node.is_boolean()) {
    (*out)[prefix] = node.get<bool>() ? 1 : 0;
  }
}

// Wall times (`seconds`, `factor_seconds`, ...) and the process's peak memory after each
// stage (`peak_memory_mb`): they depend on the machine and its load.
bool IsTiming(const std::string& name) {
  const std::string last = name.substr(name.rfind('.') + 1);
  return last == "seconds" || last == "peak_memory_mb" ||
         (last.size() > 8 && last.compare(last.size() - 8, 8, "_seconds") == 0);
}

// The metrics of a report, per stage in pipeline order: (dotted name, value).
std::vector<std::pair<std::string, json>> StageMetrics(const json& report) {
  std::vector<std::pair<std::string, json>> metrics;
  if (!report.contains("stages")) return metrics;
  for (const auto& stage : StageNames()) {
    if (!report["stages"].contains(stage)) continue;
    std::map<std::string, json> flat;
    FlattenNumbers(report["stages"][stage], "stages." + stage, &flat);
    for (auto& entry : flat) metrics.emplace_back(entry.first, entry.second);
  }
  return metrics;
}

std::string RunLabel(const SweepRun& run) { return run.name; }

// ---- the Pareto figure ----

Status WriteParetoFigure(const SweepPlan& plan, const std::vector<RunState>& states,
                         const std::vector<json>& reports) {
  struct Axis {
    const char* stage;
    const char* metric;
    const char* label;
  };
  const Axis planarity{"planarize", "planarity_max", "planarity δ, max"};
  const Axis compliance{"analyze", "compliance_node_mean", "nodal compliance, mean [J]"};
  const Axis alignment{"levelset", "alignment_rms_deg", "alignment to the guidance, RMS [°]"};
  const Axis closeness{"planarize", "closeness_mean", "closeness to the reference, mean [m]"};
  const auto value = [](const json& report, const Axis& axis, double* v) {
    if (!report.contains("stages") || !report["stages"].contains(axis.stage)) return false;
    const json& stage = report["stages"][axis.stage];
    if (!stage.contains(axis.metric) || !stage[axis.metric].is_number()) return false;
    *v = stage[axis.metric].get<double>();
    return std::isfinite(*v);
  };
  std::vector<ScatterPanel> panels(2);
  panels[0] = {"Planarity vs stiffness", planarity.label, compliance.label, {}};
  panels[1] = {"Alignment vs closeness", alignment.label, closeness.label, {}};
  const Axis* axes[2][2] = {{&planarity, &compliance}, {&alignment, &closeness}};
  int finished = 0, failed = 0;
  for (size_t i = 0; i < plan.runs.size(); ++i) {
    if (states[i] == RunState::kFailed) ++failed;
    if (states[i] != RunState::kFinished) continue;
    ++finished;
    for (int p = 0; p < 2; ++p) {
      ScatterPoint point;
      point.label = RunLabel(plan.runs[i]);
      if (value(reports[i], *axes[p][0], &point.x) && value(reports[i], *axes[p][1], &point.y))
        panels[p].points.push_back(point);
    }
  }
  std::string note = std::to_string(finished) + " finished run" + (finished == 1 ? "" : "s");
  if (failed) note += ", " + std::to_string(failed) + " failed (not shown)";
  note += "; lower is better on every axis; labels are the runs' folders";
  std::string title = "Sweep over";
  for (size_t i = 0; i < plan.parameters.size(); ++i) title += (i ? ", " : " ") + plan.parameters[i].key;
  return WriteTextFileAtomically((fs::path(plan.out_dir) / "figures" / "pareto.svg").string(),
                                 ScatterPanelsSvg(panels, title, note));
}

}  // namespace

std::string SweepCsv(const SweepPlan& plan, const std::vector<RunState>& states, const std::vector<json>& reports,
                     const std::vector<std::string>& errors) {
  // Metric columns: the union over the finished runs, stages in pipeline order.
  std::vector<std::string> columns;
  std::set<std::string> seen;
  std::vector<std::map<std::string, json>> rows(plan.runs.size());
  for (const auto& stage : StageNames()) {
    std::set<std::string> stage_columns;
    for (size_t i = 0; i < plan.runs.size(); ++i) {
      if (states[i] != RunState::kFinished) continue;
      for (auto& [name, value] : StageMetrics(reports[i])) {
        if (IsTiming(name) || name.rfind("stages." + stage + ".", 0) != 0) continue;
        stage_columns.insert(name);
        rows[i][name] = value;
      }
    }
    for (const auto& c : stage_columns)
      if (seen.insert(c).second) columns.push_back(c);
  }
  std::ostringstream csv;
  csv << "run,status";
  for (const auto& p : plan.parameters) csv << "," << CsvField(p.key);
  for (const auto& c : columns) csv << "," << CsvField(c);
  csv << ",error\n";
  for (size_t i = 0; i < plan.runs.size(); ++i) {
    if (states[i] == RunState::kPending) continue;
    const SweepRun& run = plan.runs[i];
    csv << CsvField(run.name) << "," << (states[i] == RunState::kFinished ? "ok" : "failed");
    for (const auto& assignment : run.assignments) csv << "," << CsvField(assignment.second);
    for (const auto& c : columns) {
      csv << ",";
      const auto it = rows[i].find(c);
      if (it != rows[i].end()) csv << CsvNumber(it->second);
    }
    csv << "," << (states[i] == RunState::kFailed ? CsvField(errors[i]) : "") << "\n";
  }
  return csv.str();
}

Status CollectSweep(const std::string& dir, CollectSummary* summary) {
  *summary = CollectSummary();
  SweepPlan plan;
  PQ_RETURN_IF_ERROR(ReadSweepManifest(dir, &plan));
  std::vector<RunState> states(plan.runs.size());
  std::vector<json> reports(plan.runs.size());
  std::vector<std::string> errors(plan.runs.size());
  std::ostringstream timings;
  timings << "run,stage,seconds\n";
  for (size_t i = 0; i < plan.runs.size(); ++i) {
    states[i] = InspectRun(plan, plan.runs[i], &errors[i]);
    if (states[i] == RunState::kFinished) {
      ++summary->finished;
      reports[i] = json::parse(ReadText(fs::path(RunFolder(plan, plan.runs[i])) / "report.json"));
      for (const auto& stage : StageNames()) {
        const json& stages = reports[i]["stages"];
        if (stages.contains(stage) && stages[stage].contains("seconds"))
          timings << CsvField(plan.runs[i].name) << "," << stage << "," << CsvNumber(stages[stage]["seconds"]) << "\n";
      }
      if (reports[i].contains("run") && reports[i]["run"].contains("total_seconds"))
        timings << CsvField(plan.runs[i].name) << ",total," << CsvNumber(reports[i]["run"]["total_seconds"]) << "\n";
    } else if (states[i] == RunState::kFailed) {
      ++summary->failed;
    } else {
      ++summary->pending;
    }
  }
  const fs::path out(dir);
  PQ_RETURN_IF_ERROR(WriteTextFileAtomically((out / "sweep.csv").string(), SweepCsv(plan, states, reports, errors)));
  PQ_RETURN_IF_ERROR(WriteTextFileAtomically((out / "timings.csv").string(), timings.str()));
  PQ_RETURN_IF_ERROR(WriteParetoFigure(plan, states, reports));
  LOG(INFO) << "collect: " << summary->finished << " finished, " << summary->failed << " failed, " << summary->pending
            << " not run; wrote " << (out / "sweep.csv").string() << " and " << (out / "figures" / "pareto.svg").string();
  return Status::Ok();
}

}  // namespace pqlayout

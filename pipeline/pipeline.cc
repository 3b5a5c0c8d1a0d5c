#include "pipeline/pipeline.h"

#include <glog/logging.h>

#include <chrono>
#include <ctime>
#include <fstream>
#include <mutex>
#include <string>
#include <vector>

#include "base/interrupt.h"
#include "base/allocator.h"
#include "pipeline/build_info.h"
#include "pipeline/layout_targets.h"
#include "pipeline/surface_fields.h"
#include "report/report_html.h"
#include "pipeline/stages.h"
#include "problems/boundary_conditions.h"
#include "solver/numerics.h"

namespace pqlayout {
namespace {

// The process's peak resident memory so far (VmHWM of /proc/self/status), MB; −1 where the
// system does not say (not Linux).
double PeakResidentMegabytes() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line))
    if (line.rfind("VmHWM:", 0) == 0) return std::stod(line.substr(6)) / 1024.0;  // kB
  return -1.0;
}

// Collects the warnings logged while it lives, for report.json ("warnings"): a run that
// finishes with a warning (δ above target, cells left out, vertices dropped) says so in its
// report too, not only on the console.
class WarningCollector : public google::LogSink {
 public:
  WarningCollector() { google::AddLogSink(this); }
  ~WarningCollector() override { google::RemoveLogSink(this); }
  WarningCollector(const WarningCollector&) = delete;

  void send(google::LogSeverity severity, const char*, const char*, int, const google::LogMessageTime&,
            const char* message, size_t length) override {
    if (severity != google::GLOG_WARNING) return;
    std::lock_guard<std::mutex> lock(mutex_);
    warnings_.emplace_back(message, length);
  }
  std::vector<std::string> warnings() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return warnings_;
  }

 private:
  mutable std::mutex mutex_;
  std::vector<std::string> warnings_;
};

struct StageEntry {
  Stage stage;
  const char* name;
  StageFunction run;
};

// The pipeline in order. Adding a stage = one file + its line here.
const StageEntry kStages[] = {
    {Stage::kSurface, "surface", &RunSurfaceStage},
    {Stage::kMembrane, "membrane", &RunMembraneStage},
    {Stage::kGuidance, "guidance", &RunGuidanceStage},
    {Stage::kLevelset, "levelset", &RunLevelsetStage},
    {Stage::kExtract, "extract", &RunExtractStage},
    {Stage::kPlanarize, "planarize", &RunPlanarizeStage},
    {Stage::kStiffen, "stiffen", &RunStiffenStage},
    {Stage::kAnalyze, "analyze", &RunAnalyzeStage},
};

std::string UtcNow() {
  const std::time_t now = std::time(nullptr);
  char text[32];
  std::strftime(text, sizeof(text), "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
  return text;
}

double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

nlohmann::json BuildInfoJson() {
  const BuildInfo& info = GetBuildInfo();
  nlohmann::json libraries = nlohmann::json::object();
  for (const auto& [name, version] : info.libraries) libraries[name] = version;
  return {{"version", info.version},
          {"git_revision", info.git_revision},
          {"libraries", libraries},
          {"malloc", AllocatorDescription()}};
}

// What report.html's 3D view draws: the final shell, its planarity, and the offset and
// compliance where computed; after --until planarize or extract the mesh of that stage;
// before extract nothing (the page has no 3D view).
View3dData View3dOf(const PipelineState& state) {
  View3dData view;
  for (const ExtractedMesh* mesh : {&state.shell, &state.planarized, &state.quads}) {
    if (mesh->mesh.n_faces() > 0) {
      view.shell = &mesh->mesh;
      break;
    }
  }
  view.surface = state.surface.get();
  view.target_delta = state.config.planarize.target_delta;
  for (const auto& [name, column] : state.analysis.nodes)
    if (name == "compliance") view.nodal_compliance = &column;
  view.normal_offset = &state.normal_offset;
  view.offset_tolerance = state.config.stiffen.tolerance;
  return view;
}

}  // namespace

const std::vector<std::string>& StageNames() {
  static const std::vector<std::string> kNames = [] {
    std::vector<std::string> names;
    for (const auto& s : kStages) names.push_back(s.name);
    return names;
  }();
  return kNames;
}

const char* StageName(Stage stage) { return kStages[static_cast<int>(stage)].name; }

std::optional<Stage> StageFromName(const std::string& name) {
  for (const auto& s : kStages)
    if (name == s.name) return s.stage;
  return std::nullopt;
}

Status RunPipeline(const Config& config, const RunOptions& options, nlohmann::json* report,
                   PipelineState* state_out) {
  const auto run_start = std::chrono::steady_clock::now();
  const WarningCollector warnings;
  std::unique_ptr<OutputFiles> out;
  PQ_RETURN_IF_ERROR(OutputFiles::Open(options.out_dir, &out));

  SetNumericThreads(config.threads);
  *report = {{"pqlayout", BuildInfoJson()},
             {"numerics", {{"threads", NumericThreads()},
                           {"blas", BlasDescription()},
                           {"blas_core", BlasCore()}}},
             {"run", {{"command", options.command_line},
                      {"config_file", options.config_path},
                      {"output_folder", out->final_dir()},
                      {"started_at", UtcNow()},
                      {"until", StageName(options.until)}}},
             {"config", ConfigToJson(config)},
             {"stages", nlohmann::json::object()}};
  PipelineState state;
  state.config = config;
  // The files written in the background (field tables, figures, surface.obj) wait until the
  // level sets are solved: until then the stages keep both cores busy (the membrane's factor,
  // the closest-point index, the second layout alongside), after it they are single-threaded.
  const bool hold_writes = static_cast<int>(options.until) > static_cast<int>(Stage::kLevelset);
  if (hold_writes) out->HoldWrites();
  nlohmann::json completed = nlohmann::json::array();
  for (const auto& entry : kStages) {
    if (static_cast<int>(entry.stage) > static_cast<int>(options.until)) break;
    PQ_RETURN_IF_ERROR(CheckInterrupt());  // SIGINT/SIGTERM: stop before the next stage
    LOG(INFO) << entry.name << ": started";
    if (options.progress) options.progress(entry.name, "started", 0.0);
    const auto stage_start = std::chrono::steady_clock::now();
    nlohmann::json metrics = nlohmann::json::object();
    PQ_RETURN_IF_ERROR(out->InFinalFolder(entry.run(&state, out.get(), &metrics)));
    metrics["seconds"] = SecondsSince(stage_start);
    if (const double peak = PeakResidentMegabytes(); peak > 0.0) metrics["peak_memory_mb"] = peak;
    (*report)["stages"][entry.name] = metrics;
    // Supports that cannot hold the frame are refused before the layout is solved, not after.
    if (entry.stage == Stage::kSurface && static_cast<int>(options.until) >= static_cast<int>(Stage::kStiffen))
      PQ_RETURN_IF_ERROR(CheckSupportsHoldTheFrameInPlan(state.supports));
    // The reference's closest-point index, which levelset (a large reference's working mesh),
    // extract, planarize and stiffen query, built on the second core during membrane and guidance.
    const bool to_levelset = static_cast<int>(options.until) >= static_cast<int>(Stage::kLevelset);
    if (entry.stage == Stage::kSurface && to_levelset) state.surface->IndexClosestPointsInBackground();
    // levelset's working mesh (problems/levelset.h) on a thread of its own during guidance: started
    // with the index, it slowed the membrane's two-threaded factor more than it saved (962k, three
    // interleaved pairs: 16.87 / 15.67 / 15.42 s against 15.91 / 15.32 / 15.22 s from here).
    if (entry.stage == Stage::kMembrane && to_levelset)
      state.working_mesh = MakeWorkingMeshInBackground(*state.surface, config.levelset, config.layout.spacing);
    completed.push_back(entry.name);
    // fields.vtk once its last input is there (pipeline/surface_fields.h), while the stages go on.
    const Stage last_input =
        static_cast<int>(options.until) < static_cast<int>(Stage::kLevelset) ? options.until : Stage::kLevelset;
    if (entry.stage == last_input && config.output.fields && !state.guidance.direction.empty())
      WriteSurfaceFieldsVtkInBackground(state, out.get());
    if (entry.stage == Stage::kLevelset && hold_writes) out->ReleaseWrites();
    LOG(INFO) << entry.name << ": done in " << metrics["seconds"].get<double>() << " s";
    if (options.progress) options.progress(entry.name, "done", metrics["seconds"].get<double>());
  }
  (*report)["targets"] = EvaluateLayoutTargets(state, (*report)["stages"]);
  if (!(*report)["targets"]["list"].empty()) LOG(INFO) << "targets: " << LayoutTargetsSummary((*report)["targets"]);
  (*report)["run"]["completed_stages"] = completed;
  (*report)["run"]["total_seconds"] = SecondsSince(run_start);
  (*report)["warnings"] = warnings.warnings();
  PQ_RETURN_IF_ERROR(out->InFinalFolder(out->WaitForWrites()));  // the field files, before the report that says they are there
  PQ_RETURN_IF_ERROR(out->InFinalFolder(out->WriteText("report.json", report->dump(2) + "\n")));
  PQ_RETURN_IF_ERROR(out->InFinalFolder(WriteReportHtml(*report, out.get(), View3dOf(state))));
  if (options.commit) {
    PQ_RETURN_IF_ERROR(out->Commit());
    LOG(INFO) << "wrote " << out->final_dir() << " in " << SecondsSince(run_start) << " s";
  } else {
    PQ_RETURN_IF_ERROR(CheckInterrupt());  // as Commit would: an interrupted run does not succeed
  }
  if (state_out) *state_out = std::move(state);
  return Status::Ok();
}

}  // namespace pqlayout

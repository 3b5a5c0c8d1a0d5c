// The pipeline: stages in the SPEC's order, each one file (problems/stage_<name>.cc) that
// reads what the earlier stages left in PipelineState, adds its own results, writes its
// output files and reports its metrics. RunPipeline times every stage, assembles
// report.json and commits the outputs only when the run succeeded.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "geometry/quad_extraction.h"
#include "geometry/surface_model.h"
#include "problems/boundary_conditions.h"
#include "problems/config.h"
#include "problems/guidance.h"
#include "problems/levelset.h"
#include "problems/output_files.h"

namespace pqlayout {

enum class Stage { kSurface, kMembrane, kGuidance, kLevelset, kExtract, kPlanarize, kStiffen, kAnalyze };

const std::vector<std::string>& StageNames();  // "surface", ..., "analyze" (SPEC names)
const char* StageName(Stage stage);
std::optional<Stage> StageFromName(const std::string& name);

// Everything the stages hand on to each other.
struct PipelineState {
  Config config;
  std::unique_ptr<SurfaceModel> surface;  // stage surface
  VertexConditions supports;              // stage surface: per boundary vertex
  // stage membrane: vertex field "v_z" on *surface
  GuidanceField guidance;                 // stage guidance
  LevelSetSolution levelsets;             // stage levelset
  ExtractedMesh quads;                    // stage extract: quad-dominant mesh + reference origins
  ExtractedMesh planarized;               // stage planarize: the same mesh with planar faces
  ExtractedMesh shell;                    // stage stiffen: the final grid shell (= planarized when off)
  std::vector<double> normal_offset;      // stage stiffen: per shell vertex, m from the planarised mesh
  std::vector<double> nodal_compliance;   // stage analyze: per shell vertex, J
};

// One stage: reads and extends state, writes files through out, fills metrics (JSON object;
// `seconds` is added by the pipeline).
using StageFunction = Status (*)(PipelineState* state, OutputFiles* out, nlohmann::json* metrics);

struct RunOptions {
  std::string config_path;          // for the report
  std::string out_dir = "out";      // output folder
  Stage until = Stage::kAnalyze;    // last stage to run
  std::string command_line;         // for the report
};

// Runs the stages up to options.until.
// On success the outputs and report.json are in options.out_dir and *report holds the report.
Status RunPipeline(const Config& config, const RunOptions& options, nlohmann::json* report);

}  // namespace pqlayout

// The pipeline: stages in the SPEC's order, each one file (pipeline/stage_<name>.cc) that
// reads what the earlier stages left in PipelineState, adds its own results, writes its
// output files and reports its metrics. RunPipeline times every stage, assembles
// report.json and commits the outputs only when the run succeeded.
#pragma once

#include <functional>
#include <future>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "geometry/quad_extraction.h"
#include "geometry/surface_model.h"
#include "problems/boundary_conditions.h"
#include "pipeline/config.h"
#include "problems/guidance.h"
#include "problems/levelset.h"
#include "solver/frame_buckling.h"
#include "base/output_files.h"

namespace pqlayout {

enum class Stage { kSurface, kMembrane, kGuidance, kLevelset, kExtract, kPlanarize, kStiffen, kAnalyze };

const std::vector<std::string>& StageNames();  // "surface", ..., "analyze" (SPEC names)
const char* StageName(Stage stage);
std::optional<Stage> StageFromName(const std::string& name);

// A table of named columns, one value per row (a node, a member): what analysis/*.csv hold,
// without their id column.
using ColumnTable = std::vector<std::pair<std::string, std::vector<double>>>;

// Stage analyze's results per node (= per vertex of the grid shell) and per member (= per
// mesh edge, or the members of a merged joint).
struct AnalysisTables {
  ColumnTable nodes;    // x, y, z, load_z, ux, uy, uz, compliance (analysis/nodes.csv)
  ColumnTable members;  // node_a, node_b, length, axial_force, ... (analysis/members.csv)
};

// Everything the stages hand on to each other.
struct PipelineState {
  Config config;
  // stage surface; shared with the figures of the reference drawn on the background writer
  // (guidance, levelset), which read it while the later stages run (SurfaceModel::FreezeFields).
  std::shared_ptr<SurfaceModel> surface;
  // levelset's working mesh, made ahead on a thread of its own from the membrane stage on (when
  // the run goes as far as levelset); declared after surface: joined before it goes.
  std::shared_future<WorkingMesh> working_mesh;
  VertexConditions supports;              // stage surface: per boundary vertex
  // stage membrane: vertex field "v_z" on *surface
  GuidanceField guidance;                 // stage guidance
  LevelSetSolution levelsets;             // stage levelset
  ExtractedMesh quads;                    // stage extract: quad-dominant mesh + reference origins
  ExtractedMesh planarized;               // stage planarize: the same mesh with planar faces
  ExtractedMesh shell;                    // stage stiffen: the final grid shell (= planarized when off)
  AnalysisTables analysis;                // stage analyze
  std::vector<double> normal_offset;      // stage stiffen: per shell vertex, m from the planarised mesh
  BucklingMemo buckling_memo;             // stages stiffen and analyze: the last buckling solve
  // stage surface: every stage works in a local frame; the file's coordinates are local +
  // origin (zero unless the file is georeferenced: see stage_surface.cc), and so are those of
  // every geometry file written.
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
};

// One stage: reads and extends state, writes files through out, fills metrics (JSON object;
// `seconds` is added by the pipeline).
using StageFunction = Status (*)(PipelineState* state, OutputFiles* out, nlohmann::json* metrics);

// Told when a stage starts ("started", seconds 0) and when it is done ("done", its seconds).
using StageProgress = std::function<void(const std::string& stage, const std::string& event, double seconds)>;

struct RunOptions {
  std::string config_path;          // for the report
  std::string out_dir = "out";      // output folder
  Stage until = Stage::kAnalyze;    // last stage to run
  std::string command_line;         // for the report
  // false: the outputs are staged as usual but never moved into out_dir (the staging folder
  // is removed at the end), for callers that want only the in-memory results.
  bool commit = true;
  StageProgress progress;           // optional
};

// Runs the stages up to options.until.
// On success the outputs and report.json are in options.out_dir (unless !options.commit),
// *report holds the report and, if state is given, *state what the stages left.
Status RunPipeline(const Config& config, const RunOptions& options, nlohmann::json* report,
                   PipelineState* state = nullptr);

}  // namespace pqlayout

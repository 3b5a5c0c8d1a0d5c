#include "cli/compare.h"

#include <glog/logging.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "base/atomic_file.h"
#include "geometry/mesh_io.h"
#include "report/figures.h"
#include "pipeline/config.h"
#include "pipeline/pipeline.h"
#include "report/report_html.h"

namespace pqlayout {
namespace {

// The rows of the table: (stage, metric, label). Lower is better for all but quad fraction
// and the rows that say so.
struct Row {
  const char* stage;
  const char* metric;
  const char* label;
};
const Row kRows[] = {
    {"stiffen", "compliance_before", "compliance, planarised [J]"},
    {"analyze", "compliance_total", "compliance total, as analysed [J]"},
    {"stiffen", "compliance_ratio", "stiffen: compliance after / before"},
    {"stiffen", "offset_max", "stiffen: normal offset max [m]"},
    {"stiffen", "planarity_max", "stiffen: planarity δ max after"},
    {"stiffen", "closeness_max", "stiffen: distance to the reference max [m]"},
    {"analyze", "compliance_node_mean", "nodal compliance, mean [J]"},
    {"analyze", "compliance_node_max", "nodal compliance, max [J]"},
    {"analyze", "compliance_per_tonne", "compliance per tonne of steel [J/t]"},
    {"analyze", "max_displacement", "max displacement [m]"},
    {"stiffen", "buckling_factor_before", "buckling load factor λ₁, planarised (higher is better)"},
    {"analyze", "buckling_factor", "buckling load factor λ₁ (higher is better)"},
    {"stiffen", "utilisation_max_before", "member utilisation η max, planarised"},
    {"analyze", "utilisation_max", "member utilisation η, max"},
    {"stiffen", "span_over_deflection_before", "span / max deflection, planarised (higher is better)"},
    {"analyze", "span_over_deflection", "span / max deflection (higher is better)"},
    {"analyze", "steel_mass", "steel mass [kg]"},
    {"analyze", "n_nodes", "nodes"},
    {"analyze", "n_members", "members"},
    {"extract", "n_faces", "faces"},
    {"extract", "quad_fraction", "quad fraction"},
    {"planarize", "planarity_max", "planarity δ, max"},
    {"planarize", "planarity_mean", "planarity δ, mean"},
    {"planarize", "closeness_max", "closeness, max [m]"},
    {"planarize", "closeness_mean", "closeness, mean [m]"},
    {"levelset", "alignment_rms_deg", "alignment to its guidance, RMS [°]"},
    {"levelset", "alignment_rms_deg_source_above_half", "alignment to the source where it is strong, RMS [°]"},
    {"guidance", "area_fallback", "area following the curvature fallback (share)"},
};

std::string Number(const nlohmann::json& v) {
  if (!v.is_number()) return "–";
  std::ostringstream s;
  s.precision(4);
  s << v.get<double>();
  return s.str();
}

// A finished run's grid shell and nodal compliance, read back from its output folder.
struct RunResult {
  std::unique_ptr<SurfaceModel> surface;
  PolyMesh mesh;
  std::vector<double> compliance;
};

Status ReadRun(const std::filesystem::path& dir, RunResult* run) {
  auto reference = std::make_unique<TriMesh>();  // handed over without a copy (SurfaceModel)
  PQ_RETURN_IF_ERROR(ReadSurfaceMesh((dir / "surface.obj").string(), reference.get()));
  run->surface = std::make_unique<SurfaceModel>(std::move(reference));
  PolygonSoup soup;
  PQ_RETURN_IF_ERROR(ReadPolygonSoup((dir / "quads.obj").string(), &soup));
  for (const auto& p : soup.points) run->mesh.add_vertex(ToOpenMesh(p));
  for (const auto& face : soup.faces) {
    std::vector<VertexHandle> corners;
    for (const int v : face) corners.emplace_back(v);
    run->mesh.add_face(corners);
  }
  std::ifstream nodes(dir / "analysis" / "nodes.csv");
  std::string line;
  std::getline(nodes, line);  // header; compliance is the last column
  while (std::getline(nodes, line)) run->compliance.push_back(std::stod(line.substr(line.rfind(',') + 1)));
  if (run->compliance.size() != run->mesh.n_vertices())
    return Status::Internal((dir / "analysis" / "nodes.csv").string() + ": one row per node of quads.obj expected");
  return Status::Ok();
}

// The strain figure's title: it names the curvature fallback when the strain run used it
// (stages.guidance.fallback), so that the figure is not read as the paper's layout.
std::string StrainFigureTitle(const nlohmann::json& strain_report) {
  const nlohmann::json::json_pointer key("/stages/guidance/fallback");
  const bool fallback = strain_report.contains(key) && strain_report[key] == "curvature";
  return fallback ? "Nodal compliance, strain-guided layout; curvature lines where weak"
                  : "Nodal compliance, strain-guided layout";
}

// figures/compliance_strain.svg and figures/compliance_curvature.svg on one colour scale.
Status WriteCompareFigures(const std::filesystem::path& dir, const nlohmann::json& strain_report) {
  RunResult strain, curvature;
  PQ_RETURN_IF_ERROR(ReadRun(dir / "strain", &strain));
  PQ_RETURN_IF_ERROR(ReadRun(dir / "curvature", &curvature));
  const double shared = std::max(*std::max_element(strain.compliance.begin(), strain.compliance.end()),
                                 *std::max_element(curvature.compliance.begin(), curvature.compliance.end()));
  PQ_RETURN_IF_ERROR(WriteComplianceFigure(*strain.surface, strain.mesh, strain.compliance, shared,
                                           StrainFigureTitle(strain_report),
                                           (dir / "figures" / "compliance_strain.svg").string()));
  return WriteComplianceFigure(*curvature.surface, curvature.mesh, curvature.compliance, shared,
                               "Nodal compliance, curvature-guided layout (reference)",
                               (dir / "figures" / "compliance_curvature.svg").string());
}

}  // namespace

std::string ComparisonTable(const nlohmann::json& c) {
  std::ostringstream s;
  s << "| metric | strain guidance | curvature guidance | strain vs curvature |\n|---|---:|---:|---:|\n";
  for (const auto& row : c["rows"]) {
    s << "| " << row["label"].get<std::string>() << " | " << Number(row["strain"]) << " | " << Number(row["curvature"])
      << " | ";
    if (row["difference_percent"].is_number()) {
      std::ostringstream d;
      d.precision(3);
      d << std::showpos << row["difference_percent"].get<double>() << " %";
      s << d.str();
    } else {
      s << "–";
    }
    s << " |\n";
  }
  return s.str();
}

Status RunCompare(const CompareOptions& options, nlohmann::json* comparison) {
  nlohmann::json reports;
  for (const std::string source : {"strain", "curvature"}) {
    std::vector<std::string> overrides = options.overrides;
    overrides.push_back("guidance.source=" + source);
    Config config;
    PQ_RETURN_IF_ERROR(LoadConfig(options.config_path, overrides, &config));
    // Both layouts at the same mean panel area, hence about the same number of nodes: the
    // strain layout's families cross more obliquely, so at equal line spacing it would have
    // ~8 % fewer nodes and members, which alone changes the compliance.
    if (config.layout.density == "auto") config.layout.density = "panel_area";
    RunOptions run;
    run.config_path = options.config_path;
    run.out_dir = (std::filesystem::path(options.out_dir) / source).string();
    run.command_line = options.command_line + "  [" + source + "]";
    LOG(INFO) << "compare: " << source << " guidance → " << run.out_dir;
    PQ_RETURN_IF_ERROR(RunPipeline(config, run, &reports[source]));
  }
  nlohmann::json rows = nlohmann::json::array();
  for (const auto& r : kRows) {
    const auto pick = [&](const char* source) -> nlohmann::json {
      const auto& stages = reports[source]["stages"];
      return stages.contains(r.stage) && stages[r.stage].contains(r.metric) ? stages[r.stage][r.metric] : nullptr;
    };
    nlohmann::json row = {{"stage", r.stage}, {"metric", r.metric}, {"label", r.label},
                          {"strain", pick("strain")}, {"curvature", pick("curvature")}};
    if (row["strain"].is_number() && row["curvature"].is_number() && row["curvature"].get<double>() != 0.0)
      row["difference_percent"] = 100.0 * (row["strain"].get<double>() / row["curvature"].get<double>() - 1.0);
    else
      row["difference_percent"] = nullptr;
    rows.push_back(row);
  }
  *comparison = {{"config_file", options.config_path}, {"overrides", options.overrides}, {"rows", rows}};
  const std::filesystem::path dir(options.out_dir);
  PQ_RETURN_IF_ERROR(WriteTextFileAtomically((dir / "compare.json").string(), comparison->dump(2) + "\n"));
  PQ_RETURN_IF_ERROR(WriteTextFileAtomically((dir / "compare" / "table.md").string(), ComparisonTable(*comparison)));
  PQ_RETURN_IF_ERROR(WriteCompareFigures(dir, reports["strain"]));
  PQ_RETURN_IF_ERROR(WriteCompareReportHtml(*comparison, dir.string()));
  LOG(INFO) << "compare: wrote " << (dir / "compare.json").string() << " and compare/table.md\n" << ComparisonTable(*comparison);
  return Status::Ok();
}

}  // namespace pqlayout

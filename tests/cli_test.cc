// The pqlayout executable as a user meets it: exit codes, one-line errors, no partial output
// on failure, --set precedence, --until, --version, and report.json's contract keys.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>

#include "tests/test_cli.h"
#include "tests/test_meshes.h"

namespace pqlayout {
namespace {

namespace fs = std::filesystem;

using Result = testing::CliResult;
using testing::CountLines;
using testing::ReadFile;
using testing::RunPqlayout;

nlohmann::json ReadReport(const std::string& dir) { return nlohmann::json::parse(ReadFile(dir + "/report.json")); }

const char* kPlaneConfig =
    "surface:\n  generator: plane\n  width: 10\n  depth: 6\n  edge_length: 1.0\n"
    "layout:\n  spacing: 2.0\n";
const std::string kDomeConfig =
    "surface:\n  generator: dome\n  width: 18\n  depth: 15\n  rise: 4\n  edge_length: 1.0\n"
    "layout:\n  spacing: 3.0\n";

TEST(Cli, VersionAndHelp) {
  const auto dir = testing::TempDir();
  Result r = RunPqlayout(dir, "--version");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.out.find("pqlayout 0."), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("Ceres 2.1"), std::string::npos) << r.out;
#ifdef PQLAYOUT_JEMALLOC
  // The executable's malloc (cli/allocator_config.cc): jemalloc, its huge-page setting taken.
  EXPECT_NE(r.out.find("malloc: jemalloc 5."), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("(thp always)"), std::string::npos) << r.out;
#endif
  r = RunPqlayout(dir, "--help");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.out.find("run"), std::string::npos);
  r = RunPqlayout(dir, "run --help");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.out.find("--until"), std::string::npos);
}

TEST(Cli, RunWritesReportAndSurface) {
  const auto dir = testing::TempDir();
  testing::WriteFile(dir, "plane.yaml", kPlaneConfig);
  const Result r = RunPqlayout(dir, "run plane.yaml --out result --set layout.spacing=1.5");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("surface: done"), std::string::npos) << r.out;
  EXPECT_EQ(r.err, "");
  ASSERT_TRUE(fs::exists(dir + "/result/surface.obj"));
  const auto report = ReadReport(dir + "/result");
  EXPECT_EQ(report["config"]["layout"]["spacing"], 1.5);  // --set wins over the file
  EXPECT_EQ(report["config"]["surface"]["width"], 10.0);
  EXPECT_GT(report["stages"]["surface"]["seconds"].get<double>(), 0.0);
  EXPECT_NEAR(report["stages"]["surface"]["area"].get<double>(), 60.0, 1e-9);
  EXPECT_EQ(report["stages"]["surface"]["supports"]["fixed"],
            report["stages"]["surface"]["n_boundary_vertices"]);
  EXPECT_FALSE(report["pqlayout"]["git_revision"].get<std::string>().empty());
  EXPECT_TRUE(report["pqlayout"]["libraries"].contains("Ceres"));
#ifdef PQLAYOUT_JEMALLOC
  EXPECT_EQ(report["pqlayout"]["malloc"].get<std::string>().rfind("jemalloc 5.", 0), 0u) << report["pqlayout"];
#else
  EXPECT_EQ(report["pqlayout"]["malloc"], "glibc malloc");
#endif
  // Field outputs (SPEC names and columns); fields.vtk carries every field for ParaView.
  const std::string vertices = ReadFile(dir + "/result/fields/vertices.csv");
  EXPECT_EQ(vertices.rfind("id,x,y,z,vx,vy,vz\n", 0), 0u);
  EXPECT_EQ(CountLines(vertices), 1 + report["stages"]["surface"]["n_vertices"].get<int>());
  const std::string faces = ReadFile(dir + "/result/fields/faces.csv");
  EXPECT_EQ(faces.rfind("id,dx,dy,dz,strain_max,strain_min,weight\n", 0), 0u);
  EXPECT_EQ(CountLines(faces), 1 + report["stages"]["surface"]["n_faces"].get<int>());
  const std::string vtk = ReadFile(dir + "/result/fields.vtk");
  EXPECT_NE(vtk.find("POINTS " + report["stages"]["surface"]["n_vertices"].dump() + " double"), std::string::npos);
  EXPECT_NE(vtk.find("CELL_DATA " + report["stages"]["surface"]["n_faces"].dump()), std::string::npos);
  for (const char* field : {"SCALARS v_z", "VECTORS guidance", "SCALARS weight", "SCALARS phi", "SCALARS psi"})
    EXPECT_NE(vtk.find(field), std::string::npos) << field;
  EXPECT_TRUE(fs::exists(dir + "/result/figures/displacement.svg"));
  EXPECT_TRUE(fs::exists(dir + "/result/figures/guidance.svg"));
  for (const char* key : {"alignment_rms_deg", "spacing_cv_phi", "spacing_cv_psi", "conjugacy_rms",
                          "min_crossing_angle_deg", "foldovers"})
    EXPECT_TRUE(report["stages"]["levelset"].contains(key)) << key;
  EXPECT_TRUE(report["stages"]["membrane"].contains("max_displacement"));
  // report.html: self-contained, every figure inlined, the metrics shown.
  const std::string html = ReadFile(dir + "/result/report.html");
  EXPECT_EQ(html.find("src=\"http"), std::string::npos);   // nothing fetched from the network
  EXPECT_EQ(html.find("href=\"http"), std::string::npos);
  EXPECT_EQ(html.find("<img"), std::string::npos);
  size_t figures = 0;
  for (size_t at = html.find("<figure data-figure="); at != std::string::npos; at = html.find("<figure data-figure=", at + 1)) ++figures;
  // displacement, guidance, level sets, 3D view, planarity before/after, offset, compliance,
  // utilisation, and the buckling mode when the frame buckles under its load.
  const bool buckles = report["stages"]["analyze"]["buckling_factor"].is_number();
  EXPECT_EQ(fs::exists(dir + "/result/figures/buckling.svg"), buckles);
  EXPECT_EQ(fs::exists(dir + "/result/analysis/buckling_modes.csv"), buckles);
  EXPECT_EQ(figures, buckles ? 10u : 9u);
  for (const char* key : {"buckling", "buckling_factors", "utilisation_max", "utilisation_mean", "span_over_deflection",
                          "deflection_max", "members_over_utilisation"})
    EXPECT_TRUE(report["stages"]["analyze"].contains(key)) << key;
  EXPECT_EQ(html.find("data-missing"), std::string::npos);
  EXPECT_NE(html.find("alignment_rms_deg"), std::string::npos);
  EXPECT_NE(html.find("max_displacement"), std::string::npos);
  // Nothing is left behind in the parent folder.
  for (const auto& entry : fs::directory_iterator(dir))
    EXPECT_EQ(entry.path().filename().string().find(".result.partial"), std::string::npos);
}

// output.fields: false leaves out the per-element field files (sweeps, 1M-triangle runs) and
// says so nowhere else: the layout, the report and the figures are all there.
TEST(Cli, OutputFieldsFalseWritesNoFieldFiles) {
  const auto dir = testing::TempDir();
  testing::WriteFile(dir, "plane.yaml", kPlaneConfig);
  const Result r = RunPqlayout(dir, "run plane.yaml --out nofields --until extract -q --set output.fields=false");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_FALSE(fs::exists(dir + "/nofields/fields"));
  EXPECT_FALSE(fs::exists(dir + "/nofields/fields.vtk"));
  EXPECT_TRUE(fs::exists(dir + "/nofields/quads_initial.obj"));
  EXPECT_TRUE(fs::exists(dir + "/nofields/figures/guidance.svg"));
  EXPECT_EQ(ReadReport(dir + "/nofields")["config"]["output"]["fields"], false);
  const std::string html = ReadFile(dir + "/nofields/report.html");
  EXPECT_EQ(html.find("fields.vtk"), std::string::npos);
  EXPECT_NE(html.find("quads.obj"), std::string::npos);
}

// --draft (= --set levelset.draft=true --set stiffen.stop_window=5 --set stiffen.stop_gain=0.01,
// ahead of the command line's own --set values) solves the level sets on a working mesh of edge 0.8 h
// instead of 0.4 h, but at most a 16th of the shortest boundary loop: here (10 × 6 m, 32 m
// round) the 1 m reference is kept at h = 2 m (0.8 m working edge) but remeshed to 1.6 m for
// the draft, and at h = 3 m the draft's 2.4 m is capped to 2 m. An explicit
// levelset.working_edge wins over the draft.
TEST(Cli, DraftSolvesTheLevelSetsOnACoarserWorkingMesh) {
  const auto dir = testing::TempDir();
  testing::WriteFile(dir, "plane.yaml", kPlaneConfig);
  struct Working {
    int triangles;
    double edge;
    bool draft;
    int stop_window;
    double stop_gain;
  };
  const auto working = [&](const std::string& name, const std::string& flags) {
    const Result r = RunPqlayout(dir, "run plane.yaml -q --until levelset --set output.fields=false --out " + name + flags);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    const auto report = ReadReport(dir + "/" + name);
    const auto& l = report["stages"]["levelset"];
    return Working{l["working_mesh_triangles"].get<int>(), l["working_edge"].get<double>(),
                   report["config"]["levelset"]["draft"].get<bool>(),
                   report["config"]["stiffen"]["stop_window"].get<int>(),
                   report["config"]["stiffen"]["stop_gain"].get<double>()};
  };
  const Working full = working("full", ""), draft = working("draft", " --draft"),
                pinned = working("pinned", " --draft --set levelset.working_edge=0.8"),
                capped = working("capped", " --draft --set layout.spacing=3");
  EXPECT_FALSE(full.draft);
  EXPECT_TRUE(draft.draft);
  EXPECT_EQ(full.stop_window, 20);
  EXPECT_EQ(full.stop_gain, 0.005);
  EXPECT_EQ(draft.stop_window, 5);
  EXPECT_EQ(draft.stop_gain, 0.01);
  // The command line's own --set values win over --draft's, wherever they stand.
  const Working own = working("own", " --set stiffen.stop_window=9 --draft --set levelset.draft=false");
  EXPECT_FALSE(own.draft);
  EXPECT_EQ(own.stop_window, 9);
  EXPECT_EQ(own.stop_gain, 0.01);
  EXPECT_EQ(own.triangles, full.triangles);
  EXPECT_DOUBLE_EQ(full.edge, 0.8);
  EXPECT_DOUBLE_EQ(draft.edge, 1.6);
  EXPECT_LT(draft.triangles, full.triangles / 2) << full.triangles;
  EXPECT_DOUBLE_EQ(pinned.edge, 0.8);
  EXPECT_EQ(pinned.triangles, full.triangles);
  EXPECT_NEAR(capped.edge, 2.0, 1e-9);
  // report.html says a draft is one, under its title.
  EXPECT_NE(ReadFile(dir + "/draft/report.html").find("<strong>draft</strong>"), std::string::npos);
  EXPECT_EQ(ReadFile(dir + "/full/report.html").find("<strong>draft</strong>"), std::string::npos);
}

// levelset.working_triangles: the working edge is at least that of N equilateral triangles
// over the roof, √(4A / (√3 N)), never coarser than a 16th of the shortest boundary loop nor than
// 1.5 h, never finer than 0.4 h. The 10 × 6 m plane at h = 2 m (0.4 h = 0.8 m, the loop 32 m: at
// most 2 m): N = 60 → 1.520 m; N = 20 → 2.632 m, held at 2 m by the loop; the default (12,000)
// and 0 leave 0.8 m.
TEST(Cli, TheWorkingMeshHasATriangleBudget) {
  const auto dir = testing::TempDir();
  testing::WriteFile(dir, "plane.yaml", kPlaneConfig);
  const auto levelset = [&](const std::string& name, const std::string& flags) {
    const Result r = RunPqlayout(dir, "run plane.yaml -q --until levelset --set output.fields=false --out " + name + flags);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return ReadReport(dir + "/" + name)["stages"]["levelset"];
  };
  const double area = 60.0, sqrt3_4 = std::sqrt(3.0) / 4.0;
  const auto budget60 = levelset("budget60", " --set levelset.working_triangles=60");
  EXPECT_NEAR(budget60["working_edge"].get<double>(), std::sqrt(area / (sqrt3_4 * 60)), 1e-9);  // 1.520 m
  EXPECT_GE(budget60["working_mesh_triangles"].get<int>(), 30);
  EXPECT_LE(budget60["working_mesh_triangles"].get<int>(), 120);
  EXPECT_NEAR(levelset("budget20", " --set levelset.working_triangles=20")["working_edge"].get<double>(), 2.0, 1e-9);
  // At h = 1 m the same 2.632 m is held at 1.5 h, below the loop's 2 m.
  EXPECT_NEAR(levelset("budget20h1", " --set levelset.working_triangles=20 --set layout.spacing=1")["working_edge"].get<double>(),
              1.5, 1e-9);
  EXPECT_DOUBLE_EQ(levelset("nobudget", " --set levelset.working_triangles=0")["working_edge"].get<double>(), 0.8);
  EXPECT_DOUBLE_EQ(levelset("default", "")["working_edge"].get<double>(), 0.8);
  EXPECT_DOUBLE_EQ(levelset("pinned", " --set levelset.working_triangles=60 --set levelset.working_edge=0.9")["working_edge"].get<double>(), 0.9);
}

TEST(Cli, UntilStopsAfterTheStageAndRemovesStaleOutputs) {
  const auto dir = testing::TempDir();
  testing::WriteFile(dir, "plane.yaml", kPlaneConfig);
  fs::create_directories(dir + "/result/figures");
  testing::WriteFile(dir + "/result", "report.json", "{}");
  testing::WriteFile(dir + "/result/figures", "old.svg", "<svg/>");
  testing::WriteFile(dir + "/result", "notes.txt", "mine");
  const Result r = RunPqlayout(dir, "run plane.yaml --out result --until surface");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto report = ReadReport(dir + "/result");
  EXPECT_EQ(report["run"]["completed_stages"], nlohmann::json::array({"surface"}));
  EXPECT_EQ(report["run"]["until"], "surface");
  EXPECT_FALSE(fs::exists(dir + "/result/figures/old.svg"));  // a stale output of an earlier run
  EXPECT_TRUE(fs::exists(dir + "/result/notes.txt"));          // not ours: kept
}

TEST(Cli, ReadsTheSurfaceFromAFile) {
  const auto dir = testing::TempDir();
  testing::WriteFile(dir, "roof.obj", testing::ObjText(testing::FlatGridSoup(4)));
  testing::WriteFile(dir, "c.yaml", "surface:\n  file: roof.obj\nlayout:\n  spacing: 1\nboundary:\n  default: free\n"
                                    "  rules:\n    - select: corners\n      condition: fixed\n");
  const Result r = RunPqlayout(dir, "run c.yaml --out o");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto report = ReadReport(dir + "/o");
  EXPECT_EQ(report["stages"]["surface"]["n_faces"], 32);
  EXPECT_EQ(report["stages"]["surface"]["supports"]["fixed"], 4);
  EXPECT_EQ(report["stages"]["surface"]["supports"]["free"], 12);
}

struct BadInput {
  std::string config, args, expected;
};

TEST(Cli, BadInputGivesOneLineExitTwoAndNoOutput) {
  const auto dir = testing::TempDir();
  testing::WriteFile(dir, "broken.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n");
  // OpenMesh's PLY reader segfaulted on this (a property before any element).
  testing::WriteFile(dir, "hostile.ply", "ply\nformat ascii 1.0\nproperty float x\nend_header\n");
  const std::vector<BadInput> cases = {
      {"levelset:\n  wieghts:\n    alignment: 2\n", "", "c.yaml:2: unknown key 'levelset.wieghts'"},
      {"surface:\n  file: missing.obj\n", "", "missing.obj: file not found"},
      {"surface:\n  file: broken.obj\n", "", "broken.obj: face 0 is degenerate"},
      {"surface:\n  file: hostile.ply\n", "", "hostile.ply:3: 'property' before any 'element'"},
      {"layout:\n  spacing: -3\n", "", "c.yaml:2: layout.spacing: must be > 0 (got -3)"},
      {"", "--set layout.spacing=x", "--set layout.spacing=x: layout.spacing: expected a number"},
      {"", "--until levelsets", "--until: levelsets not in"},
      {"surface:\n  generator: plane\n  edge_length: 1e-7\n", "", "surface.edge_length"},
      {"boundary:\n  rules:\n    - select: inner\n      condition: free\n",
       "--set surface.generator=plane --set surface.edge_length=2", "c.yaml:3: boundary.rules[0]: selects inner loops"},
  };
  for (const auto& c : cases) {
    testing::WriteFile(dir, "c.yaml", c.config);
    const Result r = RunPqlayout(dir, "run c.yaml --out bad " + c.args);
    EXPECT_EQ(r.exit_code, 2) << c.expected << "\n" << r.err;
    EXPECT_EQ(CountLines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find(c.expected), std::string::npos) << r.err;
    EXPECT_EQ(r.err.rfind("pqlayout: error: ", 0), 0u) << r.err;
    EXPECT_FALSE(fs::exists(dir + "/bad")) << c.expected;
  }
  const Result missing = RunPqlayout(dir, "run nothing.yaml");
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(missing.err.find("nothing.yaml: config file not found"), std::string::npos);
  const Result unknown = RunPqlayout(dir, "fly");
  EXPECT_EQ(unknown.exit_code, 2);
  EXPECT_EQ(CountLines(unknown.err), 1) << unknown.err;
}

// λ₁ < 1 (the frame buckles before it carries its load) is a warning in report.json and at the
// top of report.html, λ₁ > 1 is not. The frame's load (self-weight and panels) scaled by 1e-2 and 1e2 (λ₁ ≈ 11 unscaled);
// curvature guidance, so that the layout does not depend on the load.
TEST(Cli, ABucklingFactorBelowOneIsAWarningInTheReport) {
  const auto dir = testing::TempDir();
  testing::WriteFile(dir, "dome.yaml", kDomeConfig + "guidance:\n  source: curvature\n");
  double factor[2] = {0.0, 0.0};
  const char* loads[2] = {"--set analysis.gravity=0.0981 --set analysis.panel_load=10",
                          "--set analysis.gravity=981 --set analysis.panel_load=100000"};
  for (int k = 0; k < 2; ++k) {
    const std::string out = k == 0 ? "light" : "heavy";
    const Result r = RunPqlayout(dir, "run dome.yaml -q --out " + out + " " + loads[k]);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto report = ReadReport(dir + "/" + out);
    ASSERT_TRUE(report["stages"]["analyze"]["buckling_factor"].is_number()) << report["stages"]["analyze"];
    factor[k] = report["stages"]["analyze"]["buckling_factor"].get<double>();
    bool warned = false;
    for (const auto& w : report["warnings"]) warned |= w.get<std::string>().rfind("analyze: the frame buckles at ", 0) == 0;
    EXPECT_EQ(warned, factor[k] < 1.0) << loads[k] << ": λ1 " << factor[k] << " " << report["warnings"];
    // report.html says it first: the targets met and missed, and every warning.
    const std::string html = ReadFile(dir + "/" + out + "/report.html");
    const size_t checks = html.find("<div class=\"checks");
    ASSERT_NE(checks, std::string::npos);
    EXPECT_LT(checks, html.find("<h2>Summary</h2>"));
    EXPECT_NE(html.find("Layout targets: " + std::to_string(report["targets"]["met"].get<int>()) + " of 11 met"),
              std::string::npos);
    EXPECT_EQ(html.find("<li>analyze: the frame buckles at ") != std::string::npos, factor[k] < 1.0) << out;
    EXPECT_EQ(html.find("<p>No warnings.</p>") != std::string::npos, report["warnings"].empty()) << out;
  }
  EXPECT_GT(factor[0], 1.0);
  EXPECT_LT(factor[1], 1.0);
  // λ₁ ∝ 1/load on one layout (stiffen, minimising a compliance ∝ load², may end a step apart).
  EXPECT_NEAR(factor[0] / factor[1], 1e4, 1e3);
}

// extract.brace_free_edges = none and all decide nothing after stiffen: the stage once read the
// decision's record, null for both, and every such run ended in an internal error (exit 1).
TEST(Cli, EveryFreeEdgeBracingChoiceRunsToTheEnd) {
  const auto dir = testing::TempDir();
  testing::WriteFile(dir, "dome.yaml", kDomeConfig);
  for (const std::string choice : {"none", "all"}) {
    const Result r = RunPqlayout(dir, "run dome.yaml -q --out braced_" + choice + " --set extract.brace_free_edges=" + choice);
    ASSERT_EQ(r.exit_code, 0) << choice << ": " << r.err;
    const auto report = ReadReport(dir + "/braced_" + choice);
    EXPECT_GT(report["stages"]["stiffen"]["compliance_after"].get<double>(), 0.0) << choice;
    EXPECT_FALSE(report["stages"]["stiffen"].contains("bracing")) << choice;
    EXPECT_TRUE(fs::exists(dir + "/braced_" + choice + "/figures/shell_3d.svg")) << choice;
  }
}

TEST(Cli, CompareRunsBothGuidanceSourcesAndTabulates) {
  const auto dir = testing::TempDir();
  testing::WriteFile(dir, "dome.yaml", kDomeConfig);
  const Result r = RunPqlayout(dir, "compare dome.yaml --out cmp");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* source : {"strain", "curvature"}) {
    const auto report = ReadReport(dir + "/cmp/" + source);
    EXPECT_EQ(report["config"]["guidance"]["source"], source);
    EXPECT_TRUE(report["stages"].contains("analyze")) << source;
    // layout.density auto → both layouts at mean panel area h² (the scale is not 1).
    EXPECT_EQ(report["config"]["layout"]["density"], "panel_area") << source;
    EXPECT_GT(std::abs(report["stages"]["levelset"]["density_scale"].get<double>() - 1.0), 1e-6) << source;
  }
  const auto comparison = nlohmann::json::parse(ReadFile(dir + "/cmp/compare.json"));
  bool has_mean = false;
  for (const auto& row : comparison["rows"]) {
    if (row["metric"] != "compliance_node_mean") continue;
    has_mean = true;
    EXPECT_GT(row["strain"].get<double>(), 0.0);
    EXPECT_GT(row["curvature"].get<double>(), 0.0);
    EXPECT_NEAR(row["difference_percent"].get<double>(),
                100.0 * (row["strain"].get<double>() / row["curvature"].get<double>() - 1.0), 1e-9);
  }
  EXPECT_TRUE(has_mean);
  for (const auto& row : comparison["rows"]) {  // the curvature run has no fallback; strain's covers a share
    if (row["metric"] != "area_fallback") continue;
    EXPECT_EQ(row["curvature"].get<double>(), 0.0);
    EXPECT_GE(row["strain"].get<double>(), 0.0);
    EXPECT_LE(row["strain"].get<double>(), 1.0);
    EXPECT_TRUE(row["difference_percent"].is_null());
  }
  // Each run's checks (targets met, warnings) in the comparison page too.
  const std::string page = ReadFile(dir + "/cmp/report.html");
  size_t boxes = 0;
  for (size_t at = page.find("<div class=\"checks"); at != std::string::npos; at = page.find("<div class=\"checks", at + 1)) ++boxes;
  EXPECT_EQ(boxes, 2u);
  for (const char* figure : {"compliance_strain.svg", "compliance_curvature.svg"}) {
    const std::string svg = ReadFile(dir + "/cmp/figures/" + figure);
    EXPECT_EQ(svg.rfind("<svg", 0), 0u) << figure;
    EXPECT_NE(svg.find("nodal compliance [J]"), std::string::npos) << figure;
  }
  // The strain figure says that its layout is not the paper's (the default curvature fallback).
  EXPECT_NE(ReadFile(dir + "/cmp/figures/compliance_strain.svg").find("strain-guided layout; curvature lines where weak"),
            std::string::npos);
  EXPECT_EQ(ReadFile(dir + "/cmp/figures/compliance_curvature.svg").find("where weak"), std::string::npos);
  EXPECT_TRUE(fs::exists(dir + "/cmp/strain/figures/compliance.svg"));
  const std::string table = ReadFile(dir + "/cmp/compare/table.md");
  EXPECT_EQ(table.rfind("| metric | strain guidance | curvature guidance | strain vs curvature |", 0), 0u);
  for (size_t at = 0, line = 0; (at = table.find('\n', at)) != std::string::npos; ++at, ++line) {
    const size_t start = table.rfind('\n', at - 1);
    const std::string row = table.substr(start == std::string::npos ? 0 : start + 1, at - (start == std::string::npos ? 0 : start + 1));
    EXPECT_EQ(std::count(row.begin(), row.end(), '|'), 5) << row;  // well-formed Markdown rows
  }
}

TEST(Cli, KeysPrintsTheReference) {
  const auto dir = testing::TempDir();
  const Result r = RunPqlayout(dir, "keys");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.out.find("`levelset.weights.alignment`"), std::string::npos);
}

}  // namespace
}  // namespace pqlayout

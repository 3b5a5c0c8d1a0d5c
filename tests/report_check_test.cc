// The report check (scripts/check_report.sh) in headless Chromium: a real run's report.html
// passes with every figure measured and a screenshot written; the same report with one
// figure replaced by an empty frame (title, colour bar, scale bar, no data) or with a figure
// missing fails and names the figure; a page whose figures claim to be fine but renders
// blank fails on its screenshot. The 3D view (report/report_view3d.h): the real report's
// passes its self-check (drawn, not blank, changes when the camera turns); one whose data
// hold no faces, or whose data cannot be read, fails and names the 3D view. Skipped, with a
// message, where /usr/bin/chromium is absent.
// Also (no browser needed) the 3D section's content, and the page `compare` writes: table,
// both runs, figures in pairs.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>

#include <nlohmann/json.hpp>

#include "report/svg_canvas.h"
#include "base/output_files.h"
#include "report/report_html.h"
#include "report/report_view3d.h"
#include "tests/test_meshes.h"

namespace pqlayout {
namespace {

namespace fs = std::filesystem;

constexpr const char* kChromium = "/usr/bin/chromium";
const char* kFigures[] = {"displacement.svg",      "guidance.svg",  "levelsets.svg", "shell_3d.svg",
                          "planarity_initial.svg", "planarity.svg", "compliance.svg"};

std::string ReadAll(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

struct Result {
  int exit_code = -1;
  std::string out;
};

Result RunIn(const std::string& dir, const std::string& command) {
  const int status = std::system(("cd '" + dir + "' && " + command + " > out.txt 2>&1").c_str());
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, ReadAll(dir + "/out.txt")};
}

Result CheckReport(const std::string& dir, const std::string& report, const std::string& shot = "") {
  return RunIn(dir, "bash '" PQLAYOUT_SOURCE_DIR "/scripts/check_report.sh' '" + report + "' " + shot);
}

class ReportCheck : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!fs::exists(kChromium))
      GTEST_SKIP() << "report check skipped: " << kChromium
                   << " not installed (Debian package chromium); scripts/check_report.sh needs it";
    dir_ = testing::TempDir();
    testing::WriteFile(dir_, "dome.yaml",
                       "surface:\n  generator: dome\n  width: 18\n  depth: 15\n  rise: 4\n"
                       "  edge_length: 1.0\nlayout:\n  spacing: 3.0\n");
    const Result run = RunIn(dir_, "'" PQLAYOUT_BINARY "' run dome.yaml --out run -q");
    ASSERT_EQ(run.exit_code, 0) << run.out;
    report_ = nlohmann::json::parse(ReadAll(dir_ + "/run/report.json"));
  }

  // A copy of the run's report in dir_/NAME with its figures copied, except those in
  // `replace`: written with the given text instead, or left out if the text is empty.
  std::string Rebuild(const std::string& name, const std::map<std::string, std::string>& replace) {
    std::unique_ptr<OutputFiles> out;
    EXPECT_TRUE(OutputFiles::Open(dir_ + "/" + name, &out).ok());
    for (const char* figure : kFigures) {
      const std::string target = out->Path(std::string("figures/") + figure);
      const auto it = replace.find(figure);
      if (it == replace.end())
        fs::copy_file(dir_ + "/run/figures/" + figure, target);
      else if (!it->second.empty())
        std::ofstream(target) << it->second;
    }
    EXPECT_TRUE(WriteReportHtml(report_, out.get()).ok());
    EXPECT_TRUE(out->Commit().ok());
    return dir_ + "/" + name + "/report.html";
  }

  std::string dir_;
  nlohmann::json report_;
};

TEST_F(ReportCheck, RealReportPassesWithEveryFigureAndAScreenshot) {
  const Result r = CheckReport(dir_, dir_ + "/run/report.html", dir_ + "/shot.png");
  EXPECT_EQ(r.exit_code, 0) << r.out;
  for (const char* figure : kFigures) EXPECT_NE(r.out.find(std::string("ok   ") + figure), std::string::npos) << figure << "\n" << r.out;
  EXPECT_NE(r.out.find("ok   screenshot"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("ok   3D view (w="), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("FAIL"), std::string::npos) << r.out;
  ASSERT_TRUE(fs::exists(dir_ + "/shot.png"));
  EXPECT_GT(fs::file_size(dir_ + "/shot.png"), 10000u);
}

TEST_F(ReportCheck, EmptyOrMissingFigureFails) {
  // A frame without data: everything a figure has around its plot.
  SvgCanvas frame(Eigen::AlignedBox2d(Eigen::Vector2d(0, 0), Eigen::Vector2d(18, 15)), 1000, "Planarity δ");
  frame.LogColourBar(BlueWhiteRed, 1e-5, 1e-1, "planarity δ", {{1e-3, "target"}});
  frame.ScaleBar();
  frame.NorthArrow();
  const Result r = CheckReport(
      dir_, Rebuild("broken", {{"planarity.svg", frame.ToSvg()}, {"compliance.svg", ""}, {"levelsets.svg", "not an svg"}}));
  EXPECT_EQ(r.exit_code, 1) << r.out;
  EXPECT_NE(r.out.find("FAIL planarity.svg: empty plot"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("FAIL compliance.svg: missing"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("FAIL levelsets.svg: missing"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("ok   planarity_initial.svg"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("ok   shell_3d.svg"), std::string::npos) << r.out;
}

// The real report with its 3D data edited: no faces (a view that draws nothing), or data
// that are not JSON (the view's script gives up). Both fail, naming the 3D view; the figures
// stay fine.
TEST_F(ReportCheck, Empty3dViewFails) {
  std::string html = ReadAll(dir_ + "/run/report.html");
  const size_t faces = html.find("\"faces\":[");
  ASSERT_NE(faces, std::string::npos);
  const size_t start = faces + std::string("\"faces\":[").size();
  html.erase(start, html.find(']', start) - start);
  const Result r = CheckReport(dir_, testing::WriteFile(dir_, "no_faces.html", html));
  EXPECT_EQ(r.exit_code, 1) << r.out;
  EXPECT_NE(r.out.find("FAIL 3D view: no faces drawn"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("ok   planarity.svg"), std::string::npos) << r.out;
}

TEST_F(ReportCheck, Broken3dViewFails) {
  std::string html = ReadAll(dir_ + "/run/report.html");
  const std::string data = "<script type=\"application/json\" id=\"view3d-data\">";
  const size_t at = html.find(data);
  ASSERT_NE(at, std::string::npos);
  html.insert(at + data.size(), "not json");
  const Result r = CheckReport(dir_, testing::WriteFile(dir_, "broken_view.html", html));
  EXPECT_EQ(r.exit_code, 1) << r.out;
  EXPECT_NE(r.out.find("FAIL 3D view: script failed"), std::string::npos) << r.out;
}

// Figures whose measurements look fine but a page that shows nothing: the screenshot check
// is what fails.
TEST_F(ReportCheck, BlankScreenshotFails) {
  const std::string page = testing::WriteFile(
      dir_, "blank.html",
      "<!DOCTYPE html><html><body data-checked=\"1\" data-page-height=\"800\">"
      "<figure data-figure=\"x.svg\" data-check=\"w=600 h=600 marks=99 ink=0.5 colours=99\"></figure>"
      "</body></html>\n");
  const Result r = CheckReport(dir_, page);
  EXPECT_EQ(r.exit_code, 1) << r.out;
  EXPECT_NE(r.out.find("ok   x.svg"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("FAIL screenshot"), std::string::npos) << r.out;
}

// A 3×2 grid of quads, z = x·y/10 (not planar), for the 3D section without a run.
PolyMesh SmallShell() {
  PolyMesh mesh;
  std::vector<VertexHandle> v;
  for (int j = 0; j <= 2; ++j)
    for (int i = 0; i <= 3; ++i) v.push_back(mesh.add_vertex(PolyMesh::Point(i, j, i * j / 10.0)));
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 3; ++i)
      mesh.add_face(std::vector<VertexHandle>{v[4 * j + i], v[4 * j + i + 1], v[4 * j + i + 5], v[4 * j + i + 4]});
  return mesh;
}

// The 3D section (no browser needed): data, metrics, three.js inlined; metrics whose
// values are unusable left out; no section without faces, nor without a shell at all.
TEST(View3dSection, HoldsDataMetricsAndThreeJs) {
  const PolyMesh mesh = SmallShell();
  const std::vector<double> compliance(mesh.n_vertices(), 2.5), offset(mesh.n_vertices(), 0.01);
  View3dData data;
  data.shell = &mesh;
  data.nodal_compliance = &compliance;
  data.normal_offset = &offset;
  data.offset_tolerance = 0.1;
  const std::string html = View3dHtml(data);
  EXPECT_NE(html.find("<section id=\"view3d\" data-faces=\"6\">"), std::string::npos);
  EXPECT_NE(html.find("\"faces\":[4,0,1,5,4,4,1,2,6,5,"), std::string::npos);
  EXPECT_NE(html.find("\"name\":\"nodal compliance"), std::string::npos);
  EXPECT_NE(html.find("\"unit\":\"J\",\"log\":false,\"lo\":0,\"hi\":2.5,\"min\":2.5,\"max\":2.5"), std::string::npos);
  EXPECT_NE(html.find("\"name\":\"planarity δ"), std::string::npos);
  EXPECT_NE(html.find("\"unit\":\"mm\",\"log\":false,\"lo\":-100,\"hi\":100,\"min\":10,\"max\":10"), std::string::npos);
  EXPECT_NE(html.find("THREE.OrbitControls"), std::string::npos);  // three.js and the controls, inlined
  EXPECT_NE(html.find("REVISION"), std::string::npos);
  EXPECT_EQ(html.find("<script src"), std::string::npos);  // nothing to fetch
  int opened = 0, closed = 0;  // no "</script" inside the inlined code ends an element early
  for (size_t at = html.find("<script"); at != std::string::npos; at = html.find("<script", at + 1)) ++opened;
  for (size_t at = html.find("</script>"); at != std::string::npos; at = html.find("</script>", at + 1)) ++closed;
  EXPECT_EQ(opened, 4);
  EXPECT_EQ(closed, 4);

  std::vector<double> bad = compliance;
  bad[3] = std::nan("");
  data.nodal_compliance = &bad;
  data.offset_tolerance = 0.0;  // stiffen off: no offset
  const std::string fewer = View3dHtml(data);
  EXPECT_EQ(fewer.find("nodal compliance"), std::string::npos);
  EXPECT_EQ(fewer.find("normal offset"), std::string::npos);
  EXPECT_NE(fewer.find("planarity δ"), std::string::npos);

  const PolyMesh empty;
  data.shell = &empty;
  EXPECT_EQ(View3dHtml(data), "");
  EXPECT_EQ(View3dHtml(View3dData{}), "");
}

// DIR/report.html after compare (no browser needed): the comparison table, the two runs'
// summaries, the figures in strain/curvature pairs with their ids made unique per figure,
// and a figure absent from one run marked missing.
TEST(CompareReport, TableRunsAndFiguresSideBySide) {
  const std::string dir = testing::TempDir();
  SvgCanvas canvas(Eigen::AlignedBox2d(Eigen::Vector2d(0, 0), Eigen::Vector2d(10, 10)), 1000, "figure");
  canvas.ColourBar(Viridis, 0.0, 1.0, "value");  // defines a gradient with id "g0"
  const std::string svg = canvas.ToSvg();
  ASSERT_NE(svg.find("id=\"g0\""), std::string::npos);
  fs::create_directories(dir + "/figures");
  testing::WriteFile(dir + "/figures", "compliance_strain.svg", svg);
  testing::WriteFile(dir + "/figures", "compliance_curvature.svg", svg);
  for (const char* source : {"strain", "curvature"}) {
    fs::create_directories(dir + "/" + source + "/figures");
    for (const char* figure : {"levelsets.svg", "planarity.svg", "shell_3d.svg", "guidance.svg"})
      if (!(std::string(source) == "curvature" && std::string(figure) == "shell_3d.svg"))
        testing::WriteFile(dir + "/" + source + "/figures", figure, svg);
    testing::WriteFile(dir + "/" + source, "report.json",
                       nlohmann::json{{"config", {{"guidance", {{"source", source}}}}},
                                      {"run", {{"completed_stages", {"surface"}}}},
                                      {"stages", {{"surface", {{"seconds", 0.5}}}}}}
                           .dump());
  }
  const nlohmann::json comparison = {
      {"config_file", "dome.yaml"},
      {"rows",
       {{{"label", "compliance total [J]"}, {"strain", 422.5}, {"curvature", 365.0}, {"difference_percent", 15.75}},
        {{"label", "nodes"}, {"strain", 50}, {"curvature", 50}, {"difference_percent", 0.0}}}}};
  ASSERT_TRUE(WriteCompareReportHtml(comparison, dir).ok());
  const std::string html = ReadAll(dir + "/report.html");
  EXPECT_NE(html.find("<td>compliance total [J]</td><td class=\"num\">422.5</td><td class=\"num\">365</td>"
                      "<td class=\"num\">+15.8 %</td>"),
            std::string::npos);
  EXPECT_NE(html.find("<h3>strain guidance</h3>"), std::string::npos);
  EXPECT_NE(html.find("<td>guidance</td><td>curvature, threshold –</td>"), std::string::npos);
  int figures = 0, missing = 0;
  for (size_t at = html.find("<figure data-figure="); at != std::string::npos; at = html.find("<figure data-figure=", at + 1))
    ++figures;
  for (size_t at = html.find("data-missing"); at != std::string::npos; at = html.find("data-missing", at + 1)) ++missing;
  EXPECT_EQ(figures, 10);
  EXPECT_EQ(missing, 1);
  EXPECT_NE(html.find("curvature/shell_3d.svg was not written"), std::string::npos);
  // Each inlined figure's gradient id is its own, and its fill refers to it (figure 7, the
  // missing curvature/shell_3d.svg, has none).
  for (const int k : {0, 1, 2, 3, 4, 5, 6, 8, 9}) {
    const std::string id = "f" + std::to_string(k) + "-g0";
    EXPECT_NE(html.find("id=\"" + id + "\""), std::string::npos) << id;
    EXPECT_NE(html.find("url(#" + id + ")"), std::string::npos) << id;
  }
  EXPECT_EQ(html.find("id=\"g0\""), std::string::npos);
}

}  // namespace
}  // namespace pqlayout

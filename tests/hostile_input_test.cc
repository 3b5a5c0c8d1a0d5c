// Hostile input (issue 15): ids, files, meshes and spacings a user can get wrong. Every case
// is refused with one line naming the key, file or element (and exit 2, no output folder,
// through the executable), or runs with a result that means something.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>

#include "geometry/mesh_io.h"
#include "geometry/mesh_validation.h"
#include "problems/boundary_conditions.h"
#include "problems/guidance.h"
#include "pipeline/layout_checks.h"
#include "base/output_files.h"
#include "tests/test_cli.h"
#include "tests/test_meshes.h"

namespace pqlayout {
namespace {

namespace fs = std::filesystem;
using testing::FlatGridSoup;

void ExpectRefused(const Status& s, const std::string& expected) {
  EXPECT_EQ(s.code(), StatusCode::kInvalidInput) << expected;
  EXPECT_NE(s.message().find(expected), std::string::npos) << "message: " << s.message();
  EXPECT_EQ(s.message().find('\n'), std::string::npos) << s.message();
}

// A 10 m × 10 m grid of unit squares with one triangle removed near its middle: a hole
// 1.41 m across (the removed triangle's diagonal).
PolygonSoup GridWithOneTriangleHole() {
  PolygonSoup soup = FlatGridSoup(10);
  soup.faces.erase(soup.faces.begin() + 2 * (5 * 10 + 5));
  return soup;
}

// --- boundary ids -------------------------------------------------------------------------

// One boundary rule on a 4 × 4 grid of unit squares (25 vertices, 16 on the boundary),
// written at c.yaml:7.
struct OneRule {
  SurfaceModel surface{testing::ToMesh(FlatGridSoup(4))};
  BoundaryRule rule;
  VertexConditions conditions;

  explicit OneRule(BoundarySelector::Kind kind) {
    rule.select.kind = kind;
    rule.origin = "c.yaml:7";
  }
  Status Resolve() {
    BoundaryOptions options;
    options.rules = {rule};
    return ResolveBoundaryConditions(options, surface, 30.0, &conditions);
  }
};

TEST(HostileIds, NegativeAndMissingIdsAreRefusedNotIndexed) {
  OneRule r(BoundarySelector::Kind::kIds);
  // Once `v >= n` only: -1 wrote before the per-vertex vector (heap corruption, exit 134).
  for (const int id : {-1, -2147483647 - 1, 25, 1000}) {
    r.rule.select.ids = {0, id};
    ExpectRefused(r.Resolve(), "c.yaml:7: boundary.rules[0]: vertex " + std::to_string(id) +
                                   " does not exist (the surface has 25 vertices, numbered from 0)");
  }
  r.rule.select.ids = {12};  // the grid's centre
  ExpectRefused(r.Resolve(), "c.yaml:7: boundary.rules[0]: vertex 12 is not a boundary vertex");
}

// Ids name the vertices of the file, in its order: before, the mesh's numbering was used, so
// unused vertices before the roof's (other objects of the export) or welded seam copies
// shifted every id onto another vertex, silently.
TEST(HostileIds, IdsAreTheFilesVerticesThoughUnusedAndWeldedOnesAreDropped) {
  PolygonSoup soup;
  soup.points = {{50, 50, 0}, {60, 50, 0}};  // used by no face
  for (const double x0 : {0.0, 2.0})         // two 2 × 2 patches, the seam x = 2 unwelded
    for (int j = 0; j <= 2; ++j)
      for (int i = 0; i <= 2; ++i) soup.points.emplace_back(x0 + i, j, 0.0);
  for (const int base : {2, 11})
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i) {
        const int a = base + 3 * j + i;
        soup.faces.push_back({a, a + 1, a + 4});
        soup.faces.push_back({a, a + 4, a + 3});
      }
  const auto dir = testing::TempDir();
  testing::WriteFile(dir, "two_patches.obj", testing::ObjText(soup));
  TriMesh mesh;
  std::vector<int> file_vertex;
  ASSERT_TRUE(ReadSurfaceMesh(dir + "/two_patches.obj", &mesh, 0.0, &file_vertex).ok());
  ASSERT_EQ(file_vertex.size(), 20u);
  const SurfaceModel surface(std::move(mesh));
  ASSERT_EQ(surface.num_vertices(), 15);  // 18 minus the 3 seam copies
  BoundaryOptions options;
  options.default_condition = BoundaryCondition::kFree;
  options.rules.push_back({});
  options.rules[0].select.kind = BoundarySelector::Kind::kIds;
  options.rules[0].select.ids = {19, 11};  // (4, 2): the far corner; (2, 0): a seam copy
  VertexConditions conditions;
  ASSERT_TRUE(ResolveBoundaryConditions(options, surface, 30.0, &conditions, &file_vertex).ok());
  std::vector<Eigen::Vector3d> fixed;
  for (int v = 0; v < surface.num_vertices(); ++v)
    if (conditions[v] == BoundaryCondition::kFixed) fixed.push_back(surface.position(v));
  ASSERT_EQ(fixed.size(), 2u);
  EXPECT_EQ(fixed[0], Eigen::Vector3d(2, 0, 0));  // the seam vertex, written first as id 4
  EXPECT_EQ(fixed[1], Eigen::Vector3d(4, 2, 0));
  options.rules[0].select.ids = {1};
  ExpectRefused(ResolveBoundaryConditions(options, surface, 30.0, &conditions, &file_vertex),
                "vertex 1 is used by no triangle of the file");
  options.rules[0].select.ids = {20};
  ExpectRefused(ResolveBoundaryConditions(options, surface, 30.0, &conditions, &file_vertex),
                "vertex 20 does not exist (the file has 20 vertices, numbered from 0)");
}

TEST(HostileIds, IdsFileErrorsNameTheFileAndLine) {
  const auto dir = testing::TempDir();
  OneRule r(BoundarySelector::Kind::kIdsFile);
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"0, 1\n# a comment\n-3\n",
       "ids.txt:3: '-3' is not a vertex id (ids are whole numbers from 0) (c.yaml:7: boundary.rules[0])"},
      {"0 1.5\n", "ids.txt:1: '1.5' is not a vertex id"},
      {"99999999999999999999\n", "ids.txt:1: '99999999999999999999' is not a vertex id"},
      {"0\n\n2 77\n",
       "ids.txt:3: vertex 77 does not exist (the surface has 25 vertices, numbered from 0) (c.yaml:7: boundary.rules[0])"},
      {"6\n", "ids.txt:1: vertex 6 is not a boundary vertex"},
      {"# nothing\n", "c.yaml:7: boundary.rules[0]: selects no boundary vertex"},
  };
  for (const auto& [text, expected] : cases) {
    r.rule.select.ids_file = testing::WriteFile(dir, "ids.txt", text);
    ExpectRefused(r.Resolve(), expected);
  }
  r.rule.select.ids_file = dir;  // a folder opens as a stream on Linux and reads as empty
  ExpectRefused(r.Resolve(), dir + ": not a vertex-id file (a folder?)");
  r.rule.select.ids_file = testing::WriteFile(dir, "ids.txt", "0\r\n4\r\n");  // Windows line ends
  r.rule.condition = BoundaryCondition::kFree;
  ASSERT_TRUE(r.Resolve().ok());
  EXPECT_EQ(r.conditions[0], BoundaryCondition::kFree);
  EXPECT_EQ(r.conditions[4], BoundaryCondition::kFree);
  EXPECT_EQ(r.conditions[1], BoundaryCondition::kFixed);  // boundary.default
}

// --- guidance file ------------------------------------------------------------------------

Status ReadGuidance(const SurfaceModel& surface, const std::string& path, GuidanceField* field) {
  GuidanceOptions options;
  options.source = "file";
  options.file = path;
  return ReadGuidanceFile(surface, options, field);
}

// Rows "id,dx,dy,dz" for every face of an n × n grid (2 n² faces), direction (1, 0, 0).
std::string Rows(int faces, const std::string& direction = "1,0,0") {
  std::string text;
  for (int f = 0; f < faces; ++f) text += std::to_string(f) + "," + direction + "\n";
  return text;
}

TEST(HostileGuidance, EveryMalformedLineIsNamed) {
  const auto dir = testing::TempDir();
  const SurfaceModel surface(testing::ToMesh(FlatGridSoup(2)));  // 8 faces
  GuidanceField field;
  const std::vector<std::pair<std::string, std::string>> cases = {
      // once exit 1 with Ceres' three-line report and a pointer address
      {Rows(8, "0,0,0"), "g.csv:1: every direction is zero or normal to the surface"},
      {"id,dx,dy,dz\n" + Rows(8, "0,0,2.5"), "g.csv:2: every direction is zero or normal to the surface"},
      // once "face id 0" (the last word of the line) and a float-to-int cast of NaN
      {"nan,1,0,0\n" + Rows(8), "g.csv:1: face id 'nan' is not a face of the surface (ids 0 to 7)"},
      {"1e300,1,0,0\n", "g.csv:1: face id '1e300' is not a face of the surface"},
      {"-1,1,0,0\n", "g.csv:1: face id '-1' is not a face of the surface"},
      {"2.5,1,0,0\n", "g.csv:1: face id '2.5' is not a face of the surface"},
      {"0,nan,0,0\n", "g.csv:1: face 0: dx is 'nan', not a finite number"},
      {"0,1,inf,0\n", "g.csv:1: face 0: dy is 'inf', not a finite number"},
      // once an int cast of inf in the figure's colour bar (UBSan)
      {"0,1e308,1e308,0\n", "g.csv:1: face 0: dx is '1e308', more than 1e12 in size (scale the field down)"},
      {"0,1,0\n", "g.csv:1: expected id,dx,dy,dz[,weight]"},
      {"0,1,0,0,1\n1,1,0,0,x\n", "g.csv:2: expected id,dx,dy,dz[,weight]"},  // line 1 may be a header
      {"0,1,0,0,1\n1,1,0,0\n", "g.csv:2: 4 values, but the first line has 5"},
      {"0,1,0,0,1.5\n", "g.csv:1: weight must be in [0, 1], got '1.5'"},
      {"0,1,0,0,nan\n", "g.csv:1: weight must be in [0, 1], got 'nan'"},
      {"0,0,0,0,1\n", "g.csv:1: face 0 has weight 1 but no direction"},
      {Rows(8) + "3,1,0,0\n", "g.csv:9: face 3 appears twice (first on line 4)"},
      {Rows(7), "g.csv: no direction for face 7 (the surface has 8 faces)"},
  };
  for (const auto& [text, expected] : cases) {
    const std::string path = testing::WriteFile(dir, "g.csv", text);
    const Status s = ReadGuidance(surface, path, &field);
    ExpectRefused(s, expected);
    EXPECT_EQ(s.message().rfind(path, 0), 0u) << s.message();  // the file comes first
  }
  ExpectRefused(ReadGuidance(surface, dir, &field), dir + ": not a guidance file (a folder?)");
  ExpectRefused(ReadGuidance(surface, dir + "/none.csv", &field), "none.csv: guidance file not found");
}

TEST(HostileGuidance, FacesWithoutADirectionGetAUnitOneAndNoWeight) {
  const auto dir = testing::TempDir();
  const SurfaceModel surface(testing::ToMesh(FlatGridSoup(2)));
  std::string text = "0,0,0,0\n1,0,0,3\n";  // zero, and normal to the (flat) faces
  for (int f = 2; f < 8; ++f) text += std::to_string(f) + ",1e12,1e12,0\n";  // as large as allowed
  GuidanceField field;
  const Status s = ReadGuidance(surface, testing::WriteFile(dir, "g.csv", text), &field);
  ASSERT_TRUE(s.ok()) << s.message();
  for (int f = 0; f < 8; ++f) EXPECT_NEAR(field.direction[f].norm(), 1.0, 1e-12) << f;
  EXPECT_EQ(field.weight[0], 0.0);
  EXPECT_EQ(field.weight[1], 0.0);
  EXPECT_EQ(field.weight[2], 1.0);
  EXPECT_NEAR(field.direction[2].x(), std::sqrt(0.5), 1e-12);
  EXPECT_TRUE(std::isfinite(field.scale));
}

// --- mesh validation ----------------------------------------------------------------------

TEST(HostileMesh, AFarAwayUnusedVertexDoesNotMakeFacesDegenerate) {
  PolygonSoup soup = FlatGridSoup(4);
  soup.points.emplace_back(1e7, 0.0, 0.0);  // used by no face: dropped later, with a warning
  EXPECT_TRUE(ValidateSurfaceSoup(soup).ok()) << ValidateSurfaceSoup(soup).message();
  soup.points.back() = Eigen::Vector3d(NAN, 0.0, 0.0);  // unused and not finite: also dropped
  EXPECT_TRUE(ValidateSurfaceSoup(soup).ok());
  // Degeneracy stays relative to the used geometry: face 0 = (0, 1, 6) flattened to 1e-12 m
  // in a 4 m grid is still refused, far vertex or not.
  soup = FlatGridSoup(4);
  soup.points[6] = Eigen::Vector3d(0.5, 1e-12, 0.0);
  ExpectRefused(ValidateSurfaceSoup(soup), "face 0 is degenerate (zero area): vertices 0, 1, 6");
  soup.points.emplace_back(1e7, 0.0, 0.0);
  ExpectRefused(ValidateSurfaceSoup(soup), "face 0 is degenerate (zero area): vertices 0, 1, 6");
}

TEST(HostileMesh, ImplausibleCoordinatesAreRefused) {
  PolygonSoup soup = FlatGridSoup(2);
  soup.points[4].x() = 1e200;  // would overflow the squared lengths
  ExpectRefused(ValidateSurfaceSoup(soup), "vertex 4 is at (1e+200, 1, 0), more than 1e+08 m from the origin");
  soup.points[4].x() = -2e8;
  ExpectRefused(ValidateSurfaceSoup(soup), "vertex 4 is at (-2e+08, 1, 0)");
}

// --- layout.spacing against the surface ---------------------------------------------------

// layout.spacing = ok passes the checks; bad is refused with `expected`.
void ExpectSpacingLimit(const SurfaceModel& surface, LayoutOptions layout, double ok, double bad,
                        const std::string& source, const std::string& expected) {
  layout.spacing = ok;
  const Status passed = CheckSpacingFitsSurface(surface, MeasureSurfaceFrame(surface), layout, source);
  EXPECT_TRUE(passed.ok()) << passed.message();
  layout.spacing = bad;
  ExpectRefused(CheckSpacingFitsSurface(surface, MeasureSurfaceFrame(surface), layout, source), expected);
}

TEST(HostileSpacing, ExtentIsMeasuredInTheBestFitPlane) {
  // A 10 × 6 plane, rotated 30° about z and tilted 20° about x: still 10 × 6.
  const Eigen::Matrix3d rotation = (Eigen::AngleAxisd(20.0 * M_PI / 180.0, Eigen::Vector3d::UnitX()) *
                                    Eigen::AngleAxisd(30.0 * M_PI / 180.0, Eigen::Vector3d::UnitZ()))
                                       .toRotationMatrix();
  TriMesh mesh = testing::GeneratedMesh("plane", 10.0, 6.0, 0.0, 1.0);
  for (auto v : mesh.vertices()) mesh.set_point(v, ToOpenMesh(rotation * ToEigen(mesh.point(v))));
  const SurfaceModel surface(std::move(mesh));
  const SurfaceExtent extent = MeasureExtent(surface);
  EXPECT_NEAR(extent.long_side, 10.0, 1e-3);  // the mesher's triangles tilt the axes slightly
  EXPECT_NEAR(extent.short_side, 6.0, 1e-3);
  ExpectSpacingLimit(surface, LayoutOptions(), 3.0, 3.01, "roof.obj",  // 3 m: exactly 2 panels across
                     "layout.spacing: 3.01 m leaves fewer than 2 panels across the surface (roof.obj is 10 m × 6 m "
                     "in its best-fit plane); use layout.spacing <= 3 m");
}

TEST(HostileSpacing, TooManyPanelsAreRefusedBeforeAnythingIsSolved) {
  const SurfaceModel surface(testing::GeneratedMesh("plane", 10.0, 6.0, 0.0, 1.0));  // 60 m²
  LayoutOptions layout;
  layout.max_panels = 1000;
  ExpectSpacingLimit(surface, layout, 0.245, 0.2, "generator plane",  // 999 and 1500 panels
                     "layout.spacing: 0.2 m would give about 1500 panels on the 60 m² of generator plane (area / h²), "
                     "more than layout.max_panels = 1000; use layout.spacing >= 0.245 m or raise layout.max_panels");
  layout.spacing = 1e-300;  // area / h² = inf
  ExpectRefused(CheckSpacingFitsSurface(surface, MeasureSurfaceFrame(surface), layout, "generator plane"), "would give about inf panels");
}

TEST(HostileSpacing, AHoleSmallerThanThePanelsIsRefused) {
  const SurfaceModel surface(testing::ToMesh(GridWithOneTriangleHole()));
  ASSERT_EQ(surface.boundary_loops().size(), 2u);
  EXPECT_NEAR(LoopDiameterBelow(surface, 1, 100.0), std::sqrt(2.0), 1e-12);
  ExpectSpacingLimit(surface, LayoutOptions(), 1.4, 2.0, "roof.obj",
                     "layout.spacing: 2 m is larger than a hole in the surface (roof.obj: boundary loop 1 at (5.67, "
                     "5.33, 0), 1.41 m across): no panel can frame it and the level lines tangle around it; fill the "
                     "hole in the mesh or use layout.spacing < 1.41 m");
}

TEST(HostileSpacing, ASeparatePartSmallerThanThePanelsIsNamedAsSuch) {
  PolygonSoup soup = FlatGridSoup(10);  // and a stray triangle 20 m away (CAD debris)
  soup.points.insert(soup.points.end(), {{30, 30, 0}, {31, 30, 0}, {30, 31, 0}});
  soup.faces.push_back({121, 122, 123});
  const SurfaceModel surface(testing::ToMesh(soup));
  ASSERT_EQ(surface.boundary_loops().size(), 2u);
  EXPECT_EQ(MeasureSurfaceFrame(surface).parts, 2);
  ExpectSpacingLimit(surface, LayoutOptions(), 1.4, 2.0, "roof.obj",
                     "layout.spacing: 2 m is larger than a separate part of the surface (roof.obj: boundary loop 1 at "
                     "(30.3, 30.3, 0), 1.41 m across, joined to the rest by no triangle): no panel can frame it; delete "
                     "it from the mesh or use layout.spacing < 1.41 m");
}

TEST(HostileOutput, MessagesNameTheOutputFolderNotTheStagingFolder) {
  const auto dir = testing::TempDir();
  std::unique_ptr<OutputFiles> out;
  ASSERT_TRUE(OutputFiles::Open(dir + "/new/deeper/result", &out).ok());
  const std::string staged = out->Path("figures/guidance.svg");
  EXPECT_EQ(staged.find(dir + "/new/deeper/result/"), std::string::npos);  // it is staged elsewhere
  const Status s = out->InFinalFolder(Status::InvalidInput(staged + ": |d| is not finite at face 0"));
  EXPECT_EQ(s.code(), StatusCode::kInvalidInput);
  EXPECT_EQ(s.message(), dir + "/new/deeper/result/figures/guidance.svg: |d| is not finite at face 0");
  out.reset();  // not committed: the staging folder and the folders Open created are gone
  EXPECT_FALSE(fs::exists(dir + "/new"));
}

// --- through the executable ---------------------------------------------------------------

struct HostileRun {
  std::string config, args, expected;
};

// Every case: exit 2, one line "pqlayout: error: ..." naming the key or file, and no output
// folder (nor the folder above it, which the run had to create).
TEST(HostileCli, EveryCaseIsOneLineExitTwoAndNoOutput) {
  const auto dir = testing::TempDir();
  testing::WriteFile(dir, "grid.obj", testing::ObjText(FlatGridSoup(10)));
  testing::WriteFile(dir, "hole.obj", testing::ObjText(GridWithOneTriangleHole()));
  testing::WriteFile(dir, "zero.csv", Rows(200, "0,0,0"));
  testing::WriteFile(dir, "nan.csv", "nan,1,0,0\n" + Rows(200));
  fs::create_directories(dir + "/adir");
  const std::string grid = "surface:\n  file: grid.obj\nlayout:\n  spacing: 2\n";
  const std::string plane = "surface: {generator: plane, width: 10, depth: 6, edge_length: 1}\n";
  const std::vector<HostileRun> cases = {
      {grid + "boundary:\n  rules: [{select: {ids: [-1]}, condition: free}]\n", "",
       "c.yaml:6: boundary.rules[0].select.ids: '-1' is not a vertex id"},
      {grid + "boundary:\n  rules: [{select: {ids: [500]}, condition: free}]\n", "",
       "c.yaml:6: boundary.rules[0]: vertex 500 does not exist (the file has 121 vertices"},
      {grid + "boundary:\n  rules: [{select: {ids_file: adir}, condition: free}]\n", "", "adir: not a vertex-id file"},
      {"[a]: 1\n", "", "c.yaml:1: keys must be plain names, got a list"},
      {"boundary:\n  rules: [{[a]: 1}]\n", "", "c.yaml:2: boundary.rules[0]: expected the keys select and condition"},
      {grid + "guidance:\n  source: file\n  file: zero.csv\n", "", "zero.csv:1: every direction is zero"},
      {grid + "guidance:\n  source: file\n  file: nan.csv\n", "", "nan.csv:1: face id 'nan' is not a face of the surface"},
      {grid + "guidance:\n  source: file\n  file: adir\n", "", "adir: not a guidance file (a folder?)"},
      {"load:\n  q: 1e300\n", "", "c.yaml:2: load.q: must be <= 1e+07 (got 1e+300)"},
      {plane + "layout: {spacing: 20}\n", "",
       "layout.spacing: 20 m leaves fewer than 2 panels across the surface (generator plane is 10 m × 6 m"},
      {plane + "layout: {spacing: 0.005}\n", "",
       "layout.spacing: 0.005 m would give about 2400000 panels on the 60 m² of generator plane"},
      {"surface:\n  file: hole.obj\nlayout:\n  spacing: 2\nboundary:\n  rules: [{select: inner, condition: free}]\n", "",
       "layout.spacing: 2 m is larger than a hole in the surface (hole.obj: boundary loop 1"},
      {"- a\n- b\n", "", "c.yaml: expected a mapping of config keys at the top level"},
      {"surface:\n  file: adir\n", "", "adir: not a regular file"},
      {"layout:\n  spacing: -1\n", "", "c.yaml:2: layout.spacing: must be > 0 (got -1)"},
      {"", "--set layout.spacing=0", "--set layout.spacing=0: layout.spacing: must be > 0 (got 0)"},
      {"guidance:\n  threshold: 2\n", "", "c.yaml:2: guidance.threshold: must be in [0, 1] (got 2)"},
      {"layout:\n  foo:\n    bar: 1\n", "", "c.yaml:2: unknown key 'layout.foo'"},
      {"levelset:\n  max_iterations: 2.5\n", "", "c.yaml:2: levelset.max_iterations: expected an integer, got '2.5'"},
      {"levelset:\n  seams: maybe\n", "", "c.yaml:2: levelset.seams: expected true or false, got 'maybe'"},
      {"surface:\n  file: [a]\n", "", "c.yaml:2: surface.file: expected a file path, got a list"},
      {"guidance:\n  source: [strain]\n", "", "c.yaml:2: guidance.source: expected one of strain | curvature | file"},
      {"boundary:\n  default: [fixed]\n", "", "c.yaml:2: boundary.default: expected one of fixed | free"},
      {"layout:\n  spacing: {a: 1}\n", "", "c.yaml:2: layout.spacing: expected a number, got a mapping"},
      {"levelset:\n  weights:\n    spacing: 0\n", "", "c.yaml:3: levelset.weights.spacing: must be > 0 (got 0)"},
      {"analysis:\n  section:\n    thickness: 0.1\n", "", "c.yaml: analysis.section.thickness: 0.1 m leaves no hollow"},
      // Refused after the surface stage, before the layout is solved (it once failed in stiffen).
      {plane + "boundary: {default: sliding}\n", "",
       "boundary: the supports cannot hold the frame in plan (0 fixed, 0 clamped, "},
  };
  for (const auto& c : cases) {
    testing::WriteFile(dir, "c.yaml", c.config);
    const testing::CliResult r = testing::RunPqlayout(dir, "run c.yaml -q --out out/result " + c.args);
    EXPECT_EQ(r.exit_code, 2) << c.expected << "\n" << r.err;
    EXPECT_EQ(testing::CountLines(r.err), 1) << r.err;
    EXPECT_EQ(r.err.rfind("pqlayout: error: ", 0), 0u) << r.err;
    EXPECT_NE(r.err.find(c.expected), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir + "/out")) << c.expected;
  }
}

// --- supports -------------------------------------------------------------------------------

TEST(HostileSupports, SlidingAloneCannotHoldTheFrameInPlan) {
  const auto B = [](int fixed, int clamped, int sliding, int free) {
    VertexConditions c(1, std::nullopt);  // an interior vertex
    c.insert(c.end(), fixed, BoundaryCondition::kFixed);
    c.insert(c.end(), clamped, BoundaryCondition::kClamped);
    c.insert(c.end(), sliding, BoundaryCondition::kSliding);
    c.insert(c.end(), free, BoundaryCondition::kFree);
    return CheckSupportsHoldTheFrameInPlan(c);
  };
  ExpectRefused(B(0, 0, 40, 0), "boundary: the supports cannot hold the frame in plan (0 fixed, 0 clamped, 40 sliding");
  ExpectRefused(B(0, 0, 40, 0), "so it can slide and turn in plan as a whole");
  ExpectRefused(B(1, 0, 39, 3), "(1 fixed, 0 clamped, 39 sliding boundary vertices");
  ExpectRefused(B(1, 0, 39, 3), "so it can turn about the fixed vertex in plan");
  EXPECT_TRUE(B(2, 0, 38, 0).ok());   // two pins hold translation and turning
  EXPECT_TRUE(B(0, 1, 39, 0).ok());   // a clamped vertex holds all six
  EXPECT_TRUE(B(40, 0, 0, 0).ok());
  EXPECT_TRUE(B(0, 0, 0, 40).ok());   // nothing held at all: the membrane stage names that part
}

TEST(HostileCli, AFarAwayUnusedVertexIsDroppedWithAWarningInTheReport) {
  const auto dir = testing::TempDir();
  PolygonSoup soup = FlatGridSoup(10);
  soup.points.emplace_back(1e7, 0.0, 0.0);
  testing::WriteFile(dir, "far.obj", testing::ObjText(soup));
  testing::WriteFile(dir, "c.yaml", "surface:\n  file: far.obj\nlayout:\n  spacing: 2\n");
  const testing::CliResult r = testing::RunPqlayout(dir, "run c.yaml --out result --until surface");
  ASSERT_EQ(r.exit_code, 0) << r.err;  // once "face 0 is degenerate": the far vertex set the scale
  const auto report = nlohmann::json::parse(testing::ReadFile(dir + "/result/report.json"));
  EXPECT_EQ(report["stages"]["surface"]["n_vertices"], 121);
  ASSERT_EQ(report["warnings"].size(), 1u) << report["warnings"];
  EXPECT_NE(report["warnings"][0].get<std::string>().find("far.obj: ignored 1 vertices that no face uses"),
            std::string::npos);
}

// A roof exported Y-up, or in millimetres, is read as given but said to be what it looks like:
// loaded sideways, or larger than any roof. The same grid lying flat says nothing.
TEST(HostileCli, ASurfaceFacingSidewaysOrKilometresAcrossIsAWarningInTheReport) {
  const auto dir = testing::TempDir();
  const PolygonSoup flat = FlatGridSoup(10);  // 10 m × 10 m in the xy plane
  PolygonSoup y_up = flat, millimetres = flat;
  for (auto& p : y_up.points) p = Eigen::Vector3d(p.x(), 0.0, -p.y());  // stood up: a wall
  for (auto& p : millimetres.points) p *= 1000.0;
  testing::WriteFile(dir, "flat.obj", testing::ObjText(flat));
  testing::WriteFile(dir, "yup.obj", testing::ObjText(y_up));
  testing::WriteFile(dir, "mm.obj", testing::ObjText(millimetres));
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"flat", ""},
      {"yup", "yup.obj faces sideways (its area points 90° from the vertical)"},
      {"mm", "mm.obj is 14142 m across, larger than any roof: if the file is in millimetres, scale it by 0.001"}};
  for (const auto& [name, expected] : cases) {
    testing::WriteFile(dir, name + ".yaml", "surface:\n  file: " + name + ".obj\nlayout:\n  spacing: 2000\n");
    const testing::CliResult r = testing::RunPqlayout(dir, "run " + name + ".yaml --out " + name + " --until surface");
    if (name != "mm") {  // h = 2000 m is too coarse for a 10 m roof, and refused so
      EXPECT_EQ(r.exit_code, 2) << name;
      testing::WriteFile(dir, name + ".yaml", "surface:\n  file: " + name + ".obj\nlayout:\n  spacing: 2\n");
    }
    const testing::CliResult run = name == "mm" ? r : testing::RunPqlayout(dir, "run " + name + ".yaml --out " + name + " --until surface");
    ASSERT_EQ(run.exit_code, 0) << name << ": " << run.err;
    const auto report = nlohmann::json::parse(testing::ReadFile(dir + "/" + name + "/report.json"));
    if (expected.empty()) {
      EXPECT_TRUE(report["warnings"].empty()) << report["warnings"];
      EXPECT_LT(report["stages"]["surface"]["facing_angle_deg"].get<double>(), 1e-6);
      continue;
    }
    ASSERT_EQ(report["warnings"].size(), 1u) << name << ": " << report["warnings"];
    EXPECT_NE(report["warnings"][0].get<std::string>().find(expected), std::string::npos) << report["warnings"][0];
  }
}

// A reference whose triangles are about as long as the panels (a CAD render mesh exported
// coarsely, or a generator's edge_length left at its default under a small spacing) is a
// warning naming its mean edge in h and the remedy for its kind; at 0.57 h (the grid under
// h = 2 m, above) none.
TEST(HostileCli, ACoarseReferenceIsAWarningInTheReport) {
  const auto dir = testing::TempDir();
  testing::WriteFile(dir, "grid.obj", testing::ObjText(FlatGridSoup(10)));  // 1 m cells: mean edge 1.13 m
  testing::WriteFile(dir, "file.yaml", "surface:\n  file: grid.obj\nlayout:\n  spacing: 1.5\n");
  testing::WriteFile(dir, "gen.yaml", "surface:\n  generator: great_court\nlayout:\n  spacing: 1.25\n");  // 1.09 m edges
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"file", "grid.obj's triangles are coarse for panels 1.5 m apart (mean edge 1.13 m, 0.753 h)"},
      {"gen", "generator great_court's triangles are coarse for panels 1.25 m apart (mean edge 1.09 m, 0.868 h)"},
      {"gen", "set surface.edge_length ≤ 0.625"}};
  for (const auto& [name, expected] : cases) {
    const testing::CliResult r = testing::RunPqlayout(dir, "run " + name + ".yaml --out " + name + " --until surface");
    ASSERT_EQ(r.exit_code, 0) << name << ": " << r.err;
    const auto report = nlohmann::json::parse(testing::ReadFile(dir + "/" + name + "/report.json"));
    ASSERT_EQ(report["warnings"].size(), 1u) << name << ": " << report["warnings"];
    EXPECT_NE(report["warnings"][0].get<std::string>().find(expected), std::string::npos) << report["warnings"][0];
  }
}

// A render mesh of strips (0.2 m × 2.7 m triangles on a 20 m × 16 m dome, as a NURBS surface is
// often exported) is solved on a remeshed copy, not on its slivers: directly on them the layout
// aligned to 9.3° (target 8°) and missed the quad fraction; remeshed, 7.6° and 10 of 11 targets.
TEST(HostileCli, ASliverRenderMeshIsSolvedOnARemeshedCopy) {
  const auto dir = testing::TempDir();
  PolygonSoup soup;
  const int nx = 100, ny = 6;
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) {
      const double x = -10.0 + 20.0 * i / nx, y = -8.0 + 16.0 * j / ny;
      soup.points.emplace_back(x, y, 4.0 * (1.0 - 0.5 * ((x / 10) * (x / 10) + (y / 8) * (y / 8))));
    }
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const int a = j * (nx + 1) + i, b = a + 1, c = b + nx + 1, d = a + nx + 1;
      soup.faces.push_back({a, b, c});
      soup.faces.push_back({a, c, d});
    }
  testing::WriteFile(dir, "strips.obj", testing::ObjText(soup));
  testing::WriteFile(dir, "c.yaml", "surface:\n  file: strips.obj\nlayout:\n  spacing: 2\n");
  const testing::CliResult r = testing::RunPqlayout(dir, "run c.yaml --out result --until levelset");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("100 % of the reference's triangles have an angle below 15°: remeshing"), std::string::npos) << r.out;
  const auto report = nlohmann::json::parse(testing::ReadFile(dir + "/result/report.json"));
  const auto& l = report["stages"]["levelset"];
  EXPECT_NE(l["working_mesh"].get<std::string>().find("CGAL remeshing"), std::string::npos) << l["working_mesh"];
  EXPECT_LE(l["alignment_rms_deg_weight_above_half"].get<double>(), 8.0);
}

// A layout that misses what was asked for still exits 0, but says so in report.json.
TEST(HostileCli, AnUnreachableCrossingAngleIsAWarningInTheReport) {
  const auto dir = testing::TempDir();
  testing::WriteFile(dir, "c.yaml",
                     "surface: {generator: plane, width: 10, depth: 6, edge_length: 1}\nlayout: {spacing: 2}\n"
                     "levelset: {min_angle: 89.9}\n");
  const testing::CliResult r = testing::RunPqlayout(dir, "run c.yaml --out result --until levelset");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto report = nlohmann::json::parse(testing::ReadFile(dir + "/result/report.json"));
  const int below = report["stages"]["levelset"]["faces_below_min_angle"].get<int>();
  EXPECT_GT(below, 0);
  ASSERT_EQ(report["warnings"].size(), 1u) << report["warnings"];
  EXPECT_EQ(report["warnings"][0].get<std::string>().rfind("levelset: " + std::to_string(below) + " faces (", 0), 0u)
      << report["warnings"][0];
  EXPECT_NE(report["warnings"][0].get<std::string>().find("cross below levelset.min_angle 89.9°"), std::string::npos);
}

}  // namespace
}  // namespace pqlayout

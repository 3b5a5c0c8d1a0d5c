// Config parsing: defaults, every kind of error naming file, line and key, `--set`
// precedence, path resolution, boundary rules, and the resolved JSON.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "pipeline/config.h"
#include "tests/test_meshes.h"

namespace pqlayout {
namespace {

Status Parse(const std::string& yaml, Config* c, const std::vector<std::string>& sets = {}) {
  return ParseConfig(yaml, "cfg.yaml", "/base", sets, c);
}

void ExpectError(const std::string& yaml, const std::vector<std::string>& sets, const std::string& expected) {
  Config c;
  const Status s = Parse(yaml, &c, sets);
  EXPECT_EQ(s.code(), StatusCode::kInvalidInput) << yaml;
  EXPECT_NE(s.message().find(expected), std::string::npos) << "message: " << s.message();
}

TEST(Config, EmptyConfigGivesTheDefaults) {
  Config c;
  ASSERT_TRUE(Parse("", &c).ok());
  EXPECT_EQ(c.surface.generator, "great_court");
  EXPECT_EQ(c.layout.spacing, 3.0);
  EXPECT_EQ(c.load.q, 1350.0);
  EXPECT_EQ(c.boundary.default_condition, BoundaryCondition::kFixed);
  EXPECT_EQ(c.analysis.panel_load, 1000.0);
  EXPECT_EQ(c.analysis.section.diameter, 0.1143);
}

TEST(Config, NestedKeysAreSet) {
  Config c;
  ASSERT_TRUE(Parse("layout:\n  spacing: 2.5\nlevelset:\n  weights:\n    alignment: 4\n"
                    "analysis:\n  export_calculix: yes\nguidance:\n  source: curvature\n", &c).ok());
  EXPECT_EQ(c.layout.spacing, 2.5);
  EXPECT_EQ(c.levelset.weights.alignment, 4.0);
  EXPECT_TRUE(c.analysis.export_calculix);
  EXPECT_EQ(c.guidance.source, "curvature");
}

TEST(Config, UnknownKeyNamesLineAndSuggests) {
  ExpectError("layout:\n  spacing: 3\nlevelset:\n  wieghts:\n    alignment: 2\n", {},
              "cfg.yaml:4: unknown key 'levelset.wieghts' (did you mean 'levelset.weights");
  ExpectError("levelset:\n  weights:\n    alignmnet: 2\n", {},
              "cfg.yaml:3: unknown key 'levelset.weights.alignmnet' (did you mean 'levelset.weights.alignment'?)");
  ExpectError("colour: red\n", {}, "cfg.yaml:1: unknown key 'colour'");
}

TEST(Config, WrongTypeAndRange) {
  ExpectError("layout:\n  spacing: three\n", {}, "cfg.yaml:2: layout.spacing: expected a number, got 'three'");
  ExpectError("layout:\n  spacing: -1\n", {}, "cfg.yaml:2: layout.spacing: must be > 0 (got -1)");
  ExpectError("layout:\n  spacing: [1, 2]\n", {}, "layout.spacing: expected a number, got a list");
  ExpectError("layout: 3\n", {}, "cfg.yaml:1: layout: is a section, expected a mapping of its keys");
  ExpectError("guidance:\n  threshold: 1.5\n", {}, "guidance.threshold: must be in [0, 1] (got 1.5)");
  ExpectError("levelset:\n  smoothness_max_guidance: 1.01\n", {}, "levelset.smoothness_max_guidance: must be in [0, 1] (got 1.01)");
  ExpectError("guidance:\n  source: strian\n", {}, "guidance.source: unknown value 'strian' (expected strain | curvature | file)");
  ExpectError("levelset:\n  max_iterations: 2.5\n", {}, "levelset.max_iterations: expected an integer");
  ExpectError("analysis:\n  export_calculix: maybe\n", {}, "analysis.export_calculix: expected true or false");
  ExpectError("load:\n  q: .nan\n", {}, "load.q: must be a finite number");
  ExpectError("layout:\n  spacing: 1\n  spacing: 2\n", {}, "cfg.yaml:3: layout.spacing: duplicate key");
  ExpectError("layout:\n  spacing: [1\n", {}, "cfg.yaml:");
  ExpectError("- a\n- b\n", {}, "expected a mapping of config keys at the top level");
}

TEST(Config, SetOverridesTheFile) {
  Config c;
  ASSERT_TRUE(Parse("layout:\n  spacing: 2\n", &c, {"layout.spacing=1.5", "levelset.weights.conjugacy=0"}).ok());
  EXPECT_EQ(c.layout.spacing, 1.5);
  EXPECT_EQ(c.levelset.weights.conjugacy, 0.0);
  // Both ends of a closed range are values (levelset.smoothness_max_guidance: 0 and its default 1).
  for (const char* value : {"levelset.smoothness_max_guidance=0", "levelset.smoothness_max_guidance=1"})
    ASSERT_TRUE(Parse("", &c, {value}).ok()) << value;
  EXPECT_EQ(c.levelset.smoothness_max_guidance, 1.0);
  // The last --set of a key wins.
  ASSERT_TRUE(Parse("", &c, {"layout.spacing=1.5", "layout.spacing=4"}).ok());
  EXPECT_EQ(c.layout.spacing, 4.0);
}

TEST(Config, SetErrorsNameTheArgument) {
  ExpectError("", {"levelset.wieghts.alignment=2"},
              "--set levelset.wieghts.alignment=2: levelset.wieghts.alignment: unknown key (did you mean 'levelset.weights.alignment'?)");
  ExpectError("", {"layout.spacing"}, "--set layout.spacing: expected KEY=VALUE");
  ExpectError("", {"layout.spacing=abc"}, "--set layout.spacing=abc: layout.spacing: expected a number, got 'abc'");
  ExpectError("", {"layout=1"}, "layout: is a section, not a key; its keys: layout.spacing, ");
  // A section names its keys instead of suggesting itself (it once said "did you mean
  // 'analysis.section'?").
  ExpectError("", {"analysis.section=nonsense"},
              "--set analysis.section=nonsense: analysis.section: is a section, not a key; its keys: analysis.section.shape, "
              "analysis.section.diameter, analysis.section.thickness, analysis.section.width, analysis.section.height");
  ExpectError("", {"levelset=1"}, "levelset.weights, ");  // a section below a section, named once
}

TEST(Config, PathsResolveAgainstTheConfigFolderButSetPathsAgainstTheWorkingDirectory) {
  Config c;
  ASSERT_TRUE(Parse("surface:\n  file: meshes/roof.obj\n", &c).ok());
  EXPECT_EQ(c.surface.file, "/base/meshes/roof.obj");
  EXPECT_EQ(c.surface.generator, "");  // a file replaces the default generator
  ASSERT_TRUE(Parse("", &c, {"surface.file=roof.obj"}).ok());
  EXPECT_EQ(c.surface.file, "roof.obj");
  EXPECT_EQ(c.surface.generator, "");
}

TEST(Config, SurfaceComesFromExactlyOneSource) {
  ExpectError("surface:\n  file: a.obj\n  generator: dome\n", {}, "set either surface.file or surface.generator, not both");
  ExpectError("surface:\n  generator: \"\"\n", {}, "set surface.file or surface.generator");
  Config c;
  ASSERT_TRUE(Parse("surface:\n  file: a.obj\n", &c, {"surface.generator=dome"}).ok());
  EXPECT_EQ(c.surface.generator, "dome");
  EXPECT_EQ(c.surface.file, "");
}

TEST(Config, BoundaryRules) {
  Config c;
  const std::string yaml =
      "boundary:\n"
      "  default: free\n"
      "  rules:\n"
      "    - select: inner\n"
      "      condition: fixed\n"
      "    - select: {box: [-1, -2, -3, 1, 2, 3]}\n"
      "      condition: sliding\n"
      "    - select: {ids_file: supports.txt}\n"
      "      condition: clamped\n"
      "    - select: {loop: 1}\n"
      "      condition: fixed\n";
  ASSERT_TRUE(Parse(yaml, &c).ok());
  EXPECT_EQ(c.boundary.default_condition, BoundaryCondition::kFree);
  ASSERT_EQ(c.boundary.rules.size(), 4u);
  EXPECT_EQ(c.boundary.rules[0].select.kind, BoundarySelector::Kind::kInner);
  EXPECT_EQ(c.boundary.rules[1].select.box_min, Eigen::Vector3d(-1, -2, -3));
  EXPECT_EQ(c.boundary.rules[1].condition, BoundaryCondition::kSliding);
  EXPECT_EQ(c.boundary.rules[2].select.ids_file, "/base/supports.txt");
  EXPECT_EQ(c.boundary.rules[3].select.loop, 1);
  EXPECT_EQ(c.boundary.rules[1].origin, "cfg.yaml:6");  // messages say FILE:LINE

  ExpectError("boundary:\n  rules:\n    - select: inenr\n      condition: fixed\n", {},
              "cfg.yaml:2: boundary.rules[0].select: unknown selector 'inenr'");  // the line of the key
  ExpectError("boundary:\n  rules:\n    - select: all\n      condition: glued\n", {},
              "boundary.rules[0].condition: expected one of fixed | free | clamped | sliding, got 'glued'");
  ExpectError("boundary:\n  rules:\n    - select: all\n", {}, "[0]: a rule needs both select and condition");
  ExpectError("boundary:\n  rules:\n    - select: {box: [1, 2]}\n      condition: free\n", {},
              "box: expected [xmin, ymin, zmin, xmax, ymax, zmax]");
  ExpectError("boundary:\n  default: pinned\n", {}, "boundary.default: expected one of fixed | free | clamped | sliding");
  ASSERT_TRUE(Parse("", &c, {"boundary.rules=[{select: outer, condition: sliding}]"}).ok());
  ASSERT_EQ(c.boundary.rules.size(), 1u);
  EXPECT_EQ(c.boundary.rules[0].select.kind, BoundarySelector::Kind::kOuter);
}

// Hostile rules (issue 15): every malformed element is one message naming the rule, the
// key and the element; none throws (a list as a key once escaped as "internal error").
TEST(Config, HostileBoundaryRulesNameTheElement) {
  ExpectError("boundary:\n  rules: [{select: {ids: [-1]}, condition: free}]\n", {},
              "cfg.yaml:2: boundary.rules[0].select.ids: '-1' is not a vertex id");
  ExpectError("boundary:\n  rules: [{select: {ids: [3, 1.5]}, condition: free}]\n", {},
              "boundary.rules[0].select.ids: '1.5' is not a vertex id");
  ExpectError("boundary:\n  rules: [{select: {ids: [99999999999]}, condition: free}]\n", {},
              "boundary.rules[0].select.ids: '99999999999' is not a vertex id");
  ExpectError("boundary:\n  rules: [{select: {ids: 3}, condition: free}]\n", {},
              "boundary.rules[0].select.ids: expected a list of vertex ids, got '3'");
  ExpectError("boundary:\n  rules: [{[a]: 1}]\n", {},
              "cfg.yaml:2: boundary.rules[0]: expected the keys select and condition, got a list");
  ExpectError("boundary:\n  rules: [{select: {[a]: 1}, condition: free}]\n", {},
              "boundary.rules[0].select: expected all, outer, inner, corners, or a mapping");
  ExpectError("boundary:\n  rules: [{select: {box: [0, 0, 0, 1, 1, .nan]}, condition: free}]\n", {},
              "boundary.rules[0].select.box: expected [xmin, ymin, zmin, xmax, ymax, zmax]: '.nan' is not a finite number");
  ExpectError("boundary:\n  rules: [{select: {loop: -1}, condition: free}]\n", {},
              "boundary.rules[0].select.loop: expected a loop index >= 0, got '-1'");
  ExpectError("boundary:\n  rules: {select: all}\n", {}, "cfg.yaml:2: boundary.rules: expected a list of {select");
  ExpectError("", {"boundary.rules=[{select: all, condition: free}, {select: {ids: [-2]}, condition: free}]"},
              "--set boundary.rules=[{select: all, condition: free}, {select: {ids: [-2]}, condition: free}]: "
              "boundary.rules[1].select.ids: '-2' is not a vertex id");
  Config c;
  ASSERT_TRUE(Parse("", &c, {"boundary.rules=[{select: {ids: [0, 7]}, condition: free}]"}).ok());
  EXPECT_EQ(c.boundary.rules[0].select.ids, std::vector<int>({0, 7}));
  EXPECT_EQ(c.boundary.rules[0].origin, "--set boundary.rules");  // no line: it is not in the file
}

TEST(Config, NonScalarKeysAreOneLineErrors) {
  ExpectError("[a]: 1\n", {}, "cfg.yaml:1: keys must be plain names, got a list");
  ExpectError("layout:\n  {a: 1}: 2\n", {}, "cfg.yaml:2: keys must be plain names, got a mapping in section layout");
  ExpectError("layout:\n  foo:\n    bar: 1\n", {}, "cfg.yaml:2: unknown key 'layout.foo'");
  ExpectError("levelset:\n  weights:\n    alignment:\n      deep: 1\n", {},
              "cfg.yaml:3: levelset.weights.alignment: expected a number, got a mapping");
  ExpectError("a: *undefined\n", {}, "cfg.yaml:1: YAML syntax error");
}

// Absurd numbers are refused by name before any stage could overflow or cast them to int.
TEST(Config, AbsurdNumbersAreRefusedByName) {
  ExpectError("load:\n  q: 1e300\n", {}, "cfg.yaml:2: load.q: must be <= 1e+07 (got 1e+300)");
  ExpectError("load:\n  q: .inf\n", {}, "load.q: must be a finite number");
  ExpectError("membrane:\n  stiffness: 1e-300\n", {}, "membrane.stiffness: must be >= 0.001 (got 1e-300)");
  ExpectError("surface:\n  width: 1e300\n", {}, "surface.width: must be <= 100000 (got 1e+300)");
  ExpectError("layout:\n  spacing: 0\n", {}, "layout.spacing: must be > 0 (got 0)");
  ExpectError("levelset:\n  weights:\n    alignment: 1e300\n", {}, "levelset.weights.alignment: must be <= 1e+06 (got 1e+300)");
  ExpectError("levelset:\n  weights:\n    spacing: 0\n", {}, "levelset.weights.spacing: must be > 0 (got 0)");
  ExpectError("planarize:\n  weights:\n    planarity: 1e300\n", {}, "planarize.weights.planarity: must be <= 1e+06");
  ExpectError("analysis:\n  material:\n    youngs_modulus: 1e300\n", {}, "analysis.material.youngs_modulus: must be <= 1e+15");
  ExpectError("analysis:\n  material:\n    youngs_modulus: 1e-300\n", {},
              "analysis.material.youngs_modulus: must be >= 1e+06 (got 1e-300)");  // once "a mechanism"
  ExpectError("analysis:\n  section:\n    diameter: 1e-300\n", {}, "analysis.section.diameter: must be >= 0.0001");
  ExpectError("layout:\n  max_panels: 0\n", {}, "layout.max_panels: must be in [1, 100000000] (got 0)");
  ExpectError("guidance:\n  threshold: -0.1\n", {}, "guidance.threshold: must be in [0, 1] (got -0.1)");
  Config c;
  ASSERT_TRUE(Parse("load:\n  q: 1e7\nmembrane:\n  stiffness: 0.001\n", &c).ok());  // the bounds themselves
  EXPECT_EQ(c.load.q, 1e7);
}

TEST(Config, KeysThatContradictEachOtherAreRefused) {
  ExpectError("analysis:\n  section:\n    thickness: 0.06\n", {},
              "cfg.yaml: analysis.section.thickness: 0.06 m leaves no hollow in a tube of analysis.section.diameter 0.1143 m");
  ExpectError("analysis:\n  section:\n    shape: rectangular_hollow\n    thickness: 0.03\n", {},
              "analysis.section.thickness: 0.03 m leaves no hollow in a box whose smaller side is 0.06 m");
  ExpectError("guidance:\n  source: file\n", {}, "cfg.yaml: guidance.file: required when guidance.source is file");
  ExpectError("analysis:\n  panel_load: 0\n  gravity: 0\n", {}, "analysis.panel_load: the frame carries no load");
  ExpectError("levelset:\n  joint_iterations: 0\n", {},
              "cfg.yaml: levelset.joint_iterations: 0 leaves the level sets unsolved (the initial guess) unless "
              "levelset.separate_solves is true");
  // A contradiction made on the command line names the --set, not the file that was fine.
  ExpectError("", {"analysis.section.thickness=0.06"},
              "--set analysis.section.thickness=0.06: analysis.section.thickness: 0.06 m leaves no hollow");
  ExpectError("analysis:\n  section:\n    thickness: 0.04\n", {"analysis.section.diameter=0.07"},
              "--set analysis.section.diameter=0.07: analysis.section.thickness: 0.04 m leaves no hollow");
  ExpectError("", {"levelset.joint_iterations=5", "levelset.joint_iterations=0"},
              "--set levelset.joint_iterations=0: levelset.joint_iterations: 0 leaves");
  ExpectError("guidance:\n  source: file\n", {"layout.spacing=2"}, "cfg.yaml: guidance.file: required");
  Config c;
  EXPECT_TRUE(Parse("analysis:\n  panel_load: 0\n", &c).ok());  // the steel's own weight is still a load
  EXPECT_TRUE(Parse("levelset:\n  joint_iterations: 0\n  separate_solves: true\n", &c).ok());  // φ, then ψ only
}

TEST(Config, ResolvedJsonMirrorsTheKeys) {
  Config c;
  ASSERT_TRUE(Parse("layout:\n  spacing: 2\n", &c, {"boundary.rules=[{select: inner, condition: free}]"}).ok());
  const auto j = ConfigToJson(c);
  EXPECT_EQ(j["layout"]["spacing"], 2.0);
  EXPECT_EQ(j["levelset"]["weights"]["alignment"], 10.0);
  EXPECT_EQ(j["boundary"]["default"], "fixed");
  EXPECT_EQ(j["boundary"]["rules"][0]["select"], "inner");
  EXPECT_EQ(j["boundary"]["rules"][0]["condition"], "free");
  EXPECT_EQ(j["analysis"]["material"]["youngs_modulus"], 210e9);
}

TEST(Config, ReferenceListsEveryContractKey) {
  const std::string reference = ConfigReferenceMarkdown();
  for (const char* key : {"surface.file", "surface.generator", "surface.edge_length", "boundary.default",
                          "boundary.rules", "load.q", "membrane.stiffness", "guidance.source",
                          "guidance.threshold", "layout.spacing", "levelset.weights.alignment",
                          "levelset.weights.spacing", "levelset.weights.smoothness", "levelset.weights.conjugacy",
                          "planarize.weights.planarity", "planarize.weights.closeness", "analysis.panel_load",
                          "analysis.export_calculix"})
    EXPECT_NE(reference.find(std::string("`") + key + "`"), std::string::npos) << key;
}

TEST(Config, LoadConfigReadsAFile) {
  const auto dir = testing::TempDir();
  const auto path = testing::WriteFile(dir, "c.yaml", "layout:\n  spacing: 2\nsurface:\n  file: roof.obj\n");
  Config c;
  ASSERT_TRUE(LoadConfig(path, {}, &c).ok());
  EXPECT_EQ(c.layout.spacing, 2.0);
  EXPECT_EQ(c.surface.file, (std::filesystem::path(dir) / "roof.obj").string());
  const Status missing = LoadConfig(dir + "/none.yaml", {}, &c);
  EXPECT_EQ(missing.code(), StatusCode::kInvalidInput);
  EXPECT_NE(missing.message().find("none.yaml: config file not found"), std::string::npos);
  const Status folder = LoadConfig(dir, {}, &c);
  EXPECT_EQ(folder.code(), StatusCode::kInvalidInput);
  EXPECT_NE(folder.message().find(dir + ": not a config file (a folder?)"), std::string::npos) << folder.message();
}

}  // namespace
}  // namespace pqlayout

namespace pqlayout {
namespace {

TEST(Config, ReadmeCarriesTheCurrentReference) {
  std::ifstream in(PQLAYOUT_SOURCE_DIR "/README.md");
  std::stringstream readme;
  readme << in.rdbuf();
  EXPECT_NE(readme.str().find(ConfigReferenceMarkdown()), std::string::npos)
      << "README.md's config reference is out of date: paste the output of `pqlayout keys`";
}

}  // namespace
}  // namespace pqlayout

// The SVG canvas helpers (colour maps, nice scale-bar lengths and ticks) and the
// figure compositions (structure, labels, grid resampling above the face cap, size of a
// 1M-triangle figure, the level-set figure of the Great Court). The shell figures (planarity,
// 3D view, line widths) are in shell_figures_test.cc.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <random>
#include <regex>
#include <set>
#include <sstream>

#include "geometry/level_lines.h"
#include "geometry/streamlines.h"
#include "geometry/surface_generators.h"
#include "report/svg_canvas.h"
#include "geometry/planarity.h"
#include "report/figures.h"
#include "tests/svg_test_helpers.h"
#include "tests/test_meshes.h"

namespace pqlayout {
namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;
using testing::Centroid;
using testing::Count;
using testing::ExpectSvgDocument;
using testing::ReadText;





// The d="..." data of the first <path> drawn with this stroke colour, "" if none.
std::string StrokedPathData(const std::string& svg, const std::string& colour) {
  const size_t at = svg.find("<path fill=\"none\" stroke=\"" + colour + "\"");
  if (at == std::string::npos) return "";
  const size_t begin = svg.find(" d=\"", at) + 4;
  return svg.substr(begin, svg.find('"', begin) - begin);
}



TEST(SvgCanvas, ViridisEndpointsArePublishedValues) {
  EXPECT_EQ(Viridis(0.0).Hex(), "#440154");
  EXPECT_EQ(Viridis(1.0).Hex(), "#fde725");
  EXPECT_EQ(Viridis(-3.0).Hex(), "#440154");  // clamped
  EXPECT_EQ(BlueWhiteRed(0.5).Hex(), "#f7f7f7");
  EXPECT_GT(BlueWhiteRed(0.0).b, BlueWhiteRed(0.0).r);
  EXPECT_GT(BlueWhiteRed(1.0).r, BlueWhiteRed(1.0).b);
}

TEST(SvgCanvas, ScaleBarLengthIsOneTwoOrFiveTimesAPowerOfTen) {
  for (const double width : {0.37, 3.0, 9.9, 10.0, 73.25, 120.0, 4321.0}) {
    const double length = NiceScaleBarLength(width);
    const double mantissa = length / std::pow(10.0, std::floor(std::log10(length) + 1e-12));
    EXPECT_TRUE(std::abs(mantissa - 1) < 1e-9 || std::abs(mantissa - 2) < 1e-9 ||
                std::abs(mantissa - 5) < 1e-9)
        << width << " -> " << length;
    EXPECT_GT(length, width / 10.0);
    EXPECT_LT(length, width / 2.0);
  }
  EXPECT_DOUBLE_EQ(NiceScaleBarLength(73.25), 20.0);  // nearest in ratio to 14.65
  EXPECT_DOUBLE_EQ(NiceScaleBarLength(30.0), 5.0);
}

void ExpectTicks(double lo, double hi, const std::vector<double>& expected) {
  const std::vector<double> ticks = NiceTicks(lo, hi);
  ASSERT_EQ(ticks.size(), expected.size()) << lo << " .. " << hi;
  for (size_t i = 0; i < ticks.size(); ++i) EXPECT_NEAR(ticks[i], expected[i], 1e-12);
}

TEST(SvgCanvas, TicksAreRoundAndInsideTheRange) {
  ExpectTicks(-12.3, 0.0, {-12, -10, -8, -6, -4, -2, 0});
  ExpectTicks(0.0, 1.0, {0, 0.2, 0.4, 0.6, 0.8, 1.0});
  ExpectTicks(0.05, 0.95, {0.2, 0.4, 0.6, 0.8});
  ExpectTicks(3.0e-5, 4.2e-4, {1e-4, 2e-4, 3e-4, 4e-4});
}

TEST(SvgCanvas, MapsTheWorldWithEqualAspectAndEscapesText) {
  const SvgCanvas canvas(Eigen::AlignedBox2d(Vector2d(-10, 0), Vector2d(10, 5)), 1000.0, "t");
  const Vector2d a = canvas.ToPx({-10, 5}), b = canvas.ToPx({10, 0});
  EXPECT_NEAR(b.x() - a.x(), 20.0 * canvas.px_per_metre(), 1e-9);
  EXPECT_NEAR(b.y() - a.y(), 5.0 * canvas.px_per_metre(), 1e-9);  // y points down
  EXPECT_GT(canvas.height(), b.y());

  SvgCanvas drawing(Eigen::AlignedBox2d(Vector2d(0, 0), Vector2d(1, 1)), 500.0, "a < b & c");
  drawing.Circle({0.5, 0.5}, 4.0, Viridis(0.5));
  drawing.Text({0.5, 0.5}, "\"q\"", SvgStyle::kLabelFont);
  const std::string svg = drawing.ToSvg();
  EXPECT_NE(svg.find("a &lt; b &amp; c"), std::string::npos);
  EXPECT_NE(svg.find("&quot;q&quot;"), std::string::npos);
  EXPECT_NE(svg.find("<circle"), std::string::npos);
  EXPECT_EQ(svg.find("xlink:href=\"http"), std::string::npos);  // self-contained
}

// A title too long for the drawing is set smaller so that it fits its width (the planarity
// figure's counts ran past the edge at 24 px); a short one keeps the style's size. Widths are
// estimated at 0.55 em per character, δ counting once.
TEST(SvgCanvas, ALongTitleIsSetSmallerToFitTheWidth) {
  auto title_size = [](const std::string& title) {
    const std::string svg = SvgCanvas(Eigen::AlignedBox2d(Vector2d(0, 0), Vector2d(1, 1)), 1000.0, title).ToSvg();
    const std::smatch m = [&] {
      std::smatch found;
      std::regex_search(svg, found, std::regex("font-size=\"([0-9.]+)\"[^>]*>" + title.substr(0, 5)));
      return found;
    }();
    return m.empty() ? -1.0 : std::stod(m[1]);
  };
  const double u = 1000.0 / SvgStyle::kReferenceWidth;
  EXPECT_DOUBLE_EQ(title_size("Short title"), SvgStyle::kTitleFont * u);
  const std::string long_title = "Planarity δ after planarisation: " + std::string(90, 'x');  // 123 characters
  const double size = title_size(long_title);
  EXPECT_LT(size, SvgStyle::kTitleFont * u);
  EXPECT_NEAR(0.55 * size * 123, 1000.0 - 2 * SvgStyle::kPadding * u, 4.0);  // the size is written to 3 digits
}

class SmallMeshFigures : public ::testing::Test {
 protected:
  SmallMeshFigures()
      : surface_(
            testing::ToMesh(testing::GridSoup(4, [](double x, double y) { return 0.1 * x * y; }))) {
    for (int v = 0; v < surface_.num_vertices(); ++v) {
      const Vector3d p = surface_.position(v);
      v_z_.push_back(-1e-3 * p.x() * (4 - p.x()) * p.y() * (4 - p.y()));
    }
    for (int f = 0; f < surface_.num_faces(); ++f) {
      const Vector2d c = Centroid(surface_, f) - Vector2d(2, 2);
      direction_.emplace_back(c.x(), c.y(), 0.0);
      magnitude_.push_back(c.norm());
      weight_.push_back(c.norm() > 1.0 ? 1.0 : 0.0);
    }
  }
  SurfaceModel surface_;
  std::vector<double> v_z_, magnitude_, weight_;
  std::vector<Vector3d> direction_;
};


// v_z is a vertex field: drawn as a smooth raster (boxes, linear inside each triangle), so
// there are more colour bands than faces' worth of flat colours would give.
TEST_F(SmallMeshFigures, DisplacementFigureIsSmoothAndHasTheColourBarLabel) {
  const std::string path = testing::TempDir() + "/displacement.svg";
  ASSERT_TRUE(WriteDisplacementFigure(surface_, v_z_, "Fig. 3: v_z under dead load", path).ok());
  const std::string svg = ReadText(path);
  ExpectSvgDocument(svg);
  EXPECT_EQ(Count(svg, "<path color="), 0);
  // v_z ranges over [-4 mm, 0]; interpolated, every one of the 64 bands appears (the 32
  // faces' means alone would give at most 32 colours).
  std::set<std::string> fills;
  const std::regex box("<path fill=\"(#[0-9a-f]{6})\" stroke=\"#[0-9a-f]{6}\" stroke-width=\"[0-9.]+\" d=\"M");
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), box); it != std::sregex_iterator(); ++it)
    fills.insert((*it)[1]);
  EXPECT_GE(fills.size(), 60u);
  EXPECT_TRUE(fills.count(Viridis(0.5 / 64).Hex()));   // the band of the minimum, -4 mm
  EXPECT_TRUE(fills.count(Viridis(63.5 / 64).Hex()));  // the band of the maximum, 0
  EXPECT_NE(svg.find("v_z [mm]"), std::string::npos);
  EXPECT_NE(svg.find("Fig. 3: v_z under dead load"), std::string::npos);
  EXPECT_NE(svg.find(">N</text>"), std::string::npos);  // north arrow
}

TEST_F(SmallMeshFigures, SignedDisplacementUsesTheDivergingMap) {
  std::vector<double> v_z = v_z_;
  v_z[7] = 0.002;
  const std::string path = testing::TempDir() + "/signed.svg";
  ASSERT_TRUE(WriteDisplacementFigure(surface_, v_z, "signed", path).ok());
  const std::string svg = ReadText(path);
  EXPECT_NE(svg.find(BlueWhiteRed(0.5 / 64).Hex()), std::string::npos);  // -4 mm of ±4 mm
  EXPECT_EQ(svg.find(Viridis(0.5 / 64).Hex()), std::string::npos);
}

TEST_F(SmallMeshFigures, GuidanceFigureHasLegendLabelAndStreamlines) {
  const std::string path = testing::TempDir() + "/guidance.svg";
  ASSERT_TRUE(WriteGuidanceFigure(surface_, direction_, magnitude_, "|ε_max|", weight_,
                                  "Fig. 6: guidance", path)
                  .ok());
  const std::string svg = ReadText(path);
  ExpectSvgDocument(svg);
  EXPECT_EQ(Count(svg, "<path color="), surface_.num_faces());
  EXPECT_NE(svg.find("weak guidance (weight &lt; 0.5): alignment weighted by it"), std::string::npos);
  EXPECT_NE(svg.find("|ε_max|"), std::string::npos);
  EXPECT_EQ(Count(svg, "<use "), 2);  // streamlines over their halo
}

TEST_F(SmallMeshFigures, AboveTheFaceCapColoursAreResampledOntoAGrid) {
  const std::string path = testing::TempDir() + "/grid.svg";
  FigureOptions options;
  options.max_face_polygons = 10;  // 32 faces: above the cap
  ASSERT_TRUE(WriteGuidanceFigure(surface_, direction_, magnitude_, "|ε_max|", weight_, "grid", path, options).ok());
  const std::string svg = ReadText(path);
  ExpectSvgDocument(svg);
  EXPECT_EQ(Count(svg, "<path color="), 0);
  EXPECT_GE(Count(svg, "H"), 1);  // boxes
}

TEST_F(SmallMeshFigures, WrongSizesAreRefusedAndNothingIsWritten) {
  const std::string path = testing::TempDir() + "/bad.svg";
  const Status status = WriteDisplacementFigure(surface_, std::vector<double>(3, 0.0), "bad", path);
  EXPECT_EQ(status.code(), StatusCode::kInvalidInput);
  EXPECT_NE(status.message().find("per vertex"), std::string::npos) << status.message();
  std::vector<double> weight = weight_;
  weight[5] = std::nan("");
  const Status nan_status =
      WriteGuidanceFigure(surface_, direction_, magnitude_, "m", weight, "bad", path);
  EXPECT_EQ(nan_status.code(), StatusCode::kInvalidInput);
  EXPECT_NE(nan_status.message().find("face 5"), std::string::npos) << nan_status.message();
  EXPECT_FALSE(std::filesystem::exists(path));
}

class LevelSetFigure : public ::testing::Test {
 protected:
  // 12 m square, h = 3 m, φ = x/h, ψ = y/h; the guidance along x, not enforced for x < 4.
  LevelSetFigure() : square_(testing::ToMesh(testing::FlatGridSoup(12))) {
    for (int v = 0; v < square_.num_vertices(); ++v) {
      phi_.push_back(square_.position(v).x() / h_);
      psi_.push_back(square_.position(v).y() / h_);
    }
    for (int f = 0; f < square_.num_faces(); ++f) {
      direction_.push_back(Vector3d::UnitX());
      weight_.push_back(Centroid(square_, f).x() < 4.0 ? 0.0 : 1.0);
    }
  }
  const double h_ = 3.0;
  SurfaceModel square_;
  std::vector<double> phi_, psi_, weight_;
  std::vector<Vector3d> direction_;
};

TEST_F(LevelSetFigure, HasOneSubpathPerLevelLineAndTheLegend) {
  const std::string path = testing::TempDir() + "/levelsets.svg";
  ASSERT_TRUE(WriteLevelSetFigure(square_, phi_, psi_, h_, direction_, weight_,
                                  "Fig. 7: level sets", path)
                  .ok());
  const std::string svg = ReadText(path);
  ExpectSvgDocument(svg);
  EXPECT_NE(svg.find("Fig. 7: level sets"), std::string::npos);
  EXPECT_NE(svg.find("level lines φ = i·h, h = 3 m (aligned with the guidance)"),
            std::string::npos);
  EXPECT_NE(svg.find("level lines ψ = j·h, h = 3 m (conjugate to φ)"), std::string::npos);
  EXPECT_NE(svg.find("integral curves of the guidance field"), std::string::npos);
  EXPECT_NE(svg.find("weak guidance (weight &lt; 0.5): alignment weighted by it"), std::string::npos);
  EXPECT_NE(svg.find(">N</text>"), std::string::npos);  // north arrow
  EXPECT_EQ(svg.find("one in"), std::string::npos);     // every level drawn
  EXPECT_EQ(Count(svg, "<path color="), 0);             // no face colours
  // Levels 1..4 of each: x = 3, 6, 9, 12 (the last along the boundary), one subpath each.
  const std::string phi_lines = StrokedPathData(svg, "#000000");
  const std::string psi_lines = StrokedPathData(svg, "#1f5fd6");
  EXPECT_EQ(Count(phi_lines, "M"), 4) << phi_lines;
  EXPECT_EQ(Count(psi_lines, "M"), 4) << psi_lines;
  EXPECT_EQ(Count(svg, "url(#"), 2);  // the hatched region and its legend swatch
}

// The x coordinates (px) of a filled region's path (`<path fill="colour" ...d="M x y L x y ...">`).
std::vector<double> RegionXs(const std::string& svg, const std::string& fill) {
  const std::string key = "<path fill=\"" + fill + "\" fill-rule=\"evenodd\" d=\"";
  const size_t start = svg.find(key);
  if (start == std::string::npos) return {};
  const std::string d = svg.substr(start + key.size(), svg.find('"', start + key.size()) - start - key.size());
  std::vector<double> xs;
  const std::regex pair("(-?[0-9.]+) (-?[0-9.]+)");
  for (auto it = std::sregex_iterator(d.begin(), d.end(), pair); it != std::sregex_iterator(); ++it)
    xs.push_back(std::stod((*it)[1]));
  return xs;
}

// With options.min_crossing_deg, faces where φ's and ψ's lines cross shallower are filled
// orange and those that fold over purple, each with a legend entry; nothing when the lines
// are orthogonal.
TEST_F(LevelSetFigure, MarksShallowCrossingsAndFoldOvers) {
  FigureOptions options;
  options.min_crossing_deg = 30.0;
  const std::string path = testing::TempDir() + "/crossings.svg";
  ASSERT_TRUE(WriteLevelSetFigure(square_, phi_, psi_, h_, direction_, weight_, "orthogonal", path, options).ok());
  std::string svg = ReadText(path);
  EXPECT_EQ(svg.find("#fdbf6f"), std::string::npos);  // ψ ⟂ φ: nothing marked
  EXPECT_EQ(svg.find("#6a3d9a"), std::string::npos);

  // From x = 6 m on, ∇ψ turns to 20° from ∇φ (lines crossing at 20°); the left part, x ≤ 4 m
  // hatched, stays orthogonal.
  const double turn = 20.0 * M_PI / 180.0;
  std::vector<double> psi = psi_;
  for (int v = 0; v < square_.num_vertices(); ++v) {
    const Vector3d p = square_.position(v);
    if (p.x() >= 6.0) psi[v] = ((p.x() - 6.0) * std::cos(turn) + p.y() * std::sin(turn)) / h_;
  }
  ASSERT_TRUE(WriteLevelSetFigure(square_, phi_, psi, h_, direction_, weight_, "sheared", path, options).ok());
  svg = ReadText(path);
  EXPECT_NE(svg.find("φ and ψ cross below 30° (sheared quads)"), std::string::npos);
  EXPECT_EQ(svg.find("#6a3d9a"), std::string::npos);
  const std::vector<double> sheared = RegionXs(svg, "#fdbf6f"), hatched = RegionXs(svg, "url(#h0)");
  ASSERT_FALSE(sheared.empty());
  ASSERT_FALSE(hatched.empty());
  // The marked faces all lie right of the hatched strip (x ≤ 4 m) and reach the right edge.
  EXPECT_GT(*std::min_element(sheared.begin(), sheared.end()), *std::max_element(hatched.begin(), hatched.end()));
  EXPECT_GT(*std::max_element(sheared.begin(), sheared.end()), 2.0 * *std::max_element(hatched.begin(), hatched.end()));

  // Measured on the mesh the level sets were solved on when given: the lines drawn orthogonal,
  // the solved ψ sheared, the marks follow the solved one.
  const SolvedLevelSets solved{square_, phi_, psi};
  ASSERT_TRUE(WriteLevelSetFigure(square_, phi_, psi_, h_, direction_, weight_, "solved", path, options, nullptr, &solved).ok());
  svg = ReadText(path);
  EXPECT_NE(svg.find("φ and ψ cross below 30° (sheared quads)"), std::string::npos);

  for (int v = 0; v < square_.num_vertices(); ++v) psi[v] = -square_.position(v).y() / h_;
  ASSERT_TRUE(WriteLevelSetFigure(square_, phi_, psi, h_, direction_, weight_, "folded", path, options).ok());  // ψ = −y/h
  svg = ReadText(path);
  EXPECT_NE(svg.find("φ and ψ fold over (inverted quads)"), std::string::npos);
  EXPECT_EQ(svg.find("#fdbf6f"), std::string::npos);
}

TEST_F(LevelSetFigure, DenseLevelsAreThinnedAndSaidSo) {
  const double h = 0.01;  // 1200 levels across a ~800 px plot
  std::vector<double> phi(square_.num_vertices()), psi(square_.num_vertices());
  for (int v = 0; v < square_.num_vertices(); ++v) {
    phi[v] = square_.position(v).x() / h;
    psi[v] = square_.position(v).y() / h;
  }
  const std::string path = testing::TempDir() + "/dense.svg";
  ASSERT_TRUE(
      WriteLevelSetFigure(square_, phi, psi, h, direction_, weight_, "dense", path).ok());
  const std::string svg = ReadText(path);
  EXPECT_NE(svg.find(", one in "), std::string::npos);
  const int drawn = Count(StrokedPathData(svg, "#000000"), "M");
  EXPECT_GE(drawn, 100);
  EXPECT_LE(drawn, 300);  // at least kMinLevelSpacingPx = 4 px apart
}

TEST_F(LevelSetFigure, WrongInputIsRefusedAndNothingIsWritten) {
  const std::string path = testing::TempDir() + "/bad.svg";
  const Status short_psi = WriteLevelSetFigure(square_, phi_, std::vector<double>(5, 0.0), h_,
                                               direction_, weight_, "bad", path);
  EXPECT_EQ(short_psi.code(), StatusCode::kInvalidInput);
  EXPECT_NE(short_psi.message().find("psi has 5 values"), std::string::npos)
      << short_psi.message();
  std::vector<double> phi = phi_;
  phi[3] = std::numeric_limits<double>::infinity();
  const Status infinite =
      WriteLevelSetFigure(square_, phi, psi_, h_, direction_, weight_, "bad", path);
  EXPECT_NE(infinite.message().find("phi is not finite at vertex 3"), std::string::npos)
      << infinite.message();
  const Status no_spacing =
      WriteLevelSetFigure(square_, phi_, psi_, 0.0, direction_, weight_, "bad", path);
  EXPECT_EQ(no_spacing.code(), StatusCode::kInvalidInput);
  EXPECT_NE(no_spacing.message().find("spacing"), std::string::npos) << no_spacing.message();
  EXPECT_EQ(WriteLevelSetFigure(square_, phi_, psi_, h_, {}, weight_, "bad", path).code(),
            StatusCode::kInvalidInput);
  EXPECT_FALSE(std::filesystem::exists(path));
}

// The Great Court at the example's resolution (~12k faces, h = 3 m), with φ, ψ standing in
// for a solution: lines around the Reading Room ring and across the rectangle.
TEST(LargeMeshFigures, GreatCourtLevelSetFigureIsSmall) {
  TriMesh mesh;
  GeneratorParams court;
  court.name = "great_court";
  court.edge_length = 1.5;
  ASSERT_TRUE(GenerateSurface(court, &mesh).ok());
  const SurfaceModel surface(std::move(mesh));
  const double h = 3.0;
  std::vector<double> phi(surface.num_vertices()), psi(surface.num_vertices());
  for (int v = 0; v < surface.num_vertices(); ++v) {
    const Vector3d p = surface.position(v);
    phi[v] = p.head<2>().norm() / h;
    psi[v] = (p.x() + 0.3 * p.y()) / h;
  }
  std::vector<Vector3d> direction(surface.num_faces());
  std::vector<double> weight(surface.num_faces());
  for (int f = 0; f < surface.num_faces(); ++f) {
    const Vector2d c = Centroid(surface, f);
    direction[f] << -c.y(), c.x(), 0.0;
    weight[f] = c.norm() > 35.0 ? 0.0 : 1.0;
  }
  const std::string path = testing::TempDir() + "/levelsets.svg";
  const auto start = std::chrono::steady_clock::now();
  ASSERT_TRUE(WriteLevelSetFigure(surface, phi, psi, h, direction, weight, "Great Court", path)
                  .ok());
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const auto size = std::filesystem::file_size(path);
  EXPECT_LT(size, 3u << 20);
  std::cout << "Great Court (" << surface.num_faces() << " faces) level-set figure: " << size
            << " bytes in " << seconds << " s\n";
}

TEST(LargeMeshFigures, OneMillionTrianglesFitInTwentyMegabytes) {
  const int n = 708;  // 2·708² = 1,002,528 triangles
  const SurfaceModel surface(testing::ToMesh(testing::GridSoup(n, [n](double x, double y) {
    return 5.0 * std::sin(M_PI * x / n) * std::sin(M_PI * y / n);
  })));
  ASSERT_GE(surface.num_faces(), 1000000);
  std::vector<double> v_z(surface.num_vertices());
  for (int v = 0; v < surface.num_vertices(); ++v) v_z[v] = -0.01 * surface.position(v).z() / 5.0;
  std::vector<Vector3d> direction(surface.num_faces());
  std::vector<double> magnitude(surface.num_faces()), weight(surface.num_faces());
  for (int f = 0; f < surface.num_faces(); ++f) {
    const Vector2d c = Centroid(surface, f) - Vector2d(0.5 * n, 0.5 * n);
    direction[f] << c, 0.0;
    magnitude[f] = c.norm();
    weight[f] = c.norm() > 0.25 * n ? 1.0 : 0.0;
  }
  const std::string dir = testing::TempDir();
  const auto start = std::chrono::steady_clock::now();
  ASSERT_TRUE(WriteDisplacementFigure(surface, v_z, "v_z, 1M triangles", dir + "/v.svg").ok());
  const auto middle = std::chrono::steady_clock::now();
  ASSERT_TRUE(WriteGuidanceFigure(surface, direction, magnitude, "|ε_max|", weight,
                                  "guidance, 1M triangles", dir + "/g.svg")
                  .ok());
  const auto end = std::chrono::steady_clock::now();
  const double h = 20.0;  // ~35 lines per family, as many as 3 m on the Great Court
  std::vector<double> phi(surface.num_vertices()), psi(surface.num_vertices());
  for (int v = 0; v < surface.num_vertices(); ++v) {
    const Vector2d c = surface.position(v).head<2>() - Vector2d(0.5 * n, 0.5 * n);
    phi[v] = c.norm() / h;
    psi[v] = std::atan2(c.y(), c.x()) * 0.25 * n / h;
  }
  ASSERT_TRUE(WriteLevelSetFigure(surface, phi, psi, h, direction, weight,
                                  "level sets, 1M triangles", dir + "/l.svg")
                  .ok());
  const auto level_end = std::chrono::steady_clock::now();
  const auto v_size = std::filesystem::file_size(dir + "/v.svg");
  const auto g_size = std::filesystem::file_size(dir + "/g.svg");
  const auto l_size = std::filesystem::file_size(dir + "/l.svg");
  EXPECT_LT(v_size, 20u << 20);
  EXPECT_LT(g_size, 20u << 20);
  EXPECT_LT(l_size, 20u << 20);
  std::cout << "1M triangles: displacement figure " << v_size << " bytes in "
            << std::chrono::duration<double>(middle - start).count() << " s, guidance figure "
            << g_size << " bytes in " << std::chrono::duration<double>(end - middle).count()
            << " s, level-set figure " << l_size << " bytes in "
            << std::chrono::duration<double>(level_end - end).count() << " s\n";
}

}  // namespace
}  // namespace pqlayout

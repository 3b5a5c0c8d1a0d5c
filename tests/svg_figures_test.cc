// Evenly spaced streamlines (straight, radial and sign-flipped line fields), the SVG canvas
// helpers (colour maps, nice scale-bar lengths and ticks) and the figure compositions
// (structure, labels, grid resampling above the face cap, size of a 1M-triangle figure).
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <random>
#include <sstream>

#include "geometry/streamlines.h"
#include "geometry/surface_generators.h"
#include "geometry/svg_canvas.h"
#include "problems/figures.h"
#include "tests/test_meshes.h"

namespace pqlayout {
namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;
using Polylines = std::vector<std::vector<Vector2d>>;

Vector2d Centroid(const SurfaceModel& s, int f) {
  Vector3d c = Vector3d::Zero();
  for (const int v : s.face_vertices(f)) c += s.position(v) / 3.0;
  return c.head<2>();
}

std::string ReadText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

int Count(const std::string& text, const std::string& what) {
  int n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

// Smallest distance between samples of two different lines.
double MinDistanceBetweenLines(const Polylines& lines) {
  double best = std::numeric_limits<double>::infinity();
  for (size_t a = 0; a < lines.size(); ++a)
    for (size_t b = a + 1; b < lines.size(); ++b)
      for (const auto& p : lines[a])
        for (const auto& q : lines[b]) best = std::min(best, (p - q).norm());
  return best;
}

TEST(Streamlines, ConstantFieldGivesEvenlySpacedHorizontalLines) {
  const double side = 20.0;
  const SurfaceModel square(testing::ToMesh(testing::FlatGridSoup(static_cast<int>(side))));
  StreamlineOptions options;
  options.separation = 1.3;
  const Polylines lines = EvenlySpacedStreamlines(
      square, std::vector<Vector3d>(square.num_faces(), Vector3d::UnitX()), options);

  EXPECT_NEAR(static_cast<double>(lines.size()), side / options.separation, 1.0);
  std::vector<double> heights;
  for (const auto& line : lines) {
    ASSERT_GE(line.size(), 2u);
    for (const auto& p : line) EXPECT_NEAR(p.y(), line.front().y(), 1e-9);
    const auto [left, right] = std::minmax(line.front().x(), line.back().x());
    EXPECT_NEAR(left, 0.0, 1e-6);  // clipped onto the boundary at both ends
    EXPECT_NEAR(right, side, 1e-6);
    heights.push_back(line.front().y());
  }
  std::sort(heights.begin(), heights.end());
  for (size_t i = 1; i < heights.size(); ++i)
    EXPECT_GE(heights[i] - heights[i - 1], options.test_ratio * options.separation);
  EXPECT_LE(heights.front(), options.separation);
  EXPECT_GE(heights.back(), side - options.separation);
}

TEST(Streamlines, RadialFieldOnDiskGivesRadialLines) {
  TriMesh mesh;
  GeneratorParams disk;
  disk.name = "disk";
  disk.width = 20.0;
  disk.edge_length = 0.25;
  ASSERT_TRUE(GenerateSurface(disk, &mesh).ok());
  const SurfaceModel surface(std::move(mesh));
  std::vector<Vector3d> radial(surface.num_faces());
  for (int f = 0; f < surface.num_faces(); ++f) radial[f] << Centroid(surface, f).normalized(), 0.0;
  StreamlineOptions options;
  options.separation = 1.0;
  const Polylines lines = EvenlySpacedStreamlines(surface, radial, options);

  ASSERT_GE(lines.size(), 20u);
  // Collinear with the centre: every point is close to the line through the centre and the
  // farthest point (the field is constant per face, so up to a fraction of an edge).
  double deviation = 0.0;
  for (const auto& line : lines) {
    const auto farthest = std::max_element(
        line.begin(), line.end(),
        [](const Vector2d& a, const Vector2d& b) { return a.squaredNorm() < b.squaredNorm(); });
    const Vector2d u = farthest->normalized();
    for (const auto& p : line)
      deviation = std::max(deviation, std::abs(u.x() * p.y() - u.y() * p.x()));
  }
  EXPECT_LT(deviation, 0.1 * disk.edge_length);
  EXPECT_GE(MinDistanceBetweenLines(lines), options.test_ratio * options.separation * (1 - 1e-9));
}

TEST(Streamlines, SignFlipsPerFaceDoNotChangeTheLines) {
  const SurfaceModel square(testing::ToMesh(testing::FlatGridSoup(16)));
  std::vector<Vector3d> field(square.num_faces()), flipped(square.num_faces());
  std::mt19937 random(7);
  for (int f = 0; f < square.num_faces(); ++f) {
    const Vector2d c = Centroid(square, f);
    const double angle = 0.15 * c.x() + 0.1 * c.y() * c.y() / 16.0;
    field[f] = Vector3d(std::cos(angle), std::sin(angle), 0.0);
    flipped[f] = (random() % 2 == 0) ? field[f] : Vector3d(-field[f]);
  }
  StreamlineOptions options;
  options.separation = 1.0;
  const Polylines reference = EvenlySpacedStreamlines(square, field, options);
  const Polylines with_flips = EvenlySpacedStreamlines(square, flipped, options);
  ASSERT_GE(reference.size(), 10u);
  ASSERT_EQ(reference.size(), with_flips.size());
  for (size_t i = 0; i < reference.size(); ++i) {
    ASSERT_EQ(reference[i].size(), with_flips[i].size());
    for (size_t k = 0; k < reference[i].size(); ++k) EXPECT_EQ(reference[i][k], with_flips[i][k]);
  }
}

TEST(Streamlines, VerticalFacesAndSizeMismatchGiveNoLines) {
  // z = 1e9·x: every face is (nearly) vertical in the top view.
  const SurfaceModel wall(
      testing::ToMesh(testing::GridSoup(4, [](double x, double) { return 1e9 * x; })));
  StreamlineOptions options;
  options.separation = 0.5;
  EXPECT_TRUE(EvenlySpacedStreamlines(
                  wall, std::vector<Vector3d>(wall.num_faces(), Vector3d::UnitY()), options)
                  .empty());
  EXPECT_TRUE(
      EvenlySpacedStreamlines(wall, std::vector<Vector3d>(3, Vector3d::UnitY()), options).empty());
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

void ExpectSvgDocument(const std::string& svg) {
  EXPECT_EQ(svg.rfind("<svg", 0), 0u);
  const size_t end = svg.find_last_not_of(" \n");
  ASSERT_NE(end, std::string::npos);
  EXPECT_EQ(svg.substr(end + 1 - 6, 6), "</svg>");
  EXPECT_EQ(Count(svg, "<svg"), 1);
}

TEST_F(SmallMeshFigures, DisplacementFigureHasOnePathPerFaceAndTheColourBarLabel) {
  const std::string path = testing::TempDir() + "/displacement.svg";
  ASSERT_TRUE(WriteDisplacementFigure(surface_, v_z_, "Fig. 3: v_z under dead load", path).ok());
  const std::string svg = ReadText(path);
  ExpectSvgDocument(svg);
  EXPECT_EQ(Count(svg, "<path color="), surface_.num_faces());
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
  EXPECT_NE(svg.find(BlueWhiteRed(0.0).Hex()), std::string::npos);
  EXPECT_EQ(svg.find(Viridis(0.0).Hex()), std::string::npos);
}

TEST_F(SmallMeshFigures, GuidanceFigureHasLegendLabelAndStreamlines) {
  const std::string path = testing::TempDir() + "/guidance.svg";
  ASSERT_TRUE(WriteGuidanceFigure(surface_, direction_, magnitude_, "|ε_max|", weight_,
                                  "Fig. 6: guidance", path)
                  .ok());
  const std::string svg = ReadText(path);
  ExpectSvgDocument(svg);
  EXPECT_EQ(Count(svg, "<path color="), surface_.num_faces());
  EXPECT_NE(svg.find("alignment not enforced (weight &lt; 0.5)"), std::string::npos);
  EXPECT_NE(svg.find("|ε_max|"), std::string::npos);
  EXPECT_EQ(Count(svg, "<use "), 2);  // streamlines over their halo
}

TEST_F(SmallMeshFigures, AboveTheFaceCapColoursAreResampledOntoAGrid) {
  const std::string path = testing::TempDir() + "/grid.svg";
  FigureOptions options;
  options.max_face_polygons = 10;
  ASSERT_TRUE(WriteDisplacementFigure(surface_, v_z_, "grid", path, options).ok());
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
  const auto v_size = std::filesystem::file_size(dir + "/v.svg");
  const auto g_size = std::filesystem::file_size(dir + "/g.svg");
  EXPECT_LT(v_size, 20u << 20);
  EXPECT_LT(g_size, 20u << 20);
  std::cout << "1M triangles: displacement figure " << v_size << " bytes in "
            << std::chrono::duration<double>(middle - start).count() << " s, guidance figure "
            << g_size << " bytes in " << std::chrono::duration<double>(end - middle).count()
            << " s\n";
}

}  // namespace
}  // namespace pqlayout

// The shell figures: the planarity figures and the oblique 3D view (shared log scale,
// painter's order), and how line widths and glyph density follow the face count (300 to
// 30,000 faces).
#include <gtest/gtest.h>

#include <array>
#include <regex>
#include <string>
#include <vector>

#include "geometry/planarity.h"
#include "geometry/surface_generators.h"
#include "report/figures.h"
#include "report/svg_canvas.h"
#include "tests/svg_test_helpers.h"
#include "tests/test_meshes.h"

namespace pqlayout {
namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;
using testing::Count;
using testing::ExpectSvgDocument;
using testing::ReadText;

// A PolyMesh of quads from a list of corner quadruples.
PolyMesh QuadMesh(const std::vector<std::array<Vector3d, 4>>& quads) {
  PolyMesh mesh;
  for (const auto& quad : quads) {
    std::vector<VertexHandle> corners;
    for (const auto& p : quad) corners.push_back(mesh.add_vertex(ToOpenMesh(p)));
    mesh.add_face(corners);
  }
  return mesh;
}

// An n × n grid of quads on [0, size]², z = 0.
PolyMesh FlatQuadGrid(int n, double size) {
  PolyMesh mesh;
  std::vector<VertexHandle> v;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) v.push_back(mesh.add_vertex(ToOpenMesh(Vector3d(size * i / n, size * j / n, 0.0))));
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      mesh.add_face({v[j * (n + 1) + i], v[j * (n + 1) + i + 1], v[(j + 1) * (n + 1) + i + 1], v[(j + 1) * (n + 1) + i]});
  return mesh;
}

// The value of attribute `name` in the first element that starts with `element_start`.
std::string Attribute(const std::string& svg, const std::string& element_start, const std::string& name) {
  const size_t at = svg.find(element_start);
  if (at == std::string::npos) return "";
  const size_t end = svg.find('>', at);
  const size_t begin = svg.find(" " + name + "=\"", at);
  if (begin == std::string::npos || begin > end) return "";
  const size_t value = begin + name.size() + 3;
  return svg.substr(value, svg.find('"', value) - value);
}

TEST(PlanarityScale, LogarithmicAndWhiteAtTheTarget) {
  const PlanarityScale scale{1e-3};
  EXPECT_DOUBLE_EQ(scale.lo(), 1e-5);
  EXPECT_DOUBLE_EQ(scale.hi(), 1e-1);
  EXPECT_EQ(scale.Colour(1e-3).Hex(), BlueWhiteRed(0.5).Hex());   // white: #f7f7f7
  EXPECT_EQ(scale.Colour(1e-2).Hex(), BlueWhiteRed(0.75).Hex());  // one decade up: a quarter
  EXPECT_EQ(scale.Colour(1e-4).Hex(), BlueWhiteRed(0.25).Hex());
  EXPECT_EQ(scale.Colour(0.0).Hex(), BlueWhiteRed(0.0).Hex());    // triangles, δ = 0
  EXPECT_EQ(scale.Colour(5.0).Hex(), BlueWhiteRed(1.0).Hex());    // clamped
}

TEST(MeshLineWidth, FollowsTheEdgeLengthOnTheDrawing) {
  EXPECT_DOUBLE_EQ(MeshLineWidth(100.0), 1.2);  // few, large faces: capped
  EXPECT_DOUBLE_EQ(MeshLineWidth(10.0), 0.5);   // 5 % of the edge
  EXPECT_DOUBLE_EQ(MeshLineWidth(5.0), 0.3);    // floor
  EXPECT_DOUBLE_EQ(MeshLineWidth(3.9), 0.0);    // too dense to draw
  EXPECT_DOUBLE_EQ(MeshLineOpacity(4.0), 0.35);
  EXPECT_DOUBLE_EQ(MeshLineOpacity(9.5), 0.625);
  EXPECT_DOUBLE_EQ(MeshLineOpacity(15.0), 0.9);
  EXPECT_DOUBLE_EQ(MeshLineOpacity(100.0), 0.9);
}

// One planar unit square and one with a corner lifted by 0.1: δ = 0 and δ = distance between
// the diagonals / mean diagonal = (0.1 · …) computed by PlanarityDelta; the figure shows each
// in its colour on the shared scale and counts the faces meeting the target.
TEST(PlanarityFigure, FacesInTheirScaleColourAndTheTargetMarked) {
  const std::array<Vector3d, 4> flat = {Vector3d(0, 0, 0), Vector3d(1, 0, 0), Vector3d(1, 1, 0), Vector3d(0, 1, 0)};
  const std::array<Vector3d, 4> warped = {Vector3d(2, 0, 0), Vector3d(3, 0, 0), Vector3d(3, 1, 0.1), Vector3d(2, 1, 0)};
  const PolyMesh mesh = QuadMesh({flat, warped});
  const double delta = PlanarityDelta({warped.begin(), warped.end()});
  ASSERT_GT(delta, 1e-2);
  const SurfaceModel surface(testing::ToMesh(testing::GridSoup(3, [](double, double) { return 0.0; })));
  const std::string path = testing::TempDir() + "/planarity.svg";
  ASSERT_TRUE(WritePlanarityFigure(surface, mesh, 1e-3, "Planarity", path).ok());
  const std::string svg = ReadText(path);
  ExpectSvgDocument(svg);
  const PlanarityScale scale{1e-3};
  EXPECT_NE(svg.find("<path color=\"" + scale.Colour(0.0).Hex() + "\""), std::string::npos);
  EXPECT_NE(svg.find("<path color=\"" + scale.Colour(delta).Hex() + "\""), std::string::npos);
  EXPECT_EQ(Count(svg, "<path color="), 2);
  EXPECT_NE(svg.find(">10⁻⁵</text>"), std::string::npos);
  EXPECT_NE(svg.find(">10⁻¹</text>"), std::string::npos);
  EXPECT_NE(svg.find("font-weight=\"bold\""), std::string::npos);
  EXPECT_NE(svg.find(">10⁻³ target</text>"), std::string::npos);
  EXPECT_NE(svg.find("(target): 1 of 2 faces"), std::string::npos);
  EXPECT_NE(svg.find(">N</text>"), std::string::npos);

  EXPECT_FALSE(WritePlanarityFigure(surface, mesh, 0.0, "bad", path + ".bad").ok());
  EXPECT_FALSE(WritePlanarityFigure(surface, PolyMesh(), 1e-3, "bad", path + ".bad").ok());
  EXPECT_FALSE(std::filesystem::exists(path + ".bad"));
  EXPECT_EQ(svg.find("folded"), std::string::npos);  // nothing marked: no outline, no entry

  // Marked faces (the panels planarisation folded): outlined and ringed in one stroked path in
  // the mark colour, counted in a legend row; a face the mesh does not have is refused.
  FigureOptions marked;
  marked.marked_faces = {1};
  marked.marked_label = "panel folded by planarisation";
  ASSERT_TRUE(WritePlanarityFigure(surface, mesh, 1e-3, "Planarity", path, marked).ok());
  const std::string with = ReadText(path);
  EXPECT_NE(with.find("1 panel folded by planarisation (outlined, ringed)"), std::string::npos);
  EXPECT_EQ(Count(with, "stroke=\"#e6a000\""), 1);  // the outline and the ring, one path
  EXPECT_EQ(Count(with, "fill=\"#e6a000\""), 1);    // the legend swatch
  marked.marked_faces = {2};
  EXPECT_FALSE(WritePlanarityFigure(surface, mesh, 1e-3, "bad", path + ".bad", marked).ok());
  EXPECT_FALSE(std::filesystem::exists(path + ".bad"));
}

// Two horizontal squares above each other: seen from above, the upper one is nearer and
// must be drawn after (over) the lower one, whichever comes first in the mesh.
TEST(Shell3dFigure, PaintersOrderDrawsTheNearerFaceLast) {
  const SurfaceModel surface(testing::ToMesh(testing::GridSoup(2, [](double, double) { return 0.0; })));
  const auto square = [](double z, double lift) {
    return std::array<Vector3d, 4>{Vector3d(0, 0, z), Vector3d(2, 0, z), Vector3d(2, 2, z + lift), Vector3d(0, 2, z)};
  };
  for (const bool planar_first : {true, false}) {
    // The planar square at z = 3 (near), the warped one at z = 0 (far).
    const std::array<Vector3d, 4> near = square(3.0, 0.0), far = square(0.0, 0.2);
    const PolyMesh mesh = planar_first ? QuadMesh({near, far}) : QuadMesh({far, near});
    const std::string path = testing::TempDir() + "/shell.svg";
    ASSERT_TRUE(WriteShell3dFigure(surface, mesh, 1e-3, "shell", path).ok());
    const std::string svg = ReadText(path);
    ExpectSvgDocument(svg);
    // Face paths in drawing order: <path fill="#rrggbb" d="..."> (the footprint has a fill-rule).
    std::vector<std::string> fills;
    const std::regex face("<path fill=\"(#[0-9a-f]{6})\" d=\"M");
    for (auto it = std::sregex_iterator(svg.begin(), svg.end(), face); it != std::sregex_iterator(); ++it)
      fills.push_back((*it)[1]);
    ASSERT_EQ(fills.size(), 2u);
    // The far (warped, red) face is drawn first, the near (planar, blue) one over it; shading
    // only darkens, so red stays red-dominant and blue blue-dominant.
    const auto channel = [](const std::string& hex, int k) { return std::stoi(hex.substr(1 + 2 * k, 2), nullptr, 16); };
    EXPECT_GT(channel(fills[0], 0), channel(fills[0], 2)) << fills[0];
    EXPECT_GT(channel(fills[1], 2), channel(fills[1], 0)) << fills[1];
    EXPECT_NE(svg.find(">up</text>"), std::string::npos);  // axis triad, no north arrow
  }
}

// 300 and 30,000 faces of the same 30 m square: member lines thin from 1.2 to 0.3 px and
// disappear at 100,000 faces; the integral curves of a constant field (the guidance
// figure's glyphs) keep their spacing on the drawing, so their number does not change.
TEST(FigureScaling, LineWidthsFollowTheFaceCountAndGlyphDensityTheDrawing) {
  // (stroke-width, stroke-opacity) of the member lines, (0, 0) if none are drawn.
  const auto member_stroke = [&](int n) {
    const PolyMesh mesh = FlatQuadGrid(n, 1.0);
    const SurfaceModel reference(testing::ToMesh(testing::GridSoup(1, [](double, double) { return 0.0; })));
    const std::string path = testing::TempDir() + "/p" + std::to_string(n) + ".svg";
    EXPECT_TRUE(WritePlanarityFigure(reference, mesh, 1e-3, "p", path).ok());
    const std::string svg = ReadText(path);
    EXPECT_EQ(Count(svg, "<path color="), n * n);
    const std::string members = "<path fill=\"none\" stroke=\"#282828\"";
    const std::string width = Attribute(svg, members, "stroke-width");
    const std::string opacity = Attribute(svg, members, "stroke-opacity");
    return width.empty() ? std::make_pair(0.0, 0.0) : std::make_pair(std::stod(width), std::stod(opacity));
  };
  // The reference is the unit square [0, 1]², `plot` px wide on the 1000 px drawing (unit 1).
  const double plot = SvgStyle::kReferenceWidth - SvgStyle::kPadding - SvgStyle::kRightBand;
  EXPECT_EQ(member_stroke(17), std::make_pair(1.2, 0.9));    // 289 faces, edges ~47 px
  const auto dense = member_stroke(173);                      // 29,929 faces, edges ~4.6 px
  EXPECT_DOUBLE_EQ(dense.first, 0.3);
  EXPECT_NEAR(dense.second, 0.35 + 0.55 * (plot / 173 - 4.0) / 11.0, 0.006);  // printed to 0.01
  EXPECT_EQ(member_stroke(316), std::make_pair(0.0, 0.0));   // 99,856 faces, edges ~2.5 px

  const auto streamline_count = [](int n) {
    const SurfaceModel surface(testing::ToMesh(testing::FlatGridSoup(n)));
    std::vector<Vector3d> direction(surface.num_faces(), Vector3d::UnitX());
    std::vector<double> magnitude(surface.num_faces(), 1.0), weight(surface.num_faces(), 1.0);
    const std::string path = testing::TempDir() + "/g" + std::to_string(n) + ".svg";
    EXPECT_TRUE(WriteGuidanceFigure(surface, direction, magnitude, "m", weight, "g", path).ok());
    const std::string svg = ReadText(path);
    const std::string d = Attribute(svg, "<path id=\"l", "d");
    return Count(d, "M");
  };
  const int coarse = streamline_count(12);   // 288 triangles
  const int fine = streamline_count(122);    // 29,768 triangles
  EXPECT_GE(coarse, 30);                     // ~800 px / 16 px
  EXPECT_NEAR(fine, coarse, 0.1 * coarse);
}

}  // namespace
}  // namespace pqlayout

// SvgCanvas: a small writer of self-contained SVG top views (x east, y north, metres) for
// the figures that roof engineers look at. The drawing has a title on top, the plot in
// equal aspect, a colour bar and a north arrow in a column on the right, and a scale bar
// and legend rows below the plot. Every size (fonts, strokes, margins) is given in
// SvgStyle for a 1000 px wide drawing and scaled with the actual width, so a figure looks
// the same whatever the face count. No external assets; fonts are generic sans-serif.
// Coordinates are printed with one decimal in px (0.1 px is below what any viewer shows),
// which keeps files small.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "base/status.h"

namespace pqlayout {

struct Rgb {
  std::uint8_t r = 0, g = 0, b = 0;
  std::string Hex() const;  // "#rrggbb"
};

// Colour maps on t in [0, 1] (clamped; NaN maps to 0).
Rgb Viridis(double t);       // perceptually uniform, for magnitudes (matplotlib's viridis)
Rgb BlueWhiteRed(double t);  // diverging, for signed values: 0 blue, ½ white, 1 red (RdBu)
using ColourMap = Rgb (*)(double);

// Every size of the drawing, in px of a 1000 px wide drawing (scaled with the width).
struct SvgStyle {
  static constexpr double kReferenceWidth = 1000.0;     // sizes below are for this width
  static constexpr double kPadding = 16.0;              // outer margin
  static constexpr double kTitleFont = 24.0;            // title font size
  static constexpr double kLabelFont = 17.0;            // colour-bar label, legend, scale bar
  static constexpr double kTickFont = 16.0;             // colour-bar tick labels
  static constexpr double kCharWidth = 0.56;            // mean glyph width / font size (layout)
  static constexpr double kTopBand = 78.0;              // title row + colour-bar label row
  static constexpr double kRightBand = 180.0;           // colour bar, tick labels, north arrow
  static constexpr double kBottomBand = 62.0;           // scale bar row
  static constexpr double kLegendRow = 26.0;            // height of one legend row
  static constexpr double kMaxAspect = 1.5;             // plot height at most this × width
  static constexpr double kTextGap = 4.0;               // between a mark and its label
  static constexpr double kColourBarGap = 24.0;         // between the plot and the colour bar
  static constexpr double kColourBarWidth = 22.0;       // width of the colour bar
  static constexpr double kColourBarFill = 0.7;         // colour bar at most this × plot height
  static constexpr double kColourBarMaxHeight = 420.0;  // colour bar at most this high
  static constexpr double kTickLength = 6.0;            // colour-bar ticks
  static constexpr double kScaleBarOffset = 22.0;       // from the plot's bottom edge
  static constexpr double kScaleBarHeight = 7.0;        // thickness of the scale bar
  static constexpr double kNorthArrowHeight = 46.0;     // north arrow incl. its "N"
  static constexpr double kNorthArrowWidth = 18.0;      // width of the arrow head
  static constexpr double kSwatchWidth = 28.0;          // legend swatch
  static constexpr double kSwatchHeight = 16.0;         // legend swatch
  static constexpr double kOutlineWidth = 1.6;          // boundary outline stroke
  static constexpr double kFaceSeamWidth = 0.5;         // same-colour stroke hiding AA seams
  static constexpr double kBoxSeamWidth = 1.0;          // the same for grid boxes (cells ≥ 2 px)
  static constexpr double kHatchSpacing = 8.0;          // hatch pattern period
  static constexpr double kHatchWidth = 1.4;            // hatch line width
  static constexpr double kHatchOpacity = 0.7;          // opacity of the hatch background
  static constexpr double kHatchLineShade = 0.7;        // hatch lines: background colour × this
  static constexpr double kHaloWidthRatio = 2.4;        // halo width / line width (HaloPolylines)
  static constexpr double kHaloOpacity = 0.4;           // halo opacity
  static constexpr double kMinPointSpacing = 0.6;       // polyline points closer are dropped
  static constexpr const char* kFont = "sans-serif";    // generic family only
  static constexpr const char* kInk = "#222222";        // text and frame colour
};

// A stroke for polylines: colour, width in px of the reference width, opacity.
struct Stroke {
  Rgb colour;
  double width = 1.0;    // px at SvgStyle::kReferenceWidth, scaled like every size
  double opacity = 1.0;  // 0 transparent .. 1 opaque
};

// A legend entry: a swatch filled with `fill` (a colour "#rrggbb" or "url(#id)") + label.
struct LegendEntry {
  std::string fill;
  std::string label;
};

// The scale-bar length for a plot `world_width` metres wide: 1, 2 or 5 × 10^k metres,
// the one nearest (in ratio) to a fifth of the width.
double NiceScaleBarLength(double world_width);

// About `target` round tick values (step 1, 2 or 5 × 10^k) inside [lo, hi], ascending.
std::vector<double> NiceTicks(double lo, double hi, int target = 5);

class SvgCanvas {
 public:
  // world: the xy box to show (metres, non-empty); width_px: total drawing width.
  SvgCanvas(const Eigen::AlignedBox2d& world, double width_px, const std::string& title);

  double width() const { return width_; }
  double height() const;                                              // grows with the legend rows
  double unit() const { return width_ / SvgStyle::kReferenceWidth; }  // px per style px
  double px_per_metre() const { return scale_; }
  Eigen::Vector2d plot_size_px() const { return plot_size_; }
  // World (metres, y north) to drawing px (y down).
  Eigen::Vector2d ToPx(const Eigen::Vector2d& world) const;

  // Filled polygon in world coordinates, one <path> element each; consecutive polygons
  // share a group that strokes each with its own colour, hiding anti-aliasing seams.
  void Polygon(const std::vector<Eigen::Vector2d>& points, Rgb fill);
  // Filled polygon with its edges stroked by `edge` (for painter's-order drawings, where
  // edges must be hidden by the faces in front); consecutive polygons with the same edge
  // stroke share a group. edge.width <= 0: same as Polygon.
  void OutlinedPolygon(const std::vector<Eigen::Vector2d>& points, Rgb fill, const Stroke& edge);
  // Axis-aligned world boxes filled with one colour, as a single <path> element.
  void Boxes(const std::vector<Eigen::AlignedBox2d>& boxes, Rgb fill);
  // Closed rings (outer rings and holes, even-odd rule) filled with `fill` (a colour or a
  // url(#id) from HatchFill), as a single <path> element.
  void Region(const std::vector<std::vector<Eigen::Vector2d>>& rings, const std::string& fill);
  // Open (or closed) polylines with one stroke, as a single <path> element; points closer
  // than SvgStyle::kMinPointSpacing px to the last kept one are dropped.
  void Polylines(const std::vector<std::vector<Eigen::Vector2d>>& lines, const Stroke& stroke,
                 bool closed = false);
  // Polylines drawn over a wider white halo so they read on dark and light backgrounds.
  void HaloPolylines(const std::vector<std::vector<Eigen::Vector2d>>& lines, const Stroke& stroke);
  // A filled circle; radius in px of the reference width.
  void Circle(const Eigen::Vector2d& centre, double radius, Rgb fill);
  // Text at a world point; size in px of the reference width; anchor start|middle|end.
  void Text(const Eigen::Vector2d& at, const std::string& text, double size,
            const std::string& anchor = "middle");

  // Defines a diagonal hatch (translucent `colour` background, darker lines) and returns
  // the fill reference "url(#...)" for Region and LegendEntry.
  std::string HatchFill(Rgb colour);

  // Vertical colour bar right of the plot for values lo..hi with ~5 round ticks and the
  // label (with units) above it; very small or large values get a common ×10^k factor.
  void ColourBar(ColourMap map, double lo, double hi, const std::string& label);
  // Vertical colour bar for values lo..hi (> 0) on a logarithmic scale, ticks at the powers
  // of ten labelled "10⁻³"; each mark (value, text) is drawn as a bold line across the bar
  // with its text after the tick label (ticks closer than a line of text to a mark that is
  // not a power of ten are left out).
  struct Mark {
    double value;
    std::string text;
  };
  void LogColourBar(ColourMap map, double lo, double hi, const std::string& label,
                    const std::vector<Mark>& marks);
  // Scale bar of NiceScaleBarLength metres below the plot, labelled "L m".
  void ScaleBar();
  // North arrow at the bottom of the right column.
  void NorthArrow();
  // Instead of the north arrow, for oblique views: arrows east, north and up as they appear
  // in the drawing (each a 2D direction, y up, length ≤ 1 = full arrow), labelled E, N, up.
  void AxisTriad(const Eigen::Vector2d& east, const Eigen::Vector2d& north,
                 const Eigen::Vector2d& up);
  // One row per entry below the scale bar: swatch + label.
  void Legend(const std::vector<LegendEntry>& entries);

  // The root element carries data-plot="x y w h": the plot rectangle in px, for checks
  // that look at the data area only (scripts/check_report.sh).
  std::string ToSvg() const;
  Status Write(const std::string& path) const;  // atomically

 private:
  void CloseFaceGroup();
  void OpenFaceGroup(const std::string& attributes);
  void FacePath(const std::string& attribute, const std::vector<Eigen::Vector2d>& points);
  Eigen::Vector2d ColourBarTopLeft() const;
  Eigen::Vector2d ColourBarSize() const;
  void ColourBarLabel(const Eigen::Vector2d& top_left, const std::string& text);
  // Tick marks at relative heights s ∈ [0, 1] (0 bottom) with their labels.
  struct Tick {
    double s;
    std::string label;
    bool bold = false;
  };
  void DrawColourBarTicks(const std::vector<Tick>& ticks, const Eigen::Vector2d& top_left,
                          const Eigen::Vector2d& size);
  void AddPx(const Eigen::Vector2d& world);  // appends "x y" in px to body_
  void TextPx(const Eigen::Vector2d& px, const std::string& text, double size,
              const std::string& anchor);
  void ColourBarGradient(ColourMap map, const Eigen::Vector2d& top_left,
                         const Eigen::Vector2d& size);
  void ColourBarTicks(double lo, double hi, int exponent, const Eigen::Vector2d& top_left,
                      const Eigen::Vector2d& size);

  Eigen::AlignedBox2d world_;
  double width_ = 0.0;
  double scale_ = 1.0;           // px per metre
  Eigen::Vector2d plot_origin_;  // px of the plot's top-left corner
  Eigen::Vector2d plot_size_;    // px
  int legend_rows_ = 0;
  int next_id_ = 0;  // for pattern/gradient ids
  std::string face_group_;  // attributes of the open face group, "" if none
  std::string defs_;
  std::string body_;
};

}  // namespace pqlayout

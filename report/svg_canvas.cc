#include "report/svg_canvas.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

#include "base/atomic_file.h"
#include "report/svg_format.h"

namespace pqlayout {

using namespace svg_format;

namespace {

struct ColourStop {
  double t;
  double r, g, b;  // in [0, 1]
};

// matplotlib's viridis table (256 entries) sampled at every 16th entry and the last.
constexpr std::array<ColourStop, 17> kViridis = {{
    {0 / 255.0, 0.267004, 0.004874, 0.329415},
    {16 / 255.0, 0.282327, 0.094955, 0.417331},
    {32 / 255.0, 0.278826, 0.175490, 0.483397},
    {48 / 255.0, 0.258965, 0.251537, 0.524736},
    {64 / 255.0, 0.229739, 0.322361, 0.545706},
    {80 / 255.0, 0.199430, 0.387607, 0.554642},
    {96 / 255.0, 0.172719, 0.448791, 0.557885},
    {112 / 255.0, 0.149039, 0.508051, 0.557250},
    {128 / 255.0, 0.127568, 0.566949, 0.550556},
    {144 / 255.0, 0.120638, 0.625828, 0.533488},
    {160 / 255.0, 0.157851, 0.683765, 0.501686},
    {176 / 255.0, 0.246070, 0.738910, 0.452024},
    {192 / 255.0, 0.369214, 0.788888, 0.382914},
    {208 / 255.0, 0.515992, 0.831158, 0.294279},
    {224 / 255.0, 0.678489, 0.863742, 0.189503},
    {240 / 255.0, 0.845561, 0.887322, 0.099702},
    {255 / 255.0, 0.993248, 0.906157, 0.143936},
}};

// ColorBrewer RdBu (11 classes), reversed so that low values are blue.
constexpr std::array<ColourStop, 11> kBlueWhiteRed = {{
    {0.0, 0x05 / 255.0, 0x30 / 255.0, 0x61 / 255.0},
    {0.1, 0x21 / 255.0, 0x66 / 255.0, 0xac / 255.0},
    {0.2, 0x43 / 255.0, 0x93 / 255.0, 0xc3 / 255.0},
    {0.3, 0x92 / 255.0, 0xc5 / 255.0, 0xde / 255.0},
    {0.4, 0xd1 / 255.0, 0xe5 / 255.0, 0xf0 / 255.0},
    {0.5, 0xf7 / 255.0, 0xf7 / 255.0, 0xf7 / 255.0},
    {0.6, 0xfd / 255.0, 0xdb / 255.0, 0xc7 / 255.0},
    {0.7, 0xf4 / 255.0, 0xa5 / 255.0, 0x82 / 255.0},
    {0.8, 0xd6 / 255.0, 0x60 / 255.0, 0x4d / 255.0},
    {0.9, 0xb2 / 255.0, 0x18 / 255.0, 0x2b / 255.0},
    {1.0, 0x67 / 255.0, 0x00 / 255.0, 0x1f / 255.0},
}};

std::uint8_t ToByte(double c) {
  return static_cast<std::uint8_t>(std::lround(std::clamp(c, 0.0, 1.0) * 255.0));
}

template <size_t N>
Rgb Interpolate(const std::array<ColourStop, N>& stops, double t) {
  t = std::isnan(t) ? 0.0 : std::clamp(t, 0.0, 1.0);
  size_t i = 1;
  while (i + 1 < N && stops[i].t < t) ++i;
  const ColourStop& a = stops[i - 1];
  const ColourStop& b = stops[i];
  const double s = (t - a.t) / (b.t - a.t);
  return {ToByte(a.r + s * (b.r - a.r)), ToByte(a.g + s * (b.g - a.g)),
          ToByte(a.b + s * (b.b - a.b))};
}

Rgb Darker(Rgb c, double factor) {
  return {ToByte(c.r / 255.0 * factor), ToByte(c.g / 255.0 * factor), ToByte(c.b / 255.0 * factor)};
}

}  // namespace

std::string Rgb::Hex() const {
  char buffer[8];
  std::snprintf(buffer, sizeof(buffer), "#%02x%02x%02x", r, g, b);
  return buffer;
}

Rgb Viridis(double t) { return Interpolate(kViridis, t); }
Rgb BlueWhiteRed(double t) { return Interpolate(kBlueWhiteRed, t); }

double NiceScaleBarLength(double world_width) {
  const double target = world_width / 5.0;
  const double power = std::pow(10.0, std::floor(std::log10(target)));
  double best = power;
  for (const double mantissa : {1.0, 2.0, 5.0, 10.0}) {
    const double length = mantissa * power;
    if (std::abs(std::log(length / target)) < std::abs(std::log(best / target))) best = length;
  }
  return best;
}

std::vector<double> NiceTicks(double lo, double hi, int target) {
  if (!(hi > lo)) return {lo};
  // The largest step (1, 2 or 5 × 10^k) that still gives at least target - 1 ticks.
  const double p = std::pow(10.0, std::floor(std::log10(hi - lo)));
  std::vector<double> ticks;
  for (const double step : {5 * p, 2 * p, p, p / 2, p / 5, p / 10}) {
    ticks.clear();
    for (double k = std::ceil(lo / step - 1e-9); k * step <= hi + 1e-9 * step; k += 1.0)
      ticks.push_back(k == 0.0 ? 0.0 : k * step);  // no "-0"
    if (static_cast<int>(ticks.size()) >= target - 1) break;
  }
  return ticks;
}

SvgCanvas::SvgCanvas(const Eigen::AlignedBox2d& world, double width_px, const std::string& title)
    : world_(world), width_(width_px) {
  const double u = unit();
  Eigen::Vector2d size = world_.sizes().cwiseMax(1e-9);
  world_.max() = world_.min() + size;
  const double plot_width = width_ - (SvgStyle::kPadding + SvgStyle::kRightBand) * u;
  scale_ = std::min(plot_width / size.x(), SvgStyle::kMaxAspect * plot_width / size.y());
  plot_origin_ = Eigen::Vector2d(SvgStyle::kPadding, SvgStyle::kTopBand) * u;
  plot_size_ = size * scale_;
  // A long title (the planarity figure's counts run to ~100 characters) is set smaller so that
  // it fits the drawing's width instead of being cut at its edge: sans-serif glyphs average
  // ~0.55 of the font size; characters are counted, not UTF-8 bytes.
  const double characters = static_cast<double>(
      std::count_if(title.begin(), title.end(), [](char c) { return (static_cast<unsigned char>(c) & 0xC0) != 0x80; }));
  const double fits = (width_ / u - 2.0 * SvgStyle::kPadding) / (0.55 * std::max(characters, 1.0));
  TextPx({SvgStyle::kPadding * u, (SvgStyle::kPadding + SvgStyle::kTitleFont) * u}, title,
         std::min(SvgStyle::kTitleFont, fits), "start");
}

double SvgCanvas::height() const {
  const double below =
      SvgStyle::kBottomBand + legend_rows_ * SvgStyle::kLegendRow + SvgStyle::kPadding;
  return plot_origin_.y() + plot_size_.y() + below * unit();
}

Eigen::Vector2d SvgCanvas::ToPx(const Eigen::Vector2d& p) const {
  return plot_origin_ +
         scale_ * Eigen::Vector2d(p.x() - world_.min().x(), world_.max().y() - p.y());
}

void SvgCanvas::AddPx(const Eigen::Vector2d& world) {
  const Eigen::Vector2d px = ToPx(world);
  AppendNumber(&body_, px.x());
  body_ += ' ';
  AppendNumber(&body_, px.y());
}

void SvgCanvas::CloseFaceGroup() {
  if (face_group_.empty()) return;
  body_ += "</g>\n";
  face_group_.clear();
}

void SvgCanvas::OpenFaceGroup(const std::string& attributes) {
  if (face_group_ == attributes) return;
  CloseFaceGroup();
  body_ += "<g " + attributes + ">\n";
  face_group_ = attributes;
}

void SvgCanvas::FacePath(const std::string& attribute, const std::vector<Eigen::Vector2d>& points) {
  body_ += "<path " + attribute + " d=\"M";
  for (size_t i = 0; i < points.size(); ++i) {
    if (i == 1) body_ += 'L';
    if (i > 1) body_ += ' ';
    AddPx(points[i]);
  }
  body_ += "Z\"/>\n";
}

void SvgCanvas::Polygon(const std::vector<Eigen::Vector2d>& points, Rgb fill) {
  if (points.size() < 3) return;
  OpenFaceGroup(
      "fill=\"currentColor\" stroke=\"currentColor\" stroke-linejoin=\"round\" stroke-width=\"" +
      Number(SvgStyle::kFaceSeamWidth * unit(), 2) + "\"");
  FacePath("color=\"" + fill.Hex() + "\"", points);
}

void SvgCanvas::OutlinedPolygon(const std::vector<Eigen::Vector2d>& points, Rgb fill,
                                const Stroke& edge) {
  if (!(edge.width > 0.0)) return Polygon(points, fill);
  if (points.size() < 3) return;
  OpenFaceGroup("stroke=\"" + edge.colour.Hex() + "\" stroke-width=\"" +
                Number(edge.width * unit(), 2) + "\" stroke-opacity=\"" + Number(edge.opacity, 2) +
                "\" stroke-linejoin=\"round\"");
  FacePath("fill=\"" + fill.Hex() + "\"", points);
}

void SvgCanvas::Boxes(const std::vector<Eigen::AlignedBox2d>& boxes, Rgb fill) {
  if (boxes.empty()) return;
  CloseFaceGroup();
  const std::string colour = fill.Hex();
  body_ += "<path fill=\"" + colour + "\" stroke=\"" + colour + "\" stroke-width=\"" +
           Number(SvgStyle::kBoxSeamWidth * unit(), 2) + "\" d=\"";
  for (const auto& box : boxes) {
    const Eigen::Vector2d a = ToPx({box.min().x(), box.max().y()});
    const Eigen::Vector2d b = ToPx({box.max().x(), box.min().y()});
    body_ += 'M';
    AppendNumber(&body_, a.x());
    body_ += ' ';
    AppendNumber(&body_, a.y());
    body_ += 'H';
    AppendNumber(&body_, b.x());
    body_ += 'V';
    AppendNumber(&body_, b.y());
    body_ += 'H';
    AppendNumber(&body_, a.x());
    body_ += 'Z';
  }
  body_ += "\"/>\n";
}

namespace {

// SVG path data "M x yL x y x y…" (px) for each line, dropping points closer than
// min_spacing px to the last kept one (the last point is always kept).
template <typename ToPxFn>
std::string PathData(const std::vector<std::vector<Eigen::Vector2d>>& lines, bool closed,
                     double min_spacing, const ToPxFn& to_px) {
  std::string d;
  for (const auto& line : lines) {
    std::vector<Eigen::Vector2d> kept;
    for (size_t i = 0; i < line.size(); ++i) {
      const Eigen::Vector2d p = to_px(line[i]);
      const bool last = (i + 1 == line.size());
      if (!kept.empty() && (p - kept.back()).norm() < min_spacing) {
        if (last && kept.size() > 1) kept.back() = p;
        continue;
      }
      kept.push_back(p);
    }
    if (kept.size() < 2) continue;
    for (size_t i = 0; i < kept.size(); ++i) {
      d += (i == 0 ? "M" : i == 1 ? "L" : " ");
      AppendNumber(&d, kept[i].x());
      d += ' ';
      AppendNumber(&d, kept[i].y());
    }
    if (closed) d += 'Z';
  }
  return d;
}

}  // namespace

void SvgCanvas::Region(const std::vector<std::vector<Eigen::Vector2d>>& rings,
                       const std::string& fill) {
  CloseFaceGroup();
  const std::string d = PathData(rings, true, SvgStyle::kMinPointSpacing * unit(),
                                 [this](const Eigen::Vector2d& p) { return ToPx(p); });
  if (d.empty()) return;
  body_ += "<path fill=\"" + fill + "\" fill-rule=\"evenodd\" d=\"" + d + "\"/>\n";
}

namespace {

std::string StrokeAttributes(const Stroke& stroke, double unit) {
  return "fill=\"none\" stroke=\"" + stroke.colour.Hex() + "\" stroke-width=\"" +
         Number(stroke.width * unit, 2) + "\" stroke-opacity=\"" + Number(stroke.opacity, 2) +
         "\" stroke-linecap=\"round\" stroke-linejoin=\"round\"";
}

}  // namespace

void SvgCanvas::Polylines(const std::vector<std::vector<Eigen::Vector2d>>& lines,
                          const Stroke& stroke, bool closed) {
  CloseFaceGroup();
  const std::string d = PathData(lines, closed, SvgStyle::kMinPointSpacing * unit(),
                                 [this](const Eigen::Vector2d& p) { return ToPx(p); });
  if (d.empty()) return;
  body_ += "<path " + StrokeAttributes(stroke, unit()) + " d=\"" + d + "\"/>\n";
}

void SvgCanvas::HaloPolylines(const std::vector<std::vector<Eigen::Vector2d>>& lines,
                              const Stroke& stroke) {
  CloseFaceGroup();
  const std::string d = PathData(lines, false, SvgStyle::kMinPointSpacing * unit(),
                                 [this](const Eigen::Vector2d& p) { return ToPx(p); });
  if (d.empty()) return;
  const std::string id = "l" + std::to_string(next_id_++);
  defs_ += "<path id=\"" + id + "\" d=\"" + d + "\"/>\n";
  const Stroke halo{Rgb{255, 255, 255}, SvgStyle::kHaloWidthRatio * stroke.width,
                    SvgStyle::kHaloOpacity};
  for (const Stroke& s : {halo, stroke})
    body_ += "<use xlink:href=\"#" + id + "\" " + StrokeAttributes(s, unit()) + "/>\n";
}

void SvgCanvas::Circle(const Eigen::Vector2d& centre, double radius, Rgb fill) {
  CloseFaceGroup();
  const Eigen::Vector2d c = ToPx(centre);
  body_ += "<circle cx=\"" + Number(c.x()) + "\" cy=\"" + Number(c.y()) + "\" r=\"" +
           Number(radius * unit()) + "\" fill=\"" + fill.Hex() + "\"/>\n";
}

void SvgCanvas::Text(const Eigen::Vector2d& at, const std::string& text, double size,
                     const std::string& anchor) {
  TextPx(ToPx(at), text, size, anchor);
}

void SvgCanvas::TextPx(const Eigen::Vector2d& px, const std::string& text, double size,
                       const std::string& anchor) {
  CloseFaceGroup();
  body_ += "<text x=\"" + Number(px.x()) + "\" y=\"" + Number(px.y()) + "\" font-size=\"" +
           Number(size * unit()) + "\" text-anchor=\"" + anchor + "\">" + EscapeXml(text) +
           "</text>\n";
}

std::string SvgCanvas::HatchFill(Rgb colour) {
  const std::string id = "h" + std::to_string(next_id_++);
  const std::string s = Number(SvgStyle::kHatchSpacing * unit());
  defs_ += "<pattern id=\"" + id + "\" patternUnits=\"userSpaceOnUse\" width=\"" + s +
           "\" height=\"" + s + "\" patternTransform=\"rotate(45)\"><rect width=\"" + s +
           "\" height=\"" + s + "\" fill=\"" + colour.Hex() + "\" fill-opacity=\"" +
           Number(SvgStyle::kHatchOpacity, 2) + "\"/><rect width=\"" +
           Number(SvgStyle::kHatchWidth * unit()) + "\" height=\"" + s + "\" fill=\"" +
           Darker(colour, SvgStyle::kHatchLineShade).Hex() + "\"/></pattern>\n";
  return "url(#" + id + ")";
}

std::string SvgCanvas::ToSvg() const {
  const std::string w = Number(width_), h = Number(height());
  std::string svg =
      "<svg xmlns=\"http://www.w3.org/2000/svg\" xmlns:xlink=\"http://www.w3.org/1999/xlink\" "
      "width=\"" +
      w + "\" height=\"" + h + "\" viewBox=\"0 0 " + w + " " + h + "\" data-plot=\"" +
      Number(plot_origin_.x()) + " " + Number(plot_origin_.y()) + " " + Number(plot_size_.x()) +
      " " + Number(plot_size_.y()) + "\" font-family=\"" +
      SvgStyle::kFont + "\" fill=\"" + SvgStyle::kInk + "\">\n";
  if (!defs_.empty()) svg += "<defs>\n" + defs_ + "</defs>\n";
  svg += "<rect width=\"" + w + "\" height=\"" + h + "\" fill=\"#ffffff\"/>\n";
  svg += body_;
  if (!face_group_.empty()) svg += "</g>\n";
  svg += "</svg>\n";
  return svg;
}

Status SvgCanvas::Write(const std::string& path) const {
  return WriteTextFileAtomically(path, ToSvg());
}

}  // namespace pqlayout

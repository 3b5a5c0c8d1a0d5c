#include "report/svg_canvas.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

#include "base/atomic_file.h"

namespace pqlayout {
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

// Appends `value` rounded to `decimals` decimals, without trailing zeros ("12.3", "-4", "0").
void AppendNumber(std::string* out, double value, int decimals = 1) {
  static constexpr long long kPow10[] = {1, 10, 100, 1000, 10000};
  const long long scale = kPow10[decimals];
  long long q = std::llround(value * static_cast<double>(scale));
  if (q < 0) {
    out->push_back('-');
    q = -q;
  }
  *out += std::to_string(q / scale);
  long long frac = q % scale;
  if (frac == 0) return;
  std::string digits = std::to_string(frac);
  digits.insert(0, static_cast<size_t>(decimals) - digits.size(), '0');
  digits.erase(digits.find_last_not_of('0') + 1);
  *out += '.' + digits;
}

std::string Number(double value, int decimals = 1) {
  std::string s;
  AppendNumber(&s, value, decimals);
  return s;
}

std::string EscapeXml(const std::string& text) {
  std::string out;
  for (const char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

// Number of characters (UTF-8 code points), for text-width estimates.
int CodePoints(const std::string& text) {
  return static_cast<int>(
      std::count_if(text.begin(), text.end(), [](char c) { return (c & 0xC0) != 0x80; }));
}

// "×10⁻⁵" for exponent -5.
std::string PowerOfTen(int exponent) {
  static const char* kSuperscript[] = {"⁰", "¹", "²", "³", "⁴", "⁵", "⁶", "⁷", "⁸", "⁹"};
  std::string digits;
  for (const char c : std::to_string(std::abs(exponent))) digits += kSuperscript[c - '0'];
  return std::string("×10") + (exponent < 0 ? "⁻" : "") + digits;
}

// Decimals needed to print multiples of `step` exactly (step from NiceTicks).
int DecimalsFor(double step) {
  return std::clamp(static_cast<int>(std::ceil(-std::log10(step) - 1e-9)), 0, 4);
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
  TextPx({SvgStyle::kPadding * u, (SvgStyle::kPadding + SvgStyle::kTitleFont) * u}, title,
         SvgStyle::kTitleFont, "start");
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

Eigen::Vector2d SvgCanvas::ColourBarTopLeft() const {
  return {plot_origin_.x() + plot_size_.x() + SvgStyle::kColourBarGap * unit(), plot_origin_.y()};
}

Eigen::Vector2d SvgCanvas::ColourBarSize() const {
  return {SvgStyle::kColourBarWidth * unit(),
          std::min(SvgStyle::kColourBarFill * plot_size_.y(),
                   SvgStyle::kColourBarMaxHeight * unit())};
}

void SvgCanvas::ColourBarLabel(const Eigen::Vector2d& top_left, const std::string& text) {
  const double u = unit();
  const double text_width = CodePoints(text) * SvgStyle::kCharWidth * SvgStyle::kLabelFont * u;
  const bool fits = top_left.x() + text_width <= width_ - SvgStyle::kPadding * u;
  TextPx({fits ? top_left.x() : width_ - SvgStyle::kPadding * u,
          top_left.y() - 3.0 * SvgStyle::kTextGap * u},
         text, SvgStyle::kLabelFont, fits ? "start" : "end");
}

void SvgCanvas::ColourBar(ColourMap map, double lo, double hi, const std::string& label) {
  const Eigen::Vector2d top_left = ColourBarTopLeft(), size = ColourBarSize();
  const double magnitude = std::max(std::abs(lo), std::abs(hi));
  const int order = magnitude > 0.0 ? static_cast<int>(std::floor(std::log10(magnitude))) : 0;
  const int exponent = (order >= 4 || order <= -3) ? order : 0;
  ColourBarGradient(map, top_left, size);
  ColourBarTicks(lo, hi, exponent, top_left, size);
  ColourBarLabel(top_left, exponent == 0 ? label : label + " " + PowerOfTen(exponent));
}

void SvgCanvas::LogColourBar(ColourMap map, double lo, double hi, const std::string& label,
                             const std::vector<Mark>& marks) {
  const Eigen::Vector2d top_left = ColourBarTopLeft(), size = ColourBarSize();
  ColourBarGradient(map, top_left, size);
  const double log_lo = std::log10(lo), log_hi = std::log10(hi);
  const auto s_of = [&](double v) { return (std::log10(v) - log_lo) / (log_hi - log_lo); };
  const double min_gap = 1.2 * SvgStyle::kTickFont * unit() / size.y();  // in s
  std::vector<Tick> ticks;
  for (int k = static_cast<int>(std::ceil(log_lo - 1e-9)); k <= log_hi + 1e-9; ++k) {
    Tick tick{s_of(std::pow(10.0, k)), "10" + PowerOfTen(k).substr(std::string("×10").size())};
    for (const Mark& mark : marks) {
      const double s = s_of(mark.value);
      if (std::abs(s - tick.s) < 1e-9) {
        tick.label += " " + mark.text;
        tick.bold = true;
      } else if (std::abs(s - tick.s) < min_gap) {
        tick.label.clear();  // room for the mark's own label
      }
    }
    ticks.push_back(tick);
  }
  for (const Mark& mark : marks) {
    const double s = s_of(mark.value);
    const bool on_tick = std::any_of(ticks.begin(), ticks.end(), [&](const Tick& t) {
      return std::abs(t.s - s) < 1e-9;
    });
    if (!on_tick && s >= 0.0 && s <= 1.0) {
      char value[32];
      std::snprintf(value, sizeof(value), "%g", mark.value);
      ticks.push_back({s, mark.text + " " + value, true});
    }
  }
  DrawColourBarTicks(ticks, top_left, size);
  ColourBarLabel(top_left, label);
}

void SvgCanvas::ColourBarGradient(ColourMap map, const Eigen::Vector2d& top_left,
                                  const Eigen::Vector2d& size) {
  CloseFaceGroup();
  const std::string id = "g" + std::to_string(next_id_++);
  defs_ += "<linearGradient id=\"" + id + "\" x1=\"0\" y1=\"1\" x2=\"0\" y2=\"0\">";
  constexpr int kStops = 16;
  for (int i = 0; i <= kStops; ++i) {
    const double t = static_cast<double>(i) / kStops;
    defs_ += "<stop offset=\"" + Number(t, 4) + "\" stop-color=\"" + map(t).Hex() + "\"/>";
  }
  defs_ += "</linearGradient>\n";
  body_ += "<rect x=\"" + Number(top_left.x()) + "\" y=\"" + Number(top_left.y()) + "\" width=\"" +
           Number(size.x()) + "\" height=\"" + Number(size.y()) + "\" fill=\"url(#" + id +
           ")\" stroke=\"" + SvgStyle::kInk + "\" stroke-width=\"" + Number(unit(), 2) + "\"/>\n";
}

void SvgCanvas::ColourBarTicks(double lo, double hi, int exponent, const Eigen::Vector2d& top_left,
                               const Eigen::Vector2d& size) {
  const double factor = std::pow(10.0, -exponent);
  const std::vector<double> values = NiceTicks(lo * factor, hi * factor);
  const int decimals = values.size() > 1 ? DecimalsFor(values[1] - values[0]) : 2;
  std::vector<Tick> ticks;
  for (const double value : values)
    ticks.push_back({hi > lo ? (value / factor - lo) / (hi - lo) : 0.5, Number(value, decimals)});
  DrawColourBarTicks(ticks, top_left, size);
}

void SvgCanvas::DrawColourBarTicks(const std::vector<Tick>& ticks, const Eigen::Vector2d& top_left,
                                   const Eigen::Vector2d& size) {
  const double u = unit();
  const double x = top_left.x() + size.x();
  std::string d, bold;
  for (const Tick& tick : ticks) {
    const double y = top_left.y() + (1.0 - tick.s) * size.y();
    if (tick.bold)  // a mark: across the bar and out like a tick
      bold += "M" + Number(top_left.x()) + " " + Number(y) + "H" +
              Number(x + SvgStyle::kTickLength * u);
    else
      d += "M" + Number(x) + " " + Number(y) + "h" + Number(SvgStyle::kTickLength * u);
    if (tick.label.empty()) continue;
    TextPx(
        {x + (SvgStyle::kTickLength + SvgStyle::kTextGap) * u, y + 0.35 * SvgStyle::kTickFont * u},
        tick.label, SvgStyle::kTickFont, "start");
    if (tick.bold) body_.insert(body_.rfind("<text ") + 6, "font-weight=\"bold\" ");
  }
  body_ += "<path fill=\"none\" stroke=\"" + std::string(SvgStyle::kInk) + "\" stroke-width=\"" +
           Number(u, 2) + "\" d=\"" + d + "\"/>\n";
  if (!bold.empty())
    body_ += "<path fill=\"none\" stroke=\"" + std::string(SvgStyle::kInk) + "\" stroke-width=\"" +
             Number(2.5 * u, 2) + "\" d=\"" + bold + "\"/>\n";
}

void SvgCanvas::ScaleBar() {
  CloseFaceGroup();
  const double u = unit();
  const double length = NiceScaleBarLength(world_.sizes().x());
  const double px = length * scale_;
  const double x = plot_origin_.x(),
               y = plot_origin_.y() + plot_size_.y() + SvgStyle::kScaleBarOffset * u;
  const double h = SvgStyle::kScaleBarHeight * u;
  const std::string ink = SvgStyle::kInk;
  for (int half = 0; half < 2; ++half)
    body_ += "<rect x=\"" + Number(x + half * 0.5 * px) + "\" y=\"" + Number(y) + "\" width=\"" +
             Number(0.5 * px) + "\" height=\"" + Number(h) + "\" fill=\"" +
             (half == 0 ? ink : std::string("#ffffff")) + "\" stroke=\"" + ink +
             "\" stroke-width=\"" + Number(u, 2) + "\"/>\n";
  const double text_y = y + h + (SvgStyle::kTextGap + SvgStyle::kLabelFont) * u;
  char text[32];
  std::snprintf(text, sizeof(text), "%g m", length);
  TextPx({x, text_y}, "0", SvgStyle::kLabelFont, "middle");
  TextPx({x + px, text_y}, text, SvgStyle::kLabelFont, "middle");
}

void SvgCanvas::NorthArrow() {
  CloseFaceGroup();
  const double u = unit();
  const double cx = plot_origin_.x() + plot_size_.x() +
                    (SvgStyle::kColourBarGap + 0.5 * SvgStyle::kColourBarWidth) * u;
  const double bottom = plot_origin_.y() + plot_size_.y();
  const double tip =
      bottom - (SvgStyle::kNorthArrowHeight - SvgStyle::kLabelFont - SvgStyle::kTextGap) * u;
  const double half = 0.5 * SvgStyle::kNorthArrowWidth * u;
  body_ += "<path fill=\"" + std::string(SvgStyle::kInk) + "\" d=\"M" + Number(cx) + " " +
           Number(tip) + "L" + Number(cx + half) + " " + Number(bottom) + " " + Number(cx) + " " +
           Number(bottom - 0.3 * (bottom - tip)) + " " + Number(cx - half) + " " + Number(bottom) +
           "Z\"/>\n";
  TextPx({cx, tip - SvgStyle::kTextGap * u}, "N", SvgStyle::kLabelFont, "middle");
}

void SvgCanvas::AxisTriad(const Eigen::Vector2d& east, const Eigen::Vector2d& north,
                          const Eigen::Vector2d& up) {
  CloseFaceGroup();
  const double u = unit();
  // Centred in the right column (between the colour-bar gap and the padding), at the bottom.
  const double column = SvgStyle::kRightBand - SvgStyle::kColourBarGap - SvgStyle::kPadding;
  const double length = 0.3 * column * u;
  const Eigen::Vector2d origin(
      plot_origin_.x() + plot_size_.x() + (SvgStyle::kColourBarGap + 0.5 * column) * u,
      plot_origin_.y() + plot_size_.y() - 0.5 * length);
  std::string d;
  const std::pair<const Eigen::Vector2d*, const char*> axes[] = {{&east, "E"}, {&north, "N"}, {&up, "up"}};
  for (const auto& [dir, label] : axes) {
    const Eigen::Vector2d tip = origin + length * Eigen::Vector2d(dir->x(), -dir->y());
    d += "M" + Number(origin.x()) + " " + Number(origin.y()) + "L" + Number(tip.x()) + " " +
         Number(tip.y());
    const double n = dir->norm();
    const Eigen::Vector2d away = n > 1e-9 ? Eigen::Vector2d(dir->x(), -dir->y()) / n : Eigen::Vector2d(0, -1);
    const Eigen::Vector2d at = tip + away * (SvgStyle::kTextGap + 0.5 * SvgStyle::kLabelFont) * u;
    TextPx({at.x(), at.y() + 0.35 * SvgStyle::kLabelFont * u}, label, SvgStyle::kLabelFont, "middle");
  }
  body_ += "<path fill=\"none\" stroke=\"" + std::string(SvgStyle::kInk) + "\" stroke-width=\"" +
           Number(1.5 * u, 2) + "\" stroke-linecap=\"round\" d=\"" + d + "\"/>\n";
}

void SvgCanvas::Legend(const std::vector<LegendEntry>& entries) {
  CloseFaceGroup();
  const double u = unit();
  for (const auto& entry : entries) {
    const double y = plot_origin_.y() + plot_size_.y() +
                     (SvgStyle::kBottomBand + legend_rows_ * SvgStyle::kLegendRow) * u;
    body_ += "<rect x=\"" + Number(plot_origin_.x()) + "\" y=\"" + Number(y) + "\" width=\"" +
             Number(SvgStyle::kSwatchWidth * u) + "\" height=\"" +
             Number(SvgStyle::kSwatchHeight * u) + "\" fill=\"" + entry.fill + "\" stroke=\"" +
             SvgStyle::kInk + "\" stroke-width=\"" + Number(u, 2) + "\"/>\n";
    TextPx({plot_origin_.x() + (SvgStyle::kSwatchWidth + 2.5 * SvgStyle::kTextGap) * u,
            y + (SvgStyle::kSwatchHeight - 3.0) * u},
           entry.label, SvgStyle::kLabelFont, "start");
    ++legend_rows_;
  }
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

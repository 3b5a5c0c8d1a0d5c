// The keys around a figure's plot: colour bars (linear and logarithmic, with their ticks and
// labels), the scale bar, the north arrow, the axis triad of oblique views and the legend.
// The canvas and its drawing primitives: svg_canvas.cc.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "report/svg_canvas.h"
#include "report/svg_format.h"

namespace pqlayout {

using namespace svg_format;

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

}  // namespace pqlayout

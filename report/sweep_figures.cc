#include "report/sweep_figures.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "report/svg_canvas.h"

namespace pqlayout {
namespace {

// Sizes in px of the drawing (fixed width: a sweep figure has at most a few hundred points).
constexpr double kPanelWidth = 540.0;  // one panel incl. its axis labels
constexpr double kTitleBand = 46.0;    // figure title
constexpr double kPanelTitle = 30.0;   // panel title
constexpr double kPlotLeft = 84.0;     // y tick labels + y axis label
constexpr double kPlotRight = 24.0;
constexpr double kPlotHeight = 360.0;
constexpr double kPlotBottom = 58.0;  // x tick labels + x axis label
constexpr double kNoteBand = 56.0;    // legend + note
constexpr double kTitleFont = 20.0, kLabelFont = 14.0, kTickFont = 12.0, kPointFont = 11.0;
constexpr double kDominatedRadius = 4.5, kFrontRadius = 6.0;
const Rgb kFront{214, 39, 40};      // highlighted: the Pareto front
const Rgb kDominated{150, 150, 150};
const Rgb kDominatedText{110, 110, 110};
const Rgb kGrid{225, 225, 225};
constexpr size_t kMaxLabelledPoints = 30;  // more: only the front is labelled

std::string Escape(const std::string& text) {
  std::string out;
  for (const char c : text) {
    if (c == '&') out += "&amp;";
    else if (c == '<') out += "&lt;";
    else if (c == '>') out += "&gt;";
    else if (c == '"') out += "&quot;";
    else out += c;
  }
  return out;
}

std::string Fixed(double v) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.1f", v);
  return text;
}

std::string TickText(double v) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.4g", v);
  return text;
}

// One axis: data range → px, linear or log10, with its ticks.
struct Axis {
  bool log = false;
  double lo = 0.0, hi = 1.0;  // in transformed units (log10 if log)
  std::vector<double> ticks;  // data values

  double T(double v) const { return log ? std::log10(v) : v; }
  double Fraction(double v) const { return (T(v) - lo) / (hi - lo); }

  static Axis Fit(const std::vector<double>& values) {
    Axis a;
    double mn = *std::min_element(values.begin(), values.end());
    double mx = *std::max_element(values.begin(), values.end());
    a.log = mn > 0.0 && mx / mn >= 30.0;
    double lo = a.T(mn), hi = a.T(mx);
    if (hi - lo < 1e-12 * std::max(1.0, std::abs(hi))) {  // one value: a window around it
      const double half = a.log ? 0.5 : (hi != 0.0 ? 0.1 * std::abs(hi) : 1.0);
      lo -= half;
      hi += half;
    }
    const double pad = 0.06 * (hi - lo);
    a.lo = lo - pad;
    a.hi = hi + pad;
    if (a.log) {
      for (int e = static_cast<int>(std::floor(a.lo)); e <= static_cast<int>(std::ceil(a.hi)); ++e)
        for (const double m : {1.0, 2.0, 5.0}) {
          const double v = m * std::pow(10.0, e);
          if (std::log10(v) >= a.lo && std::log10(v) <= a.hi && (m == 1.0 || a.hi - a.lo < 2.5)) a.ticks.push_back(v);
        }
    } else {
      a.ticks = NiceTicks(a.lo, a.hi, 5);
    }
    return a;
  }
};

void TextAt(std::ostringstream& s, double x, double y, const std::string& text, double size,
            const std::string& anchor, const std::string& extra = "") {
  s << "<text x=\"" << Fixed(x) << "\" y=\"" << Fixed(y) << "\" font-size=\"" << size << "\" text-anchor=\""
    << anchor << "\"" << extra << ">" << Escape(text) << "</text>\n";
}

void DrawPanel(std::ostringstream& s, const ScatterPanel& panel, double left, double top) {
  const double x0 = left + kPlotLeft, y0 = top + kPanelTitle;
  const double w = kPanelWidth - kPlotLeft - kPlotRight, h = kPlotHeight;
  TextAt(s, x0 + w / 2, top + kPanelTitle - 10, panel.title, kLabelFont + 2, "middle", " font-weight=\"bold\"");
  if (panel.points.empty()) {
    s << "<rect x=\"" << Fixed(x0) << "\" y=\"" << Fixed(y0) << "\" width=\"" << Fixed(w) << "\" height=\""
      << Fixed(h) << "\" fill=\"none\" stroke=\"" << SvgStyle::kInk << "\"/>\n";
    TextAt(s, x0 + w / 2, y0 + h / 2, "no finished run has these metrics", kLabelFont, "middle");
    return;
  }
  std::vector<double> xs, ys;
  for (const auto& p : panel.points) {
    xs.push_back(p.x);
    ys.push_back(p.y);
  }
  const Axis ax = Axis::Fit(xs), ay = Axis::Fit(ys);
  const auto px = [&](double v) { return x0 + ax.Fraction(v) * w; };
  const auto py = [&](double v) { return y0 + (1.0 - ay.Fraction(v)) * h; };
  // Grid and ticks.
  for (const double t : ax.ticks) {
    s << "<line x1=\"" << Fixed(px(t)) << "\" y1=\"" << Fixed(y0) << "\" x2=\"" << Fixed(px(t)) << "\" y2=\""
      << Fixed(y0 + h) << "\" stroke=\"" << kGrid.Hex() << "\"/>\n";
    TextAt(s, px(t), y0 + h + 17, TickText(t), kTickFont, "middle");
  }
  for (const double t : ay.ticks) {
    s << "<line x1=\"" << Fixed(x0) << "\" y1=\"" << Fixed(py(t)) << "\" x2=\"" << Fixed(x0 + w) << "\" y2=\""
      << Fixed(py(t)) << "\" stroke=\"" << kGrid.Hex() << "\"/>\n";
    TextAt(s, x0 - 6, py(t) + 4, TickText(t), kTickFont, "end");
  }
  s << "<rect x=\"" << Fixed(x0) << "\" y=\"" << Fixed(y0) << "\" width=\"" << Fixed(w) << "\" height=\"" << Fixed(h)
    << "\" fill=\"none\" stroke=\"" << SvgStyle::kInk << "\"/>\n";
  TextAt(s, x0 + w / 2, y0 + h + 42, panel.x_label + (ax.log ? " (log scale)" : ""), kLabelFont, "middle");
  const double ly = y0 + h / 2, lx = left + 18;
  TextAt(s, lx, ly, panel.y_label + (ay.log ? " (log scale)" : ""), kLabelFont, "middle",
         " transform=\"rotate(-90 " + Fixed(lx) + " " + Fixed(ly) + ")\"");
  // The front's staircase, then the points (dominated first, so the front is on top).
  const std::vector<bool> front = NonDominated(panel.points);
  std::vector<const ScatterPoint*> best;
  for (size_t i = 0; i < panel.points.size(); ++i)
    if (front[i]) best.push_back(&panel.points[i]);
  std::sort(best.begin(), best.end(), [](const ScatterPoint* a, const ScatterPoint* b) {
    return a->x < b->x || (a->x == b->x && a->y > b->y);
  });
  if (best.size() > 1) {
    s << "<path d=\"M" << Fixed(px(best[0]->x)) << " " << Fixed(py(best[0]->y));
    for (size_t i = 1; i < best.size(); ++i)
      s << " H" << Fixed(px(best[i]->x)) << " V" << Fixed(py(best[i]->y));
    s << "\" fill=\"none\" stroke=\"" << kFront.Hex() << "\" stroke-width=\"1.5\" stroke-dasharray=\"5 4\"/>\n";
  }
  // Labels left of points in the right half, so they stay inside the plot; dominated points
  // are labelled in grey while there are few enough points to read them.
  const auto label = [&](const ScatterPoint& p, double size, const std::string& colour) {
    const bool right_half = px(p.x) > x0 + w / 2;
    TextAt(s, px(p.x) + (right_half ? -9 : 9), py(p.y) - 6, p.label, size, right_half ? "end" : "start",
           " fill=\"" + colour + "\"");
  };
  for (size_t i = 0; i < panel.points.size(); ++i) {
    if (front[i]) continue;
    const ScatterPoint& p = panel.points[i];
    s << "<circle cx=\"" << Fixed(px(p.x)) << "\" cy=\"" << Fixed(py(p.y)) << "\" r=\"" << kDominatedRadius
      << "\" fill=\"white\" stroke=\"" << kDominated.Hex() << "\" stroke-width=\"1.5\"><title>" << Escape(p.label)
      << "</title></circle>\n";
    if (panel.points.size() <= kMaxLabelledPoints) label(p, kPointFont - 1, kDominatedText.Hex());
  }
  for (const ScatterPoint* p : best) {
    s << "<circle cx=\"" << Fixed(px(p->x)) << "\" cy=\"" << Fixed(py(p->y)) << "\" r=\"" << kFrontRadius
      << "\" fill=\"" << kFront.Hex() << "\" stroke=\"" << SvgStyle::kInk << "\" stroke-width=\"0.8\"><title>"
      << Escape(p->label) << "</title></circle>\n";
    label(*p, kPointFont, SvgStyle::kInk);
  }
}

}  // namespace

std::vector<bool> NonDominated(const std::vector<ScatterPoint>& points) {
  std::vector<bool> front(points.size(), true);
  for (size_t i = 0; i < points.size(); ++i)
    for (size_t j = 0; j < points.size() && front[i]; ++j) {
      const ScatterPoint &p = points[i], &q = points[j];
      if (q.x <= p.x && q.y <= p.y && (q.x < p.x || q.y < p.y)) front[i] = false;
    }
  return front;
}

std::string ScatterPanelsSvg(const std::vector<ScatterPanel>& panels, const std::string& title,
                             const std::string& note) {
  const double width = kPanelWidth * std::max<size_t>(panels.size(), 1);
  const double height = kTitleBand + kPanelTitle + kPlotHeight + kPlotBottom + kNoteBand;
  std::ostringstream s;
  s << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width << "\" height=\"" << height
    << "\" viewBox=\"0 0 " << width << " " << height << "\" font-family=\"" << SvgStyle::kFont << "\" fill=\""
    << SvgStyle::kInk << "\">\n";
  s << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  TextAt(s, width / 2, 30, title, kTitleFont, "middle");
  for (size_t p = 0; p < panels.size(); ++p) DrawPanel(s, panels[p], p * kPanelWidth, kTitleBand);
  const double legend_y = kTitleBand + kPanelTitle + kPlotHeight + kPlotBottom + 18;
  double x = kPlotLeft;
  s << "<circle cx=\"" << Fixed(x) << "\" cy=\"" << Fixed(legend_y - 4) << "\" r=\"" << kFrontRadius << "\" fill=\""
    << kFront.Hex() << "\" stroke=\"" << SvgStyle::kInk << "\" stroke-width=\"0.8\"/>\n";
  TextAt(s, x + 12, legend_y, "non-dominated (Pareto front, dashed)", kLabelFont, "start");
  x += 330;
  s << "<circle cx=\"" << Fixed(x) << "\" cy=\"" << Fixed(legend_y - 4) << "\" r=\"" << kDominatedRadius
    << "\" fill=\"white\" stroke=\"" << kDominated.Hex() << "\" stroke-width=\"1.5\"/>\n";
  TextAt(s, x + 12, legend_y, "dominated", kLabelFont, "start");
  TextAt(s, kPlotLeft - 8, legend_y + 24, note, kTickFont, "start");
  s << "</svg>\n";
  return s.str();
}

}  // namespace pqlayout

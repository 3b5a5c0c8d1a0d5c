// Scatter plots for sweeps: panels of (x, y) points where lower is better on both axes; the
// non-dominated points (the Pareto front) are highlighted, joined by the front's staircase
// and labelled. Self-contained SVG in the style of the other figures (svg_canvas.h colours,
// round ticks), but with data axes instead of a map view.
#pragma once

#include <string>
#include <vector>

namespace pqlayout {

struct ScatterPoint {
  double x = 0.0, y = 0.0;
  std::string label;
};

struct ScatterPanel {
  std::string title, x_label, y_label;
  std::vector<ScatterPoint> points;
};

// For points to be minimised in x and y: true where no other point is at least as good in
// both and better in one. Equal points are all non-dominated.
std::vector<bool> NonDominated(const std::vector<ScatterPoint>& points);

// The panels side by side under `title`, with `note` below. An axis is logarithmic when its
// values are all positive and span a factor of 30 or more.
std::string ScatterPanelsSvg(const std::vector<ScatterPanel>& panels, const std::string& title,
                             const std::string& note);

}  // namespace pqlayout

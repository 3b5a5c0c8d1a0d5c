// report.html: one self-contained page (no network, no external assets) that gathers a run:
// summary (surface, supports, load, spacing, counts), key results, timings per stage, every
// scalar metric of report.json per stage, and the run's figures inlined as SVG with
// captions. After `pqlayout compare`, DIR/report.html shows the comparison table and the two
// layouts' figures side by side.
//
// Every figure is a <figure data-figure="NAME.svg">; a figure whose stage completed but
// whose file is missing is still listed, with data-missing="1" and a note. A small inline
// script measures each figure once the page has loaded (rendered size, number of drawn
// elements, and — rasterised onto a canvas — the fraction of non-white pixels and the
// number of distinct colours inside the SVG's data-plot rectangle) and stores the result
// in the figure's data-check attribute; scripts/check_report.sh reads these from headless
// Chromium's --dump-dom. Between the summary and the figures, the 3D view of the grid shell
// (report/report_view3d.h) measures itself likewise. The ids inside each inlined SVG are prefixed per figure, so that
// the gradients and patterns of one figure never resolve to another's.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "base/output_files.h"
#include "report/report_view3d.h"

namespace pqlayout {

// Reads the figures already written under out's figures/ folder. view3d: what the 3D view
// draws (report/report_view3d.h); without a shell (the default) the page has no 3D view.
Status WriteReportHtml(const nlohmann::json& report, OutputFiles* out, const View3dData& view3d = {});

// DIR/report.html after compare: `comparison` is compare.json's content; reads
// DIR/figures/compliance_{strain,curvature}.svg and DIR/{strain,curvature}/figures/*.svg.
Status WriteCompareReportHtml(const nlohmann::json& comparison, const std::string& dir);

}  // namespace pqlayout

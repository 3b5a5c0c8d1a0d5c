// report.html: one self-contained page (no network, no external assets) that gathers a run:
// summary (surface, supports, load, spacing, counts), timings per stage, every scalar metric
// of report.json per stage, and the run's figures inlined as SVG with captions.
#pragma once

#include <nlohmann/json.hpp>

#include "problems/output_files.h"

namespace pqlayout {

// Reads the figures already written under out's figures/ folder.
Status WriteReportHtml(const nlohmann::json& report, OutputFiles* out);

}  // namespace pqlayout

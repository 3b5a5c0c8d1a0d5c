// `pqlayout compare CONFIG`: the same config run twice, with guidance.source = strain (the
// paper's statics-sensitive layout) and = curvature (the reference layout the paper compares
// against), same spacing and weights; then a side-by-side table (SPEC "Comparison").
// Outputs: DIR/strain/ and DIR/curvature/ (complete runs), DIR/compare.json,
// DIR/compare/table.md, and DIR/figures/compliance_{strain,curvature}.svg on one colour
// scale (paper Figs. 9 and 14).
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "base/status.h"

namespace pqlayout {

struct CompareOptions {
  std::string config_path;
  std::vector<std::string> overrides;  // --set KEY=VALUE, applied to both runs
  std::string out_dir;
  std::string command_line;
};

Status RunCompare(const CompareOptions& options, nlohmann::json* comparison);

// The Markdown table of a comparison (rows: metrics; columns: strain, curvature, difference).
std::string ComparisonTable(const nlohmann::json& comparison);

}  // namespace pqlayout

// The layout targets (issue 17): what a layout must reach on any roof, checked at the end of
// every run and written to report.json "targets", each miss with its cause in one line,
// measured from the run: where the worst element is and what is there (a singularity of the
// guidance and its index, a hole, a boundary corner, the boundary).
//
//   levelset   alignment RMS where weight > 0.5 ≤ 8° (met when no face has weight > 0.5),
//              fold-overs 0, min crossing ≥ 25°, area crossing below levelset.min_angle ≤ 1 %,
//              spacing CV (max of φ and ψ) ≤ 0.25
//   extract    quads / faces ≥ 0.80, non-quads touching no boundary 0, boundary deviation
//              ≤ 0.01 h, shortest edge ≥ 0.2 h
//   planarize  δ max ≤ 1e-3, closeness max ≤ 0.02 h
//
// A stage that did not run (--until) has no targets. benchmarks/corpus.py reads this object.
#pragma once

#include <nlohmann/json.hpp>

#include "pipeline/pipeline.h"

namespace pqlayout {

// {"met": n, "missed": [names], "list": [{"name", "stage", "what", "target", "value", "met",
// "cause"}]}; value null where the metric does not apply (met).
nlohmann::json EvaluateLayoutTargets(const PipelineState& state, const nlohmann::json& stages);

// One line for the log: "11 of 11 met" or "9 of 11 met; missed: alignment (…), …".
std::string LayoutTargetsSummary(const nlohmann::json& targets);

}  // namespace pqlayout

// The engineering checks that `analyze` adds to the compliance (issue 18), on the same frame
// and load case: what an engineer signing off a single-layer grid shell looks at first.
//   - linear buckling: the smallest load factors λ of (K + λ K_G) φ = 0 and their modes
//     (solver/frame_buckling.h; analysis.buckling_modes of them, 0 = skipped);
//   - member utilisation η (solver/member_checks.h, analysis.material.yield_strength);
//   - deflection: max |u_z| and span / max |u_z|, span = the longer side of the plan
//     bounding box of the frame's nodes.
// Not modelled: buckling of single members between nodes, lateral–torsional buckling,
// imperfections and the nonlinear (snap-through) path; so λ is an upper bound of the
// load factor that an engineer would design with (Eurocode-style knock-down not applied).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "problems/options.h"
#include "problems/grid_frame.h"
#include "solver/frame_buckling.h"

namespace pqlayout {

struct StructuralChecks {
  BucklingResult buckling;
  bool buckling_run = false;
  bool buckling_reused = false;  // the same frame and forces as the memo's last solve: its result taken
  double buckling_seconds = 0.0;
  std::vector<double> utilisation;  // per frame member
  double deflection_max = 0.0, span = 0.0;
  nlohmann::json ToJson(const GridFrame& frame) const;
};

// log: the results as INFO lines and a warning for members over η = 1 (analyze does; stiffen,
// which checks the frame before and after, logs its own summary). memo (optional): the
// buckling solve through it (solver/frame_buckling.h, BucklingMemo), so that a frame checked
// twice, as stiffen's last shell and then by analyze, is solved once.
Status RunStructuralChecks(const GridFrame& frame, const FrameResult& linear, const AnalysisOptions& a,
                           StructuralChecks* checks, bool log = true, BucklingMemo* memo = nullptr);

}  // namespace pqlayout

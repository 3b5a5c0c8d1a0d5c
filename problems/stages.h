// The stage functions (one file each), registered in pipeline.cc in the SPEC's order.
#pragma once

#include "problems/pipeline.h"

namespace pqlayout {

// surface: load or generate the reference surface, validate it, resolve the supports;
// writes surface.obj.
Status RunSurfaceStage(PipelineState* state, OutputFiles* out, nlohmann::json* metrics);

}  // namespace pqlayout

// fields.vtk: the reference surface with every per-element result the stages have produced
// so far (v_z, guidance, strains, weights, φ, ψ), for ParaView. Each stage that adds a field
// rewrites it, so the file always matches the last completed stage.
#pragma once

#include "pipeline/pipeline.h"

namespace pqlayout {

Status WriteSurfaceFieldsVtk(const PipelineState& state, OutputFiles* out);

}  // namespace pqlayout

// fields.vtk: the reference surface with every per-element result the stages have produced
// (v_z, guidance, strains, weights, φ, ψ), for ParaView. Written once, by RunPipeline after
// its last stage (guidance and levelset each rewrote it before: twice the time at a million
// triangles), so the file matches the last completed stage.
#pragma once

#include "pipeline/pipeline.h"

namespace pqlayout {

Status WriteSurfaceFieldsVtk(const PipelineState& state, OutputFiles* out);

}  // namespace pqlayout

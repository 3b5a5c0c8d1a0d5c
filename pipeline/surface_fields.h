// fields.vtk: the reference surface with every per-element result the stages have produced
// (v_z, guidance, strains, weights, φ, ψ), for ParaView. Written once (guidance and levelset
// each rewrote it before: twice the time at a million triangles), by RunPipeline as soon as
// the last stage that feeds it has run (levelset, or the last stage asked for before it), and
// in the background (OutputFiles::WriteInBackground): its ~1 s at a million triangles overlaps
// extraction, planarisation and stiffen. No later stage changes what it holds.
#pragma once

#include "pipeline/pipeline.h"

namespace pqlayout {

// Copies the field values the file holds out of `state` and queues its writing on out's
// background writer, which reads the reference's points and triangles itself (the reference is
// shared and read-only from the surface stage on: SurfaceModel::FreezeFields).
void WriteSurfaceFieldsVtkInBackground(const PipelineState& state, OutputFiles* out);

}  // namespace pqlayout

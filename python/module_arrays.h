// What a finished run left in PipelineState, as Python dicts of numpy arrays (copies: the
// arrays own their memory and outlive the run). Called with the GIL held.
//   surface:  {"vertices": (N,3) float64, "faces": (M,3) int64}
//   fields:   {"v_z": (N,), "guidance": (M,3), "strain_max", "strain_min", "weight": (M,),
//              "phi", "psi": (N,)} — only what the stages that ran produced
//   a grid:   {"vertices": (V,3) float64, "face_offsets": (F+1,) int64, "face_vertices": (Σ,) int64}:
//              face f is face_vertices[face_offsets[f]:face_offsets[f+1]], in the order of the OBJ
//   analysis: {"nodes": {column: (V,)}, "members": {column: (E,)}} with the columns of
//              analysis/nodes.csv and analysis/members.csv (without id)
#pragma once

#include <pybind11/pybind11.h>

#include "pipeline/pipeline.h"

namespace pqlayout::python {

// Every key above whose stage completed (stages: report["run"]["completed_stages"]).
pybind11::dict StateToDict(const PipelineState& state, const std::vector<std::string>& completed_stages);

}  // namespace pqlayout::python

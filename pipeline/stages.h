// The stage functions (one file each), registered in pipeline.cc in the SPEC's order.
#pragma once

#include "pipeline/pipeline.h"

namespace pqlayout {

// surface: load or generate the reference surface, validate it, resolve the supports;
// writes surface.obj.
Status RunSurfaceStage(PipelineState* state, OutputFiles* out, nlohmann::json* metrics);

// membrane: v_z under dead load (CHOLMOD); vertex field "v_z".
Status RunMembraneStage(PipelineState* state, OutputFiles* out, nlohmann::json* metrics);

// guidance: per-face direction and alignment weight (strain, curvature or file);
// writes fields/vertices.csv, fields/faces.csv, fields.vtk.
Status RunGuidanceStage(PipelineState* state, OutputFiles* out, nlohmann::json* metrics);

// levelset: φ and ψ (Ceres); vertex fields "phi", "psi".
Status RunLevelsetStage(PipelineState* state, OutputFiles* out, nlohmann::json* metrics);

// extract: quad-dominant mesh from the level lines φ, ψ ∈ ℤ (state->quads);
// writes quads_initial.obj, quads_initial.ply (planarity δ as face colour).
Status RunExtractStage(PipelineState* state, OutputFiles* out, nlohmann::json* metrics);

// planarize: planar faces, on the reference (Ceres); writes quads_planarized.obj/.ply and,
// until stiffen replaces them, quads.obj/.ply.
Status RunPlanarizeStage(PipelineState* state, OutputFiles* out, nlohmann::json* metrics);

// stiffen: the planarised mesh reshaped within stiffen.tolerance for a lower compliance
// (state->shell); writes quads.obj, quads.ply, figures/offset.svg.
Status RunStiffenStage(PipelineState* state, OutputFiles* out, nlohmann::json* metrics);

// analyze: the final mesh (state->shell) as a steel frame; writes analysis/nodes.csv, members.csv.
Status RunAnalyzeStage(PipelineState* state, OutputFiles* out, nlohmann::json* metrics);

// What planarize and stiffen both write (stage_planarize.cc): NAME.obj and NAME.ply (faces
// coloured by δ: blue at 0, red at ≥ 10 × target).
// origin: PipelineState::origin (the files are in the surface file's coordinates).
Status WriteShellMesh(const PolyMesh& mesh, double target_delta, const Eigen::Vector3d& origin, OutputFiles* out,
                      const std::string& name);

}  // namespace pqlayout

// Resolves boundary.default and boundary.rules into one support condition per boundary
// vertex of the reference surface (SPEC §2: selectors all, loop by index or inner/outer,
// bounding box, vertex-id list or file; plus corners).
#pragma once

#include <optional>
#include <vector>

#include "geometry/surface_model.h"
#include "problems/options.h"

namespace pqlayout {

// Per vertex: the condition of a boundary vertex, std::nullopt for interior vertices.
using VertexConditions = std::vector<std::optional<BoundaryCondition>>;

// corner_angle: turning angle in degrees for the `corners` selector (extract.corner_angle).
// A rule that selects no boundary vertex, an index out of range or an id that is not a
// boundary vertex is InvalidInput naming the rule ("cfg.yaml:14: boundary.rules[2]: ..."; for
// an ids_file its name and line come first: "ids.txt:3: vertex 7 ... (cfg.yaml:14: boundary.rules[2])").
// file_vertex (a surface read from a file; see ReadSurfaceMesh): ids are the file's vertices,
// mapped through it, so that unused and welded vertices do not shift them; null: the surface's.
Status ResolveBoundaryConditions(const BoundaryOptions& options, const SurfaceModel& surface,
                                 double corner_angle, VertexConditions* conditions,
                                 const std::vector<int>* file_vertex = nullptr);

// Whether the supports can hold the steel frame (stiffen, analyze) against moving as a whole in
// plan: sliding holds u_z only (SPEC §7), so without a clamped vertex or two fixed ones the
// frame slides or turns about a vertical axis, a mechanism that the frame solve would only
// find after the layout stages. InvalidInput naming the counts and the remedy. Necessary, not
// sufficient: the frame solve still names any other mechanism. No support at all passes: the
// membrane stage refuses that, naming the part.
Status CheckSupportsHoldTheFrameInPlan(const VertexConditions& conditions);

}  // namespace pqlayout

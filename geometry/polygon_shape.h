// Shape of a (possibly non-planar) polygon given as indices into a position array: its
// Newell normal and how far it is from degenerate. Used by the extraction's clean-up passes
// to choose between alternative ways of cutting or merging cells.
#pragma once

#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace pqlayout {

// Newell's normal of the polygon, normalised (zero for a degenerate polygon).
Eigen::Vector3d NewellNormal(const std::vector<Eigen::Vector3d>& position, const std::vector<int>& polygon);

// The smallest of the polygon's interior angles and of their supplements (a corner of nearly
// 180° makes a quad a triangle with an extra point), in radians, measured in the plane with
// the given normal; negative where a corner is reflex.
double ShapeAngle(const std::vector<Eigen::Vector3d>& position, const std::vector<int>& polygon,
                  const Eigen::Vector3d& normal);

// The same in the polygon's own (Newell) plane; −1 for a degenerate polygon.
double ShapeAngle(const std::vector<Eigen::Vector3d>& position, const std::vector<int>& polygon);

// n · (e_in × e_out) at every corner: positive where the polygon turns the way of `normal`
// (convex there), negative where it is reflex or folded.
std::vector<double> CornerTurns(const std::vector<Eigen::Vector3d>& position, const std::vector<int>& polygon,
                                const Eigen::Vector3d& normal);

// Whether a polygon that turned the same way at every corner with its vertices at `start`
// (round its Newell normal there) no longer does at `now`: a corner turned inside out, or
// the polygon folded or flipped over.
bool FoldedSince(const std::vector<Eigen::Vector3d>& start, const std::vector<Eigen::Vector3d>& now,
                 const std::vector<int>& polygon);

}  // namespace pqlayout

// Level lines {u = c} of a P1 function u (one value per vertex, linear on each triangle) on
// the reference triangle surface: the curves φ = i, ψ = j of the level-set layout (paper
// §3.1; with the stage's convention |∇φ| ≈ 1/h they lie h metres apart), for the figures
// and the quad-mesh extraction.
//
// Per face crossed by the level, one straight segment between the two edge crossing points
// (linear interpolation along the edge); segments are chained into polylines through the
// crossing points they share, so a level line is one polyline, not one piece per face.
//
// Conventions (the contract the callers rely on):
// - Ties: a vertex whose value equals c exactly counts as above c (symbolic perturbation
//   c → c − ε). An edge is crossed iff one end is below c and the other is not; its crossing
//   point is at the upper end when that end's value is exactly c. A level through vertices
//   thus gives exactly one line through them: faces that only touch it at one vertex give no
//   segment, and a segment along an edge shared by two crossed faces (a ridge exactly at c)
//   is kept once. Consequence: a level equal to the minimum of u over a region gives no line
//   there (u is nowhere below it), a level equal to its maximum gives the line along it
//   (e.g. along the boundary where u is largest).
// - Crossing points are computed from the edge's lower to its upper end, so the point on a
//   shared edge is bit-identical for both faces.
// - Orientation: every polyline runs along n × ∇u, n the face normal of the mesh's
//   orientation (faces counter-clockwise seen from n): seen from n's side, larger values lie
//   on the right. Decided combinatorially per face, so consistent along a line.
// - Open polylines end on the boundary or at a vertex where more than one line piece comes
//   in or goes out (a saddle exactly at c; pieces meet there but are not joined). Closed
//   loops repeat their first point as their last point (front() == back(), exactly).
// - Output order is deterministic (faces in index order start the walks).
#pragma once

#include <vector>

#include <Eigen/Core>

#include "geometry/surface_model.h"

namespace pqlayout {

// The polylines (3D points on the surface, metres) of {u = value}; u: one value per vertex
// (#V). Returns no lines if the size does not match or value is not finite; non-finite
// vertex values make their faces uncrossed.
std::vector<std::vector<Eigen::Vector3d>> LevelLines(const SurfaceModel& surface,
                                                     const std::vector<double>& values,
                                                     double value);

}  // namespace pqlayout

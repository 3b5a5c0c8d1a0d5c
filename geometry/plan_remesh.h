// A working mesh for a fine reference that is a height field over the plan, built the way the
// built-in generators build their roofs (height_field.h: MeshPlanarDomain, lift, remesh on the
// surface) with the heights read from the reference's own triangles. The level-set stage
// solves on such a copy when the reference is much finer than the layout needs.
//
// Why not CGAL's isotropic remeshing (geometry/remesh.h), which serves any surface: it gets to
// 12k triangles from a million by ~1M edge collapses, 22–28 s on the 968k-triangle Great Court
// (CGAL's edge_collapse with edge-length cost 22.6 s, OpenMesh's Decimater 28.8 s, its
// multiple-choice decimater 12.6 s: measured on that reference, 2026-12-03). Meshing the plan
// anew costs what the working mesh costs (~0.1 s), plus one pass over the reference (~0.5 s).
// Roofs are height fields almost always; a reference that is not (a face steeper than
// kMaxSlopeDeg or facing the other way, a boundary that crosses itself in the plan) gets the
// CGAL path. (With every face facing one way and simple, disjoint boundary loops in the plan,
// the projection onto the plan is one-to-one: the surface is a height field.)
#pragma once

#include <string>

#include "geometry/mesh.h"
#include "geometry/surface_model.h"

namespace pqlayout {

// Faces steeper than this (normal more than this from ±z) make the plan path decline.
constexpr double kMaxSlopeDeg = 80.0;

// The reference's boundary loops, resampled through their own vertices about edge_length apart
// (3D arc length; every boundary vertex turning by more than corner_angle_deg kept), meshed
// in the plan at edge_length and lifted onto the reference (heights by barycentric
// interpolation in the reference triangle under each point; a point just outside the plan
// boundary, on a chord of a concave stretch, takes the nearest triangle's edge); then three
// rounds of CGAL's isotropic remeshing of that small mesh (remesh.h), its interior vertices
// lifted onto the reference again and its boundary vertices put on the reference's boundary.
// Every vertex lies on the reference; faces are oriented as the reference's.
// Returns false, with *why_not saying why and *out cleared, if the reference is not a height
// field or the plan domain cannot be meshed: the caller then remeshes another way.
bool RemeshOverPlan(const SurfaceModel& surface, double edge_length, double corner_angle_deg, TriMesh* out,
                    std::string* why_not);

}  // namespace pqlayout

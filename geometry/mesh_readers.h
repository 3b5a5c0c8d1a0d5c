// pqlayout's own readers for the mesh formats it accepts (ReadPolygonSoup picks one by the
// file's extension). Each fills the soup exactly as the file lists it, coordinates as doubles.
//
// They replace OpenMesh's readers, which read coordinates in single precision and which
// malformed headers send into a segfault (a PLY `property` before any `element`), an endless
// loop (a PLY without `end_header`) or unbounded allocation (an OFF declaring -5 vertices).
// Here every count a header declares is checked against the file's size before anything is
// allocated, every face index must name a vertex of the file, and every loop consumes input,
// so reading ends in time proportional to the file's size whatever its bytes. Every failure
// is InvalidInput with one line "PATH[:LINE]: what is wrong", naming the element where there
// is one. Non-finite coordinates are left to ValidateSurfaceSoup (it names the vertex), except
// in STL, whose vertices have no index of their own (the reader names the facet).
#pragma once

#include <string>

#include "geometry/mesh_io.h"
#include "base/status.h"

namespace pqlayout {

// Wavefront OBJ: `v` and `f` statements (v, v/vt, v//vn, v/vt/vn corners; negative indices
// count back from the last vertex so far); other statements carry nothing pqlayout uses.
Status ReadObjSoup(const std::string& path, PolygonSoup* soup);

// OFF and its variants with per-vertex extras (COFF, NOFF, STOFF, ...; the extras and face
// colours are skipped). Three-dimensional ASCII only: 4OFF, nOFF and binary OFF are refused.
Status ReadOffSoup(const std::string& path, PolygonSoup* soup);

// Binary STL (recognised by its size: 84 + 50 bytes per triangle, whatever the 80-byte header
// says) or ASCII STL (starting with `solid`). Facets list their corners, so corners at exactly
// the same position are merged into one vertex.
Status ReadStlSoup(const std::string& path, PolygonSoup* soup);

// PLY: ascii, binary_little_endian or binary_big_endian. Reads the `vertex` element's x, y, z
// (any numeric type) and the `face` element's `vertex_indices` (or `vertex_index`) list of
// integers; every other element and property is skipped.
Status ReadPlySoup(const std::string& path, PolygonSoup* soup);

}  // namespace pqlayout

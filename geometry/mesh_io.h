// Mesh input and output. OBJ is read at full double precision by our own parser; PLY, OFF and
// STL go through OpenMesh's readers, which parse coordinates in single precision. Either way
// the file is read into a
// raw polygon soup first, because OpenMesh's own importer silently repairs non-manifold
// input by duplicating vertices; the soup is validated (mesh_validation.h) and only then
// turned into a half-edge mesh. Writing (OBJ, PLY) is our own too, atomic and at full double
// precision (OpenMesh's writers also go through floats).
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "geometry/mesh.h"
#include "geometry/status.h"

namespace pqlayout {

// Vertices and faces exactly as they are in the file (0-based indices).
struct PolygonSoup {
  std::vector<Eigen::Vector3d> points;
  std::vector<std::vector<int>> faces;
};

// File extensions (lower case, with dot) that ReadPolygonSoup accepts.
const std::vector<std::string>& ReadableMeshExtensions();

// Reads a mesh file into a soup. InvalidInput naming the file if it is missing, unreadable
// or of an unsupported format.
Status ReadPolygonSoup(const std::string& path, PolygonSoup* soup);

// Builds a triangle mesh from a soup that passed ValidateSurfaceSoup. Vertices that no face
// uses are dropped (their number is returned in dropped_vertices, may be null).
Status BuildTriMesh(const PolygonSoup& soup, TriMesh* mesh, int* dropped_vertices);

// Reads, validates and builds the reference surface: every failure is InvalidInput with one
// line "PATH: what is wrong (element index)".
Status ReadSurfaceMesh(const std::string& path, TriMesh* mesh);

// Writes OBJ or PLY (chosen by extension; PLY as ASCII) atomically with 17 significant
// digits, so doubles survive the round trip. Face colours, if the mesh has them, go to PLY.
Status WriteMesh(const TriMesh& mesh, const std::string& path);
Status WriteMesh(const PolyMesh& mesh, const std::string& path);

}  // namespace pqlayout

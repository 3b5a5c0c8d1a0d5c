// Mesh input and output. OBJ, PLY, OFF and STL are read at full double precision by our own
// readers (mesh_readers.h), which refuse malformed files with one line instead of crashing,
// hanging or allocating without bound as OpenMesh's readers do. The file is read into a raw
// polygon soup first, because OpenMesh's own importer silently repairs non-manifold input by
// duplicating vertices; the soup is validated (mesh_validation.h) and only then turned into a
// half-edge mesh, so OpenMesh only ever sees input that has been checked. Writing (OBJ, PLY)
// is our own too, atomic and at full double precision (OpenMesh's writers go through floats).
#pragma once

#include <array>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "geometry/mesh.h"
#include "base/status.h"

namespace pqlayout {

// Vertices and faces exactly as they are in the file (0-based indices).
struct PolygonSoup {
  std::vector<Eigen::Vector3d> points;
  std::vector<std::vector<int>> faces;
  bool single_precision = false;  // the file stores binary float32 coordinates (binary STL or PLY)
};

// File extensions (lower case, with dot) that ReadPolygonSoup accepts.
const std::vector<std::string>& ReadableMeshExtensions();

// Reads a mesh file into a soup, choosing the reader by extension. InvalidInput naming the
// file (and the line or element, where there is one) if it is missing, unreadable, of an
// unsupported format or malformed. Every face index names a vertex of the soup.
Status ReadPolygonSoup(const std::string& path, PolygonSoup* soup);

// Builds a triangle mesh from a soup that passed ValidateSurfaceSoup. Vertices that no face
// uses are dropped: mesh_vertex_of (may be null) gets, per soup vertex, its mesh vertex or -1.
Status BuildTriMesh(const PolygonSoup& soup, TriMesh* mesh, std::vector<int>* mesh_vertex_of);

// What ReadSurfaceMesh does between reading and building: quads split (SplitQuads), the
// repairs CAD exports need made (soup_repair.h: unwelded seams, T-junctions, orientation),
// then validated (mesh_validation.h). Logs what it changed; InvalidInput "PATH: ..." if the
// soup is still not a surface. weld_tolerance: see RepairSurfaceSoup (0: its default);
// vertex_of (may be null): per soup vertex, the one that stands for it after welding.
Status PrepareSurfaceSoup(const std::string& path, PolygonSoup* soup, double weld_tolerance = 0.0,
                          std::vector<int>* vertex_of = nullptr);

// Reads, validates and builds the reference surface: every failure is InvalidInput with one
// line "PATH: what is wrong (element index)".
// file_vertex (may be null): per vertex of the file, in its order from 0, the mesh vertex
// that stands for it (welded ones share one), or -1 if no face uses it: vertex ids given
// for the file (boundary.rules' ids) are resolved through it.
Status ReadSurfaceMesh(const std::string& path, TriMesh* mesh, double weld_tolerance = 0.0,
                       std::vector<int>* file_vertex = nullptr);

// Splits every quad of four valid vertex indices into two triangles along its shorter
// diagonal, in place (ReadSurfaceMesh does it before validating: CAD render meshes are mostly
// quads); a quad with a vertex repeated next to itself becomes that triangle. Larger polygons
// are left to validation, which refuses them. Returns the quads split.
int SplitQuads(PolygonSoup* soup);

// Writes OBJ or PLY (chosen by extension; PLY as ASCII) atomically with 17 significant
// digits, so doubles survive the round trip. Face colours, if the mesh has them, go to PLY.
// origin is added to every point (a georeferenced surface is solved in a local frame).
Status WriteMesh(const TriMesh& mesh, const std::string& path, const Eigen::Vector3d& origin = Eigen::Vector3d::Zero());
Status WriteMesh(const PolyMesh& mesh, const std::string& path, const Eigen::Vector3d& origin = Eigen::Vector3d::Zero());

// A triangle mesh as plain arrays (points, 0-based vertex indices per face), copied out of a
// mesh so that it can be written on another thread while the mesh is in use (stage surface
// writes surface.obj in the background: ~0.25 s at a million triangles).
struct TriangleArrays {
  std::vector<Eigen::Vector3d> points;
  std::vector<std::array<int, 3>> triangles;
};
TriangleArrays CopyTriangles(const TriMesh& mesh);
// The same bytes as WriteMesh(mesh, path, origin) for the mesh copied and an .obj path.
Status WriteObj(const TriangleArrays& mesh, const std::string& path, const Eigen::Vector3d& origin);

}  // namespace pqlayout

// CloseShortEdges and CutDarts (panel_repair.h).
#include "geometry/panel_repair.h"

#include "geometry/polygon_shape.h"
#include "geometry/quad_cleanup.h"

namespace pqlayout {

// At most this many rounds of CollapseRound (each closes edges on disjoint neighbourhoods).
constexpr int kMaxRounds = 10;

int CloseShortEdges(double min_length, ExtractedMesh* mesh, std::vector<Eigen::Vector3d>* start) {
  extraction_internal::Polygons now, then;
  for (const auto v : mesh->mesh.vertices()) now.position.push_back(ToEigen(mesh->mesh.point(v)));
  now.origin = mesh->origin;
  for (const auto f : mesh->mesh.faces()) {
    std::vector<int> face;
    for (const auto v : mesh->mesh.fv_range(f)) face.push_back(v.idx());
    now.faces.push_back(std::move(face));
  }
  int closed = 0;
  for (int round = 0; round < kMaxRounds; ++round) {
    const int n = extraction_internal::CollapseRound(min_length, &now);
    if (n == 0) break;
    closed += n;
  }
  if (closed == 0) return 0;
  then.position = *start;
  then.origin = now.origin;
  then.faces = now.faces;
  extraction_internal::Compact(&now);  // the same renumbering for both: it follows the faces
  extraction_internal::Compact(&then);
  int rejected = 0;
  mesh->mesh = BuildPolyMesh(now.position, now.faces, &rejected);
  mesh->origin = std::move(now.origin);
  mesh->stats.rejected_faces += rejected;
  *start = std::move(then.position);
  return closed;
}

int CutDarts(ExtractedMesh* mesh) {
  std::vector<Eigen::Vector3d> position;
  for (const auto v : mesh->mesh.vertices()) position.push_back(ToEigen(mesh->mesh.point(v)));
  std::vector<std::vector<int>> faces;
  int cut = 0;
  for (const auto f : mesh->mesh.faces()) {
    std::vector<int> face;
    for (const auto v : mesh->mesh.fv_range(f)) face.push_back(v.idx());
    int reflex = -1, count = 0;
    if (face.size() == 4) {
      const std::vector<double> turns = CornerTurns(position, face, NewellNormal(position, face));
      for (int k = 0; k < 4; ++k)
        if (turns[k] < 0.0) reflex = k, ++count;
    }
    if (count != 1) {
      faces.push_back(std::move(face));
      continue;
    }
    const int r = reflex;
    faces.push_back({face[r], face[(r + 1) % 4], face[(r + 2) % 4]});
    faces.push_back({face[(r + 2) % 4], face[(r + 3) % 4], face[r]});
    ++cut;
  }
  if (cut == 0) return 0;
  int rejected = 0;
  mesh->mesh = BuildPolyMesh(position, faces, &rejected);
  mesh->stats.rejected_faces += rejected;
  return cut;
}

}  // namespace pqlayout

#include "geometry/line_field_singularities.h"

#include <cmath>

namespace pqlayout {

std::vector<LineFieldSingularity> FindLineFieldSingularities(const SurfaceModel& surface,
                                                             const std::vector<Eigen::Vector3d>& direction,
                                                             double min_projected_length) {
  std::vector<LineFieldSingularity> singularities;
  const TriMesh& mesh = surface.mesh();
  // Each face's doubled top-view angle, once (a vertex's ring visits each face three times);
  // NaN where the direction is too steep to have one.
  std::vector<double> face_angle(mesh.n_faces());
  for (size_t f = 0; f < face_angle.size(); ++f) {
    const Eigen::Vector2d d = direction[f].head<2>();
    face_angle[f] = d.norm() < min_projected_length ? std::nan("") : 2.0 * std::atan2(d.y(), d.x());
  }
  std::vector<double> doubled;
  for (const auto v : mesh.vertices()) {
    if (mesh.is_boundary(v)) continue;
    doubled.clear();
    bool usable = true;
    int first_face = -1;
    for (const auto f : mesh.vf_ccw_range(v)) {
      if (first_face < 0) first_face = f.idx();
      if (std::isnan(face_angle[f.idx()])) {
        usable = false;
        break;
      }
      doubled.push_back(face_angle[f.idx()]);
    }
    if (!usable || doubled.empty()) continue;
    double winding = 0.0;
    for (size_t k = 0; k < doubled.size(); ++k) {
      const double step = doubled[(k + 1) % doubled.size()] - doubled[k];
      winding += std::remainder(step, 2.0 * M_PI);
    }
    const long turns = std::lround(winding / (2.0 * M_PI));
    if (turns != 0) {
      // Counter-clockwise about the normal is counter-clockwise in the top view only where
      // the surface faces up.
      const double orientation = surface.face_normal(first_face).z() >= 0 ? 1.0 : -1.0;
      singularities.push_back({v.idx(), orientation * 0.5 * static_cast<double>(turns), surface.position(v)});
    }
  }
  return singularities;
}

}  // namespace pqlayout

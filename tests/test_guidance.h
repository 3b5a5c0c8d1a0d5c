// Guidance fields for tests: a direction per face from a function of the face's centroid,
// projected into the face's plane, every weight 1.
#pragma once

#include <functional>

#include <Eigen/Core>

#include "geometry/surface_model.h"
#include "problems/guidance.h"

namespace pqlayout::testing {

inline GuidanceField UniformGuidance(const SurfaceModel& s,
                                     const std::function<Eigen::Vector3d(const Eigen::Vector3d&)>& d) {
  GuidanceField g;
  for (int f = 0; f < s.num_faces(); ++f) {
    const auto ids = s.face_vertices(f);
    const Eigen::Vector3d centre = (s.position(ids[0]) + s.position(ids[1]) + s.position(ids[2])) / 3.0;
    const Eigen::Vector3d& n = s.face_normal(f);
    const Eigen::Vector3d dir = d(centre);
    g.direction.push_back((dir - n * n.dot(dir)).normalized());
    g.weight.push_back(1.0);
    g.magnitude.push_back(1.0);
  }
  g.major = g.minor = g.magnitude;
  g.scale = 1.0;
  return g;
}

}  // namespace pqlayout::testing

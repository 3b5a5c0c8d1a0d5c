#include "geometry/polygon_shape.h"

#include <algorithm>
#include <cmath>

namespace pqlayout {

Eigen::Vector3d NewellNormal(const std::vector<Eigen::Vector3d>& position, const std::vector<int>& polygon) {
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  for (size_t k = 0; k < polygon.size(); ++k)
    normal += position[polygon[k]].cross(position[polygon[(k + 1) % polygon.size()]]);
  return normal.norm() > 0.0 ? Eigen::Vector3d(normal.normalized()) : normal;
}

double ShapeAngle(const std::vector<Eigen::Vector3d>& position, const std::vector<int>& polygon,
                  const Eigen::Vector3d& normal) {
  double smallest = M_PI;
  const size_t n = polygon.size();
  for (size_t k = 0; k < n; ++k) {
    const Eigen::Vector3d p = position[polygon[k]];
    const Eigen::Vector3d in = p - position[polygon[(k + n - 1) % n]], out = position[polygon[(k + 1) % n]] - p;
    const double turn = std::atan2(in.cross(out).dot(normal), in.dot(out));
    smallest = std::min({smallest, M_PI - turn, turn});
  }
  return smallest;
}

double ShapeAngle(const std::vector<Eigen::Vector3d>& position, const std::vector<int>& polygon) {
  const Eigen::Vector3d normal = NewellNormal(position, polygon);
  return normal.norm() > 0.0 ? ShapeAngle(position, polygon, normal) : -1.0;
}

std::vector<double> CornerTurns(const std::vector<Eigen::Vector3d>& position, const std::vector<int>& polygon,
                                const Eigen::Vector3d& normal) {
  const size_t m = polygon.size();
  std::vector<double> turns(m);
  for (size_t k = 0; k < m; ++k) {
    const Eigen::Vector3d& a = position[polygon[(k + m - 1) % m]];
    const Eigen::Vector3d& b = position[polygon[k]];
    const Eigen::Vector3d& c = position[polygon[(k + 1) % m]];
    turns[k] = normal.dot((b - a).cross(c - b));
  }
  return turns;
}

bool FoldedSince(const std::vector<Eigen::Vector3d>& start, const std::vector<Eigen::Vector3d>& now,
                 const std::vector<int>& polygon) {
  const Eigen::Vector3d n = NewellNormal(start, polygon);
  const auto turns_all = [&](const std::vector<Eigen::Vector3d>& p) {
    for (const double t : CornerTurns(p, polygon, n))
      if (!(t > 0.0)) return false;
    return true;
  };
  return turns_all(start) && !turns_all(now);
}

}  // namespace pqlayout

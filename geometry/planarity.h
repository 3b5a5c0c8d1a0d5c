// Planarity δ of a polygon face (SPEC stage 6, paper §3.2): for a quad, the distance between
// its two diagonal lines divided by the mean length of the diagonals; for an n-gon, n > 4,
// the maximum over all quads spanned by 4 of its vertices in cyclic order; 0 for triangles.
// Scale-free: δ = 0.01 on a 3 m quad means diagonals 4 cm apart. The same function is the
// heat map of quads_initial.ply, the planarisation's stopping test and the tests' oracle.
#pragma once

#include <algorithm>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

namespace pqlayout {

// δ of the quad (a, b, c, d): diagonals a–c and b–d.
inline double QuadPlanarityDelta(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                                 const Eigen::Vector3d& d) {
  const Eigen::Vector3d d1 = c - a, d2 = d - b;
  const double mean_diagonal = 0.5 * (d1.norm() + d2.norm());
  if (!(mean_diagonal > 0.0)) return 0.0;
  const Eigen::Vector3d normal = d1.cross(d2);
  double distance;
  if (normal.norm() > 1e-12 * d1.norm() * d2.norm()) {
    distance = std::abs((b - a).dot(normal)) / normal.norm();
  } else {  // parallel diagonals: distance from b to the line a–c
    distance = d1.norm() > 0.0 ? (b - a).cross(d1).norm() / d1.norm() : (b - a).norm();
  }
  return distance / mean_diagonal;
}

// polygon: the n vertices in cyclic order.
inline double PlanarityDelta(const std::vector<Eigen::Vector3d>& polygon) {
  const int n = static_cast<int>(polygon.size());
  double delta = 0.0;
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j)
      for (int k = j + 1; k < n; ++k)
        for (int l = k + 1; l < n; ++l)
          delta = std::max(delta, QuadPlanarityDelta(polygon[i], polygon[j], polygon[k], polygon[l]));
  return delta;
}

struct FacePlane {
  Eigen::Vector3d n;
  double mean_diagonal;
  Eigen::Vector3d centroid;  // of the polygon's vertices; the plane passes through it
};

// Least-squares plane of a polygon {x : n · (x − centroid) = 0} (normal from the covariance,
// oriented like the polygon's vector area) and its mean diagonal length (mean edge length for
// a triangle): the start of the auxiliary planes of planarize and stiffen, whose offsets are
// measured from the centroid (PlanarityResidual).
inline FacePlane FitPolygonPlane(const std::vector<Eigen::Vector3d>& polygon) {
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero(), area = Eigen::Vector3d::Zero();
  for (const auto& p : polygon) centroid += p;
  centroid /= static_cast<double>(polygon.size());
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (size_t i = 0; i < polygon.size(); ++i) {
    covariance += (polygon[i] - centroid) * (polygon[i] - centroid).transpose();
    area += (polygon[i] - centroid).cross(polygon[(i + 1) % polygon.size()] - centroid);
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(covariance);
  Eigen::Vector3d n = eig.eigenvectors().col(0);
  if (n.dot(area) < 0) n = -n;
  double diagonal = 0.0;
  int count = 0;
  for (size_t i = 0; i < polygon.size(); ++i)
    for (size_t j = i + 2; j < polygon.size(); ++j)
      if (!(i == 0 && j == polygon.size() - 1)) diagonal += (polygon[i] - polygon[j]).norm(), ++count;
  if (count == 0)  // a triangle: use its mean edge length
    for (size_t i = 0; i < polygon.size(); ++i) diagonal += (polygon[i] - polygon[(i + 1) % polygon.size()]).norm(), ++count;
  return {n, diagonal / count, centroid};
}

}  // namespace pqlayout

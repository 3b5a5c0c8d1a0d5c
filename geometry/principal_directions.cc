#include "geometry/principal_directions.h"

#include <cmath>

#include <Eigen/Eigenvalues>

#include "base/parallel_ranges.h"

namespace pqlayout {

Eigen::Matrix3d GreenLagrangeStrain(const Eigen::Vector3d& n, const Eigen::Vector3d& grad_vz) {
  const Eigen::Matrix3d P = Eigen::Matrix3d::Identity() - n * n.transpose();
  const Eigen::Matrix3d DT = P + Eigen::Vector3d::UnitZ() * grad_vz.transpose();
  return 0.5 * (DT.transpose() * DT - P);
}

void TangentBasis(const Eigen::Vector3d& n, Eigen::Vector3d* t1, Eigen::Vector3d* t2) {
  // Start from the world axis least aligned with n, so the basis is well conditioned.
  Eigen::Vector3d axis = Eigen::Vector3d::UnitX();
  if (std::abs(n.x()) > std::abs(n.y())) axis = Eigen::Vector3d::UnitY();
  if (std::abs(n.dot(axis)) > std::abs(n.z())) axis = Eigen::Vector3d::UnitZ();
  *t1 = (axis - n * n.dot(axis)).normalized();
  *t2 = n.cross(*t1);
}

TangentEigen DecomposeOnTangentPlane(const Eigen::Matrix3d& tensor, const Eigen::Vector3d& n, int orientation) {
  Eigen::Vector3d t1, t2;
  TangentBasis(n, &t1, &t2);
  Eigen::Matrix2d m;
  m << t1.dot(tensor * t1), t1.dot(tensor * t2), t2.dot(tensor * t1), t2.dot(tensor * t2);
  m = 0.5 * (m + m.transpose()).eval();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(m);
  const Eigen::Vector2d lambda = eig.eigenvalues();
  const int major = orientation == 0 ? (std::abs(lambda[0]) > std::abs(lambda[1]) ? 0 : 1)
                                     : (orientation * lambda[0] > orientation * lambda[1] ? 0 : 1);
  TangentEigen out;
  out.major = eig.eigenvalues()[major];
  out.minor = eig.eigenvalues()[1 - major];
  const Eigen::Vector2d a = eig.eigenvectors().col(major), b = eig.eigenvectors().col(1 - major);
  out.major_direction = (a.x() * t1 + a.y() * t2).normalized();
  out.minor_direction = (b.x() * t1 + b.y() * t2).normalized();
  return out;
}

std::vector<Eigen::Vector3d> VertexNormals(const SurfaceModel& surface) {
  std::vector<Eigen::Vector3d> normals(surface.num_vertices(), Eigen::Vector3d::Zero());
  for (int f = 0; f < surface.num_faces(); ++f) {
    const auto ids = surface.face_vertices(f);
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d a = surface.position(ids[(k + 1) % 3]) - surface.position(ids[k]);
      const Eigen::Vector3d b = surface.position(ids[(k + 2) % 3]) - surface.position(ids[k]);
      const double angle = std::atan2(a.cross(b).norm(), a.dot(b));
      normals[ids[k]] += angle * surface.face_normal(f);
    }
  }
  for (auto& n : normals) n.normalize();
  return normals;
}

namespace {

// Vertex normals on the boundary see faces on one side only and are tilted by O(h / R),
// which makes the fitted shape operator of a face touching the boundary wrong by O(1 / R).
// Such faces take the operator of the nearest interior face (breadth-first across edges),
// re-expressed in their own tangent plane.
void ExtendShapeOperatorsToBoundaryFaces(const SurfaceModel& surface, std::vector<Eigen::Matrix3d>* shape) {
  const TriMesh& mesh = surface.mesh();
  std::vector<int> source(surface.num_faces(), -1);
  std::vector<int> queue;
  for (int f = 0; f < surface.num_faces(); ++f) {
    const auto ids = surface.face_vertices(f);
    if (!surface.is_boundary(ids[0]) && !surface.is_boundary(ids[1]) && !surface.is_boundary(ids[2])) {
      source[f] = f;
      queue.push_back(f);
    }
  }
  for (size_t head = 0; head < queue.size(); ++head) {
    const int f = queue[head];
    for (const auto g : mesh.ff_range(FaceHandle(f))) {
      if (source[g.idx()] >= 0) continue;
      source[g.idx()] = source[f];
      queue.push_back(g.idx());
    }
  }
  for (int f = 0; f < surface.num_faces(); ++f) {
    if (source[f] < 0 || source[f] == f) continue;
    const Eigen::Vector3d& n = surface.face_normal(f);
    const Eigen::Matrix3d P = Eigen::Matrix3d::Identity() - n * n.transpose();
    (*shape)[f] = P * (*shape)[source[f]] * P;
  }
}

// The three-edge fit of one face is noisy on irregular meshes; as Rusinkiewicz averages
// over the faces at a vertex, each face takes the area-weighted mean of the operators of the
// faces sharing a vertex with it, projected onto its own tangent plane.
std::vector<Eigen::Matrix3d> AverageOverNeighbourFaces(const SurfaceModel& surface,
                                                       const std::vector<Eigen::Matrix3d>& shape) {
  std::vector<Eigen::Matrix3d> vertex_sum(surface.num_vertices(), Eigen::Matrix3d::Zero());
  std::vector<double> vertex_area(surface.num_vertices(), 0.0);
  for (int f = 0; f < surface.num_faces(); ++f) {
    for (const int v : surface.face_vertices(f)) {
      vertex_sum[v] += surface.face_area(f) * shape[f];
      vertex_area[v] += surface.face_area(f);
    }
  }
  std::vector<Eigen::Matrix3d> averaged(surface.num_faces());
  ParallelRanges(surface.num_faces(), [&](int begin, int end) {
    for (int f = begin; f < end; ++f) {
      Eigen::Matrix3d sum = Eigen::Matrix3d::Zero();
      double area = 0.0;
      for (const int v : surface.face_vertices(f)) {
        sum += vertex_sum[v];
        area += vertex_area[v];
      }
      const Eigen::Vector3d& n = surface.face_normal(f);
      const Eigen::Matrix3d P = Eigen::Matrix3d::Identity() - n * n.transpose();
      averaged[f] = P * (sum / area) * P;
    }
  });
  return averaged;
}

}  // namespace

std::vector<Eigen::Matrix3d> FaceShapeOperators(const SurfaceModel& surface) {
  const std::vector<Eigen::Vector3d> normals = VertexNormals(surface);
  std::vector<Eigen::Matrix3d> shape(surface.num_faces());
  // Each face's fit on its own (base/parallel_ranges.h: the same bits on any number of threads).
  ParallelRanges(surface.num_faces(), [&](int begin, int end) {
    for (int f = begin; f < end; ++f) {
      const auto ids = surface.face_vertices(f);
      Eigen::Vector3d t1, t2;
      TangentBasis(surface.face_normal(f), &t1, &t2);
      // Unknowns (a, b, c) of S = [a b; b c] in the basis (t1, t2); two equations per edge.
      Eigen::Matrix<double, 6, 3> A;
      Eigen::Matrix<double, 6, 1> rhs;
      for (int k = 0; k < 3; ++k) {
        const int from = ids[(k + 1) % 3], to = ids[(k + 2) % 3];
        const Eigen::Vector3d e = surface.position(to) - surface.position(from);
        const Eigen::Vector3d dn = normals[to] - normals[from];
        const double u = e.dot(t1), v = e.dot(t2);
        A.row(2 * k) << u, v, 0.0;
        A.row(2 * k + 1) << 0.0, u, v;
        rhs(2 * k) = dn.dot(t1);
        rhs(2 * k + 1) = dn.dot(t2);
      }
      const Eigen::Vector3d abc = A.colPivHouseholderQr().solve(rhs);
      Eigen::Matrix<double, 3, 2> basis;
      basis << t1, t2;
      Eigen::Matrix2d s;
      s << abc(0), abc(1), abc(1), abc(2);
      shape[f] = basis * s * basis.transpose();
    }
  });
  ExtendShapeOperatorsToBoundaryFaces(surface, &shape);
  return AverageOverNeighbourFaces(surface, shape);
}

}  // namespace pqlayout

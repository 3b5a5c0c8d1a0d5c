// Per-face tensors on the tangent plane and their principal directions: the Green–Lagrange
// membrane strain of the paper (§2.2, equation 2) and a discrete shape operator.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "geometry/surface_model.h"

namespace pqlayout {

// Green–Lagrange tensor ε = ½ (DTᵀ DT − P) of the deformation T = x + v on a face with unit
// normal n, for a vertical displacement v = v_z e_z whose P1 gradient on the face is grad_vz
// (tangent to the face). DT = P + e_z grad_vzᵀ is the face-wise Jacobian of T in world
// coordinates and P = I − n nᵀ; ε is 3×3 with n in its kernel.
Eigen::Matrix3d GreenLagrangeStrain(const Eigen::Vector3d& n, const Eigen::Vector3d& grad_vz);

// Eigen-decomposition of a symmetric tensor restricted to the plane normal to n.
// orientation 0: the major eigenvalue is the one of largest modulus (the paper's "absolute
// maximum principal strain", §2.2: its direction turns by 90° where the two eigenvalues have
// opposite signs and equal moduli). orientation ±1: the major eigenvalue is the larger of
// orientation·λ (the signed ordering of principal curvatures κ1 ≥ κ2: continuous everywhere
// but at umbilics, also where the mean curvature changes sign).
struct TangentEigen {
  double major = 0.0;  // see orientation above (signed)
  double minor = 0.0;  // the other eigenvalue
  Eigen::Vector3d major_direction = Eigen::Vector3d::Zero();  // unit, tangent
  Eigen::Vector3d minor_direction = Eigen::Vector3d::Zero();
};
TangentEigen DecomposeOnTangentPlane(const Eigen::Matrix3d& tensor, const Eigen::Vector3d& n, int orientation = 0);

// Two unit vectors spanning the plane normal to n (right-handed with n).
void TangentBasis(const Eigen::Vector3d& n, Eigen::Vector3d* t1, Eigen::Vector3d* t2);

// Angle-weighted unit vertex normals.
std::vector<Eigen::Vector3d> VertexNormals(const SurfaceModel& surface);

// Discrete shape operator per face (3×3, tangent, symmetric): the least-squares fit of
// S e = Δn over the face's three edges e and the differences Δn of the vertex normals at
// their ends (Rusinkiewicz 2004). For a sphere of radius R with outward normals S = P / R.
// Faces touching the boundary take the operator of the nearest interior face (one-sided
// vertex normals there bias the fit); a mesh without interior faces keeps its raw fit.
std::vector<Eigen::Matrix3d> FaceShapeOperators(const SurfaceModel& surface);

}  // namespace pqlayout

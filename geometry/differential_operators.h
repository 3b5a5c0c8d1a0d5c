// P1 (piecewise linear) finite-element operators on the reference triangle surface.
#pragma once

#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "geometry/surface_model.h"

namespace pqlayout {

// Stiffness matrix K_ij = ∫ ∇φ_i · ∇φ_j of the P1 hat functions (#V by #V, symmetric,
// positive semidefinite, rows summing to zero): the cotangent formula
// K_ij = −½ (cot α_ij + cot β_ij) for an edge ij, K_ii = −Σ_j K_ij.
Eigen::SparseMatrix<double> CotanStiffness(const SurfaceModel& surface);

// Gradient of the P1 interpolant of per-vertex `values` on face f: a vector in the face's
// plane (world coordinates), constant on the face.
Eigen::Vector3d FaceGradient(const SurfaceModel& surface, int f, const std::vector<double>& values);

// The three P1 basis gradients of face f (∇φ_a, ∇φ_b, ∇φ_c for its vertices in order):
// the gradient of any P1 function is Σ_k value_k ∇φ_k.
std::array<Eigen::Vector3d, 3> FaceBasisGradients(const SurfaceModel& surface, int f);

// Connected components of the mesh (vertex → component id, ids 0..count−1).
int ConnectedComponents(const SurfaceModel& surface, std::vector<int>* component);

}  // namespace pqlayout

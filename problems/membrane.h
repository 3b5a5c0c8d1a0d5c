// Stage `membrane` (paper §2.1–2.2, SPEC §2): the reference surface as a membrane under
// dead load. Equation (1) with λ_b = 0, −λ_m Δv = f, in P1 finite elements: the cotangent
// stiffness λ_m K, lumped load f_i = −q A_i e_z. By the paper's maximum-principle argument
// only v_z is non-zero, so this is one scalar sparse SPD system, factored by CHOLMOD
// (simplicial), or from 100k unknowns by our supernodal factor in nested-dissection order
// (problems/membrane.cc). Boundary vertices that are `fixed`, `clamped` or `sliding` (u_z = 0 in all
// three) are Dirichlet (v_z = 0); `free` ones are Neumann (natural).
#pragma once

#include <string>
#include <vector>

#include "geometry/surface_model.h"
#include "problems/boundary_conditions.h"
#include "problems/options.h"

namespace pqlayout {

struct MembraneSolution {
  std::vector<double> v_z;        // per vertex, metres (negative = downwards)
  int n_dirichlet = 0;            // vertices held at v_z = 0
  int n_unknowns = 0;             // size of the SPD system
  double relative_residual = 0.0; // ‖K v − f‖ / ‖f‖ over the unknowns
  double assemble_seconds = 0.0, factor_seconds = 0.0, solve_seconds = 0.0;
  std::string ordering;           // the factor's fill-reducing ordering: "CHOLMOD" or "nested dissection"
  std::string factor;             // "CHOLMOD simplicial" or "supernodal multifrontal"
  double factor_flops = 0.0;      // of the Cholesky factorisation (CHOLMOD's count, or ours with the relaxed supernodes' zeros)
};

// InvalidInput if a connected component of the surface has no Dirichlet vertex (the
// problem would be singular), naming a vertex of that component.
Status SolveMembrane(const SurfaceModel& surface, const VertexConditions& supports,
                     const MembraneOptions& options, double q, MembraneSolution* solution);

}  // namespace pqlayout

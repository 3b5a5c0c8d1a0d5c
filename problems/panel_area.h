// `layout.density: panel_area` (stage `levelset`): the common factor s by which φ and ψ are
// multiplied so that the layout's mean panel area is h².
//
// With φ, ψ in level units (the curves are φ = i, ψ = j), the number of cells per unit area
// is the Jacobian |∇φ × ∇ψ| = |∇φ||∇ψ| sin γ (γ the crossing angle), so the mean cell area
// is A / ∫|∇φ × ∇ψ| dA. Solved for spacing h, two families crossing at γ < 90° give cells
// of area h²/sin γ: fewer nodes than an orthogonal layout of the same spacing. Scaling both
// functions by s = √(A / (h² ∫|∇φ × ∇ψ| dA)) makes the mean cell area h² and changes nothing
// else: directions, crossing angles, conjugacy and the spacing CV are scale free.
#pragma once

#include <vector>

#include "base/status.h"
#include "geometry/surface_model.h"
#include "problems/levelset.h"

namespace pqlayout {

// s as above; 1 if the Jacobian vanishes everywhere.
double PanelAreaScale(const SurfaceModel& surface, const std::vector<double>& phi, const std::vector<double>& psi,
                      double h);

// Scales φ, ψ of solution by `factor` (s above). With seams the offsets become round(factor·a)
// and φ, ψ are refitted to the scaled gradients under the rounded transitions (one Poisson
// solve each), so that level lines still meet across the seams.
Status ScaleLevelSets(double factor, double h, LevelSetSolution* solution);

}  // namespace pqlayout

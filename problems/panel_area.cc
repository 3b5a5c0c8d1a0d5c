#include "problems/panel_area.h"

#include <cmath>

#include "geometry/differential_operators.h"
#include "problems/levelset_internal.h"

namespace pqlayout {

double PanelAreaScale(const SurfaceModel& surface, const std::vector<double>& phi, const std::vector<double>& psi,
                      double h) {
  double cells = 0.0;  // ∫ |∇φ × ∇ψ| dA
  for (int f = 0; f < surface.num_faces(); ++f)
    cells += surface.face_area(f) * FaceGradient(surface, f, phi).cross(FaceGradient(surface, f, psi)).norm();
  if (!(cells > 0.0)) return 1.0;
  return std::sqrt(surface.total_area() / (h * h * cells));
}

Status ScaleLevelSets(double factor, double h, LevelSetSolution* solution) {
  using namespace levelset_internal;
  LevelSetSeams& seams = solution->seams;
  if (!seams.cut) {
    for (double& value : solution->phi) value *= factor;
    for (double& value : solution->psi) value *= factor;
    return Status::Ok();
  }
  const SurfaceModel& s = seams.cut->cut();
  const LevelSetGeometry geo = Precompute(s);
  for (int family = 0; family < 2; ++family) {
    std::vector<double>& u = family == 0 ? solution->phi_cut : solution->psi_cut;
    std::vector<double>& offsets = family == 0 ? seams.phi_offset : seams.psi_offset;
    std::vector<Eigen::Vector3d> target(s.num_faces());
    for (int f = 0; f < s.num_faces(); ++f) target[f] = factor * Gradient(geo, s, f, u);
    for (double& a : offsets) a *= factor;
    RoundOffsets(seams, &offsets);
    PQ_RETURN_IF_ERROR(PoissonFit(s, geo, target, std::vector<double>(s.num_faces(), 1.0), &u, &seams, family, false, h));
    ProjectTransitions(seams, offsets, &u);
  }
  solution->phi = seams.cut->ToOriginal(solution->phi_cut);
  solution->psi = seams.cut->ToOriginal(solution->psi_cut);
  return Status::Ok();
}

}  // namespace pqlayout

#include "problems/panel_area.h"

#include <cmath>

#include "geometry/differential_operators.h"

namespace pqlayout {

double PanelAreaScale(const SurfaceModel& surface, const std::vector<double>& phi, const std::vector<double>& psi,
                      double h) {
  double cells = 0.0;  // ∫ |∇φ × ∇ψ| dA
  for (int f = 0; f < surface.num_faces(); ++f)
    cells += surface.face_area(f) * FaceGradient(surface, f, phi).cross(FaceGradient(surface, f, psi)).norm();
  if (!(cells > 0.0)) return 1.0;
  return std::sqrt(surface.total_area() / (h * h * cells));
}

}  // namespace pqlayout

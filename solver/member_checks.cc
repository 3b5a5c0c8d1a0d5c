#include "solver/member_checks.h"

#include <algorithm>
#include <cmath>

namespace pqlayout {

SectionModuli SectionModuli::CircularHollow(double D, double t) {
  const FrameSection s = FrameSection::CircularHollow(D, t);
  return {s.inertia_y / (0.5 * D), s.inertia_z / (0.5 * D), true};
}

SectionModuli SectionModuli::RectangularHollow(double b, double h, double t) {
  const FrameSection s = FrameSection::RectangularHollow(b, h, t);
  return {s.inertia_y / (0.5 * h), s.inertia_z / (0.5 * b), false};
}

std::vector<double> MemberUtilisation(const FrameModel& m, const FrameResult& r, const SectionModuli& W, double fy) {
  std::vector<double> eta(m.members.size(), 0.0);
  for (size_t e = 0; e < m.members.size() && e < r.member_end_forces.size(); ++e) {
    const auto& f = r.member_end_forces[e];
    for (const int end : {0, 6}) {
      const double N = std::abs(f[end]), My = f[end + 4], Mz = f[end + 5];
      const double bending = W.circular ? std::hypot(My, Mz) / W.y : std::abs(My) / W.y + std::abs(Mz) / W.z;
      eta[e] = std::max(eta[e], (N / m.section.area + bending) / fy);
    }
  }
  return eta;
}

}  // namespace pqlayout

// Member checks of a frame (issue 18): the elastic utilisation of each member's section at
// both of its ends under the linear solve's end forces, and what it needs from the section.
//   η = |N| / (A f_y) + bending,
//   bending = √(M_y² + M_z²) / (W_el f_y) for a circular hollow section (every axis is a
//             principal one), |M_y| / (W_el,y f_y) + |M_z| / (W_el,z f_y) for a rectangular
//             hollow section (the linear interaction, conservative);
// η per member is the larger of its two ends. Shear, torsion and member buckling are not in
// it (single members of a grid shell are short and stocky; global buckling is
// solver/frame_buckling.h), nor any code's partial factors: it is the elastic check, η ≤ 1
// means no fibre yields at the member ends under the analysed load.
#pragma once

#include <vector>

#include "solver/frame_analysis.h"

namespace pqlayout {

struct SectionModuli {
  double y = 0.0, z = 0.0;  // W_el about local y (for M_y) and about local z (for M_z), m³
  bool circular = true;
  // W = I / (D/2) about both axes, I = π/64 (D⁴ − d⁴), d = D − 2t.
  static SectionModuli CircularHollow(double diameter, double thickness);
  // W_y = I_y / (h/2), W_z = I_z / (b/2) (FrameSection::RectangularHollow's I).
  static SectionModuli RectangularHollow(double width, double height, double thickness);
};

std::vector<double> MemberUtilisation(const FrameModel& model, const FrameResult& linear, const SectionModuli& W,
                                      double yield_strength);

}  // namespace pqlayout

// The level sets' metrics (alignment, spacing CV, conjugacy, crossing angles, fold-overs; problems/levelset.h).
#include "problems/levelset_internal.h"

#include <glog/logging.h>

#include <algorithm>
#include <cmath>

#include "problems/residuals/conjugacy_residual.h"

namespace pqlayout {

using namespace levelset_internal;

nlohmann::json LevelSetMetrics::ToJson() const {
  return {{"alignment_rms_deg", alignment_rms_deg},
          {"alignment_rms_deg_weight_above_half", alignment_rms_deg_strong},
          {"alignment_rms_deg_source_above_half", alignment_rms_deg_source_strong},
          {"spacing_cv_phi", spacing_cv_phi},
          {"spacing_cv_psi", spacing_cv_psi},
          {"spacing_cv_phi_weight_above_half", spacing_cv_phi_strong},
          {"spacing_cv_psi_weight_above_half", spacing_cv_psi_strong},
          {"conjugacy_rms", conjugacy_rms},
          {"min_crossing_angle_deg", min_crossing_angle_deg},
          {"faces_below_min_angle", faces_below_min_angle},
          {"area_fraction_below_min_angle", area_below_min_angle},
          {"foldovers", foldovers}};
}

namespace levelset_internal {

// Area-weighted coefficient of variation of the local spacing 1/|∇u| over faces with mask.
double SpacingCv(const SurfaceModel& s, const std::vector<Eigen::Vector3d>& gradient, const std::vector<char>& mask) {
  double area = 0.0, sum = 0.0, sum_sq = 0.0;
  for (int f = 0; f < s.num_faces(); ++f) {
    if (!mask[f] || gradient[f].norm() <= 0.0) continue;
    const double spacing = 1.0 / gradient[f].norm(), a = s.face_area(f);
    area += a;
    sum += a * spacing;
    sum_sq += a * spacing * spacing;
  }
  if (area <= 0.0) return 0.0;
  const double mean = sum / area;
  return std::sqrt(std::max(0.0, sum_sq / area - mean * mean)) / mean;
}

LevelSetMetrics Measure(const SurfaceModel& s, const LevelSetGeometry& geo, const GuidanceField& g,
                        const std::vector<double>& phi, const std::vector<double>& psi, double min_angle_deg) {
  LevelSetMetrics m;
  std::vector<Eigen::Vector3d> gphi(s.num_faces()), gpsi(s.num_faces());
  std::vector<char> all(s.num_faces(), 1), strong(s.num_faces(), 0);
  double align = 0.0, align_w = 0.0, align_s = 0.0, align_sw = 0.0, align_src = 0.0, align_srcw = 0.0, conj = 0.0;
  const bool blended = !g.source_weight.empty();
  m.min_crossing_angle_deg = 90.0;
  for (int f = 0; f < s.num_faces(); ++f) {
    const Eigen::Vector3d& n = s.face_normal(f);
    gphi[f] = Gradient(geo, s, f, phi);
    gpsi[f] = Gradient(geo, s, f, psi);
    strong[f] = g.weight[f] > 0.5;
    // The angle of φ's level line (⊥ ∇φ) to direction d, degrees.
    const auto angle_to = [&](const Eigen::Vector3d& d) {
      return std::asin(std::min(1.0, std::abs(gphi[f].normalized().dot(d)))) * kDegrees;
    };
    const double angle = angle_to(g.direction[f]), wa = g.weight[f] * s.face_area(f);
    align += wa * angle * angle;
    align_w += wa;
    if (strong[f]) align_s += wa * angle * angle, align_sw += wa;
    if (blended && g.source_weight[f] > 0.5) {
      const double source_angle = angle_to(g.source_direction[f]), swa = g.source_weight[f] * s.face_area(f);
      align_src += swa * source_angle * source_angle, align_srcw += swa;
    }
    const Eigen::Vector3d t1 = n.cross(gphi[f]).normalized(), t2 = n.cross(gpsi[f]).normalized();
    const Eigen::Matrix3d S = ConjugacyResidual::Regularised(geo.S[f], n, geo.flat_curvature);
    const double c = t1.dot(S * t2) / (ConjugacyResidual::CurvatureSum(geo.S[f], n) + geo.flat_curvature);
    if (std::isfinite(c)) conj += s.face_area(f) * c * c;
    const double crossing = std::acos(std::min(1.0, std::abs(t1.dot(t2)))) * kDegrees;
    if (std::isfinite(crossing)) m.min_crossing_angle_deg = std::min(m.min_crossing_angle_deg, crossing);
    if (!(crossing >= min_angle_deg)) {
      ++m.faces_below_min_angle, m.area_below_min_angle += s.face_area(f);
      VLOG(2) << "levelset: face " << f << " at " << geo.centroid[f].transpose() << " crosses at " << crossing << "°";
    }
    if (!(n.dot(gphi[f].cross(gpsi[f])) > 0.0)) ++m.foldovers;
  }
  m.alignment_rms_deg = align_w > 0 ? std::sqrt(align / align_w) : 0.0;
  m.alignment_rms_deg_strong = align_sw > 0 ? std::sqrt(align_s / align_sw) : 0.0;
  m.alignment_rms_deg_source_strong =
      !blended ? m.alignment_rms_deg_strong : align_srcw > 0 ? std::sqrt(align_src / align_srcw) : 0.0;
  m.spacing_cv_phi = SpacingCv(s, gphi, all);
  m.spacing_cv_psi = SpacingCv(s, gpsi, all);
  m.spacing_cv_phi_strong = SpacingCv(s, gphi, strong);
  m.spacing_cv_psi_strong = SpacingCv(s, gpsi, strong);
  m.conjugacy_rms = std::sqrt(conj / s.total_area());
  m.area_below_min_angle /= s.total_area();
  return m;
}

}  // namespace levelset_internal

LevelSetMetrics MeasureLevelSets(const SurfaceModel& surface, const GuidanceField& guidance,
                                 const std::vector<double>& phi, const std::vector<double>& psi,
                                 double min_angle_deg) {
  return Measure(surface, Precompute(surface), guidance, phi, psi, min_angle_deg);
}
}  // namespace pqlayout

// Poles (levelset.poles): where the guidance turns a whole turn (index +1: the top of a dome,
// a bump), level lines can only ring the point or fan out of it. A single-valued φ can do
// neither for both families, and splits the difference: on the corpus's circular dome the
// strain layout misaligned by 10.8° with ragged cells. A pole gives each family its shape:
// the disc of the cap radius round the crown is left out of the solve, the hole it leaves is
// joined to the boundary by a seam (levelset_solve.cc), across which the fanning family
// jumps by whole levels (as the radial lines round the Great Court's Reading Room do), and
// the other family rings the hole. The extraction closes the innermost ring with one polygon,
// the cap: a crown ring or an oculus, as on a ribbed (Schwedler) dome. The dome then aligns
// to 0.5°; what it costs is spacing: the radial lines are closer near the cap than at the rim.
#include <glog/logging.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "geometry/mesh_io.h"
#include "geometry/mesh_validation.h"
#include "problems/levelset_internal.h"

namespace pqlayout::levelset_internal {

constexpr double kMinCapRadius = 1.0;    // × h: the cap is at least this wide in radius ...
constexpr double kCapShare = 0.25;       // ... and this share of the crown's distance to the boundary,
                                         // so that the rays stay ≳ 0.2 h apart at the cap (square
                                         // dome: 5 triangles next to the cap at 0.2, 3 at 0.25)
constexpr double kCapClearance = 2.0;    // × h: rings between the cap and the boundary, at least
constexpr double kPoleGain = 0.75;       // poles are kept if they align to below this × the layout without
constexpr double kPoleTryAbove = 8.0;    // °: poles are tried only if the layout without aligns worse, or folds over

std::vector<LevelSetCap> FindCaps(const SurfaceModel& s, const GuidanceField& g, double h) {
  // Nothing strongly guided (a dome's curvature field: umbilic all over): nothing to align.
  if (std::none_of(g.weight.begin(), g.weight.end(), [](double w) { return w > 0.5; })) return {};
  int cancelled = 0;
  std::vector<Eigen::Vector3d> crowns;
  SeamTips(s, g, h, &cancelled, &crowns);
  std::vector<LevelSetCap> caps;
  for (const Eigen::Vector3d& c : crowns) {
    double to_boundary = std::numeric_limits<double>::infinity();
    for (int v = 0; v < s.num_vertices(); ++v)
      if (s.is_boundary(v)) to_boundary = std::min(to_boundary, (s.position(v) - c).norm());
    const double radius = std::max(kMinCapRadius * h, kCapShare * to_boundary);
    if (to_boundary < radius + kCapClearance * h) continue;
    bool apart = true;
    for (const LevelSetCap& o : caps) apart = apart && (o.centre - c).norm() > o.radius + radius + kCapClearance * h;
    if (apart) caps.push_back({c, radius});
  }
  return caps;
}

// The surface without the triangles inside a cap (all three corners within its radius) and
// the guidance on what is left (same face order). If that is not one clean hole per cap (a
// pinched vertex, a cap that swallowed nothing), no cap is cut: *holed stays null.
Status CutCaps(const SurfaceModel& s, const GuidanceField& g, std::vector<LevelSetCap>* caps,
               std::shared_ptr<const SurfaceModel>* holed, GuidanceField* holed_guidance) {
  holed->reset();
  PolygonSoup soup;
  for (int v = 0; v < s.num_vertices(); ++v) soup.points.push_back(s.position(v));
  std::vector<int> kept;
  for (int f = 0; f < s.num_faces(); ++f) {
    const auto ids = s.face_vertices(f);
    bool inside = false;
    for (const LevelSetCap& cap : *caps) {
      bool all = true;
      for (const int v : ids) all = all && (s.position(v) - cap.centre).norm() < cap.radius;
      inside = inside || all;
    }
    if (inside) continue;
    soup.faces.push_back({ids[0], ids[1], ids[2]});
    kept.push_back(f);
  }
  TriMesh mesh;
  if (!ValidateSurfaceSoup(soup).ok() || !BuildTriMesh(soup, &mesh, nullptr).ok()) {
    LOG(WARNING) << "levelset: the guidance has " << caps->size() << " crown(s), but cutting their caps out of the "
                 << "solve mesh would leave it non-manifold: no poles";
    caps->clear();
    return Status::Ok();
  }
  auto model = std::make_shared<const SurfaceModel>(std::move(mesh));
  if (model->boundary_loops().size() != s.boundary_loops().size() + caps->size()) {
    LOG(WARNING) << "levelset: cutting " << caps->size() << " cap(s) out of the solve mesh gave "
                 << model->boundary_loops().size() - s.boundary_loops().size() << " new holes: no poles";
    caps->clear();
    return Status::Ok();
  }
  *holed_guidance = GuidanceField();
  holed_guidance->scale = g.scale;
  for (const int f : kept) AppendFace(g, f, holed_guidance);
  *holed = std::move(model);
  return Status::Ok();
}

// The layout with poles at the crowns (caps) or without: plain and poles solve each into
// their LevelSetSolution (with a Finish: to the joint solve, the rest left there).
Status ChoosePoles(std::vector<LevelSetCap> caps, const LayoutSolve& plain, const LayoutSolve& poles, int alongside_budget,
                   LevelSetSolution* solution) {
  // The layout without poles first. Poles are tried only if it misses the alignment target
  // (kPoleTryAbove, report.json's) or folds over: a pole buys alignment at the crown with the
  // rays' uneven spacing, and solving both layouts doubles the stage's time (the Great Court ×
  // strain has two crowns, both cancelled ±½ pairs in weak guidance, and aligns to 5.9°
  // without; with poles it was 6.0°, not kept, at twice the time).
  // The layouts are compared after their joint solves, and only the one kept runs its
  // crossing rounds (a few seconds to a minute each): the rounds move φ within one vertex ring
  // of the faces they lift and change alignment by at most 2.6° (measured on every corpus run
  // with a crown: 5.2–35.7° after the joint solve against 5.9–38.2° at the end), while the
  // poles are kept only where they align clearly better (kPoleGain). On the corpus every
  // decision came out as when both layouts were finished (benchmarks/RESULTS.md, 2026-12-04).
  // A layout without poles that aligns after its joint solve is finished first; if its rounds
  // leave a fold-over, the poles are tried as a whole layout and compared finished.
  // levelset.alongside: the poles' layout, to its joint solves, on a second thread from the
  // start, in case it is needed (plain and poles read nothing the other writes; each finish
  // runs here, on this thread). It goes on while the plain layout is finished, and is joined
  // only once it is needed; a plain layout that aligns and does not fold over cancels it (its
  // Ceres solve ends within one iteration) instead of waiting for it.
  Finish finish_plain, finish_poles;
  LevelSetSolution with_poles;
  AlongsideSolve ahead;  // after what its thread writes: destroyed (cancelled, joined) first
  const bool alongside = ahead.Start([&] { return poles(&with_poles, &finish_poles); }, alongside_budget);
  if (alongside)
    LOG(INFO) << "levelset: " << caps.size() << " crown(s) of the guidance: the layout with poles there solved "
              << "alongside, in case it is needed";
  PQ_RETURN_IF_ERROR(plain(solution, &finish_plain));
  bool finished = false;
  if (solution->metrics.alignment_rms_deg_strong <= kPoleTryAbove) {
    PQ_RETURN_IF_ERROR(finish_plain());
    finished = true;
    if (solution->metrics.foldovers == 0) {
      LOG(INFO) << "levelset: " << caps.size() << " crown(s) of the guidance, no pole tried: the layout aligns to "
                << solution->metrics.alignment_rms_deg_strong << "° where weight > 0.5 without";
      solution->rejected_poles = {{"crowns", caps.size()},
                                  {"tried", false},
                                  {"alignment_without", solution->metrics.alignment_rms_deg_strong}};
      return Status::Ok();
    }
  }
  // Both layouts, the poles' kept only if they align clearly better (kPoleGain) without more
  // fold-overs: where the crown sits in weak guidance or the field is no dome's (the L-shaped
  // roof, the hypar, the wavy roof under strain: 15.5°, 12.8°, 17.0° against 10.3°, 12.9°,
  // 16.6° without, after the joint solves) the fan only costs.
  for (const LevelSetCap& c : caps)
    LOG(INFO) << "levelset: a crown of the guidance at (" << c.centre.x() << ", " << c.centre.y()
              << "): trying a pole, its cap " << c.radius << " m in radius left out of the solve";
  if (!alongside) {
    PQ_RETURN_IF_ERROR(poles(&with_poles, finished ? nullptr : &finish_poles));
  } else {
    PQ_RETURN_IF_ERROR(ahead.Join());
    if (finished) PQ_RETURN_IF_ERROR(finish_poles());  // as if solved whole: the plain layout was
  }
  const LevelSetMetrics a = with_poles.metrics, b = solution->metrics;
  const bool better = a.alignment_rms_deg_strong < kPoleGain * b.alignment_rms_deg_strong && a.foldovers <= b.foldovers;
  const char* when = finished ? "finished" : "after the joint solves";
  LOG(INFO) << "levelset: with " << caps.size() << " pole(s) alignment " << a.alignment_rms_deg_strong << "° where weight > 0.5 ("
            << a.foldovers << " fold-overs), without " << b.alignment_rms_deg_strong << "° (" << b.foldovers
            << "), " << when << ": " << (better ? "poles kept" : "no poles");
  if (!better) {
    if (!finished) PQ_RETURN_IF_ERROR(finish_plain());
    solution->rejected_poles = {{"crowns", caps.size()},
                                {"tried", true},
                                {"compared", when},
                                {"alignment_with_poles", a.alignment_rms_deg_strong},
                                {"alignment_without", b.alignment_rms_deg_strong},
                                {"foldovers_with_poles", a.foldovers}};
    return Status::Ok();
  }
  if (!finished) PQ_RETURN_IF_ERROR(finish_poles());
  *solution = std::move(with_poles);
  solution->caps = std::move(caps);
  return Status::Ok();
}

}  // namespace pqlayout::levelset_internal

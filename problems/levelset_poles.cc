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

#include "geometry/mesh_io.h"
#include "geometry/mesh_validation.h"
#include "problems/levelset_internal.h"

namespace pqlayout::levelset_internal {

constexpr double kMinCapRadius = 1.0;    // × h: the cap is at least this wide in radius ...
constexpr double kCapShare = 0.25;       // ... and this share of the crown's distance to the boundary,
                                         // so that the rays stay ≳ 0.2 h apart at the cap (square
                                         // dome: 5 triangles next to the cap at 0.2, 3 at 0.25)
constexpr double kCapClearance = 2.0;    // × h: rings between the cap and the boundary, at least

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

}  // namespace pqlayout::levelset_internal

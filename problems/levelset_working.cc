// The mesh the level sets are solved on (SolveLevelSets): the reference itself, or a remeshed
// copy whose edges are the working edge long; made on the caller's thread or ahead, on a thread
// of its own (MakeWorkingMeshInBackground).
#include <glog/logging.h>

#include <algorithm>
#include <cmath>
#include <future>
#include <sstream>
#include <string>

#include "geometry/plan_remesh.h"
#include "geometry/remesh.h"
#include "problems/levelset.h"

namespace pqlayout {
namespace {

constexpr double kWorkingCornerAngle = 30.0;  // corners the working mesh keeps (extract.corner_angle's default)
constexpr double kReuseReference = 0.7;       // solve on the reference if its mean edge ≥ this × working edge
constexpr double kDefaultWorkingEdge = 0.4;   // × h: CGAL lands near 12k triangles on the Great Court at h = 3 m
// × h, levelset.draft: a quarter of the triangles (2.9k on the Great Court), level sets ~5× faster;
// over seven Great Court meshes the shell after stiffen is a median 9 % (strain) and 5 %
// (curvature) softer and one of eleven targets is missed (the shortest edge at the hole):
// README "Draft runs". Never coarser than 1/kDraftLoopEdges of the shortest boundary loop (nor
// finer than the default): at 0.8 h the two_holes roof's openings (10 and 12.6 m round, h =
// 1.5 m) got 8–10 working edges each and its planarisation failed (δ 0.3–1.0).
constexpr double kDraftWorkingEdge = 0.8;
constexpr double kDraftLoopEdges = 16.0;
// levelset.working_triangles: the working mesh's edge is at least that of N equilateral
// triangles covering the roof, √(4A / (√3 N)), so that a fine spacing on a large roof does not
// multiply the level sets' unknowns by (0.4 h)⁻². The guidance and the surface have features of
// a fixed size, which that many triangles resolve; the panels' size only enters through the
// level lines drawn, and φ, ψ are linear on each triangle, so several lines may cross one.
// Measured on the Great Court at h = 1.25 m (reference at 0.5 h, strain): 71.4k working triangles
// (0.4 h) took 134 s of level sets, 12.1k (edge 1.2 m) 8.6 s, every target met by both, planarised
// quads 0.894 / 0.889, compliance after stiffen 23,764 / 23,251 J (benchmarks/RESULTS.md, "The
// working mesh's triangle budget"). Like the draft, never coarser than 1/kDraftLoopEdges of the
// shortest boundary loop, and never coarser than kBudgetMaxEdge × h: at h = 0.75 m its 1.09 m
// (1.45 h) met every target (quads 0.975 as extracted, 0.866 planarised); N = 1 at h = 1 m gave
// 8.7 m (8.7 h) and planarisation cut 1,047 folded panels (quads 0.96 → 0.58).
constexpr double kEquilateralArea = 0.43301270189221932;  // √3 / 4: an equilateral triangle of edge 1
constexpr double kBudgetMaxEdge = 1.5;                     // × h

// The edge at most `edge` (never below `floor`) that gives every boundary loop kDraftLoopEdges edges.
double WithinLoops(const SurfaceModel& s, double edge, double floor) {
  for (const auto& loop : s.boundary_loops()) edge = std::min(edge, loop.length / kDraftLoopEdges);
  return std::max(edge, floor);
}

double WorkingEdge(const SurfaceModel& s, const LevelsetOptions& options, double h, const std::string& prefix) {
  if (options.working_edge > 0.0) return options.working_edge;
  const double fine = kDefaultWorkingEdge * h;
  double edge = fine;
  if (options.draft) {
    edge = WithinLoops(s, kDraftWorkingEdge * h, fine);
    LOG(INFO) << prefix << "draft: φ, ψ on a working mesh of edge " << edge << " m (" << kDraftWorkingEdge
              << " h, at most 1/" << kDraftLoopEdges << " of the shortest boundary loop; a quick look, not the final "
              << "layout: README \"Draft runs\")";
  }
  if (options.working_triangles <= 0) return edge;
  const double wanted = std::sqrt(s.total_area() / (kEquilateralArea * options.working_triangles));
  const double budget = WithinLoops(s, std::min(wanted, kBudgetMaxEdge * h), fine);
  if (budget <= edge) return edge;
  LOG(INFO) << prefix << "φ, ψ on a working mesh of edge " << budget << " m (" << budget / h
            << " h) instead of " << edge << " m: about " << options.working_triangles
            << " triangles over the roof's " << s.total_area() << " m² (levelset.working_triangles)";
  return budget;
}
constexpr int kRemeshIterations = 3;
// A reference whose triangles are mostly slivers (a NURBS render mesh: strips of 0.2 × 2.7 m
// on a 20 m dome) is remeshed even where it is not finer than the working mesh: solved on
// directly, its P1 gradients aligned to 9.3° where an isotropic mesh of the same dome gives
// 6.0°. Generated references never qualify (every angle ≥ 20°: RoofGenerator tests).
constexpr double kSliverAngleDeg = 15.0;
constexpr double kSliverFraction = 0.1;

// The share of the triangles with an angle below kSliverAngleDeg.
double SliverFraction(const SurfaceModel& s) {
  if (s.num_faces() == 0) return 0.0;
  const double limit = std::cos(kSliverAngleDeg * M_PI / 180.0);
  int slivers = 0;
  for (int f = 0; f < s.num_faces(); ++f) {
    const auto v = s.face_vertices(f);
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d a = (s.position(v[(k + 1) % 3]) - s.position(v[k])).normalized();
      const Eigen::Vector3d b = (s.position(v[(k + 2) % 3]) - s.position(v[k])).normalized();
      if (a.dot(b) > limit) {
        ++slivers;
        break;
      }
    }
  }
  return static_cast<double>(slivers) / s.num_faces();
}
// References with at least this many triangles get their working mesh from the plan when they
// are height fields (plan_remesh.h): CGAL's remeshing of the whole reference costs ~7 µs per
// triangle (1.5 s here, 22–28 s at 1M). Below it CGAL's remeshing stays: on the corpus roofs
// (8k triangles) the plan path gave 36 misses instead of 33 (interior non-quads on the saddle
// 0 → 8, the hypar 0 → 2, the square dome under strain 3 → 9; quads of the square dome under
// curvature 1.0 → 0.83), a cause not found yet (benchmarks/RESULTS.md, 2026-12-03).
constexpr int kPlanFromTriangles = 200000;
}  // namespace

// A reference much finer than the layout needs, or one of slivers (a NURBS render mesh of
// strips, on which the gradients are poor): the solve runs on a remeshed copy whose edges are
// the working edge long (the level lines are h apart; 0.4 h resolves them), and φ and ψ are
// interpolated to the reference's vertices. Stage time then follows h, not the reference size.
// A large height-field reference is meshed anew in the plan (plan_remesh.h, < 0.5 s at 1M
// triangles); any other goes through CGAL's isotropic remeshing (~25 s at 1M), with a
// progress line first.
WorkingMesh MakeWorkingMesh(const SurfaceModel& s, const LevelsetOptions& options, double h, bool ahead) {
  const std::string prefix = ahead ? "levelset (made ahead, beside the guidance): " : "levelset: ";
  WorkingMesh w;
  w.edge = WorkingEdge(s, options, h, prefix);
  const double reference_edge = MeanEdgeLength(s.mesh());
  const bool finer = reference_edge < kReuseReference * w.edge;
  const double slivers = finer ? 0.0 : SliverFraction(s);
  if (!finer && slivers <= kSliverFraction) return w;
  std::ostringstream why;
  if (finer)
    why << "reference mean edge " << reference_edge << " m < " << kReuseReference << " × working edge " << w.edge << " m";
  else
    why << 100.0 * slivers << " % of the reference's triangles have an angle below " << kSliverAngleDeg << "°";
  TriMesh mesh;
  std::string why_not = "fewer than " + std::to_string(kPlanFromTriangles) + " triangles";
  if (s.num_faces() >= kPlanFromTriangles && RemeshOverPlan(s, w.edge, kWorkingCornerAngle, &mesh, &why_not)) {
    LOG(INFO) << prefix << why.str() << ": its plan meshed anew as a working mesh";
    w.kind = "plan";
  } else {
    LOG(INFO) << prefix << why.str() << ": remeshing its " << s.num_faces()
              << " triangles to a working mesh (CGAL isotropic remeshing, " << kRemeshIterations
              << " rounds; not from the plan: " << why_not << ") ...";
    w.status = RemeshIsotropic(s, w.edge, kWorkingCornerAngle, kRemeshIterations, &mesh).WithContext("levelset working mesh");
    if (!w.status.ok()) return w;
    w.kind = "CGAL remeshing (not from the plan: " + why_not + ")";
  }
  w.mesh = std::make_shared<const SurfaceModel>(std::move(mesh));
  return w;
}

std::shared_future<WorkingMesh> MakeWorkingMeshInBackground(const SurfaceModel& s, const LevelsetOptions& options,
                                                            double h) {
  return std::async(std::launch::async, [&s, options, h] { return MakeWorkingMesh(s, options, h, true); }).share();
}

}  // namespace pqlayout

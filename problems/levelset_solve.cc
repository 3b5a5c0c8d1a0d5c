// The level-set solves' drivers (paper §3.1): which seams to cut (SeamTips, SolveWithSeams) and
// the solve on the working mesh (SolveLevelSets; the mesh itself is levelset_working.cc); the
// problem on one mesh is levelset_problem.cc.
#include "problems/levelset_internal.h"

#include <glog/logging.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <thread>

#include "base/parallel_ranges.h"
#include "geometry/closest_point.h"
#include "geometry/line_field_singularities.h"

namespace pqlayout {

using namespace levelset_internal;

namespace levelset_internal {

int AlongsideBudget(const LevelsetOptions& options) {
  if (options.alongside == "true") return AlongsideSolve::kNoLimit;
  if (options.alongside == "false") return 0;
  if (options.alongside == "1") return 1;
  return std::max(1, static_cast<int>(std::thread::hardware_concurrency())) - 1;  // "auto"
}

// The guidance on the working mesh: each working face takes the direction (projected into
// its plane) and weight of the reference face closest to its centroid.
GuidanceField TransferGuidance(const SurfaceModel& reference, const GuidanceField& g, const SurfaceModel& working) {
  const ClosestPointQuery& query = reference.closest_points();
  GuidanceField out;
  out.scale = g.scale;
  for (int f = 0; f < working.num_faces(); ++f) {
    const auto ids = working.face_vertices(f);
    const Eigen::Vector3d centroid =
        (working.position(ids[0]) + working.position(ids[1]) + working.position(ids[2])) / 3.0;
    const int r = query.OnSurface(centroid).element;
    const Eigen::Vector3d& n = working.face_normal(f);
    const auto project = [&n](const Eigen::Vector3d& direction) {
      const Eigen::Vector3d d = direction - direction.dot(n) * n;
      return d.norm() > 0.0 ? Eigen::Vector3d(d.normalized()) : Eigen::Vector3d(n.unitOrthogonal());
    };
    AppendFace(g, r, &out);
    out.direction.back() = project(g.direction[r]);
    if (!out.source_direction.empty()) out.source_direction.back() = project(g.source_direction[r]);
  }
  return out;
}

constexpr double kCancelDistance = 2.0;  // × h: two ±½ singularities closer than this get no seam
constexpr double kMinSeamWeight = 1.0;   // × h: a seam whose path has less weighted length is not cut
constexpr double kCancelInZone = 3.0;    // × h: two of one sign in one weak zone closer than this get no seam

// The tips of the seams: the guidance's singularities of index ±½, less pairs, closest
// first: two closer than kCancelDistance·h, or two of the same sign closer than
// kCancelInZone·h in one connected weak zone (faces with weight < 0.5). Around such a pair the
// field turns by a whole turn or none (opposite indices cancel: a wrinkle; equal ones make an
// index ±1, e.g. a crown that the nearly isotropic field there splits in two), so a
// single-valued φ crosses it; two seams would only add two branch points (on the L-shaped
// corpus roof the two halves of the strain crown, 2.3 h apart in its weak zone, made φ fan out
// of two branch points into 28 triangles). The distance bound: with the strain weight that
// vanishes where e_max swaps (guidance.shear_switch, problems/guidance.cc) the wavy corpus
// roof's weak zones join across the roof, and pairs 4.6–12 h apart were cancelled: one seam
// instead of four, alignment 22.9° instead of 8.5°.
// crowns (may be null): where the field turns a whole turn (index +1, or a cancelled pair of
// +½ at its midpoint), for the poles (levelset_poles.cc).
std::vector<int> SeamTips(const SurfaceModel& s, const GuidanceField& g, double h, int* cancelled,
                          std::vector<Eigen::Vector3d>* crowns) {
  std::vector<LineFieldSingularity> half;
  for (const auto& x : FindLineFieldSingularities(s, g.direction)) {
    if (std::abs(std::abs(x.index) - 0.5) < 1e-9) half.push_back(x);
    else if (crowns != nullptr && std::abs(x.index - 1.0) < 1e-9) crowns->push_back(x.position);
  }
  // Weak zones: vertices joined through faces with weight < 0.5 (-1: on no such face).
  std::vector<int> zone(s.num_vertices(), -1), parent(s.num_vertices());
  std::iota(parent.begin(), parent.end(), 0);
  const auto find = [&](int v) {
    while (parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
  };
  for (int f = 0; f < s.num_faces(); ++f) {
    if (!(g.weight[f] < 0.5)) continue;
    const auto ids = s.face_vertices(f);
    for (const int v : ids) zone[v] = 0, parent[find(v)] = find(ids[0]);
  }
  const auto same_weak_zone = [&](int a, int b) { return zone[a] >= 0 && zone[b] >= 0 && find(a) == find(b); };
  std::vector<std::tuple<double, int, int>> candidates;
  for (size_t i = 0; i < half.size(); ++i)
    for (size_t j = i + 1; j < half.size(); ++j) {
      const double d = (half[i].position - half[j].position).norm();
      if (d < kCancelDistance * h ||
          (half[i].index == half[j].index && d < kCancelInZone * h && same_weak_zone(half[i].vertex, half[j].vertex)))
        candidates.emplace_back(d, i, j);
    }
  std::sort(candidates.begin(), candidates.end());
  std::vector<char> gone(half.size(), 0);
  *cancelled = 0;
  for (const auto& [d, i, j] : candidates) {
    if (gone[i] || gone[j]) continue;
    gone[i] = gone[j] = 1;
    ++*cancelled;
    if (crowns != nullptr && half[i].index > 0.0 && half[j].index > 0.0)
      crowns->push_back(0.5 * (half[i].position + half[j].position));
  }
  std::vector<int> tips;
  for (size_t i = 0; i < half.size(); ++i)
    if (!gone[i]) tips.push_back(half[i].vertex);
  return tips;
}

// The surface cut open along `paths` (null if there are none) and the seams' signs.
Status CutAlong(const SurfaceModel& s, const GuidanceField& g, const std::vector<std::vector<int>>& paths,
                LevelSetSeams* seams) {
  seams->cut.reset();
  seams->sign.clear();
  if (paths.empty()) return Status::Ok();
  std::unique_ptr<SeamCut> cut;
  PQ_RETURN_IF_ERROR(SeamCut::Build(s, paths, &cut).WithContext("levelset seams"));
  seams->sign = SeamSigns(*cut, OrientedCrossField(cut->cut(), g));
  seams->cut = std::move(cut);
  return Status::Ok();
}

// The hole seams (from a boundary, sign +1) across which neither φ nor ψ of the initial guess
// (levelset_problem.cc) jumps by more than kMaxRingPeriod levels: their level lines ring the
// hole, and a single-valued φ hides the one or two levels of mismatch in a short band. Cut,
// such a seam only costs: on the Great Court at 112k reference triangles the strain field's
// ring seam (φ jump −2, ψ 0) made the solve misalign by 18.6° (quad fraction 0.68) where the
// uncut solve reaches 6.4° (0.84). The seams that carry radial lines (the curvature field's
// ring, φ jump ±61; the off-centre hole's strain seam, 37) are kept.
constexpr int kMaxRingPeriod = 2;
Status RingSeams(const GuidanceField& g, const LevelsetOptions& options, double h, LevelSetSeams* seams,
                 std::vector<char>* ring) {
  const SeamCut& cut = *seams->cut;
  ring->assign(cut.num_paths(), 0);
  bool any = false;
  for (int p = 0; p < cut.num_paths(); ++p) any = any || (!cut.starts_inside(p) && seams->sign[p] > 0);
  if (!any) return Status::Ok();
  const LevelSetGeometry geo = Precompute(cut.cut());
  LevelSetSolution guess;
  PQ_RETURN_IF_ERROR(InitialGuess(cut.cut(), geo, InteriorEdges(cut.cut(), geo), g, options, h, seams, &guess));
  for (int p = 0; p < cut.num_paths(); ++p)
    (*ring)[p] = !cut.starts_inside(p) && seams->sign[p] > 0 && std::abs(seams->phi_offset[p]) <= kMaxRingPeriod &&
                 std::abs(seams->psi_offset[p]) <= kMaxRingPeriod;
  return Status::Ok();
}

// Drops the paths marked in `drop` (counting them in *count) and cuts again.
Status DropPaths(const SurfaceModel& s, const GuidanceField& g, const std::vector<char>& drop,
                 std::vector<std::vector<int>>* paths, int* count, LevelSetSeams* seams) {
  std::vector<std::vector<int>> kept;
  for (size_t p = 0; p < paths->size(); ++p)
    if (!drop[p]) kept.push_back(std::move((*paths)[p]));
  if (kept.size() == paths->size()) {
    *paths = std::move(kept);
    return Status::Ok();
  }
  *count += static_cast<int>(paths->size() - kept.size());
  *paths = std::move(kept);
  return CutAlong(s, g, *paths, seams);
}

// SolveOnMesh on the surface cut open along seams (geometry/seams.h); φ, ψ per original
// vertex are the first copies' values, per cut vertex in phi_cut / psi_cut. A seam is cut
// only where a single-valued φ would have to misalign a weighted length of kMinSeamWeight·h
// or more (PathWeight of its route): on the Great Court the curvature field's four umbilics
// and the ring qualify (3.3–16 m at h = 3 m); the strain field's singularities sit in the
// weak bands along the edges, where a hidden cut costs at most 1.6 m, and get none.
Status SolveWithSeams(const SurfaceModel& s, const GuidanceField& g, const LevelsetOptions& options, double h,
                      LevelSetSolution* solution, Finish* finish) {
  LevelSetSeams& seams = solution->seams;
  seams = LevelSetSeams();
  const std::vector<int> tips = SeamTips(s, g, h, &seams.cancelled_pairs, nullptr);
  std::vector<std::vector<int>> paths;
  for (auto& path : RouteSeams(s, g.weight, tips)) {
    if (PathWeight(s, g.weight, path) >= kMinSeamWeight * h) paths.push_back(std::move(path));
    else ++seams.light_paths;
  }
  PQ_RETURN_IF_ERROR(CutAlong(s, g, paths, &seams));
  if (seams.cut) {
    // A seam from a singularity must flip the orientation (sign −1). If the guidance on the
    // cut surface says otherwise, the "singularity" was a wrinkle that a nearby uncancelled
    // one undoes (e.g. where two principal directions swap roles): no seam there.
    std::vector<char> orientable(paths.size());
    for (size_t p = 0; p < paths.size(); ++p) orientable[p] = !s.is_boundary(paths[p].front()) && seams.sign[p] > 0;
    PQ_RETURN_IF_ERROR(DropPaths(s, g, orientable, &paths, &seams.orientable_tips, &seams));
  }
  if (seams.cut) {
    std::vector<char> ring;
    PQ_RETURN_IF_ERROR(RingSeams(g, options, h, &seams, &ring));
    PQ_RETURN_IF_ERROR(DropPaths(s, g, ring, &paths, &seams.ring_holes, &seams));
  }
  if (paths.empty()) return SolveOnMesh(s, g, options, h, nullptr, solution, finish);
  for (const auto& path : paths)
    if (!s.is_boundary(path.front())) seams.tips.push_back(path.front());
  LOG(INFO) << "levelset: " << paths.size() << " seams: " << seams.tips.size() << " from guidance singularities, "
            << paths.size() - seams.tips.size() << " joining holes to the outer boundary (" << seams.cancelled_pairs
            << " close singularity pairs, " << seams.light_paths << " routes through weak guidance, "
            << seams.orientable_tips << " tips the guidance does not flip around and " << seams.ring_holes
            << " holes the level lines ring left uncut)";
  const auto to_original = [solution]() {
    solution->phi_cut = std::move(solution->phi);
    solution->psi_cut = std::move(solution->psi);
    solution->phi = solution->seams.cut->ToOriginal(solution->phi_cut);
    solution->psi = solution->seams.cut->ToOriginal(solution->psi_cut);
  };
  Finish rounds;
  PQ_RETURN_IF_ERROR(SolveOnMesh(seams.cut->cut(), g, options, h, &seams, solution, finish ? &rounds : nullptr));
  if (finish == nullptr) {
    to_original();
    return Status::Ok();
  }
  *finish = [rounds, to_original]() {
    PQ_RETURN_IF_ERROR(rounds());
    to_original();
    return Status::Ok();
  };
  return Status::Ok();
}

}  // namespace levelset_internal

nlohmann::json LevelSetSeams::ToJson() const {
  nlohmann::json paths = nlohmann::json::array();
  if (cut)
    for (int p = 0; p < cut->num_paths(); ++p)
      paths.push_back({{"vertices", cut->path(p).size()},
                       {"sign", sign[p]},
                       {"phi_offset", static_cast<long>(phi_offset[p])},
                       {"psi_offset", static_cast<long>(psi_offset[p])},
                       {"branch_point", cut->starts_inside(p)}});
  return {{"count", paths.size()},
          {"branch_points", tips.size()},
          {"cancelled_singularity_pairs", cancelled_pairs},
          {"uncut_weak_routes", light_paths},
          {"uncut_orientable_tips", orientable_tips},
          {"uncut_ring_holes", ring_holes},
          {"on_working_mesh", working != nullptr},
          {"paths", paths}};
}

namespace {

// φ, ψ solved on `working` (coarse) interpolated to the reference's vertices for the field
// files; the solve's own values, metrics and seams move into *solution (see SolveOnWorking).
void InterpolateFromWorking(const SurfaceModel& s, const std::shared_ptr<const SurfaceModel>& working, bool holed,
                            LevelSetSolution* coarse_ptr, LevelSetSolution* solution) {
  LevelSetSolution& coarse = *coarse_ptr;
  const ClosestPointQuery& query = working->closest_points();
  solution->phi.assign(s.num_vertices(), 0.0);
  solution->psi.assign(s.num_vertices(), 0.0);
  // Each vertex on its own (base/parallel_ranges.h; the tree answers const queries from any
  // thread): 482k queries, ~0.5 s on one thread, at a million triangles.
  ParallelRanges(s.num_vertices(), [&](int begin, int end) {
    for (int v = begin; v < end; ++v) {
      const SurfacePoint p = query.OnSurface(s.position(v));
      const Eigen::Vector3d w = TriangleBarycentric(*working, p.element, holed ? p.point : s.position(v));
      const auto ids = working->face_vertices(p.element);
      for (int k = 0; k < 3; ++k) {
        solution->phi[v] += w[k] * coarse.phi[ids[k]];
        solution->psi[v] += w[k] * coarse.psi[ids[k]];
      }
    }
  });
  // The metrics are those of the solve, on the working mesh: on the reference, a small
  // triangle straddling a kink of the working mesh's piecewise linear φ gets a blend of the
  // two gradients, which says nothing about the layout but would dominate the minimum
  // crossing angle and inflate the spacing CV.
  solution->initial = coarse.initial;
  solution->metrics = coarse.metrics;
  solution->solver = coarse.solver;
  solution->crossing_rounds_kept = coarse.crossing_rounds_kept;
  solution->tip_cone = coarse.tip_cone;
  solution->working_faces = working->num_faces();
  solution->seams = std::move(coarse.seams);  // with the counters of the seams not cut
  solution->working = working;
  if (solution->seams.cut) {
    solution->seams.working = working;
    solution->phi_cut = std::move(coarse.phi_cut);
    solution->psi_cut = std::move(coarse.psi_cut);
  } else {
    solution->phi_working = std::move(coarse.phi);
    solution->psi_working = std::move(coarse.psi);
  }
}


// The rest of a solve on the working mesh: its rounds, then the interpolation to the reference.
// A struct rather than a lambda for the order its members go in: `rounds` may hold the cone's
// retry still running on its thread (levelset.alongside), reading the seams and cut surface that
// `interpolate` owns (the solution on the heap), so `rounds` goes first — cancelling and joining
// that thread — and `interpolate` after it. A finish that is never called (ChoosePoles keeps only
// one layout) is destroyed in that order too. (A lambda's captures go in an unspecified order:
// ThreadSanitizer caught the seams freed before the thread was joined.)
struct WorkingFinish {
  std::function<Status()> interpolate;
  Finish rounds;  // declared last: destroyed first
  Status operator()() const {
    PQ_RETURN_IF_ERROR(rounds());
    return interpolate();
  }
};

// φ, ψ solved on `working` (a remeshed or holed copy of the reference s), then interpolated
// to the reference's vertices for the field files; extraction runs on `working`. holed: a
// reference vertex inside a cap takes the values at its closest point on the cap's rim (not
// those of the rim triangle's plane extrapolated to it).
Status SolveOnWorking(const SurfaceModel& s, std::shared_ptr<const SurfaceModel> working,
                      const GuidanceField& working_guidance, const LevelsetOptions& options, double h,
                      LevelSetSolution* solution, bool holed = false, Finish* finish = nullptr) {
  auto coarse = std::make_shared<LevelSetSolution>();  // on the heap: with `finish` it outlives this call
  // With seams the solution stays on the working mesh's cut surface (extraction runs there);
  // the per-vertex φ, ψ interpolated below (first copies) are for the field files only.
  Finish rounds;
  Finish* inner = finish != nullptr ? &rounds : nullptr;
  if (options.seams) PQ_RETURN_IF_ERROR(SolveWithSeams(*working, working_guidance, options, h, coarse.get(), inner));
  else PQ_RETURN_IF_ERROR(SolveOnMesh(*working, working_guidance, options, h, nullptr, coarse.get(), inner));
  solution->metrics = coarse->metrics;  // the joint solve's, until finished
  const auto interpolate = [&s, working, solution, holed, coarse]() {
    InterpolateFromWorking(s, working, holed, coarse.get(), solution);
    return Status::Ok();
  };
  if (finish == nullptr) return interpolate();
  *finish = WorkingFinish{interpolate, rounds};
  return Status::Ok();
}

}  // namespace

Status SolveLevelSets(const SurfaceModel& s, const GuidanceField& g, const LevelsetOptions& options, double h,
                      LevelSetSolution* solution, const WorkingMesh* made) {
  const WorkingMesh own = made != nullptr ? WorkingMesh() : MakeWorkingMesh(s, options, h);
  const WorkingMesh& w = made != nullptr ? *made : own;
  PQ_RETURN_IF_ERROR(w.status);
  const double working_edge = w.edge;
  const std::shared_ptr<const SurfaceModel>& working = w.mesh;
  const std::string& working_kind = w.kind;
  GuidanceField working_guidance;
  if (working) {
    LOG(INFO) << "levelset: solving on the remeshed copy, " << working->num_faces() << " triangles";
    working_guidance = TransferGuidance(s, g, *working);
  }
  solution->caps.clear();
  solution->rejected_poles = nlohmann::json();
  const auto plain = [&](LevelSetSolution* out, Finish* finish) {
    out->working_mesh = working_kind;
    out->working_edge = working_edge;
    if (working) return SolveOnWorking(s, working, working_guidance, options, h, out, false, finish);
    out->working_faces = s.num_faces();
    if (options.seams) return SolveWithSeams(s, g, options, h, out, finish);
    return SolveOnMesh(s, g, options, h, nullptr, out, finish);
  };
  if (!options.seams || !options.poles) return plain(solution, nullptr);
  const SurfaceModel& m = working ? *working : s;
  const GuidanceField& mg = working ? working_guidance : g;
  std::vector<LevelSetCap> caps = FindCaps(m, mg, h);
  std::shared_ptr<const SurfaceModel> holed;
  GuidanceField holed_guidance;
  if (!caps.empty()) PQ_RETURN_IF_ERROR(CutCaps(m, mg, &caps, &holed, &holed_guidance));
  if (!holed) return plain(solution, nullptr);
  const auto poles = [&](LevelSetSolution* out, Finish* finish) {
    out->working_mesh = working_kind;
    out->working_edge = working_edge;
    return SolveOnWorking(s, holed, holed_guidance, options, h, out, true, finish);
  };
  return ChoosePoles(std::move(caps), plain, poles, AlongsideBudget(options), solution);
}
}  // namespace pqlayout
// The level-set solves (paper §3.1): φ, ψ and joint on one mesh, the crossing rounds, seams, the working mesh.
#include "problems/levelset_internal.h"

#include <glog/logging.h>

#include <algorithm>
#include <cmath>
#include <numeric>

#include "geometry/closest_point.h"
#include "geometry/line_field_singularities.h"
#include "geometry/remesh.h"
#include "problems/residuals/alignment_residual.h"
#include "problems/residuals/conjugacy_residual.h"
#include "problems/residuals/smoothness_residual.h"
#include "problems/residuals/transversality_residual.h"

namespace pqlayout {

using namespace levelset_internal;


namespace levelset_internal {

// ---- Crossing-angle rounds ------------------------------------------------------------
//
// The transversality hinge is a penalty: at the joint optimum it balances against
// alignment and spacing, and leaves a few percent of the faces crossing below min_angle
// (on the Great Court near the guidance singularities and the rectangle's corners; with a
// global weight ×10 the solve stalls and folds instead). So after the joint solve the
// faces still crossing below min_angle + kCrossingSlack get their transversality weight
// multiplied by kCrossingBoost, the hinge is raised by kCrossingMargin, and φ, ψ are
// re-solved near those faces only: ψ within kPsiRings vertex rings, φ within kPhiRings
// (φ moves as little as possible, to keep its alignment); the rest is held. Repeated until
// no face crosses below min_angle or levelset.crossing_rounds is used up.
constexpr double kCrossingSlack = 1.0;   // degrees above min_angle that still count as failing
constexpr double kCrossingMargin = 1.5;  // degrees the hinge is raised by in the rounds
constexpr double kCrossingBoost = 4.0;   // weight factor per round on a failing face
constexpr int kPhiRings = 1, kPsiRings = 3;
constexpr int kCrossingIterations = 30;  // Ceres iterations per round

// Marks the failing faces (see above), multiplies their boost and returns how many faces
// cross below min_angle (0: nothing to do). live_phi / live_psi: the vertices free to move.
int RaiseCrossings(const SurfaceModel& s, const LevelSetGeometry& geo, const std::vector<double>& phi,
                   const std::vector<double>& psi, double min_angle, std::vector<double>* boost,
                   std::vector<char>* live_phi, std::vector<char>* live_psi) {
  int below = 0;
  const double sin_failing = std::sin(min_angle + kCrossingSlack / kDegrees);
  std::vector<char> live(s.num_vertices(), 0);
  for (int f = 0; f < s.num_faces(); ++f) {
    const Eigen::Vector3d a = Gradient(geo, s, f, phi), b = Gradient(geo, s, f, psi);
    const double sine = s.face_normal(f).dot(a.cross(b)) / (a.norm() * b.norm());
    if (!(sine >= std::sin(min_angle))) ++below;
    if (sine >= sin_failing) continue;
    (*boost)[f] *= kCrossingBoost;
    for (const int v : s.face_vertices(f)) live[v] = 1;
  }
  for (int ring = 1; ring <= std::max(kPhiRings, kPsiRings); ++ring) {
    std::vector<char> next = live;
    for (int v = 0; v < s.num_vertices(); ++v)
      if (live[v])
        for (const auto u : s.mesh().vv_range(VertexHandle(v))) next[u.idx()] = 1;
    live.swap(next);
    if (ring == kPhiRings) *live_phi = live;
    if (ring == kPsiRings) *live_psi = live;
  }
  return below;
}

// A seam edge as the seam smoothness term sees it (cut vertex ids): i, j, k in the minus face
// f, i, j, l in the plus face g (i, j the same original vertices).
struct SeamEdgeTerm {
  int path;
  int i_minus, j_minus, k, i_plus, j_plus, l;
  Eigen::Matrix3d Gf, Gg;
  double area, distance;
};

std::vector<SeamEdgeTerm> SeamEdgeTerms(const SurfaceModel& s, const LevelSetGeometry& geo, const SeamCut& cut) {
  std::vector<SeamEdgeTerm> terms;
  for (const auto& e : cut.seam_edges()) {
    const auto ids_f = s.face_vertices(e.minus_face), ids_g = s.face_vertices(e.plus_face);
    const TriMesh& m = s.mesh();
    const auto h = m.halfedge_handle(EdgeHandle(e.cut_edge_minus), 0);
    const int a = cut.original_vertex(m.from_vertex_handle(h).idx()), b = cut.original_vertex(m.to_vertex_handle(h).idx());
    SeamEdgeTerm t;
    t.path = e.path;
    t.i_minus = t.j_minus = t.k = t.i_plus = t.j_plus = t.l = -1;
    for (int c = 0; c < 3; ++c) {
      const int of = cut.original_vertex(ids_f[c]), og = cut.original_vertex(ids_g[c]);
      (of == a ? t.i_minus : of == b ? t.j_minus : t.k) = ids_f[c];
      (og == a ? t.i_plus : og == b ? t.j_plus : t.l) = ids_g[c];
    }
    t.Gf = OrderedBasis(geo, s, e.minus_face, {t.i_minus, t.j_minus, t.k});
    t.Gg = OrderedBasis(geo, s, e.plus_face, {t.i_plus, t.j_plus, t.l});
    t.area = (s.face_area(e.minus_face) + s.face_area(e.plus_face)) / 3.0;
    t.distance = (geo.centroid[e.minus_face] - geo.centroid[e.plus_face]).norm();
    terms.push_back(t);
  }
  return terms;
}

// The level sets on the mesh they are solved on (see SolveLevelSets for the working mesh).
// seams: null, or the seams s is the cut surface of, with their signs (SolveWithSeams); the
// offsets are set here.
// Long (~170 lines) because the four solves (φ, ψ, joint, crossing rounds) share the charts and
// the term builders, lambdas closing over them; splitting it wants a LevelSetProblem class that
// owns them (issue 20, next step), and the order residual blocks are added in must not change.
Status SolveOnMesh(const SurfaceModel& s, const GuidanceField& g, const LevelsetOptions& options, double h,
                   LevelSetSeams* seams, LevelSetSolution* solution) {
  const LevelSetGeometry geo = Precompute(s);
  const std::vector<InteriorEdge> edges = InteriorEdges(s, geo);
  const auto& w = options.weights;
  const double min_angle = options.min_angle / kDegrees;
  const bool seamed = seams != nullptr && seams->cut != nullptr;

  // Initial guess: φ from the oriented cross field (weak pull where the guidance is weak),
  // then ψ from the conjugate direction of φ's level lines.
  std::vector<Eigen::Vector3d> target = OrientedCrossField(s, g);
  for (auto& t : target) t /= h;
  std::vector<double> omega(s.num_faces());
  for (int f = 0; f < s.num_faces(); ++f) omega[f] = std::max(g.weight[f], 0.05);
  std::vector<SeamEdgeTerm> seam_terms;
  if (seamed) {
    // On the cut surface the oriented field (`target`, from which SolveWithSeams took the
    // signs) has no hidden branch cut left: the Poisson fit with the seams' transitions is
    // the guess (the eigenvector below is for a single-valued φ).
    seams->phi_offset.assign(seams->cut->num_paths(), 0.0);
    seams->psi_offset.assign(seams->cut->num_paths(), 0.0);
    seam_terms = SeamEdgeTerms(s, geo, *seams->cut);
    PQ_RETURN_IF_ERROR(SeamedPoissonFit(s, geo, target, omega, h, 0, seams, &solution->phi));
    PQ_RETURN_IF_ERROR(SeamedPoissonFit(s, geo, ConjugateTargets(s, geo, solution->phi, h, min_angle),
                                        std::vector<double>(s.num_faces(), 1.0), h, 1, seams, &solution->psi));
  } else {
    PQ_RETURN_IF_ERROR(PoissonFit(s, geo, target, omega, &solution->phi));
    PQ_RETURN_IF_ERROR(SmallestEigenvector(s, geo, g, edges, h, w, &solution->phi));
    PQ_RETURN_IF_ERROR(PoissonFit(s, geo, ConjugateTargets(s, geo, solution->phi, h, min_angle),
                                  std::vector<double>(s.num_faces(), 1.0), &solution->psi));
  }

  std::vector<double>& phi = solution->phi;
  std::vector<double>& psi = solution->psi;
  Chart phi_chart{&phi, {}}, psi_chart{&psi, {}};
  std::vector<int> fixed_tips;  // branch points of sign −1 seams: u = a/2 on both sides
  if (seamed) {
    phi_chart.map = psi_chart.map = std::vector<Scalar>(s.num_vertices());
    for (int v = 0; v < s.num_vertices(); ++v) phi_chart.map[v] = psi_chart.map[v] = {v};
    for (const auto& pair : seams->cut->copy_pairs()) {
      const double sign = seams->sign[pair.path];
      if (pair.minus == pair.plus) {
        if (sign < 0) fixed_tips.push_back(pair.minus);
        continue;
      }
      phi_chart.map[pair.plus] = {pair.minus, sign, seams->phi_offset[pair.path]};
      psi_chart.map[pair.plus] = {pair.minus, sign, seams->psi_offset[pair.path]};
    }
  }
  const auto project = [&] {
    if (!seamed) return;
    ProjectTransitions(*seams, seams->phi_offset, &phi);
    ProjectTransitions(*seams, seams->psi_offset, &psi);
  };
  const auto hold_tips = [&](ceres::Problem* problem) {
    for (const int v : fixed_tips)
      for (double* x : {&phi[v], &psi[v]})
        if (problem->HasParameterBlock(x)) problem->SetParameterBlockConstant(x);
  };
  // Smoothness across the seams: f on the minus side, g on the plus side; with the plus face's
  // third vertex l read as s·(u_l − a) (its plus-chart value mapped back), the ordinary
  // smoothness term measures ∇u_f − s·∇u_g, the jump in one chart.
  const auto add_seam_smoothness = [&](ceres::Problem* problem, const Chart& u, const std::vector<double>& offsets,
                                       const std::vector<char>* live) {
    if (w.smoothness <= 0.0) return;
    for (const auto& t : seam_terms) {
      if (!Live(live, {t.i_minus, t.j_minus, t.k, t.l})) continue;
      const double sign = seams->sign[t.path];
      Scalar l = u.At(t.l);
      l = {l.vertex, sign * l.scale, sign * (l.offset - offsets[t.path])};
      AddMapped(problem, SmoothnessResidual::Create(t.Gf, t.Gg, t.area, t.distance, h), Weight(w.smoothness),
                {{&u, u.At(t.i_minus)}, {&u, u.At(t.j_minus)}, {&u, u.At(t.k)}, {&u, l}});
    }
  };
  // φ's terms: alignment + spacing + smoothness.
  auto add_phi_terms = [&](ceres::Problem* problem, const std::vector<char>* live = nullptr) {
    for (int f = 0; f < s.num_faces(); ++f) {
      const auto ids = s.face_vertices(f);
      if (!Live(live, {ids[0], ids[1], ids[2]})) continue;
      if (w.alignment > 0.0 && g.weight[f] > 0.0)
        AddMapped(problem, AlignmentResidual::Create(geo.G[f], g.direction[f], g.weight[f], s.face_area(f), h),
                  Weight(w.alignment),
                  {{&phi_chart, phi_chart.At(ids[0])}, {&phi_chart, phi_chart.At(ids[1])},
                   {&phi_chart, phi_chart.At(ids[2])}});
    }
    AddSpacing(s, geo, h, w.spacing, phi_chart, problem, live);
    AddSmoothness(edges, h, w.smoothness, phi_chart, problem, live);
    if (seamed) add_seam_smoothness(problem, phi_chart, seams->phi_offset, live);
  };
  std::vector<double> boost(s.num_faces(), 1.0);  // per-face transversality weight factor (RaiseCrossings)
  // ψ's terms: conjugacy + transversality (both also involve φ) + spacing + smoothness.
  double hinge_angle = min_angle;
  auto add_psi_terms = [&](ceres::Problem* problem, const std::vector<char>* live = nullptr) {
    for (int f = 0; f < s.num_faces(); ++f) {
      const auto ids = s.face_vertices(f);
      if (!Live(live, {ids[0], ids[1], ids[2]})) continue;
      const std::initializer_list<std::pair<const Chart*, Scalar>> blocks{
          {&phi_chart, phi_chart.At(ids[0])}, {&phi_chart, phi_chart.At(ids[1])}, {&phi_chart, phi_chart.At(ids[2])},
          {&psi_chart, psi_chart.At(ids[0])}, {&psi_chart, psi_chart.At(ids[1])}, {&psi_chart, psi_chart.At(ids[2])}};
      const Eigen::Vector3d& n = s.face_normal(f);
      if (w.conjugacy > 0.0)
        AddMapped(problem, ConjugacyResidual::Create(geo.G[f], n, geo.S[f], geo.flat_curvature, s.face_area(f)),
                  Weight(w.conjugacy), blocks);
      if (w.transversality > 0.0)
        AddMapped(problem, TransversalityResidual::Create(geo.G[f], n, hinge_angle, s.face_area(f), h),
                  Weight(w.transversality * boost[f]), blocks);
    }
    AddSpacing(s, geo, h, w.spacing, psi_chart, problem, live);
    AddSmoothness(edges, h, w.smoothness, psi_chart, problem, live);
    if (seamed) add_seam_smoothness(problem, psi_chart, seams->psi_offset, live);
  };

  project();
  solution->initial = Measure(s, geo, g, phi, psi, options.min_angle);
  // 1. φ alone.
  ceres::Problem phi_problem;
  add_phi_terms(&phi_problem);
  hold_tips(&phi_problem);
  if (phi_problem.NumResidualBlocks() > 0)
    PQ_RETURN_IF_ERROR(Solve("phi", options.max_iterations, &phi_problem, &solution->solver["phi"]));
  project();
  // 2. ψ with φ held.
  ceres::Problem psi_problem;
  add_psi_terms(&psi_problem);
  for (double& value : phi)
    if (psi_problem.HasParameterBlock(&value)) psi_problem.SetParameterBlockConstant(&value);
  hold_tips(&psi_problem);
  if (psi_problem.NumResidualBlocks() > 0)
    PQ_RETURN_IF_ERROR(Solve("psi", options.max_iterations, &psi_problem, &solution->solver["psi"]));
  project();
  // 3. Both together, so that φ can give way where ψ cannot cross it steeply enough.
  if (options.joint_iterations > 0) {
    ceres::Problem joint_problem;
    add_phi_terms(&joint_problem);
    add_psi_terms(&joint_problem);
    hold_tips(&joint_problem);
    PQ_RETURN_IF_ERROR(Solve("joint", options.joint_iterations, &joint_problem, &solution->solver["joint"]));
    project();
  }
  // 4. Local re-solves for the crossing angle (see RaiseCrossings). The best state (fewest
  // fold-overs, then fewest faces below min_angle; the joint solve's counts too) is kept: where
  // no crossing can be raised (closed level lines of φ around an index +1 singularity, which
  // every ψ line must touch somewhere) the boosted weights grow ×4 per round and tear the
  // solution apart (the wavy corpus roof: 23 → 66 fold-overs), while elsewhere a round that
  // adds a fold-over is often undone by later ones (two_holes: ending the rounds at the first
  // such round left 1 fold-over, running them all leaves 0).
  LevelSetMetrics best = Measure(s, geo, g, phi, psi, options.min_angle);
  std::vector<double> best_phi = phi, best_psi = psi;
  for (int round = 0; round < options.crossing_rounds; ++round) {
    std::vector<char> live_phi, live_psi;
    if (RaiseCrossings(s, geo, phi, psi, min_angle, &boost, &live_phi, &live_psi) == 0) break;
    for (int v = 0; v < s.num_vertices(); ++v) {  // a live plus copy frees its parameter
      if (live_phi[v]) live_phi[phi_chart.At(v).vertex] = 1;
      if (live_psi[v]) live_psi[psi_chart.At(v).vertex] = 1;
    }
    hinge_angle = min_angle + kCrossingMargin / kDegrees;
    ceres::Problem local;
    add_phi_terms(&local, &live_psi);
    add_psi_terms(&local, &live_psi);
    for (int v = 0; v < s.num_vertices(); ++v) {
      if (!live_phi[v] && local.HasParameterBlock(&phi[v])) local.SetParameterBlockConstant(&phi[v]);
      if (!live_psi[v] && local.HasParameterBlock(&psi[v])) local.SetParameterBlockConstant(&psi[v]);
    }
    hold_tips(&local);
    const std::string name = "crossing_round_" + std::to_string(round + 1);
    PQ_RETURN_IF_ERROR(Solve(name, kCrossingIterations, &local, &solution->solver[name]));
    project();
    const LevelSetMetrics now = Measure(s, geo, g, phi, psi, options.min_angle);
    if (std::make_pair(now.foldovers, now.faces_below_min_angle) <=
        std::make_pair(best.foldovers, best.faces_below_min_angle)) {
      best = now;
      best_phi = phi;
      best_psi = psi;
    }
  }
  phi = best_phi;  // a round may pass through worse states (more faces below) on its way
  psi = best_psi;
  solution->metrics = Measure(s, geo, g, phi, psi, options.min_angle);
  return Status::Ok();
}

// The guidance on the working mesh: each working face takes the direction (projected into
// its plane) and weight of the reference face closest to its centroid.
GuidanceField TransferGuidance(const SurfaceModel& reference, const GuidanceField& g, const SurfaceModel& working) {
  const ClosestPointQuery query(reference);
  GuidanceField out;
  out.scale = g.scale;
  for (int f = 0; f < working.num_faces(); ++f) {
    const auto ids = working.face_vertices(f);
    const Eigen::Vector3d centroid =
        (working.position(ids[0]) + working.position(ids[1]) + working.position(ids[2])) / 3.0;
    const int r = query.OnSurface(centroid).element;
    const Eigen::Vector3d& n = working.face_normal(f);
    Eigen::Vector3d d = g.direction[r] - g.direction[r].dot(n) * n;
    d = d.norm() > 0.0 ? Eigen::Vector3d(d.normalized()) : Eigen::Vector3d(n.unitOrthogonal());
    out.direction.push_back(d);
    out.major.push_back(g.major[r]);
    out.minor.push_back(g.minor[r]);
    out.magnitude.push_back(g.magnitude[r]);
    out.weight.push_back(g.weight[r]);
  }
  return out;
}

constexpr double kWorkingCornerAngle = 30.0;  // corners the working mesh keeps (extract.corner_angle's default)
constexpr double kReuseReference = 0.7;       // solve on the reference if its mean edge ≥ this × working edge
constexpr double kDefaultWorkingEdge = 0.4;   // × h: CGAL lands near 12k triangles on the Great Court at h = 3 m
constexpr int kRemeshIterations = 3;
constexpr double kCancelDistance = 2.0;  // × h: two ±½ singularities closer than this get no seam
constexpr double kMinSeamWeight = 1.0;   // × h: a seam whose path has less weighted length is not cut

// The tips of the seams: the guidance's singularities of index ±½, less pairs, closest
// first: two closer than kCancelDistance·h, or two of the same sign in one connected weak zone
// (faces with weight < 0.5). Around such a pair the field turns by a whole turn or none
// (opposite indices cancel: a wrinkle; equal ones make an index ±1, e.g. a crown that the
// nearly isotropic field there splits in two), so a single-valued φ crosses it; two seams
// would only add two branch points (on the L-shaped corpus roof the two halves of the strain
// crown, 2.3 h apart in its weak zone, made φ fan out of two branch points into 28 triangles).
std::vector<int> SeamTips(const SurfaceModel& s, const GuidanceField& g, double h, int* cancelled) {
  std::vector<LineFieldSingularity> half;
  for (const auto& x : FindLineFieldSingularities(s, g.direction))
    if (std::abs(std::abs(x.index) - 0.5) < 1e-9) half.push_back(x);
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
      if (d < kCancelDistance * h || (half[i].index == half[j].index && same_weak_zone(half[i].vertex, half[j].vertex)))
        candidates.emplace_back(d, i, j);
    }
  std::sort(candidates.begin(), candidates.end());
  std::vector<char> gone(half.size(), 0);
  *cancelled = 0;
  for (const auto& [d, i, j] : candidates) {
    if (gone[i] || gone[j]) continue;
    gone[i] = gone[j] = 1;
    ++*cancelled;
  }
  std::vector<int> tips;
  for (size_t i = 0; i < half.size(); ++i)
    if (!gone[i]) tips.push_back(half[i].vertex);
  return tips;
}

// SolveOnMesh on the surface cut open along seams (geometry/seams.h); φ, ψ per original
// vertex are the first copies' values, per cut vertex in phi_cut / psi_cut. A seam is cut
// only where a single-valued φ would have to misalign a weighted length of kMinSeamWeight·h
// or more (PathWeight of its route): on the Great Court the curvature field's four umbilics
// and the ring qualify (3.3–16 m at h = 3 m); the strain field's singularities sit in the
// weak bands along the edges, where a hidden cut costs at most 1.6 m, and get none.
Status SolveWithSeams(const SurfaceModel& s, const GuidanceField& g, const LevelsetOptions& options, double h,
                      LevelSetSolution* solution) {
  LevelSetSeams& seams = solution->seams;
  seams = LevelSetSeams();
  const std::vector<int> tips = SeamTips(s, g, h, &seams.cancelled_pairs);
  std::vector<std::vector<int>> paths;
  for (auto& path : RouteSeams(s, g.weight, tips)) {
    if (PathWeight(s, g.weight, path) >= kMinSeamWeight * h) paths.push_back(std::move(path));
    else ++seams.light_paths;
  }
  std::unique_ptr<SeamCut> cut;
  if (!paths.empty()) {
    // A seam from a singularity must flip the orientation (sign −1). If the guidance on the
    // cut surface says otherwise, the "singularity" was a wrinkle that a nearby uncancelled
    // one undoes (e.g. where two principal directions swap roles): no seam there.
    PQ_RETURN_IF_ERROR(SeamCut::Build(s, paths, &cut).WithContext("levelset seams"));
    seams.sign = SeamSigns(*cut, OrientedCrossField(cut->cut(), g));
    std::vector<std::vector<int>> kept;
    for (size_t p = 0; p < paths.size(); ++p) {
      if (s.is_boundary(paths[p].front()) || seams.sign[p] < 0) kept.push_back(paths[p]);
      else ++seams.orientable_tips;
    }
    if (kept.size() < paths.size()) {
      paths = std::move(kept);
      cut.reset();
      seams.sign.clear();
      if (!paths.empty()) {
        PQ_RETURN_IF_ERROR(SeamCut::Build(s, paths, &cut).WithContext("levelset seams"));
        seams.sign = SeamSigns(*cut, OrientedCrossField(cut->cut(), g));
      }
    }
  }
  if (paths.empty()) return SolveOnMesh(s, g, options, h, nullptr, solution);
  for (const auto& path : paths)
    if (!s.is_boundary(path.front())) seams.tips.push_back(path.front());
  seams.cut = std::move(cut);
  LOG(INFO) << "levelset: " << paths.size() << " seams: " << seams.tips.size() << " from guidance singularities, "
            << paths.size() - seams.tips.size() << " joining holes to the outer boundary (" << seams.cancelled_pairs
            << " close singularity pairs, " << seams.light_paths << " routes through weak guidance and "
            << seams.orientable_tips << " tips the guidance does not flip around left uncut)";
  PQ_RETURN_IF_ERROR(SolveOnMesh(seams.cut->cut(), g, options, h, &seams, solution));
  solution->phi_cut = std::move(solution->phi);
  solution->psi_cut = std::move(solution->psi);
  solution->phi = seams.cut->ToOriginal(solution->phi_cut);
  solution->psi = seams.cut->ToOriginal(solution->psi_cut);
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
          {"on_working_mesh", working != nullptr},
          {"paths", paths}};
}

Status SolveLevelSets(const SurfaceModel& s, const GuidanceField& g, const LevelsetOptions& options, double h,
                      LevelSetSolution* solution) {
  const double working_edge = options.working_edge > 0.0 ? options.working_edge : kDefaultWorkingEdge * h;
  const double reference_edge = MeanEdgeLength(s.mesh());
  if (reference_edge >= kReuseReference * working_edge) {
    solution->working_faces = s.num_faces();
    if (options.seams) return SolveWithSeams(s, g, options, h, solution);
    return SolveOnMesh(s, g, options, h, nullptr, solution);
  }
  // A reference much finer than the layout needs: solve on a remeshed copy whose edges are
  // working_edge long (the level lines are h apart; 0.4 h resolves them), then interpolate
  // φ and ψ to the reference's vertices. Stage time then follows h, not the reference size.
  TriMesh working_mesh;
  PQ_RETURN_IF_ERROR(RemeshIsotropic(s, working_edge, kWorkingCornerAngle, kRemeshIterations, &working_mesh)
                         .WithContext("levelset working mesh"));
  auto working = std::make_shared<const SurfaceModel>(std::move(working_mesh));
  LOG(INFO) << "levelset: reference mean edge " << reference_edge << " m < " << kReuseReference << " × working edge "
            << working_edge << " m: solving on a remeshed copy with " << working->num_faces() << " triangles";
  LevelSetSolution coarse;
  // With seams the solution stays on the working mesh's cut surface (extraction runs there);
  // the per-vertex φ, ψ interpolated below (first copies) are for the field files only.
  const GuidanceField working_guidance = TransferGuidance(s, g, *working);
  if (options.seams) PQ_RETURN_IF_ERROR(SolveWithSeams(*working, working_guidance, options, h, &coarse));
  else PQ_RETURN_IF_ERROR(SolveOnMesh(*working, working_guidance, options, h, nullptr, &coarse));
  const ClosestPointQuery query(*working);
  solution->phi.assign(s.num_vertices(), 0.0);
  solution->psi.assign(s.num_vertices(), 0.0);
  for (int v = 0; v < s.num_vertices(); ++v) {
    const SurfacePoint p = query.OnSurface(s.position(v));
    const Eigen::Vector3d w = TriangleBarycentric(*working, p.element, s.position(v));
    const auto ids = working->face_vertices(p.element);
    for (int k = 0; k < 3; ++k) {
      solution->phi[v] += w[k] * coarse.phi[ids[k]];
      solution->psi[v] += w[k] * coarse.psi[ids[k]];
    }
  }
  // The metrics are those of the solve, on the working mesh: on the reference, a small
  // triangle straddling a kink of the working mesh's piecewise linear φ gets a blend of the
  // two gradients, which says nothing about the layout but would dominate the minimum
  // crossing angle and inflate the spacing CV.
  solution->initial = coarse.initial;
  solution->metrics = coarse.metrics;
  solution->solver = coarse.solver;
  solution->working_faces = working->num_faces();
  if (coarse.seams.cut) {
    solution->seams = std::move(coarse.seams);
    solution->seams.working = working;
    solution->phi_cut = std::move(coarse.phi_cut);
    solution->psi_cut = std::move(coarse.psi_cut);
  }
  return Status::Ok();
}
}  // namespace pqlayout

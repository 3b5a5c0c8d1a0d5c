#include "problems/stiffen_problem.h"

#include <ceres/ceres.h>

#include <algorithm>
#include <cmath>

#include "base/interrupt.h"
#include "geometry/planarity.h"
#include "problems/residuals/anchor_residual.h"
#include "problems/residuals/planarity_budget_residual.h"
#include "solver/ceres_options.h"

namespace pqlayout {
namespace {

using Vec3 = Eigen::Vector3d;

constexpr double kMinMemberOfDepth = 1.1;  // members ≥ 1.1 × section depth
constexpr double kJointOfDepth = 0.9;      // joints ≤ 0.9 × section depth
constexpr int kMaxStiffenSides = 8;        // larger faces are held where planarize left them
constexpr double kSlideOfSpacing = 0.1;    // the tangential slide is at most this × h
constexpr double kRiseSafety = 1.5;        // the normal room leaves this × the reference's sampled rise
constexpr int kNarrowings = 5;             // a box past the boundary: slide, ½, ¼, ⅛ of it, then none

// How far the reference rises or falls off the tangent plane of frame f over the square
// [a ± s] × [b ± s] of a box: max |n · (surface point − f)| over the square's 3 × 3 grid (on a
// smooth surface the extreme lies at a corner; a triangle mesh is planar between its vertices).
double SurfaceRise(const ClosestPointQuery& query, const PointFrame& f, double a, double b, double s) {
  double rise = 0.0;
  for (int i = -1; i <= 1; ++i)
    for (int j = -1; j <= 1; ++j) {
      const Vec3 p = f.ToWorld(Vec3(a + i * s, b + j * s, 0.0));
      rise = std::max(rise, std::abs(f.rotation.col(2).dot(query.OnSurface(p).point - f.origin)));
    }
  return rise;
}

// Whether the box corners (a ± s, b ± s, ±room) of frame f all lie within t of the reference,
// measured exactly (room is 1e-9 t short of it: rounding in the corners is not a miss). Under
// the surface they do by the rise allowance; a box that reaches past the reference's boundary
// (a vertex closer to it than the slide) has corners beside the surface, not over it, whose
// distance the rise does not see.
bool CornersWithin(const ClosestPointQuery& query, const PointFrame& f, double a, double b, double s, double room, double t) {
  for (int corner = 0; corner < 8; ++corner) {
    const Vec3 local(a + (corner & 1 ? s : -s), b + (corner & 2 ? s : -s), corner & 4 ? room : -room);
    if (!(query.OnSurface(f.ToWorld(local)).distance <= t)) return false;
  }
  return true;
}

// Each vertex's frame (tangents and normal of the reference at the foot point of its
// planarised position) and box (problems/stiffen.h). Vertices that cannot move are held.
void SetUpVariables(const ClosestPointQuery& query, const ExtractedMesh& mesh, const GridFrame& frame,
                    const StiffenOptions& o, double spacing, StiffenProblem* P, std::vector<Vec3>* q) {
  const int n = static_cast<int>(mesh.mesh.n_vertices());
  // A joint (frame node of several vertices) with a vertex on the boundary is held whole.
  std::vector<bool> node_held(frame.model.nodes.size(), false);
  for (int v = 0; v < n; ++v)
    if (mesh.origin[v].on_boundary || mesh.origin[v].corner) node_held[frame.node_of[v]] = true;
  // So is every vertex of a face with more than kMaxStiffenSides sides (a pole's cap): its
  // C(k, 4) sub-quads would make a dense Gram matrix (a 35-gon: 52,360 rows on 105 columns).
  for (const auto f : mesh.mesh.faces())
    if (static_cast<int>(mesh.mesh.valence(f)) > kMaxStiffenSides)
      for (const auto v : mesh.mesh.fv_range(f)) node_held[frame.node_of[v.idx()]] = true;
  P->frames.resize(n), P->lower.resize(n), P->upper.resize(n), P->held.assign(n, false), q->resize(n);
  const double t = o.tolerance * (1.0 - 1e-9);
  const double slide = std::min(o.slide, kSlideOfSpacing * spacing);
  for (int v = 0; v < n; ++v) {
    const Vec3 p = ToEigen(mesh.mesh.point(VertexHandle(v)));
    const SurfacePoint foot = query.OnSurface(p);
    const Vec3 normal = foot.normal.normalized();
    const Vec3 e1 = normal.unitOrthogonal(), e2 = normal.cross(e1);
    PointFrame& f = P->frames[v];
    f.origin = foot.point;
    f.rotation.col(0) = e1, f.rotation.col(1) = e2, f.rotation.col(2) = normal;
    Vec3& local = (*q)[v] = f.ToLocal(p);
    // A point (a, b, c) of the box lies within |c| + rise of the reference (the surface under
    // it is within `rise` of the tangent plane), so ±(t − 1.5 rise) along the normal keeps it
    // within t however far it slides: the slide does not use up the tolerance. The corners
    // are then checked exactly (CornersWithin) and the slide narrowed where one is beyond t.
    double s = slide, normal_room = 0.0;
    bool within = false;
    for (int k = 0; k < kNarrowings && !within && !node_held[frame.node_of[v]]; ++k) {
      if (k > 0) s = k + 1 < kNarrowings ? 0.5 * s : 0.0;  // past the boundary: a narrower slide, at last none
      normal_room = t - kRiseSafety * SurfaceRise(query, f, local[0], local[1], s);
      within = normal_room > 0.0 && CornersWithin(query, f, local[0], local[1], s, normal_room, o.tolerance);
    }
    P->held[v] = !within;
    if (P->held[v]) {
      f.origin = p, f.rotation.setIdentity(), local.setZero();  // exactly where it is
      P->lower[v] = P->upper[v] = local;
      continue;
    }
    // A planarised vertex farther than t off the reference (planarize's closeness target is
    // 0.02 h, more than a tight tolerance) starts where it is, on the edge of its box: it may
    // come in, never go farther out. Pulling it in at the start bent the panels it belongs to
    // (δ 0.0016 on the Great Court at t = 5 mm), which no retraction inside the boxes undid.
    P->lower[v] = Vec3(local[0] - s, local[1] - s, std::min(-normal_room, local[2]));
    P->upper[v] = Vec3(local[0] + s, local[1] + s, std::max(normal_room, local[2]));
  }
}

Vec3 SecondDifference(const std::vector<Vec3>& x, const std::array<int, 3>& t) { return x[t[0]] - 2.0 * x[t[1]] + x[t[2]]; }

}  // namespace

void SetUpStiffenProblem(const ClosestPointQuery& query, const ExtractedMesh& mesh, const GridFrame& frame,
                         const SectionOptions& section, const StiffenOptions& o, double spacing, StiffenProblem* P,
                         std::vector<Vec3>* q) {
  P->h = spacing;
  P->weights = o.weights;
  SetUpVariables(query, mesh, frame, o, spacing, P, q);
  const PolyMesh& m = mesh.mesh;
  std::vector<Vec3> x0(m.n_vertices());
  for (const auto v : m.vertices()) x0[v.idx()] = ToEigen(m.point(v));
  for (const auto f : m.faces()) {
    std::vector<int> ids;
    for (const auto v : m.fv_range(f)) ids.push_back(v.idx());
    P->faces.push_back(ids);
    const int k = static_cast<int>(ids.size());
    if (k > kMaxStiffenSides) continue;  // held (SetUpVariables): no constraint can move
    for (int i = 0; i < k; ++i)
      for (int j = i + 1; j < k; ++j)
        for (int l = j + 1; l < k; ++l)
          for (int r = l + 1; r < k; ++r) P->sub_quads.push_back({ids[i], ids[j], ids[l], ids[r]});
  }
  for (const auto v : m.vertices()) {
    if (m.is_boundary(v) || m.valence(v) != 4) continue;
    std::vector<int> ring;
    for (const auto w : m.vv_range(v)) ring.push_back(w.idx());
    P->triples.push_back({ring[0], v.idx(), ring[2]});
    P->triples.push_back({ring[1], v.idx(), ring[3]});
  }
  for (const auto& t : P->triples) P->second_difference0.push_back(SecondDifference(x0, t));
  for (const auto e : m.edges()) {
    const auto he = m.halfedge_handle(e, 0);
    const int i = m.from_vertex_handle(he).idx(), j = m.to_vertex_handle(he).idx();
    if (frame.node_of[i] == frame.node_of[j])  // no longer than 0.9 × depth, or than it already is
      P->joint_edges.emplace_back(i, j, std::max(kJointOfDepth * SectionDepth(section), (x0[i] - x0[j]).norm()));
  }
  for (const auto& [i, j] : frame.member_vertices) {
    const double length = (x0[i] - x0[j]).norm();
    P->members.emplace_back(i, j, std::min(length, std::max(kMinMemberOfDepth * SectionDepth(section), o.min_member * length)));
  }
}

std::vector<Vec3> World(const StiffenProblem& P, const std::vector<Vec3>& q) {
  std::vector<Vec3> x(q.size());
  for (size_t v = 0; v < q.size(); ++v) x[v] = P.frames[v].ToWorld(q[v]);
  return x;
}

BoxVariables::BoxVariables(const StiffenProblem& P) : P_(P), step_scale_(StepScale(P.h)), index_(P.held.size(), -1) {
  for (size_t v = 0; v < P.held.size(); ++v)
    if (!P.held[v]) index_[v] = static_cast<int>(free_.size()), free_.push_back(static_cast<int>(v));
}

std::vector<Vec3> BoxVariables::Local(const double* z) const {
  std::vector<Vec3> q(P_.held.size(), Vec3::Zero());  // held vertices: q = 0 in the identity frame at p
  for (size_t k = 0; k < free_.size(); ++k)
    for (int c = 0; c < 3; ++c) {
      const int v = free_[k];
      q[v][c] = Centre(v, c) + Radius(v, c) * std::sin(Stretch(v, c) * z[3 * k + c]);
    }
  return q;
}

std::vector<double> BoxVariables::Parameters(const std::vector<Vec3>& q) const {
  std::vector<double> z(size(), 0.0);
  for (size_t k = 0; k < free_.size(); ++k)
    for (int c = 0; c < 3; ++c) {
      const int v = free_[k];
      const double radius = Radius(v, c);
      z[3 * k + c] =
          radius > 0.0 ? std::asin(std::clamp((q[v][c] - Centre(v, c)) / radius, -1.0, 1.0)) / Stretch(v, c) : 0.0;
    }
  return z;
}

Vec3 BoxVariables::Derivative(int k, int c, const double* z) const {
  const int v = free_[k];
  const double s = Stretch(v, c);
  return P_.frames[v].rotation.col(c) * (Radius(v, c) * s * std::cos(s * z[3 * k + c]));
}

void SetPoints(const std::vector<Vec3>& x, PolyMesh* mesh) {
  for (size_t v = 0; v < x.size(); ++v) mesh->set_point(VertexHandle(static_cast<int>(v)), {x[v].x(), x[v].y(), x[v].z()});
}

double MaxPlanarity(const StiffenProblem& P, const std::vector<Vec3>& x) {
  double delta = 0.0;
  std::vector<Vec3> polygon;
  for (const auto& face : P.faces) {
    polygon.clear();
    for (const int v : face) polygon.push_back(x[v]);
    delta = std::max(delta, PlanarityDelta(polygon));
  }
  return delta;
}

Status RestorePlanarity(const StiffenProblem& P, double target_delta, std::vector<Vec3>* q) {
  double weight = 1e6, budget = 0.4 * target_delta;  // per-vertex plane distance ε ≈ δ/2
  for (int round = 0; round < 8 && MaxPlanarity(P, World(P, *q)) > target_delta; ++round, weight *= 10.0, budget *= 0.7) {
    const std::vector<Vec3> xk = World(P, *q);
    ceres::Problem problem;
    for (size_t v = 0; v < q->size(); ++v) {
      double* block = (*q)[v].data();
      problem.AddParameterBlock(block, 3);
      if (P.held[v]) {
        problem.SetParameterBlockConstant(block);
        continue;
      }
      // A coordinate whose box has no width (stiffen.slide = 0: no tangential slide) is held
      // by a subset manifold: Ceres refuses a bound with lower = upper as infeasible.
      std::vector<int> fixed;
      for (int k = 0; k < 3; ++k) {
        if (P.lower[v][k] >= P.upper[v][k]) {
          fixed.push_back(k);
          continue;
        }
        problem.SetParameterLowerBound(block, k, P.lower[v][k]);
        problem.SetParameterUpperBound(block, k, P.upper[v][k]);
      }
      if (fixed.size() == 3) problem.SetParameterBlockConstant(block);
      else if (!fixed.empty()) problem.SetManifold(block, new ceres::SubsetManifold(3, fixed));
      problem.AddResidualBlock(new FramedPointCost(AnchorResidual::Create(xk[v], 1.0, P.h), {&P.frames[v]}), nullptr, block);
    }
    std::vector<std::array<double, 4>> planes(P.faces.size());
    for (size_t f = 0; f < P.faces.size(); ++f) {
      if (P.faces[f].size() < 4) continue;
      std::vector<Vec3> polygon;
      for (const int v : P.faces[f]) polygon.push_back(xk[v]);
      const FacePlane plane = FitPolygonPlane(polygon);
      planes[f] = {plane.n.x(), plane.n.y(), plane.n.z(), 0.0};  // n · (x − centroid) = 0
      problem.AddParameterBlock(planes[f].data(), 4,
                                new ceres::ProductManifold<ceres::SphereManifold<3>, ceres::EuclideanManifold<1>>());
      for (const int v : P.faces[f])
        problem.AddResidualBlock(
            new FramedPointCost(PlanarityBudgetResidual::Create(weight, plane.mean_diagonal, budget, plane.centroid), {nullptr, &P.frames[v]}),
            nullptr, planes[f].data(), (*q)[v].data());
    }
    ceres::Solver::Summary summary;
    ceres::Solve(SparseCholeskyOptions(50), &problem, &summary);
    if (!summary.IsSolutionUsable()) return Status::Internal("stiffen: Ceres failed restoring planarity: " + summary.message);
    PQ_RETURN_IF_ERROR(CheckInterrupt());
  }
  return Status::Ok();
}

}  // namespace pqlayout

#include "pipeline/layout_targets.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <iomanip>
#include <sstream>
#include <string>
#include <vector>

#include "geometry/boundary_refinement.h"
#include "geometry/differential_operators.h"
#include "geometry/line_field_singularities.h"
#include "geometry/planarity.h"
#include "problems/levelset_internal.h"

namespace pqlayout {
namespace {

constexpr double kDeg = 180.0 / M_PI;

std::string Fixed(double value, int digits) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(digits) << value;
  return s.str();
}
std::string At(const Eigen::Vector3d& p) { return "(" + Fixed(p.x(), 1) + ", " + Fixed(p.y(), 1) + ")"; }

// Per face of the surface the level sets live on: φ's level-line angle to the guidance (faces
// with weight > 0.5, else −1), the crossing angle (negative: a fold-over) and the spacings.
struct FaceMeasures {
  std::vector<Eigen::Vector3d> centroid;
  std::vector<double> misalignment, crossing, spacing_phi, spacing_psi, area;
};

FaceMeasures MeasureFaces(const PipelineState& state) {
  const LevelSetSolution& ls = state.levelsets;
  const SurfaceModel& reference = *state.surface;
  const bool cut = ls.seams.cut != nullptr;
  // With seams the values live on the cut surface, whose faces are those of the mesh the
  // level sets were solved on (the reference, or the working mesh).
  const SurfaceModel& s = cut ? ls.seams.cut->cut() : reference;
  const std::vector<double>& phi = cut ? ls.phi_cut : ls.phi;
  const std::vector<double>& psi = cut ? ls.psi_cut : ls.psi;
  // The guidance per face of s (moved to the working mesh's faces as the solve did).
  const GuidanceField guidance = cut && ls.seams.working
                                     ? levelset_internal::TransferGuidance(reference, state.guidance, s)
                                     : state.guidance;
  FaceMeasures m;
  for (int f = 0; f < s.num_faces(); ++f) {
    const auto ids = s.face_vertices(f);
    const Eigen::Vector3d c = (s.position(ids[0]) + s.position(ids[1]) + s.position(ids[2])) / 3.0;
    const Eigen::Vector3d a = FaceGradient(s, f, phi), b = FaceGradient(s, f, psi);
    const Eigen::Vector3d& n = s.face_normal(f);
    const double sine = n.dot(a.cross(b)) / std::max(a.norm() * b.norm(), 1e-300);
    m.centroid.push_back(c);
    m.area.push_back(s.face_area(f));
    m.crossing.push_back(std::asin(std::clamp(sine, -1.0, 1.0)) * kDeg);
    m.spacing_phi.push_back(1.0 / std::max(a.norm(), 1e-300));
    m.spacing_psi.push_back(1.0 / std::max(b.norm(), 1e-300));
    double miss = -1.0;
    if (guidance.weight[f] > 0.5) {
      const Eigen::Vector3d t = n.cross(a).normalized();
      miss = std::acos(std::min(1.0, std::abs(t.dot(guidance.direction[f])))) * kDeg;
    }
    m.misalignment.push_back(miss);
  }
  return m;
}

// What lies near a point: a guidance singularity within 2 h, a hole or the boundary within h,
// a boundary corner within 1.5 h.
class Surroundings {
 public:
  explicit Surroundings(const PipelineState& state)
      : state_(state), h_(state.config.layout.spacing), boundary_(*state.surface) {
    singularities_ = state.guidance.singularities;  // the guidance stage's
    for (size_t v = 0; v < state.quads.origin.size(); ++v)
      if (state.quads.origin[v].corner)
        corners_.push_back(ToEigen(state.quads.mesh.point(VertexHandle(static_cast<int>(v)))));
  }

  std::string Describe(const Eigen::Vector3d& p) const {
    std::string out = "at " + At(p);
    const LineFieldSingularity* near = nullptr;
    for (const auto& x : singularities_)
      if ((x.position - p).norm() < 2.0 * h_ && (!near || (x.position - p).norm() < (near->position - p).norm()))
        near = &x;
    if (near) out += ", " + Fixed((near->position - p).norm() / h_, 1) + " h from the guidance's index " +
                     Index(near->index) + " singularity at " + At(near->position);
    for (const auto& c : corners_)
      if ((c - p).norm() < 1.5 * h_) return out + ", at the boundary corner " + At(c);
    const ReferenceBoundary::Location where = boundary_.Locate(p);
    if (where.distance < h_) {
      const bool hole = !state_.surface->boundary_loops()[where.loop].is_outer;
      out += hole ? ", " + Fixed(where.distance / h_, 1) + " h from the edge of a hole" : ", at the boundary";
    }
    return out;
  }

  ReferenceBoundary::Location Locate(const Eigen::Vector3d& p) const { return boundary_.Locate(p); }
  const ReferenceBoundary& boundary() const { return boundary_; }

  // Whole turns of the guidance: clusters of singularities (each within 2 h of another) whose
  // indices add up to +1 or more (a crown, a bump top; the discrete field often splits one
  // into two +½, or dresses it with ±½ pairs).
  std::vector<LineFieldSingularity> WholeTurns() const {
    const size_t n = singularities_.size();
    std::vector<size_t> cluster(n);
    for (size_t i = 0; i < n; ++i) cluster[i] = i;
    for (size_t i = 0; i < n; ++i)
      for (size_t j = 0; j < i; ++j)
        if ((singularities_[i].position - singularities_[j].position).norm() < 2.0 * h_) {
          const size_t from = cluster[i], to = cluster[j];
          for (auto& c : cluster) c = c == from ? to : c;
        }
    std::vector<LineFieldSingularity> out;
    for (size_t c = 0; c < n; ++c) {
      LineFieldSingularity sum;
      int members = 0;
      for (size_t i = 0; i < n; ++i)
        if (cluster[i] == c) sum.index += singularities_[i].index, sum.position += singularities_[i].position, ++members;
      if (members > 0 && sum.index >= 1.0) out.push_back({-1, sum.index, sum.position / members});
    }
    return out;
  }
  static std::string Index(double index) { return (index > 0 ? "+" : "−") + Fixed(std::abs(index), index == std::round(index) ? 0 : 1); }

 private:
  const PipelineState& state_;
  double h_;
  ReferenceBoundary boundary_;
  std::vector<LineFieldSingularity> singularities_;
  std::vector<Eigen::Vector3d> corners_;
};

// Why a short edge at a polygonal boundary could not be avoided, if an end sits on a sharp kink
// of the reference boundary (SharpKinkTurn: the chord refinement puts a vertex there, or moves
// one onto it): both ends → the reference's own segment is that short; one end → the other
// could not move onto the kink (SlideToKink refused it). "" otherwise.
std::string KinkNote(const PipelineState& state, const ReferenceBoundary& boundary, const Eigen::Vector3d& a,
                     const Eigen::Vector3d& b) {
  const double h = state.config.layout.spacing;
  const double sharp = SharpKinkTurn(state.config.extract.boundary_tolerance * h, state.config.extract.min_edge * h);
  const double at_a = boundary.TurnAt(a, 1e-6 * h), at_b = boundary.TurnAt(b, 1e-6 * h);
  const auto degrees = [](double t) { return Fixed(t * 180.0 / M_PI, 0) + "°"; };
  if (at_a > sharp && at_b > sharp)
    return "both ends sit on kinks of the reference boundary (it turns by " + degrees(at_a) + " and " + degrees(at_b) +
           "), which panels must follow within extract.boundary_tolerance: the reference's own segment is this short";
  if (at_a > sharp || at_b > sharp)
    return "one end sits on a kink of the reference boundary (it turns by " + degrees(std::max(at_a, at_b)) +
           "), which panels must follow within extract.boundary_tolerance; the other end could not move onto the "
           "kink (a corner, a vertex already placed, or one whose panel would get an angle more than 3° below "
           "min(20°, its own) or a shorter edge)";
  return "";
}

// "; the guidance turns a whole turn around (x, y) (index +1): …" or "", or with poles
// (problems/levelset_poles.cc) what they cost.
std::string WholeTurnNote(const Surroundings& around, const PipelineState& state) {
  const auto& caps = state.levelsets.caps;
  if (!caps.empty()) {
    std::string where;
    for (size_t k = 0; k < caps.size() && k < 3; ++k) where += (k ? ", " : "") + At(caps[k].centre);
    return "; the layout has a pole at " + where +
           " (the guidance turns a whole turn there): one family rings its cap, the other fans out of it in rays, "
           "which are closer at the cap than further out";
  }
  const auto turns = around.WholeTurns();
  if (turns.empty()) return "";
  std::string where;
  for (size_t k = 0; k < turns.size() && k < 3; ++k)
    where += (k ? ", " : "") + At(turns[k].position) + " (index " + Surroundings::Index(turns[k].index) + ")";
  const nlohmann::json& tried = state.levelsets.rejected_poles;
  const std::string poles =
      tried.is_null() ? ""
      : tried.value("tried", true)
          ? "; poles there (levelset.poles) were tried and aligned only to " +
                Fixed(tried.at("alignment_with_poles").get<double>(), 1) + "°, not kept"
          : "; no pole was tried there: the layout aligns to " + Fixed(tried.at("alignment_without").get<double>(), 1) +
                "° without";
  return "; the guidance turns a whole turn around " + where +
         " (a crown or a bump top): level lines can only ring such a point or fan out of it, and a "
         "single-valued conjugate family cannot cross rings everywhere, so alignment and even spacing give way" +
         poles;
}

int Worst(const std::vector<double>& value, bool largest, const std::vector<double>* only_if_nonnegative = nullptr) {
  int best = -1;
  for (size_t f = 0; f < value.size(); ++f) {
    if (only_if_nonnegative && (*only_if_nonnegative)[f] < 0.0) continue;
    if (best < 0 || (largest ? value[f] > value[best] : value[f] < value[best])) best = static_cast<int>(f);
  }
  return best;
}

std::string LevelSetCause(const std::string& name, const PipelineState& state, const FaceMeasures& m,
                          const Surroundings& around) {
  const double h = state.config.layout.spacing;
  if (name == "alignment") {
    double strong = 0.0, off = 0.0;
    for (size_t f = 0; f < m.area.size(); ++f)
      if (m.misalignment[f] >= 0.0) strong += m.area[f], off += m.misalignment[f] > 16.0 ? m.area[f] : 0.0;
    if (strong <= 0.0) return "no face has weight > 0.5" + WholeTurnNote(around, state);
    const int w = Worst(m.misalignment, true);
    return Fixed(100.0 * off / strong, 0) + " % of the strongly guided area is more than 16° off, the worst (" +
           Fixed(m.misalignment[w], 0) + "°) " + around.Describe(m.centroid[w]) + WholeTurnNote(around, state);
  }
  if (name == "spacing_cv") {
    const bool phi = state.levelsets.metrics.spacing_cv_phi >= state.levelsets.metrics.spacing_cv_psi;
    const std::vector<double>& spacing = phi ? m.spacing_phi : m.spacing_psi;
    const int lo = Worst(spacing, false), hi = Worst(spacing, true);
    return std::string(phi ? "φ" : "ψ") + "'s lines are " + Fixed(spacing[lo] / h, 2) + " h apart " +
           around.Describe(m.centroid[lo]) + " and " + Fixed(std::min(spacing[hi] / h, 99.0), 2) + " h " +
           around.Describe(m.centroid[hi]) + WholeTurnNote(around, state);
  }
  // min_crossing, area_below_30, foldovers: the sharpest crossing.
  // Counts as the stage measured them (on the mesh it solved on); the place from the faces here.
  const int w = Worst(m.crossing, false);
  const LevelSetMetrics& lm = state.levelsets.metrics;
  return std::to_string(lm.faces_below_min_angle) + " faces cross below " + Fixed(state.config.levelset.min_angle, 0) +
         "° (" + std::to_string(lm.foldovers) + " folded over), the sharpest " + around.Describe(m.centroid[w]) +
         WholeTurnNote(around, state);
}

// The centre of the pole whose cap lies within 1.5 h of p's cap rim (`At`), or "".
std::string NearCap(const PipelineState& state, const Eigen::Vector3d& p) {
  for (const LevelSetCap& cap : state.levelsets.caps)
    if ((p - cap.centre).norm() < cap.radius + 1.5 * state.config.layout.spacing) return At(cap.centre);
  return "";
}

std::string ExtractCause(const std::string& name, const PipelineState& state, const Surroundings& around) {
  const PolyMesh& mesh = state.quads.mesh;
  const ExtractionStats& stats = state.quads.stats;
  const double h = state.config.layout.spacing;
  const auto on_boundary = [&](VertexHandle v) { return mesh.is_boundary(v); };  // as MeasureExtractedMesh
  const auto centroid = [&](FaceHandle f) {
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    int n = 0;
    for (const auto v : mesh.fv_range(f)) c += ToEigen(mesh.point(v)), ++n;
    return Eigen::Vector3d(c / n);
  };
  if (name == "quad_fraction" || name == "interior_non_quads") {
    int boundary_faces = 0, boundary_triangles = 0, boundary_other = 0, inner = 0;
    std::string first;
    for (const auto f : mesh.faces()) {
      const bool touches = std::any_of(mesh.fv_range(f).begin(), mesh.fv_range(f).end(), on_boundary);
      const int sides = static_cast<int>(mesh.valence(f));
      boundary_faces += touches;
      if (sides == 4) continue;
      if (!touches && ++inner <= 2)
        first += (first.empty() ? "" : "; ") + std::to_string(sides) + "-gon " + around.Describe(centroid(f)) +
                 (sides == 3 && !NearCap(state, centroid(f)).empty()
                      ? " (two rays of the fan round the pole at " + NearCap(state, centroid(f)) +
                            " end at one point: the fan loses a ray there)"
                  : sides == 3 ? " (a quad that lost a corner to a collapsed short edge)"
                  : sides == 5 ? " (a level line ends inside: a branch point)"
                               : " (a large cell that the split into quads refused: its quads would have angles outside 20°–160°)");
      if (touches) (sides == 3 ? boundary_triangles : boundary_other)++;
    }
    if (name == "interior_non_quads")
      return first + (stats.regions_with_holes > 0 ? "; " + std::to_string(stats.regions_with_holes) +
                                                         " cells were left out (not discs: the level sets fold over)"
                                                   : "");
    const std::string refined =
        stats.refined_boundary_edges > 0
            ? "; " + std::to_string(stats.refined_boundary_edges) + " vertices were added to keep chords within " +
                  Fixed(state.config.extract.boundary_tolerance, 2) +
                  " h of a curved boundary, each cutting off a triangle so that no panel has three vertices on it"
            : ", where level lines meet the boundary obliquely";
    return std::to_string(boundary_triangles + boundary_other) + " of the " + std::to_string(boundary_triangles + boundary_other + inner) +
           " non-quads touch the boundary (" + std::to_string(boundary_triangles) + " triangles" + refined + ")" +
           ", and " + std::to_string(boundary_faces) + " of " + std::to_string(mesh.n_faces()) +
           " panels touch the boundary: the boundary row weighs " + Fixed(100.0 * boundary_faces / std::max<size_t>(1, mesh.n_faces()), 0) +
           " % on a roof " + Fixed(std::sqrt(state.surface->total_area()) / h, 0) + " panels across";
  }
  if (name == "edge_min_h") {
    double shortest = 1e300;
    Eigen::Vector3d where = Eigen::Vector3d::Zero();
    int u = -1, v = -1;
    for (const auto e : mesh.edges()) {
      const auto he = mesh.halfedge_handle(e, 0);
      const auto a = mesh.from_vertex_handle(he), b = mesh.to_vertex_handle(he);
      const double length = (ToEigen(mesh.point(a)) - ToEigen(mesh.point(b))).norm();
      if (length < shortest) shortest = length, where = 0.5 * ToEigen(mesh.point(a) + mesh.point(b)), u = a.idx(), v = b.idx();
    }
    const char* blocker = u >= 0 ? ShortEdgeBlocker(state.quads, u, v) : nullptr;
    std::string why = blocker ? std::string("not collapsed because ") + blocker
                              : "made after the short-edge collapses, by the boundary clean-up or the chord refinement";
    const ReferenceBoundary::Location at = around.Locate(where);
    const std::string kinks = u >= 0 && !blocker ? KinkNote(state, around.boundary(), ToEigen(mesh.point(OpenMesh::VertexHandle(u))),
                                                            ToEigen(mesh.point(OpenMesh::VertexHandle(v))))
                                                 : "";
    if (!kinks.empty()) {
      why = kinks;
    } else if (!blocker && at.distance < 0.5 * h) {
      // A boundary loop of length ℓ curves with radius ~ℓ/2π if round; a chord of length L stands
      // L²/8R off it, so chords stay within the tolerance t only if L ≤ √(8 R t).
      const double radius = state.surface->boundary_loops()[at.loop].length / (2.0 * M_PI);
      const double chord = std::sqrt(8.0 * radius * state.config.extract.boundary_tolerance * h);
      if (chord < 1.5 * h)
        why += ": a loop " + Fixed(radius / h, 1) + " h in radius if round keeps chords within " +
               Fixed(state.config.extract.boundary_tolerance, 2) + " h only if they are shorter than " + Fixed(chord / h, 2) +
               " h, so vertices are inserted between the level lines' ends, some close to one";
    }
    return "the shortest edge (" + Fixed(shortest / h, 2) + " h) is " + around.Describe(where) + ": " + why;
  }
  // boundary_deviation_h
  return stats.regions_with_holes > 0 ? std::to_string(stats.regions_with_holes) + " cells left out (not discs: the level sets fold over) open a gap at the boundary"
                                      : "a boundary chord could not be split without a panel edge shorter than extract.min_edge";
}

std::string PlanarizeCause(const std::string& name, const nlohmann::json& stage) {
  if (name == "planarity_max")
    return "planarisation stopped at δ max " + Fixed(stage.value("planarity_max", 0.0) * 1e3, 2) +
           "e-3 after " + std::to_string(stage.value("rounds", 0)) + " rounds (see stages.planarize)";
  return "vertices had to move " + Fixed(stage.value("closeness_max", 0.0), 3) +
         " m off the reference to make the panels planar (" + Fixed(stage.value("max_displacement", 0.0), 3) +
         " m in all): the extracted panels were far from planar";
}

struct TargetDef {
  const char* name;
  const char* stage;
  const char* what;
  const char* target;
  std::function<bool(double)> ok;
};

const std::vector<TargetDef>& Definitions() {
  static const std::vector<TargetDef> defs = {
      {"alignment", "levelset", "alignment RMS where weight > 0.5, °", "≤ 8°", [](double v) { return v <= 8.0; }},
      {"foldovers", "levelset", "fold-overs", "0", [](double v) { return v == 0.0; }},
      {"min_crossing", "levelset", "min crossing angle, °", "≥ 25°", [](double v) { return v >= 25.0; }},
      {"area_below_30", "levelset", "area fraction crossing below levelset.min_angle", "≤ 1 %", [](double v) { return v <= 0.01; }},
      {"spacing_cv", "levelset", "spacing CV, max of φ and ψ", "≤ 0.25", [](double v) { return v <= 0.25; }},
      {"quad_fraction", "extract", "quads / faces", "≥ 0.80", [](double v) { return v >= 0.80; }},
      {"interior_non_quads", "extract", "non-quads touching no boundary", "0", [](double v) { return v == 0.0; }},
      {"boundary_deviation_h", "extract", "boundary deviation / h", "≤ 0.01 h", [](double v) { return v <= 0.01; }},
      {"edge_min_h", "extract", "shortest edge / h", "≥ 0.2 h", [](double v) { return v >= 0.2 - 1e-9; }},
      {"planarity_max", "planarize", "δ max", "≤ 1e-3", [](double v) { return v <= 1e-3; }},
      {"closeness_h", "planarize", "closeness max / h", "≤ 0.02 h", [](double v) { return v <= 0.02; }},
  };
  return defs;
}

// The metric's value from the stage metrics (null: does not apply).
nlohmann::json ValueOf(const std::string& name, const nlohmann::json& stages, double h) {
  const nlohmann::json& lv = stages.value("levelset", nlohmann::json::object());
  const nlohmann::json& ex = stages.value("extract", nlohmann::json::object());
  const nlohmann::json& pl = stages.value("planarize", nlohmann::json::object());
  if (name == "alignment")
    return stages.at("guidance").value("area_weight_above_half", 0.0) > 0.0 ? lv.at("alignment_rms_deg_weight_above_half")
                                                                            : nlohmann::json();
  if (name == "foldovers") return lv.at("foldovers");
  if (name == "min_crossing") return lv.at("min_crossing_angle_deg");
  if (name == "area_below_30") return lv.at("area_fraction_below_min_angle");
  if (name == "spacing_cv") return std::max(lv.at("spacing_cv_phi").get<double>(), lv.at("spacing_cv_psi").get<double>());
  if (name == "quad_fraction") return ex.at("quad_fraction");
  if (name == "interior_non_quads") return ex.at("interior_non_quads").size();
  if (name == "boundary_deviation_h") return ex.at("boundary_deviation").get<double>() / h;
  if (name == "edge_min_h") return ex.at("edge_length_min");  // extract reports edge lengths relative to h
  if (name == "planarity_max") return pl.at("planarity_max");
  return pl.at("closeness_max").get<double>() / h;
}

}  // namespace

nlohmann::json EvaluateLayoutTargets(const PipelineState& state, const nlohmann::json& stages) {
  nlohmann::json list = nlohmann::json::array(), missed = nlohmann::json::array();
  if (!stages.contains("levelset")) return {{"met", 0}, {"missed", missed}, {"list", list}};
  const double h = state.config.layout.spacing;
  const FaceMeasures faces = MeasureFaces(state);
  const Surroundings around(state);
  int met = 0;
  for (const TargetDef& def : Definitions()) {
    if (!stages.contains(def.stage)) continue;
    const nlohmann::json value = ValueOf(def.name, stages, h);
    const bool ok = value.is_null() || def.ok(value.get<double>());
    nlohmann::json entry = {{"name", def.name}, {"stage", def.stage}, {"what", def.what},
                            {"target", def.target}, {"value", value}, {"met", ok}};
    if (!ok) {
      const std::string stage = def.stage;
      entry["cause"] = stage == "levelset" ? LevelSetCause(def.name, state, faces, around)
                       : stage == "extract" ? ExtractCause(def.name, state, around)
                                            : PlanarizeCause(def.name, stages.at(stage));
      missed.push_back(def.name);
    }
    met += ok;
    list.push_back(std::move(entry));
  }
  return {{"met", met}, {"missed", missed}, {"list", list}};
}

std::string LayoutTargetsSummary(const nlohmann::json& targets) {
  std::string out = std::to_string(targets.at("met").get<int>()) + " of " + std::to_string(targets.at("list").size()) + " met";
  for (const auto& t : targets.at("list")) {
    if (t.at("met").get<bool>()) continue;
    std::ostringstream value;
    value << t.at("value").get<double>();
    out += "; missed " + t.at("name").get<std::string>() + " " + value.str() + " (" + t.at("target").get<std::string>() +
           "): " + t.at("cause").get<std::string>();
  }
  return out;
}

}  // namespace pqlayout

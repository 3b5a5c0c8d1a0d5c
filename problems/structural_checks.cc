#include "problems/structural_checks.h"

#include <glog/logging.h>

#include <algorithm>
#include <chrono>
#include <numeric>

#include "solver/member_checks.h"

namespace pqlayout {
namespace {

constexpr int kListedMembers = 20;  // report.json lists at most this many members over η = 1

SectionModuli ModuliOf(const SectionOptions& s) {
  return s.shape == "rectangular_hollow" ? SectionModuli::RectangularHollow(s.width, s.height, s.thickness)
                                         : SectionModuli::CircularHollow(s.diameter, s.thickness);
}

}  // namespace

Status RunStructuralChecks(const GridFrame& frame, const FrameResult& r, const AnalysisOptions& a, StructuralChecks* c,
                           bool log, BucklingMemo* memo) {
  const FrameModel& model = frame.model;
  c->utilisation = MemberUtilisation(model, r, ModuliOf(a.section), a.material.yield_strength);
  Eigen::AlignedBox2d plan;
  for (size_t i = 0; i < model.nodes.size(); ++i) {
    plan.extend(model.nodes[i].head<2>());
    c->deflection_max = std::max(c->deflection_max, std::abs(r.displacement[i][2]));
  }
  c->span = plan.sizes().maxCoeff();
  if (a.buckling_modes > 0) {
    const auto start = std::chrono::steady_clock::now();
    if (memo != nullptr)
      PQ_RETURN_IF_ERROR(memo->Solve(model, r, a.buckling_modes, &c->buckling, &c->buckling_reused));
    else
      PQ_RETURN_IF_ERROR(SolveBuckling(model, r, a.buckling_modes, &c->buckling));
    c->buckling_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    c->buckling_run = true;
    if (log && c->buckling.buckles)
      LOG(INFO) << "analyze: buckling factor " << c->buckling.factors.front() << " (" << c->buckling.factors.size()
                << " found, " << c->buckling.operations << " solves, "
                << (c->buckling_reused ? "stiffen's, the same frame" : std::to_string(c->buckling_seconds) + " s") << ")";
    if (log && !c->buckling.buckles) LOG(INFO) << "analyze: no buckling under this load (no member is compressed enough)";
  }
  const double eta_max = c->utilisation.empty() ? 0.0 : *std::max_element(c->utilisation.begin(), c->utilisation.end());
  if (!log) return Status::Ok();
  LOG(INFO) << "analyze: utilisation η max " << eta_max << " (f_y " << a.material.yield_strength / 1e6
            << " MPa); deflection max " << c->deflection_max * 1000.0 << " mm, span / deflection "
            << (c->deflection_max > 0.0 ? c->span / c->deflection_max : 0.0);
  if (eta_max > 1.0) LOG(WARNING) << "analyze: members over utilisation 1 (η max " << eta_max << "): see figures/utilisation.svg";
  // λ₁ < 1: the linear estimate, an upper bound, already says the frame buckles before it
  // carries its load; as loud as a member over η = 1 (a demanding engineer's first question).
  if (c->buckling_run && c->buckling.buckles && c->buckling.factors.front() < 1.0)
    LOG(WARNING) << "analyze: the frame buckles at " << c->buckling.factors.front()
                 << " × its load (linear buckling factor below 1, an upper bound): not stable under this load with "
                    "this section; see figures/buckling.svg (a deeper section: analysis.section; shorter members: layout.spacing)";
  return Status::Ok();
}

nlohmann::json StructuralChecks::ToJson(const GridFrame& frame) const {
  nlohmann::json j;
  if (buckling_run) {
    j["buckling_factor"] = buckling.buckles ? nlohmann::json(buckling.factors.front()) : nlohmann::json(nullptr);
    j["buckling_factors"] = buckling.factors;
    j["buckling"] = buckling.buckles ? "linear buckling factor of the analysed load" : "no buckling under this load";
    j["buckling_seconds"] = buckling_seconds;
    j["buckling_reused"] = buckling_reused;
    j["buckling_solves"] = buckling.operations;
  }
  const size_t m = utilisation.size();
  std::vector<size_t> order(m);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return utilisation[a] > utilisation[b]; });
  nlohmann::json over = nlohmann::json::array();
  int count = 0;
  for (const size_t e : order) {
    if (utilisation[e] <= 1.0) break;
    if (++count <= kListedMembers)
      over.push_back({{"vertices", {frame.member_vertices[e].first, frame.member_vertices[e].second}}, {"utilisation", utilisation[e]}});
  }
  j["utilisation_max"] = m > 0 ? utilisation[order.front()] : 0.0;
  j["utilisation_mean"] = m > 0 ? std::accumulate(utilisation.begin(), utilisation.end(), 0.0) / m : 0.0;
  j["members_over_utilisation"] = count;
  j["overutilised_members"] = over;  // the worst kListedMembers, mesh vertex ids
  j["deflection_max"] = deflection_max;
  j["span"] = span;
  j["span_over_deflection"] = deflection_max > 0.0 ? nlohmann::json(span / deflection_max) : nlohmann::json(nullptr);
  return j;
}

}  // namespace pqlayout

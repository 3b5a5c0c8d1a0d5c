// Stage `guidance`: the guidance field (problems/guidance.h) of the configured source, its
// metrics (singularities, sources), fields/vertices.csv, fields/faces.csv, fields.vtk and
// figures/guidance.svg.
#include <glog/logging.h>

#include <algorithm>
#include <map>
#include <memory>
#include <sstream>

#include "geometry/field_writers.h"
#include "geometry/line_field_singularities.h"
#include "geometry/scalar_field_extrema.h"
#include "pipeline/stages.h"
#include "problems/guidance.h"
#include "report/figures.h"

namespace pqlayout {

namespace {

// fields/vertices.csv and fields/faces.csv, written in the background (base/background_writer.h)
// from copies of their columns.
void WriteGuidanceOutputs(const SurfaceModel& surface, const Eigen::Vector3d& origin, const std::vector<double>& v_z,
                          const GuidanceField& g, OutputFiles* out) {
  const int nv = surface.num_vertices(), nf = surface.num_faces();
  auto vertex_columns = std::make_shared<std::vector<std::vector<double>>>(6, std::vector<double>(nv, 0.0));
  std::vector<std::vector<double>>& vc = *vertex_columns;  // x, y, z, vx, vy, vz
  for (int v = 0; v < nv; ++v) {
    const Eigen::Vector3d p = surface.position(v) + origin;  // the file's coordinates
    vc[0][v] = p.x(), vc[1][v] = p.y(), vc[2][v] = p.z();
  }
  vc[5] = v_z;
  auto face_columns = std::make_shared<std::vector<std::vector<double>>>(3, std::vector<double>(nf));
  std::vector<std::vector<double>>& fc = *face_columns;  // dx, dy, dz, strain_max, strain_min, weight
  for (int f = 0; f < nf; ++f) fc[0][f] = g.direction[f].x(), fc[1][f] = g.direction[f].y(), fc[2][f] = g.direction[f].z();
  fc.insert(fc.end(), {g.major, g.minor, g.weight});
  const auto pointers = [](const std::vector<std::vector<double>>& columns) {
    std::vector<const std::vector<double>*> p;
    for (const auto& c : columns) p.push_back(&c);
    return p;
  };
  out->WriteInBackground([vertex_columns, face_columns, pointers, vertices = out->Path("fields/vertices.csv"),
                          faces = out->Path("fields/faces.csv")] {
    PQ_RETURN_IF_ERROR(WriteCsvTable({"id", "x", "y", "z", "vx", "vy", "vz"}, pointers(*vertex_columns), vertices));
    return WriteCsvTable({"id", "dx", "dy", "dz", "strain_max", "strain_min", "weight"}, pointers(*face_columns), faces);
  });
}

nlohmann::json SingularityMetrics(const GuidanceField& g) {
  const auto& singularities = g.singularities;
  nlohmann::json list = nlohmann::json::array();
  std::map<std::string, int> by_index;
  for (const auto& s : singularities) {
    std::ostringstream index;
    index << std::showpos << s.index;
    ++by_index[index.str()];
    list.push_back({{"vertex", s.vertex}, {"index", s.index}, {"x", s.position.x()}, {"y", s.position.y()}});
  }
  return {{"count", singularities.size()}, {"by_index", by_index}, {"list", list}};
}

// The sources of the guidance field (paper Fig. 6): the points where its integral curves
// converge, i.e. where the field's magnitude (|ε_max|) vanishes. Counted robustly as the
// interior minima of the magnitude (averaged to the vertices) whose persistence exceeds
// 2 % of the largest magnitude.
nlohmann::json SourceMetrics(const SurfaceModel& surface, const GuidanceField& g) {
  std::vector<double> at_vertex(surface.num_vertices(), 0.0), area(surface.num_vertices(), 0.0);
  for (int f = 0; f < surface.num_faces(); ++f) {
    for (const int v : surface.face_vertices(f)) {
      at_vertex[v] += surface.face_area(f) * g.magnitude[f];
      area[v] += surface.face_area(f);
    }
  }
  for (int v = 0; v < surface.num_vertices(); ++v) at_vertex[v] /= area[v];
  nlohmann::json list = nlohmann::json::array();
  for (const auto& m : PersistentMinima(surface, at_vertex, 0.02 * g.scale)) {
    const Eigen::Vector3d p = surface.position(m.vertex);
    list.push_back({{"vertex", m.vertex}, {"x", p.x()}, {"y", p.y()}, {"magnitude", m.value}});
  }
  return list;
}

}  // namespace

Status RunGuidanceStage(PipelineState* state, OutputFiles* out, nlohmann::json* metrics) {
  SurfaceModel& surface = *state->surface;
  const GuidanceOptions& options = state->config.guidance;
  const std::vector<double> v_z = surface.VertexFieldValues("v_z");
  GuidanceField& g = state->guidance;
  if (options.source == "strain") PQ_RETURN_IF_ERROR(ComputeStrainGuidance(surface, v_z, options, &g));
  else if (options.source == "curvature") PQ_RETURN_IF_ERROR(ComputeCurvatureGuidance(surface, options, &g));
  else PQ_RETURN_IF_ERROR(ReadGuidanceFile(surface, options, &g));
  if (options.source == "curvature") {
    const double h = state->config.layout.spacing;
    const int swapped = CombCurvatureNet(surface, h * h, &g);
    LOG(INFO) << "guidance: curvature net combed, " << swapped << " faces follow the other family";
  }
  const bool fallback = options.fallback == "curvature" && options.source != "curvature";
  double fallback_area = 0.0;
  if (fallback) {
    GuidanceField curvature;
    PQ_RETURN_IF_ERROR(ComputeCurvatureGuidance(surface, options, &curvature));
    fallback_area = AddCurvatureFallback(surface, curvature, options.fallback_weight, &g);
  }

  g.singularities = FindLineFieldSingularities(surface, g.direction);  // the field is final now

  double weight_sum = 0.0, area_above_half = 0.0;
  int faces_above_half = 0;
  for (int f = 0; f < surface.num_faces(); ++f) {
    weight_sum += g.weight[f];
    if (g.weight[f] > 0.5) {
      ++faces_above_half;
      area_above_half += surface.face_area(f);
    }
  }
  *metrics = {{"source", options.source},
              {"scale", g.scale},
              {"max_principal", g.major.empty() ? 0.0 : *std::max_element(g.magnitude.begin(), g.magnitude.end())},
              {"weight_mean", weight_sum / surface.num_faces()},
              {"faces_weight_above_half", static_cast<double>(faces_above_half) / surface.num_faces()},
              {"area_weight_above_half", area_above_half / surface.total_area()},
              {"singularities", SingularityMetrics(g)},
              {"fallback", fallback ? options.fallback : "none"},
              {"area_fallback", fallback_area}};
  (*metrics)["sources"] = SourceMetrics(surface, g);
  (*metrics)["n_sources"] = (*metrics)["sources"].size();
  LOG(INFO) << "guidance: " << options.source
            << (fallback ? ", curvature lines where it is weak (" + std::to_string(std::lround(100.0 * fallback_area)) +
                               " % of the area)"
                         : std::string())
            << ", " << 100.0 * faces_above_half / surface.num_faces()
            << " % of faces with weight > 0.5, " << (*metrics)["singularities"]["count"] << " singularities "
            << (*metrics)["singularities"]["by_index"].dump()
            << ", " << (*metrics)["n_sources"] << " sources (minima of the field's magnitude)";
  if (state->config.output.fields) WriteGuidanceOutputs(surface, state->origin, v_z, g, out);
  const bool strain = options.source == "strain";
  // (The fallback's title drops "(integral curves)": the long one ran off the figure.)
  const std::string title = fallback ? "Guidance: " + options.source + "; curvature lines where weak"
                            : strain ? "Guidance: principal strain directions (integral curves)"
                                     : "Guidance: " + options.source + " directions (integral curves)";
  const std::string label = strain ? "|ε_max|" : options.source == "curvature" ? "|κ1 − κ2| [1/m]" : "|d|";
  // On the background writer (~0.4 s at a million triangles), from copies of the field; the
  // reference is shared, read-only from here on (SurfaceModel::FreezeFields).
  out->WriteInBackground([reference = std::shared_ptr<const SurfaceModel>(state->surface), direction = g.direction,
                          magnitude = g.magnitude, weight = g.weight, singularities = g.singularities, label, title,
                          path = out->Path("figures/guidance.svg")] {
    FigureOptions figure;
    figure.guidance_singularities = &singularities;
    return WriteGuidanceFigure(*reference, direction, magnitude, label, weight, title, path, figure);
  });
  return Status::Ok();
}

}  // namespace pqlayout

#include "problems/report_html.h"

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace pqlayout {
namespace {

std::string Escape(const std::string& text) {
  std::string out;
  for (const char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string Format(const nlohmann::json& value) {
  if (value.is_number_float()) {
    std::ostringstream s;
    s.precision(4);
    s << value.get<double>();
    return s.str();
  }
  if (value.is_string()) return value.get<std::string>();
  return value.dump();
}

// The figures a run can produce, in the order of the paper, with their captions.
struct FigureEntry {
  const char* file;
  const char* caption;
};
const FigureEntry kFigures[] = {
    {"displacement.svg", "Membrane displacement v_z under dead load (paper Fig. 3)."},
    {"guidance.svg", "Guidance field: integral curves over its magnitude; hatched where alignment is not enforced (paper Fig. 6)."},
    {"levelsets.svg", "Level lines φ = i·h (black, aligned with the guidance) and ψ = j·h (blue, conjugate) (paper Fig. 7, 12)."},
    {"planarity_initial.svg", "Planarity δ per face before planarisation (paper Fig. 8a)."},
    {"planarity.svg", "Planarity δ per face after planarisation (paper Fig. 8b)."},
    {"compliance.svg", "Nodal compliance of the grid shell (paper Fig. 9, 14)."},
};

std::string MetricsTable(const nlohmann::json& metrics) {
  std::ostringstream s;
  s << "<table><tr><th>metric</th><th>value</th></tr>\n";
  for (const auto& [key, value] : metrics.items()) {
    if (value.is_object() || value.is_array()) continue;  // lists stay in report.json
    s << "<tr><td>" << Escape(key) << "</td><td>" << Escape(Format(value)) << "</td></tr>\n";
  }
  s << "</table>\n";
  return s.str();
}

std::string Summary(const nlohmann::json& report) {
  const auto& config = report["config"];
  const auto& stages = report["stages"];
  std::ostringstream s;
  s << "<table>\n";
  auto row = [&s](const std::string& k, const std::string& v) {
    s << "<tr><td>" << Escape(k) << "</td><td>" << Escape(v) << "</td></tr>\n";
  };
  if (stages.contains("surface")) {
    const auto& sf = stages["surface"];
    row("surface", Format(sf["source"]) + ": " + Format(sf["n_faces"]) + " triangles, " + Format(sf["n_vertices"]) +
                       " vertices, area " + Format(sf["area"]) + " m²");
    row("supports", "default " + Format(config["boundary"]["default"]) + "; per condition " + sf["supports"].dump());
  }
  row("dead load q", Format(config["load"]["q"]) + " N/m²");
  row("guidance", Format(config["guidance"]["source"]) + ", threshold " + Format(config["guidance"]["threshold"]));
  row("spacing h", Format(config["layout"]["spacing"]) + " m");
  row("pqlayout", Format(report["pqlayout"]["version"]) + " (git " + Format(report["pqlayout"]["git_revision"]) + ")");
  row("run", Format(report["run"]["started_at"]) + ", " + Format(report["run"]["total_seconds"]) + " s");
  s << "</table>\n";
  return s.str();
}

// Stage names in pipeline order (report.json's objects are sorted by key).
std::vector<std::string> StagesInOrder(const nlohmann::json& report) {
  std::vector<std::string> names;
  for (const auto& name : report["run"].value("completed_stages", nlohmann::json::array())) names.push_back(name);
  return names;
}

std::string Timings(const nlohmann::json& report) {
  std::ostringstream s;
  s << "<table><tr><th>stage</th><th>seconds</th></tr>\n";
  for (const auto& name : StagesInOrder(report))
    s << "<tr><td>" << Escape(name) << "</td><td>" << Format(report["stages"][name]["seconds"]) << "</td></tr>\n";
  s << "</table>\n";
  return s.str();
}

}  // namespace

Status WriteReportHtml(const nlohmann::json& report, OutputFiles* out) {
  std::ostringstream page;
  page << "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n"
       << "<title>pqlayout report</title>\n<style>\n"
       << "body{font-family:sans-serif;max-width:1100px;margin:2em auto;color:#222}\n"
       << "table{border-collapse:collapse;margin:0.5em 0 1.5em}td,th{border:1px solid #ccc;padding:3px 8px;"
          "text-align:left}th{background:#f0f0f0}\n"
       << "figure{margin:1.5em 0}figure svg{width:100%;height:auto;border:1px solid #ddd}"
          "figcaption{color:#555;margin-top:0.3em}\n</style></head><body>\n"
       << "<h1>pqlayout: statics-sensitive layout</h1>\n<h2>Summary</h2>\n"
       << Summary(report) << "<h2>Timings</h2>\n" << Timings(report);
  for (const auto& name : StagesInOrder(report))
    page << "<h2>Stage " << Escape(name) << "</h2>\n" << MetricsTable(report["stages"][name]);
  page << "<h2>Figures</h2>\n";
  for (const auto& figure : kFigures) {
    std::ifstream in(out->Path(std::string("figures/") + figure.file));
    if (!in) continue;
    std::stringstream svg;
    svg << in.rdbuf();
    std::string text = svg.str();
    const size_t start = text.find("<svg");  // drop any XML prolog
    if (start == std::string::npos) continue;
    page << "<figure>\n" << text.substr(start) << "\n<figcaption>" << Escape(figure.caption)
         << "</figcaption></figure>\n";
  }
  page << "<p>Full data: report.json, fields.vtk (ParaView), fields/*.csv.</p>\n</body></html>\n";
  return out->WriteText("report.html", page.str());
}

}  // namespace pqlayout

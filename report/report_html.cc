#include "report/report_html.h"

#include <algorithm>
#include <filesystem>
#include <initializer_list>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "base/atomic_file.h"
#include "report/report_view3d.h"

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
  if (value.is_null()) return "–";
  return value.dump();
}

// The value at json[key0][key1]..., null if any is absent (a const json's operator[] must
// not be used on a missing key).
const nlohmann::json& At(const nlohmann::json& json, std::initializer_list<std::string> path) {
  static const nlohmann::json kNull;
  const nlohmann::json* at = &json;
  for (const auto& key : path) {
    if (!at->is_object() || !at->contains(key)) return kNull;
    at = &(*at)[key];
  }
  return *at;
}

// report["stages"][stage][key] formatted, "–" if absent.
std::string Metric(const nlohmann::json& report, const std::string& stage, const std::string& key) {
  return Format(At(report, {"stages", stage, key}));
}

// The figures a run can produce, in the order of the paper, with the stage that writes each.
struct FigureEntry {
  const char* file;
  const char* stage;
  const char* caption;
  bool optional = false;  // not every run writes it (buckling.svg: only when the frame buckles)
};
const FigureEntry kFigures[] = {
    {"displacement.svg", "membrane", "Membrane displacement v_z under dead load (paper Fig. 3)."},
    {"guidance.svg", "guidance",
     "Guidance field: integral curves over its magnitude; hatched where alignment is not enforced "
     "(paper Fig. 6)."},
    {"levelsets.svg", "levelset",
     "Level lines φ = i·h (black, aligned with the guidance) and ψ = j·h (blue, conjugate) "
     "(paper Fig. 7, 12); orange where they cross below levelset.min_angle (sheared quads), "
     "purple where they fold over."},
    {"shell_3d.svg", "planarize",
     "The planarised grid shell in an oblique view (orthographic, from the south-west), faces "
     "coloured by planarity δ, lightly shaded; the reference footprint in grey on the ground."},
    {"planarity_initial.svg", "extract",
     "Planarity δ per face of the extracted mesh, before planarisation (paper Fig. 8a). Same "
     "logarithmic scale as after: white at the target, blue meets it, red does not."},
    {"planarity.svg", "planarize", "Planarity δ per face after planarisation (paper Fig. 8b)."},
    {"offset.svg", "stiffen",
     "How stiffen reshaped the planar grid: normal offset of each face's vertices from the "
     "planarised mesh, blue down, red up, the colour scale spanning ± stiffen.tolerance."},
    {"compliance.svg", "analyze", "Nodal compliance of the grid shell as a steel frame (paper Fig. 9, 14)."},
    {"utilisation.svg", "analyze",
     "Member utilisation η = |N|/(A f_y) + bending/(W_el f_y) at the worse end of each member (elastic check); "
     "members over 1 are the brightest."},
    {"buckling.svg", "analyze",
     "First linear buckling mode of the frame under the analysed load (|u| normalised to 1), its load factor λ "
     "in the title.",
     true},
};

const char* kStyle = R"(body{font-family:sans-serif;max-width:1240px;margin:1.5em auto;padding:0 1em;color:#222}
h1{margin-bottom:0.2em}h2{margin-top:1.6em;border-bottom:1px solid #ddd;padding-bottom:0.2em}
.sub{color:#666;margin-top:0}
table{border-collapse:collapse;margin:0.4em 0 1em}td,th{border:1px solid #ccc;padding:3px 8px;text-align:left}
th{background:#f0f0f0}td.num{text-align:right;font-variant-numeric:tabular-nums}
.cols{display:flex;flex-wrap:wrap;gap:0 2.5em;align-items:flex-start}
.metrics{display:grid;grid-template-columns:repeat(auto-fill,minmax(360px,1fr));gap:0 1.5em}
.metrics h3{margin:0.6em 0 0.2em;font-size:1em}.metrics table{width:100%;font-size:0.88em}.metrics td:first-child{word-break:break-all}
.bar{display:inline-block;height:0.8em;background:#4a7fc1;vertical-align:middle}
.figures{display:grid;grid-template-columns:repeat(auto-fill,minmax(540px,1fr));gap:1.2em}
.pair{display:grid;grid-template-columns:1fr 1fr;gap:1.2em}
figure{margin:0}figure svg{display:block;width:100%;height:auto;border:1px solid #ddd}
figcaption{color:#555;margin-top:0.3em;font-size:0.92em}
.missing{border:2px dashed #c33;color:#c33;padding:2em;text-align:center}
.checks{border-left:5px solid #c33;background:#fdf3f1;padding:0.3em 1em;margin:0.8em 0}
.checks.ok{border-color:#3a8a3a;background:#f1f8f1}.checks ul{margin:0.2em 0 0.5em}
)";

// After load: measure every figure (see report_html.h) into its data-check attribute.
const char* kCheckScript = R"(<script>
(function () {
  async function measure(figure) {
    const svg = figure.querySelector('svg');
    if (!svg) return 'nosvg';
    const box = svg.getBoundingClientRect();
    const marks = svg.querySelectorAll('path,rect,circle,use,polygon,polyline,line').length;
    const view = svg.viewBox.baseVal;
    const width = Math.max(1, Math.min(400, Math.round(box.width)));
    const scale = width / view.width, height = Math.max(1, Math.round(view.height * scale));
    const image = new Image();
    image.src = 'data:image/svg+xml;charset=utf-8,' +
                encodeURIComponent(new XMLSerializer().serializeToString(svg));
    await image.decode();
    const canvas = document.createElement('canvas');
    canvas.width = width;
    canvas.height = height;
    const g = canvas.getContext('2d');
    g.fillStyle = '#ffffff';
    g.fillRect(0, 0, width, height);
    g.drawImage(image, 0, 0, width, height);
    let plot = (svg.getAttribute('data-plot') || '').split(' ').map(Number);
    if (plot.length !== 4 || plot.some(isNaN)) plot = [0, 0, view.width, view.height];
    const [x, y, w, h] = plot.map(v => Math.round(v * scale));
    const data = g.getImageData(x, y, Math.max(1, w), Math.max(1, h)).data;
    let ink = 0;
    const colours = new Set();
    for (let i = 0; i < data.length; i += 4) {
      if (data[i] < 245 || data[i + 1] < 245 || data[i + 2] < 245) ++ink;
      colours.add(((data[i] >> 4) << 8) | ((data[i + 1] >> 4) << 4) | (data[i + 2] >> 4));
    }
    return 'w=' + Math.round(box.width) + ' h=' + Math.round(box.height) + ' marks=' + marks +
           ' ink=' + (ink / (data.length / 4)).toFixed(3) + ' colours=' + colours.size;
  }
  window.addEventListener('load', async function () {
    const figures = document.querySelectorAll('figure[data-figure]');
    for (const figure of figures) {
      try {
        figure.dataset.check = figure.dataset.missing ? 'missing' : await measure(figure);
      } catch (e) {
        figure.dataset.check = 'error ' + e;
      }
    }
    document.body.dataset.pageHeight = document.documentElement.scrollHeight;
    document.body.dataset.checked = figures.length;
  });
})();
</script>
)";

std::string PageStart(const std::string& title) {
  return "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n<title>" + Escape(title) +
         "</title>\n<style>\n" + kStyle + "</style>\n" + kCheckScript + "</head><body>\n";
}

std::string ReadFile(const std::filesystem::path& path, bool* found) {
  std::ifstream in(path, std::ios::binary);
  *found = static_cast<bool>(in);
  std::stringstream text;
  if (*found) text << in.rdbuf();
  return text.str();
}

// Replaces every occurrence of `from` in text by `to`.
void ReplaceAll(std::string* text, const std::string& from, const std::string& to) {
  for (size_t at = text->find(from); at != std::string::npos; at = text->find(from, at + to.size()))
    text->replace(at, from.size(), to);
}

// The <svg> element of an SVG file, its ids (and the references to them) prefixed with
// `prefix`; "" if the file holds no <svg>.
std::string InlineSvg(const std::string& file_text, const std::string& prefix) {
  const size_t start = file_text.find("<svg");  // drop any XML prolog
  if (start == std::string::npos) return "";
  std::string svg = file_text.substr(start);
  ReplaceAll(&svg, "id=\"", "id=\"" + prefix);
  ReplaceAll(&svg, "url(#", "url(#" + prefix);
  ReplaceAll(&svg, "href=\"#", "href=\"#" + prefix);
  return svg;
}

// One <figure>: the SVG at `path` inlined, or the note that it is missing. `index` makes the
// figure's id prefix unique in the page.
std::string FigureHtml(const std::filesystem::path& path, const std::string& name,
                       const std::string& caption, int index) {
  bool found = false;
  const std::string svg = InlineSvg(ReadFile(path, &found), "f" + std::to_string(index) + "-");
  std::ostringstream s;
  if (svg.empty()) {
    s << "<figure data-figure=\"" << Escape(name) << "\" data-missing=\"1\"><div class=\"missing\">"
      << Escape(name) << (found ? " holds no SVG" : " was not written") << "</div>";
  } else {
    s << "<figure data-figure=\"" << Escape(name) << "\">\n" << svg;
  }
  s << "<figcaption>" << Escape(caption) << "</figcaption></figure>\n";
  return s.str();
}

bool Completed(const nlohmann::json& report, const std::string& stage) {
  for (const auto& name : At(report, {"run", "completed_stages"}))
    if (name == stage) return true;
  return false;
}

std::string Row(const std::string& key, const std::string& value) {
  return "<tr><td>" + Escape(key) + "</td><td>" + Escape(value) + "</td></tr>\n";
}


// What the run says about itself, first: report.json's targets (met, and each miss with its
// cause) and its warnings (buckling, utilisation, crossings, ...); green when nothing is missed
// or warned about, red otherwise.
std::string Checks(const nlohmann::json& report) {
  const nlohmann::json& targets = At(report, {"targets", "list"});
  const nlohmann::json& warnings = At(report, {"warnings"});
  const size_t n_warnings = warnings.is_array() ? warnings.size() : 0;
  if (!targets.is_array() && n_warnings == 0) return "";
  std::string misses;
  int met = 0, total = 0;
  for (const auto& t : targets.is_array() ? targets : nlohmann::json::array()) {
    ++total;
    if (At(t, {"met"}) == true) {
      ++met;
      continue;
    }
    misses += "<li>" + Escape(Format(At(t, {"what"})) + ": " + Format(At(t, {"value"})) + " (target " +
                              Format(At(t, {"target"})) + "): " + Format(At(t, {"cause"}))) + "</li>\n";
  }
  std::string s = std::string("<div class=\"checks") + (misses.empty() && n_warnings == 0 ? " ok" : "") + "\">";
  if (total > 0)
    s += "<p><strong>Layout targets: " + std::to_string(met) + " of " + std::to_string(total) + " met</strong>" +
         (misses.empty() ? "" : "; missed:") + "</p>\n" + (misses.empty() ? "" : "<ul>\n" + misses + "</ul>\n");
  if (n_warnings > 0) {
    s += "<p><strong>Warnings (" + std::to_string(n_warnings) + ")</strong></p>\n<ul>\n";
    for (const auto& w : warnings) s += "<li>" + Escape(Format(w)) + "</li>\n";
    s += "</ul>\n";
  } else {
    s += "<p>No warnings.</p>\n";
  }
  return s + "</div>\n";
}

// "; N quads on free edges braced by stiffen ..." when stiffen cut some (the grid shell row
// counts the extracted mesh, before them), else "".
std::string BracingNote(const nlohmann::json& report) {
  const nlohmann::json& braced = At(report, {"stages", "stiffen", "bracing", "braced_quads"});
  if (!braced.is_number_integer() || braced.get<int>() <= 0) return "";
  return "; " + std::to_string(braced.get<int>()) +
         " quads on free edges then braced by stiffen, two triangles each (extract.brace_free_edges)";
}

std::string Summary(const nlohmann::json& report) {
  const auto& config = At(report, {"config"});
  const auto& stages = At(report, {"stages"});
  std::string s = "<table>\n";
  if (stages.contains("surface")) {
    const auto& sf = At(stages, {"surface"});
    s += Row("surface", Format(At(sf, {"source"})) + ": " + Format(At(sf, {"n_faces"})) + " triangles, " +
                            Format(At(sf, {"n_vertices"})) + " vertices, area " + Format(At(sf, {"area"})) + " m²");
    std::string supports;
    for (const auto& [condition, count] : At(sf, {"supports"}).items())
      supports += (supports.empty() ? "" : ", ") + Format(count) + " " + condition;
    s += Row("supports", supports + " boundary vertices (default " + Format(At(config, {"boundary", "default"})) +
                             ", " + std::to_string(At(config, {"boundary", "rules"}).size()) + " rules)");
  }
  s += Row("dead load q", Format(At(config, {"load", "q"})) + " N/m²");
  s += Row("guidance", Format(At(config, {"guidance", "source"})) + ", threshold " +
                           Format(At(config, {"guidance", "threshold"})));
  s += Row("spacing h", Format(At(config, {"layout", "spacing"})) + " m");
  if (stages.contains("extract"))
    s += Row("grid shell", Metric(report, "extract", "n_faces") + " faces (" +
                               Metric(report, "extract", "quad_fraction") + " quads), " +
                               Metric(report, "extract", "n_vertices") + " nodes, " +
                               Metric(report, "extract", "n_edges") + " members" + BracingNote(report));
  s += Row("pqlayout", Format(At(report, {"pqlayout", "version"})) + " (git " +
                           Format(At(report, {"pqlayout", "git_revision"})) + ")");
  s += Row("run", Format(At(report, {"run", "started_at"})) + ", " + Format(At(report, {"run", "total_seconds"})) +
                      " s, config " + Format(At(report, {"run", "config_file"})));
  return s + "</table>\n";
}

// The headline numbers: (stage, metric, label).
struct KeyResult {
  const char* stage;
  const char* metric;
  const char* label;
};
const KeyResult kKeyResults[] = {
    {"membrane", "max_displacement", "membrane max |v_z| [m]"},
    {"levelset", "alignment_rms_deg", "alignment to the guidance, RMS [°]"},
    {"extract", "planarity_max", "planarity δ max, before"},
    {"planarize", "planarity_max", "planarity δ max, after"},
    {"planarize", "closeness_max", "distance to the reference, max [m]"},
    {"stiffen", "compliance_ratio", "stiffen: compliance after / before"},
    {"stiffen", "offset_max", "stiffen: normal offset max [m]"},
    {"analyze", "compliance_total", "compliance total [J]"},
    {"analyze", "max_displacement", "frame max displacement [m]"},
    {"analyze", "steel_mass", "steel mass [kg]"},
    {"analyze", "buckling_factor", "buckling load factor λ₁"},
    {"analyze", "utilisation_max", "member utilisation η, max"},
    {"analyze", "span_over_deflection", "span / max deflection"},
};

std::string KeyResults(const nlohmann::json& report) {
  std::string s = "<table><tr><th>result</th><th>value</th></tr>\n";
  for (const auto& k : kKeyResults)
    if (At(report, {"stages"}).contains(k.stage))
      s += "<tr><td>" + Escape(k.label) + "</td><td class=\"num\">" + Escape(Metric(report, k.stage, k.metric)) +
           "</td></tr>\n";
  return s + "</table>\n";
}

std::vector<std::string> StagesInOrder(const nlohmann::json& report) {
  std::vector<std::string> names;
  for (const auto& name : At(report, {"run", "completed_stages"})) names.push_back(name);
  return names;
}

double Seconds(const nlohmann::json& report, const std::string& stage) {
  const nlohmann::json& seconds = At(report, {"stages", stage, "seconds"});
  return seconds.is_number() ? seconds.get<double>() : 0.0;
}

std::string Timings(const nlohmann::json& report) {
  double longest = 0.0;
  for (const auto& name : StagesInOrder(report))
    longest = std::max(longest, Seconds(report, name));
  std::ostringstream s;
  s << "<table><tr><th>stage</th><th>seconds</th><th></th></tr>\n";
  for (const auto& name : StagesInOrder(report)) {
    const double seconds = Seconds(report, name);
    s << "<tr><td>" << Escape(name) << "</td><td class=\"num\">" << Format(seconds)
      << "</td><td><span class=\"bar\" style=\"width:"
      << (longest > 0.0 ? static_cast<int>(120.0 * seconds / longest) : 0) << "px\"></span></td></tr>\n";
  }
  s << "</table>\n";
  return s.str();
}

std::string MetricsTables(const nlohmann::json& report) {
  std::string s = "<div class=\"metrics\">\n";
  for (const auto& name : StagesInOrder(report)) {
    s += "<div><h3>" + Escape(name) + "</h3><table>\n";
    for (const auto& [key, value] : At(report, {"stages", name}).items()) {
      if (value.is_object() || value.is_array()) continue;  // lists stay in report.json
      s += "<tr><td>" + Escape(key) + "</td><td class=\"num\">" + Escape(Format(value)) + "</td></tr>\n";
    }
    s += "</table></div>\n";
  }
  return s + "</div>\n";
}

}  // namespace

Status WriteReportHtml(const nlohmann::json& report, OutputFiles* out, const View3dData& view3d) {
  std::ostringstream page;
  page << PageStart("pqlayout report") << "<h1>pqlayout: statics-sensitive layout</h1>\n"
       << "<p class=\"sub\">" << Escape(Metric(report, "surface", "source")) << " · "
       << Escape(Format(At(report, {"config", "guidance", "source"}))) << " guidance · h = "
       << Escape(Format(At(report, {"config", "layout", "spacing"}))) << " m"
       << (At(report, {"config", "levelset", "draft"}) == true
               ? " · <strong>draft</strong> (levelset.draft: the level sets on a coarser working mesh, a quick look, "
                 "not the final layout)"
               : "")
       << "</p>\n"
       << Checks(report) << "<h2>Summary</h2>\n<div class=\"cols\"><div>" << Summary(report) << "</div><div>"
       << KeyResults(report) << "</div><div>" << Timings(report) << "</div></div>\n"
       << View3dHtml(view3d) << "<h2>Figures</h2>\n<div class=\"figures\">\n";
  int index = 0;
  for (const auto& figure : kFigures) {
    if (!Completed(report, figure.stage)) continue;
    if (figure.optional && !std::filesystem::exists(out->Path(std::string("figures/") + figure.file))) continue;
    page << FigureHtml(out->Path(std::string("figures/") + figure.file), figure.file, figure.caption, index++);
  }
  page << "</div>\n<h2>Metrics per stage</h2>\n" << MetricsTables(report)
       << "<p>Full data: report.json, "
       << (std::filesystem::exists(out->Path("fields.vtk")) ? "fields.vtk (ParaView), fields/*.csv, " : "")
       << "quads.obj, quads.ply, analysis/*.csv.</p>\n</body></html>\n";
  return out->WriteText("report.html", page.str());
}

Status WriteCompareReportHtml(const nlohmann::json& comparison, const std::string& dir) {
  const std::filesystem::path root(dir);
  std::ostringstream page;
  page << PageStart("pqlayout comparison") << "<h1>pqlayout: strain vs curvature guidance</h1>\n"
       << "<p class=\"sub\">config " << Escape(Format(At(comparison, {"config_file"}))) << " · "
       << "runs: <a href=\"strain/report.html\">strain</a>, <a href=\"curvature/report.html\">curvature</a></p>\n"
       << "<h2>Comparison</h2>\n<table><tr><th>metric</th><th>strain guidance</th><th>curvature guidance</th>"
       << "<th>strain vs curvature</th></tr>\n";
  for (const auto& row : At(comparison, {"rows"})) {
    std::string difference = "–";
    const nlohmann::json& percent = At(row, {"difference_percent"});
    if (percent.is_number()) {
      std::ostringstream d;
      d.precision(3);
      d << std::showpos << percent.get<double>() << " %";
      difference = d.str();
    }
    page << "<tr><td>" << Escape(Format(At(row, {"label"}))) << "</td><td class=\"num\">" << Escape(Format(At(row, {"strain"})))
         << "</td><td class=\"num\">" << Escape(Format(At(row, {"curvature"}))) << "</td><td class=\"num\">"
         << Escape(difference) << "</td></tr>\n";
  }
  page << "</table>\n<h2>Runs</h2>\n<div class=\"pair\">\n";
  for (const char* source : {"strain", "curvature"}) {
    bool found = false;
    const std::string text = ReadFile(root / source / "report.json", &found);
    const nlohmann::json run = nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/false);
    page << "<div><h3>" << source << " guidance</h3>\n"
         << (found && run.is_object() ? Checks(run) + Summary(run) + Timings(run)
                                      : std::string("<p>report.json missing</p>\n"))
         << "</div>\n";
  }
  page << "</div>\n";
  struct Pair {
    const char* heading;
    std::filesystem::path strain, curvature;
    const char* caption;
  };
  const Pair pairs[] = {
      {"Nodal compliance (one colour scale)", root / "figures" / "compliance_strain.svg",
       root / "figures" / "compliance_curvature.svg", "Nodal compliance (paper Fig. 9, 14)."},
      {"Layouts", root / "strain" / "figures" / "levelsets.svg", root / "curvature" / "figures" / "levelsets.svg",
       "Level lines φ = i·h, ψ = j·h."},
      {"Planarity after planarisation", root / "strain" / "figures" / "planarity.svg",
       root / "curvature" / "figures" / "planarity.svg", "Planarity δ per face."},
      {"Grid shells", root / "strain" / "figures" / "shell_3d.svg", root / "curvature" / "figures" / "shell_3d.svg",
       "Oblique view, faces coloured by planarity δ."},
      {"Guidance", root / "strain" / "figures" / "guidance.svg", root / "curvature" / "figures" / "guidance.svg",
       "Guidance field."},
  };
  int index = 0;
  for (const auto& pair : pairs) {
    page << "<h2>" << Escape(pair.heading) << "</h2>\n<div class=\"pair\">\n";
    page << FigureHtml(pair.strain, "strain/" + pair.strain.filename().string(),
                       std::string("Strain guidance. ") + pair.caption, index++);
    page << FigureHtml(pair.curvature, "curvature/" + pair.curvature.filename().string(),
                       std::string("Curvature guidance (reference). ") + pair.caption, index++);
    page << "</div>\n";
  }
  page << "</body></html>\n";
  return WriteTextFileAtomically((root / "report.html").string(), page.str());
}

}  // namespace pqlayout

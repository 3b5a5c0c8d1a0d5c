#include "pipeline/config.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <set>
#include <sstream>

#include "geometry/surface_generators.h"
#include "pipeline/config_rules.h"
#include "pipeline/config_table.h"
#include "pipeline/config_yaml.h"

namespace pqlayout {

using config_yaml::Describe;
using config_yaml::FormatNumber;
using config_yaml::KeyName;
using config_yaml::ScalarAs;
using nlohmann::json;

namespace config_internal {

// Long on purpose: one flat line per config key, in the order of the config reference.
KeyTable::KeyTable(Config* c) {
  Integer("threads", &c->threads, 1, 256,
          "threads of Ceres, OpenBLAS and OpenMP; 1 (default) gives bit-identical results on every machine, more may not");
  auto& s = c->surface;
  Path("surface.file", &s.file, "reference mesh (OBJ, PLY, OFF or STL; metres); relative paths are relative to the config file");
  std::vector<std::string> generators = {""};
  for (const auto& name : GeneratorNames()) generators.push_back(name);
  Choice("surface.generator", &s.generator, generators,
         "built-in reference surface, used when surface.file is empty (the corpus roofs: examples/corpus)");
  Number("surface.edge_length", &s.edge_length, Positive(kMaxLength), "generator: target triangle edge length, m");
  Number("surface.width", &s.width, Positive(kMaxLength), "generator: x extent, m (disk, annulus: outer diameter)");
  Number("surface.depth", &s.depth, Positive(kMaxLength), "generator: y extent, m (annulus: inner diameter)");
  Number("surface.rise", &s.rise, NonNegative(kMaxLength), "generator: crown height above the supports (or relief), m; not for plane, disk, annulus");
  Number("surface.weld_tolerance", &s.weld_tolerance, NonNegative(kMaxLength),
         "file: boundary vertices this close are welded and T-junctions this far off an edge closed (an exported seam), m; "
         "0: 1e-6 × the diagonal");

  Condition("boundary.default", &c->boundary.default_condition, "support of every boundary vertex unless a rule overrides it");
  Rules("boundary.rules", &c->boundary.rules,
        "list of {select, condition}, applied in order; select: all | outer | inner | corners | {loop: N} | "
        "{box: [xmin, ymin, zmin, xmax, ymax, zmax]} | {ids: [...]} | {ids_file: PATH}");

  Number("load.q", &c->load.q, Positive(kMaxPressure), "dead load per area for the membrane solve, N/m²");
  Number("membrane.stiffness", &c->membrane.stiffness, AtLeast(1e-3, kMaxModulus), "λ_m, membrane stiffness, N/m: v scales with 1/λ_m; the strain directions depend on it only through ε's quadratic term ½∇v∇vᵀ");
  Number("membrane.bending", &c->membrane.bending, NonNegative(kMaxModulus), "λ_b, bending stiffness, N·m (0 = pure membrane, as in the paper)");

  auto& g = c->guidance;
  Choice("guidance.source", &g.source, {"strain", "curvature", "file"},
         "guidance field: principal strain (the paper), principal curvature (the reference layout) or a CSV file");
  Number("guidance.threshold", &g.threshold, kFraction, "no alignment to the source where |ε_max| (less |ε_min| where the two differ in sign: guidance.shear_switch) < threshold × max |ε_max| (guidance.fallback fills in there)");
  Number("guidance.ramp", &g.ramp, kFraction, "alignment weight ramps from 0 to 1 over [threshold, threshold + ramp] × max");
  Path("guidance.file", &g.file, "guidance.source = file: per-face CSV id,dx,dy,dz[,weight]");
  Choice("guidance.fallback", &g.fallback, {"curvature", "none"},
         "where the strain (or file) weight is below 1, the principal curvature lines fill in, blended as line fields "
         "(none: alignment only where the source's weight says, as in the paper); not used with guidance.source = curvature");
  Number("guidance.fallback_weight", &g.fallback_weight, kFraction,
         "β: the curvature fallback's alignment weight is (1 − source weight) × β × curvature weight");
  Choice("guidance.shear_switch", &g.shear_switch, {"weak", "paper"},
         "strain: where ε_max and ε_min have opposite signs the weight comes from |ε_max| − |ε_min|, so it vanishes "
         "where e_max (largest modulus) swaps by 90° (weak; the fallback fills in there), or from |ε_max| as in the paper");

  Number("layout.spacing", &c->layout.spacing, Positive(kMaxLength), "h, distance between neighbouring level lines, m");
  Choice("layout.density", &c->layout.density, {"auto", "spacing", "panel_area"},
         "spacing: level lines h apart; panel_area: φ, ψ then scaled together so that the mean panel area is h² (equal node counts for layouts that cross at different angles); auto: panel_area in `compare`, spacing otherwise");
  Integer("layout.max_panels", &c->layout.max_panels, 1, 100000000,
          "refuse a layout.spacing that would give more panels than this, estimated as the surface's area / h² "
          "(the level-set solve's and the extraction's time and memory grow with it)");

  auto& lw = c->levelset.weights;
  Number("levelset.weights.alignment", &lw.alignment, NonNegative(kMaxWeight), "φ's level lines follow the guidance field");
  Number("levelset.weights.spacing", &lw.spacing, Positive(kMaxWeight),
         "even spacing: h|∇φ| = 1, h|∇ψ| = 1 (> 0: without it nothing keeps the level lines apart)");
  Number("levelset.weights.smoothness", &lw.smoothness, NonNegative(kMaxWeight), "gradient difference across interior edges");
  Number("levelset.weights.conjugacy", &lw.conjugacy, NonNegative(kMaxWeight), "the two families are conjugate: II(n×∇φ, n×∇ψ) = 0");
  Number("levelset.weights.transversality", &lw.transversality, NonNegative(kMaxWeight), "crossing angle of the families ≥ levelset.min_angle");
  Number("levelset.min_angle", &c->levelset.min_angle, Range{0.0, 90.0, true, true}, "minimum crossing angle of the two families, degrees");
  Number("levelset.smoothness_max_guidance", &c->levelset.smoothness_max_guidance, Range{0.0, 1.0},
         "the smoothness term acts on the interior edges with a face whose guidance weight is at most this (1: on every "
         "edge; 0.5: only where the guidance leaves φ's direction open: level sets ~1.3–1.6× faster, a different layout, "
         "as stiff over seven Great Court meshes, but the Great Court's curvature layout crosses at 29.4°; seams always smoothed)");
  Choice("levelset.linear_solver", &c->levelset.linear_solver, {"cholesky", "cg"},
         "each step of the level-set solves: cholesky (sparse Cholesky, exact) or cg (conjugate gradients "
         "preconditioned by the factor without the smoothness terms: the joint solve's steps ~2× cheaper, level sets "
         "~1.2–1.6× faster on the corpus, a different layout, as stiff over seven Great Court meshes)");
  Number("levelset.tip_cone_radius", &c->levelset.tip_cone_radius, Range{0.0, 10.0},
         "× h: a layout with branch points (tips of sign −1 seams) that still crosses below levelset.min_angle or "
         "folds over after its rounds is solved again with the spacing term following the cone within this of each "
         "branch point, h|∇u| = (d / (this × h))^½ at distance d instead of 1 (the cells there grow instead of "
         "shearing), and the better end kept (0: no second solve)");
  Choice("levelset.alongside", &c->levelset.alongside, {"auto", "true", "false", "1"},
         "true: solve the second layouts that may be needed (the cone's retry where the layout has branch points, "
         "the layout with poles where the guidance has crowns, the rounds' floor way where the crossing rounds may "
         "fall short) on threads of their own beside the first, each cancelled as soon as it is known not to be needed (the same outputs; on 2 cores the level sets "
         "~0.7× as long where they are needed, ~1.1× where they are not); false: one thread, each only once needed; "
         "auto: as many at once as the hardware threads less one (one on 2 cores); 1: one at a time (auto's schedule on "
         "2 cores, on any machine)");
  Bool("levelset.separate_solves", &c->levelset.separate_solves,
       "solve φ alone, then ψ with φ held, before the solve of both together (the paper's order); false: the "
       "joint solve starts from the initial guess (as stiff or stiffer, the level sets ~3× faster: "
       "benchmarks/RESULTS.md)");
  Integer("levelset.max_iterations", &c->levelset.max_iterations, 1, 100000,
          "Ceres iterations of the φ solve and of the ψ solve (with levelset.separate_solves)");
  Integer("levelset.joint_iterations", &c->levelset.joint_iterations, 0, 100000,
          "Ceres iterations of the solve of φ and ψ together, at most (0: none, only with "
          "levelset.separate_solves; past 100 it also ends once 24 iterations lowered its cost by less than 0.5 %)");
  Integer("levelset.crossing_rounds", &c->levelset.crossing_rounds, 0, 100,
          "local re-solves after it that raise transversality on the faces still crossing below levelset.min_angle, "
          "at most (0: none; they also end after 3 rounds in a row that do not reach the best state); if they "
          "leave a fold-over or a face below min_angle, as many floor rounds (a barrier under the "
          "worst face) and again crossing rounds over that floor, and the better end is kept; none where more "
          "than half the area crosses below min_angle after the joint solve (out of reach: a warning says so)");
  Bool("levelset.seams", &c->levelset.seams,
       "cut seams from the guidance's ±½ singularities and from holes to the boundary; φ, ψ jump by whole levels "
       "across them (branch points, as in the paper's curvature reference); false: single-valued φ, ψ");
  Bool("levelset.poles", &c->levelset.poles,
       "a crown of the guidance (a whole turn, index +1: a dome's top) becomes a pole: one family rings it, the "
       "other fans out of it, and a cap polygon (a crown ring) closes the innermost ring; needs levelset.seams");
  Number("levelset.working_edge", &c->levelset.working_edge, NonNegative(kMaxLength),
         "edge length of the mesh φ, ψ are solved on, m (0: 0.4 h, 0.8 h with levelset.draft, coarser where levelset.working_triangles asks); a reference finer than 0.7 × this is remeshed");
  Bool("levelset.draft", &c->levelset.draft,
       "a quick look: φ, ψ solved on a working mesh of edge 0.8 h (at most 1/16 of the shortest boundary loop; "
       "a quarter of the triangles, level sets ~5× faster), a different and usually somewhat softer layout; "
       "ignored if levelset.working_edge is set (README \"Draft runs\")");
  Integer("levelset.working_triangles", &c->levelset.working_triangles, 0, 100000000,
          "the working mesh's edge is never shorter than that of this many equilateral triangles covering the roof, "
          "so a fine spacing on a large roof does not multiply the level sets' unknowns (the Great Court at h = 1.25 m: "
          "14.5k triangles instead of 71k, level sets 134 → 28 s, compliance × 1.015); never coarser than 1.5 h; "
          "0: 0.4 h however many; ignored if levelset.working_edge is set");

  Number("extract.corner_angle", &c->extract.corner_angle, Range{0.0, 180.0, true, true}, "boundary turning angle above which a vertex is a corner, degrees");
  Number("extract.min_edge", &c->extract.min_edge, Range{0.0, 1.0, false, true}, "edges shorter than min_edge × h are merged");
  Number("extract.boundary_tolerance", &c->extract.boundary_tolerance, Range{0.0, 1.0, false, true}, "mesh boundary edges further than this × h from a curved reference boundary get an extra boundary vertex (0: never)");
  Choice("extract.brace_free_edges", &c->extract.brace_free_edges, {"none", "paying", "all"},
         "quads on a free (unsupported) stretch of the boundary cut into two triangles: none; paying: after stiffen, a stretch at a time, kept where the stiffened shell's compliance drops ≥ 1 % (the barrel with free gables: × 0.54); all: every stretch, at extraction");

  auto& pw = c->planarize.weights;
  Number("planarize.weights.planarity", &pw.planarity, NonNegative(kMaxWeight), "faces planar");
  Number("planarize.weights.closeness", &pw.closeness, NonNegative(kMaxWeight), "vertices stay on the reference surface");
  Number("planarize.weights.boundary", &pw.boundary, NonNegative(kMaxWeight), "boundary vertices stay on the reference boundary");
  Number("planarize.weights.fairness", &pw.fairness, NonNegative(kMaxWeight), "second differences along the mesh polylines");
  Number("planarize.weights.anchor", &pw.anchor, NonNegative(kMaxWeight), "vertices stay near where the layout put them (raised with closeness, ×3 a round)");
  Number("planarize.weights.edge_length", &pw.edge_length, NonNegative(kMaxWeight),
         "× the planarity weight: no edge shrinks below a quarter of its extracted length (or of h); 0: off");
  Number("planarize.weights.orientation", &pw.orientation, NonNegative(kMaxWeight),
         "× the first round's planarity weight: no triangle turns over or flattens below 5 % of its extracted area; 0: off");
  Number("planarize.target_delta", &c->planarize.target_delta, Positive(1.0), "stop when max planarity δ ≤ target_delta");
  Integer("planarize.max_rounds", &c->planarize.max_rounds, 1, 1000, "outer rounds (planarity weight raised after each)");
  Number("planarize.split_warped", &c->planarize.split_warped, NonNegative(1.0),
         "quads whose planarity δ as extracted is above this are cut into two triangles before planarisation "
         "(the diagonal with the larger smallest angle): flattening them would move their vertices far and fold "
         "their neighbours (0: none)");
  Number("planarize.close_edges", &c->planarize.close_edges, NonNegative(1.0),
         "edges that planarisation shortens below close_edges × h are closed (their ends one vertex: a quad "
         "becomes the triangle it has turned into), panels it folded are cut into triangles, and the mesh "
         "planarised again, up to 8 passes; planar quads with a reflex corner are then cut into two triangles "
         "(0: none of it)");

  auto& st = c->stiffen;
  Number("stiffen.tolerance", &st.tolerance, NonNegative(kMaxLength),
         "how far a vertex may be from the reference surface after stiffening, m, both sides (0: stage off)");
  Number("stiffen.slide", &st.slide, NonNegative(kMaxLength), "how far a vertex may also slide along the reference, m, per tangent direction (at most 0.1 h); the slide does not use up stiffen.tolerance");
  Number("stiffen.min_member", &st.min_member, Range{0.0, 1.0, true, true}, "no member shorter than this × its planarised length (nor than 1.1 × the section depth)");
  Integer("stiffen.max_iterations", &st.max_iterations, 1, 100000, "L-BFGS iterations in all, one or two frame solves each (stiffen.tolerance = 0 turns the stage off)");
  Integer("stiffen.stop_window", &st.stop_window, 2, 100000,
          "the stage ends once this many iterations lowered its objective by less than stiffen.stop_gain of it (--draft: 5)");
  Number("stiffen.stop_gain", &st.stop_gain, Range{0.0, 1.0, true, true},
         "see stiffen.stop_window (--draft: 0.01; 0.005 leaves C/C₀ within ~0.5 % of its converged value)");
  Number("stiffen.weights.fairness", &st.weights.fairness, NonNegative(kMaxWeight), "mesh polylines keep their planarised second differences (panel kinks)");
  Number("stiffen.weights.edge_length", &st.weights.edge_length, NonNegative(kMaxWeight), "members stay longer than their minimum");

  auto& a = c->analysis;
  Number("analysis.panel_load", &a.panel_load, NonNegative(kMaxPressure), "panel dead load, N/m² of face area");
  Number("analysis.gravity", &a.gravity, NonNegative(1e3), "g, m/s²");
  Bool("analysis.export_calculix", &a.export_calculix, "also write analysis/model.inp for CalculiX (and analysis/model_buckle.inp, a *BUCKLE deck, when the frame buckles)");
  Choice("analysis.calculix_element", &a.calculix_element, {"u1", "b32r"},
         "CalculiX beam: u1 = ccx's 2-node beam with the model's Euler–Bernoulli stiffness; b32r = 3-node beam ccx expands to bricks of the true section");
  Integer("analysis.buckling_modes", &a.buckling_modes, 0, 20, "linear buckling load factors (and mode shapes) to find; 0: none");
  Integer("analysis.calculix_subdivisions", &a.calculix_subdivisions, 1, 64, "CalculiX elements per member (b32r converges as this grows)");
  Number("analysis.material.youngs_modulus", &a.material.youngs_modulus, AtLeast(1e6, kMaxModulus), "E, Pa");
  Number("analysis.material.poisson_ratio", &a.material.poisson_ratio, Range{-1.0, 0.5, true, true}, "ν; G = E / (2(1+ν))");
  Number("analysis.material.density", &a.material.density, NonNegative(1e6), "ρ, kg/m³");
  Number("analysis.material.yield_strength", &a.material.yield_strength, AtLeast(1e6, kMaxModulus), "f_y, Pa, for the member utilisation η (S355: 355e6)");
  Choice("analysis.section.shape", &a.section.shape, {"circular_hollow", "rectangular_hollow"}, "member cross-section");
  Number("analysis.section.diameter", &a.section.diameter, AtLeast(kMinSection, 100.0), "circular hollow: outside diameter D, m");
  Number("analysis.section.thickness", &a.section.thickness, AtLeast(kMinSection, 100.0), "wall thickness t, m");
  Number("analysis.section.width", &a.section.width, AtLeast(kMinSection, 100.0), "rectangular hollow: width (in the surface), m");
  Number("analysis.section.height", &a.section.height, AtLeast(kMinSection, 100.0), "rectangular hollow: height (along the surface normal), m");

  Bool("output.fields", &c->output.fields,
       "write fields/*.csv and fields.vtk (one row per reference vertex or face: ~300 MB at 1M triangles); false for sweeps");
}

}  // namespace config_internal

namespace {

using namespace config_internal;  // the key table (pipeline/config_table.h)

int EditDistance(const std::string& a, const std::string& b) {
  std::vector<int> prev(b.size() + 1), cur(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) prev[j] = static_cast<int>(j);
  for (size_t i = 1; i <= a.size(); ++i) {
    cur[0] = static_cast<int>(i);
    for (size_t j = 1; j <= b.size(); ++j)
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + (a[i - 1] != b[j - 1])});
    std::swap(prev, cur);
  }
  return prev[b.size()];
}

}  // namespace

namespace config_internal {

std::string KeyTable::Suggest(const std::string& key) const {
  std::string best;
  int best_distance = std::max(2, static_cast<int>(key.size()) / 5) + 1;
  // Candidates: every key and every section (dotted prefix of a key).
  for (const auto& e : entries_) {
    for (size_t end = e.key.find('.'); ; end = e.key.find('.', end + 1)) {
      const std::string candidate = e.key.substr(0, end);
      const int d = EditDistance(key, candidate);
      if (d < best_distance) {
        best_distance = d;
        best = candidate;
      }
      if (end == std::string::npos) break;
    }
  }
  return best.empty() ? "" : " (did you mean '" + best + "'?)";
}

}  // namespace config_internal

namespace {

using namespace config_internal;

// Walks a YAML mapping, setting every leaf it finds; records the keys it set.
Status ApplyMapping(const YAML::Node& node, const std::string& prefix, const std::string& source,
                    KeyTable* table, std::set<std::string>* set_keys) {
  std::set<std::string> seen;
  for (const auto& kv : node) {
    const std::string where = source + ":" + std::to_string(kv.first.Mark().line + 1);
    std::string name;
    if (!KeyName(kv.first, &name))
      return Status::InvalidInput(where + ": keys must be plain names, got " + Describe(kv.first) +
                                  (prefix.empty() ? "" : " in section " + prefix));
    const std::string key = prefix.empty() ? name : prefix + "." + name;
    if (!seen.insert(name).second) return Status::InvalidInput(where + ": " + key + ": duplicate key");
    if (const KeyEntry* entry = table->Find(key)) {
      const std::string error = entry->set(kv.second);
      if (!error.empty()) return Status::InvalidInput(where + ": " + KeyError(key, error));
      set_keys->insert(key);
    } else if (table->IsSection(key)) {
      if (kv.second.IsNull()) continue;  // an empty section
      if (!kv.second.IsMap())
        return Status::InvalidInput(where + ": " + key + ": is a section, expected a mapping of its keys, got " +
                                    Describe(kv.second));
      PQ_RETURN_IF_ERROR(ApplyMapping(kv.second, key, source, table, set_keys));
    } else {
      return Status::InvalidInput(where + ": unknown key '" + key + "'" + table->Suggest(key));
    }
  }
  return Status::Ok();
}

Status ApplyOverride(const std::string& assignment, KeyTable* table, std::string* key_out) {
  const std::string where = "--set " + assignment;
  const size_t eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0)
    return Status::InvalidInput(where + ": expected KEY=VALUE");
  const std::string key = assignment.substr(0, eq);
  const KeyEntry* entry = table->Find(key);
  if (!entry) {
    if (table->IsSection(key)) return Status::InvalidInput(where + ": " + key + ": is a section, not a key" + table->ChildKeys(key));
    return Status::InvalidInput(where + ": " + key + ": unknown key" + table->Suggest(key));
  }
  YAML::Node value;
  try {
    value = YAML::Load(assignment.substr(eq + 1));
  } catch (const YAML::Exception& e) {
    return Status::InvalidInput(where + ": " + key + ": value is not valid YAML: " + e.msg);
  }
  const std::string error = entry->set(value);
  if (!error.empty()) return Status::InvalidInput(where + ": " + KeyError(key, error));
  *key_out = key;
  return Status::Ok();
}

// Keys that are valid one by one but not together. The message names where the value came
// from: `--set KEY=VALUE` for the first key of the check given on the command line (the last
// such assignment), else the config file.
Status CheckKeysTogether(const Config& c, const std::string& source, const std::map<std::string, std::string>& overridden) {
  auto refuse = [&](std::initializer_list<const char*> keys, const std::string& message) {
    for (const char* key : keys)
      if (const auto it = overridden.find(key); it != overridden.end())
        return Status::InvalidInput("--set " + it->second + ": " + message);
    return Status::InvalidInput(source + ": " + message);
  };
  if (c.guidance.source == "file" && c.guidance.file.empty())
    return refuse({"guidance.source", "guidance.file"}, "guidance.file: required when guidance.source is file");
  const SectionOptions& section = c.analysis.section;
  const bool circular = section.shape == "circular_hollow";
  const double smallest = circular ? section.diameter : std::min(section.width, section.height);
  if (!(2.0 * section.thickness < smallest))
    return refuse({"analysis.section.thickness", "analysis.section.shape", "analysis.section.diameter",
                   "analysis.section.width", "analysis.section.height"},
                  "analysis.section.thickness: " + FormatNumber(section.thickness) + " m leaves no hollow in a " +
                      (circular ? "tube of analysis.section.diameter " : "box whose smaller side is ") +
                      FormatNumber(smallest) + " m (it must be less than half of that)");
  if (c.levelset.joint_iterations == 0 && !c.levelset.separate_solves)
    return refuse({"levelset.joint_iterations", "levelset.separate_solves"},
                  "levelset.joint_iterations: 0 leaves the level sets unsolved (the initial guess) unless "
                  "levelset.separate_solves is true");
  const AnalysisOptions& a = c.analysis;
  if (a.panel_load == 0.0 && a.material.density * a.gravity == 0.0)
    return refuse({"analysis.panel_load", "analysis.material.density", "analysis.gravity"},
                  "analysis.panel_load: the frame carries no load (analysis.panel_load and the steel's weight, "
                  "analysis.material.density × analysis.gravity, are both 0), so its compliance would be 0");
  return Status::Ok();
}

}  // namespace

Status ParseConfig(const std::string& yaml_text, const std::string& source_name,
                   const std::string& base_dir, const std::vector<std::string>& overrides,
                   Config* config) {
  *config = Config();
  KeyTable table(config);
  table.set_base_dir(base_dir);
  table.set_source(source_name, true);
  YAML::Node root;
  try {
    root = YAML::Load(yaml_text);
  } catch (const YAML::Exception& e) {
    const std::string line = e.mark.is_null() ? "" : ":" + std::to_string(e.mark.line + 1);
    return Status::InvalidInput(source_name + line + ": YAML syntax error: " + e.msg);
  }
  std::set<std::string> file_keys;
  if (!root.IsNull()) {
    if (!root.IsMap()) return Status::InvalidInput(source_name + ": expected a mapping of config keys at the top level");
    PQ_RETURN_IF_ERROR(ApplyMapping(root, "", source_name, &table, &file_keys));
  }
  auto& surface = config->surface;
  if (file_keys.count("surface.file") && file_keys.count("surface.generator") && !surface.file.empty() &&
      !surface.generator.empty())
    return Status::InvalidInput(source_name + ": surface: set either surface.file or surface.generator, not both");
  if (!surface.file.empty()) surface.generator.clear();

  table.set_base_dir("");  // paths given on the command line are relative to the working directory
  table.set_source("--set boundary.rules", false);
  std::map<std::string, std::string> overridden;  // key → its (last) assignment on the command line
  for (const auto& assignment : overrides) {
    std::string key;
    PQ_RETURN_IF_ERROR(ApplyOverride(assignment, &table, &key));
    overridden[key] = assignment;
    // The surface comes from one source: setting one of the two clears the other.
    if (key == "surface.file" && !surface.file.empty()) surface.generator.clear();
    if (key == "surface.generator" && !surface.generator.empty()) surface.file.clear();
  }
  if (surface.file.empty() && surface.generator.empty())
    return Status::InvalidInput(source_name + ": surface: set surface.file or surface.generator");
  return CheckKeysTogether(*config, source_name, overridden);
}

Status LoadConfig(const std::string& path, const std::vector<std::string>& overrides, Config* config) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::exists(path, ec)) return Status::InvalidInput(path + ": config file not found");
  if (!fs::is_regular_file(path, ec)) return Status::InvalidInput(path + ": not a config file (a folder?)");
  std::ifstream in(path);
  if (!in) return Status::InvalidInput(path + ": cannot read config file");
  std::stringstream text;
  text << in.rdbuf();
  return ParseConfig(text.str(), path, fs::path(path).parent_path().string(), overrides, config);
}

json ConfigToJson(const Config& config) {
  Config copy = config;
  KeyTable table(&copy);
  json out = json::object();
  for (const auto& e : table.entries()) {
    std::string pointer = "/" + e.key;
    std::replace(pointer.begin(), pointer.end(), '.', '/');
    out[json::json_pointer(pointer)] = e.get();
  }
  return out;
}

json ConfigReference() {
  Config defaults;
  KeyTable table(&defaults);
  json keys = json::array();
  for (const auto& e : table.entries())
    keys.push_back({{"key", e.key}, {"type", e.type}, {"default", e.get()}, {"meaning", e.comment}});
  return keys;
}

std::string ConfigReferenceMarkdown() {
  std::ostringstream s;
  s << "| key | type | default | meaning |\n|---|---|---|---|\n";
  for (const auto& e : ConfigReference()) {
    std::string type = e["type"].get<std::string>();
    std::replace(type.begin(), type.end(), '|', '/');
    s << "| `" << e["key"].get<std::string>() << "` | " << type << " | `" << e["default"].dump() << "` | "
      << e["meaning"].get<std::string>() << " |\n";
  }
  return s.str();
}

}  // namespace pqlayout

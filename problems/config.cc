#include "problems/config.h"

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

namespace pqlayout {

const char* BoundaryConditionName(BoundaryCondition c) {
  switch (c) {
    case BoundaryCondition::kFixed: return "fixed";
    case BoundaryCondition::kFree: return "free";
    case BoundaryCondition::kClamped: return "clamped";
    case BoundaryCondition::kSliding: return "sliding";
  }
  return "?";
}

namespace {

using nlohmann::json;
constexpr double kInf = std::numeric_limits<double>::infinity();

// A closed or open interval for numeric keys.
struct Range {
  double lo = -kInf, hi = kInf;
  bool lo_open = false, hi_open = false;
  bool Contains(double v) const {
    return (lo_open ? v > lo : v >= lo) && (hi_open ? v < hi : v <= hi);
  }
  std::string Describe() const {
    std::ostringstream s;
    if (hi == kInf) s << (lo_open ? "> " : ">= ") << lo;
    else if (lo == -kInf) s << (hi_open ? "< " : "<= ") << hi;
    else s << "in " << (lo_open ? "(" : "[") << lo << ", " << hi << (hi_open ? ")" : "]");
    return s.str();
  }
};
const Range kPositive{0.0, kInf, true, false};
const Range kNonNegative{0.0, kInf, false, false};
const Range kFraction{0.0, 1.0, false, false};

std::string Describe(const YAML::Node& n) {
  switch (n.Type()) {
    case YAML::NodeType::Scalar: return "'" + n.Scalar() + "'";
    case YAML::NodeType::Sequence: return "a list";
    case YAML::NodeType::Map: return "a mapping";
    default: return "nothing";
  }
}

template <typename T>
bool ScalarAs(const YAML::Node& n, T* value) {
  if (!n.IsScalar()) return false;
  try {
    *value = n.as<T>();
    return true;
  } catch (const YAML::Exception&) {
    return false;
  }
}

// Converts a list node (yaml-cpp's as<std::vector<T>>), false if any element does not convert.
template <typename T>
bool ListAs(const YAML::Node& n, std::vector<T>* value) {
  if (!n.IsSequence()) return false;
  try {
    *value = n.as<std::vector<T>>();
    return true;
  } catch (const YAML::Exception&) {
    return false;
  }
}

std::string FormatNumber(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

// The schema: every key bound to a field. Setters return "" or the reason a value is refused.
struct KeyEntry {
  std::string key, type, comment;
  std::function<std::string(const YAML::Node&)> set;
  std::function<json()> get;
};

class KeyTable {
 public:
  explicit KeyTable(Config* c);
  KeyTable(const KeyTable&) = delete;

  const KeyEntry* Find(const std::string& key) const {
    for (const auto& e : entries_)
      if (e.key == key) return &e;
    return nullptr;
  }
  bool IsSection(const std::string& prefix) const {
    for (const auto& e : entries_)
      if (e.key.rfind(prefix + ".", 0) == 0) return true;
    return false;
  }
  std::string Suggest(const std::string& key) const;
  const std::vector<KeyEntry>& entries() const { return entries_; }
  void set_base_dir(std::string dir) { base_dir_ = std::move(dir); }
  std::string ResolvePath(const std::string& p) const {
    if (p.empty() || std::filesystem::path(p).is_absolute() || base_dir_.empty()) return p;
    return (std::filesystem::path(base_dir_) / p).lexically_normal().string();
  }

 private:
  void Number(const std::string& key, double* f, Range r, const std::string& comment) {
    entries_.push_back({key, "number", comment, [f, r](const YAML::Node& n) -> std::string {
      double v;
      if (!ScalarAs(n, &v)) return "expected a number, got " + Describe(n);
      if (!std::isfinite(v)) return "must be a finite number";
      if (!r.Contains(v)) return "must be " + r.Describe() + " (got " + FormatNumber(v) + ")";
      *f = v;
      return "";
    }, [f] { return json(*f); }});
  }
  void Integer(const std::string& key, int* f, int lo, int hi, const std::string& comment) {
    entries_.push_back({key, "integer", comment, [f, lo, hi](const YAML::Node& n) -> std::string {
      int v;
      if (!ScalarAs(n, &v)) return "expected an integer, got " + Describe(n);
      if (v < lo || v > hi)
        return "must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "] (got " + std::to_string(v) + ")";
      *f = v;
      return "";
    }, [f] { return json(*f); }});
  }
  void Bool(const std::string& key, bool* f, const std::string& comment) {
    entries_.push_back({key, "boolean", comment, [f](const YAML::Node& n) -> std::string {
      bool v;
      if (!ScalarAs(n, &v)) return "expected true or false, got " + Describe(n);
      *f = v;
      return "";
    }, [f] { return json(*f); }});
  }
  void Path(const std::string& key, std::string* f, const std::string& comment) {
    entries_.push_back({key, "path", comment, [this, f](const YAML::Node& n) -> std::string {
      if (n.IsNull()) { f->clear(); return ""; }
      if (!n.IsScalar()) return "expected a file path, got " + Describe(n);
      *f = ResolvePath(n.Scalar());
      return "";
    }, [f] { return json(*f); }});
  }
  void Choice(const std::string& key, std::string* f, std::vector<std::string> allowed,
              const std::string& comment) {
    std::string list;
    for (const auto& a : allowed) list += (list.empty() ? "" : " | ") + (a.empty() ? "\"\"" : a);
    entries_.push_back({key, list, comment, [f, allowed, list](const YAML::Node& n) -> std::string {
      std::string v;
      if (n.IsNull()) v.clear();
      else if (!ScalarAs(n, &v)) return "expected one of " + list + ", got " + Describe(n);
      if (std::find(allowed.begin(), allowed.end(), v) == allowed.end())
        return "unknown value '" + v + "' (expected " + list + ")";
      *f = v;
      return "";
    }, [f] { return json(*f); }});
  }
  void Condition(const std::string& key, BoundaryCondition* f, const std::string& comment);
  void Rules(const std::string& key, std::vector<BoundaryRule>* f, const std::string& comment);

  std::vector<KeyEntry> entries_;
  std::string base_dir_;
};

bool ParseCondition(const YAML::Node& n, BoundaryCondition* c) {
  std::string s;
  if (!ScalarAs(n, &s)) return false;
  for (auto k : {BoundaryCondition::kFixed, BoundaryCondition::kFree, BoundaryCondition::kClamped,
                 BoundaryCondition::kSliding}) {
    if (s == BoundaryConditionName(k)) {
      *c = k;
      return true;
    }
  }
  return false;
}
const char* kConditionList = "fixed | free | clamped | sliding";

void KeyTable::Condition(const std::string& key, BoundaryCondition* f, const std::string& comment) {
  entries_.push_back({key, kConditionList, comment, [f](const YAML::Node& n) -> std::string {
    if (!ParseCondition(n, f)) return "expected one of " + std::string(kConditionList) + ", got " + Describe(n);
    return "";
  }, [f] { return json(BoundaryConditionName(*f)); }});
}

// select: all | outer | inner | corners | {loop: N} | {box: [x0,y0,z0,x1,y1,z1]} |
//         {ids: [...]} | {ids_file: PATH}
std::string ParseSelector(const YAML::Node& n, const KeyTable& table, BoundarySelector* s) {
  const std::string expected =
      "expected all, outer, inner, corners, or a mapping with one of loop, box, ids, ids_file";
  using K = BoundarySelector::Kind;
  if (n.IsScalar()) {
    const std::map<std::string, K> names{{"all", K::kAll}, {"outer", K::kOuter},
                                         {"inner", K::kInner}, {"corners", K::kCorners}};
    const auto it = names.find(n.Scalar());
    if (it == names.end()) return "unknown selector '" + n.Scalar() + "' (" + expected + ")";
    s->kind = it->second;
    return "";
  }
  if (!n.IsMap() || n.size() != 1) return expected + ", got " + Describe(n);
  const std::string kind = n.begin()->first.as<std::string>();
  const YAML::Node v = n.begin()->second;
  if (kind == "loop") {
    if (ScalarAs(v, &s->loop) && s->loop >= 0) { s->kind = K::kLoop; return ""; }
    return "loop: expected a loop index >= 0, got " + Describe(v);
  }
  if (kind == "box") {
    std::vector<double> b;
    if (v.size() != 6 || !ListAs(v, &b))
      return "box: expected [xmin, ymin, zmin, xmax, ymax, zmax], got " + Describe(v);
    s->box_min = Eigen::Vector3d(b[0], b[1], b[2]);
    s->box_max = Eigen::Vector3d(b[3], b[4], b[5]);
    if ((s->box_min.array() > s->box_max.array()).any()) return "box: min corner exceeds max corner";
    s->kind = K::kBox;
    return "";
  }
  if (kind == "ids") {
    if (!ListAs(v, &s->ids)) return "ids: expected a list of vertex ids, got " + Describe(v);
    s->kind = K::kIds;
    return "";
  }
  if (kind == "ids_file") {
    if (!v.IsScalar()) return "ids_file: expected a file path, got " + Describe(v);
    s->ids_file = table.ResolvePath(v.Scalar());
    s->kind = K::kIdsFile;
    return "";
  }
  return "unknown selector '" + kind + "' (" + expected + ")";
}

json SelectorToJson(const BoundarySelector& s) {
  using K = BoundarySelector::Kind;
  switch (s.kind) {
    case K::kAll: return "all";
    case K::kOuter: return "outer";
    case K::kInner: return "inner";
    case K::kCorners: return "corners";
    case K::kLoop: return json{{"loop", s.loop}};
    case K::kBox:
      return json{{"box", {s.box_min.x(), s.box_min.y(), s.box_min.z(), s.box_max.x(), s.box_max.y(), s.box_max.z()}}};
    case K::kIds: return json{{"ids", s.ids}};
    case K::kIdsFile: return json{{"ids_file", s.ids_file}};
  }
  return nullptr;
}

void KeyTable::Rules(const std::string& key, std::vector<BoundaryRule>* f, const std::string& comment) {
  entries_.push_back({key, "list", comment, [this, f](const YAML::Node& n) -> std::string {
    if (n.IsNull()) { f->clear(); return ""; }
    if (!n.IsSequence()) return "expected a list of {select: ..., condition: ...}, got " + Describe(n);
    std::vector<BoundaryRule> rules;
    for (size_t i = 0; i < n.size(); ++i) {
      const YAML::Node item = n[i];
      const std::string where = "[" + std::to_string(i) + "]";
      if (!item.IsMap()) return where + ": expected {select: ..., condition: ...}, got " + Describe(item);
      BoundaryRule rule;
      rule.origin = "line " + std::to_string(item.Mark().line + 1);
      bool has_select = false, has_condition = false;
      for (const auto& kv : item) {
        const std::string k = kv.first.as<std::string>();
        if (k == "select") {
          const std::string err = ParseSelector(kv.second, *this, &rule.select);
          if (!err.empty()) return where + ".select: " + err;
          has_select = true;
        } else if (k == "condition") {
          if (!ParseCondition(kv.second, &rule.condition))
            return where + ".condition: expected one of " + std::string(kConditionList) + ", got " + Describe(kv.second);
          has_condition = true;
        } else {
          return where + ": unknown key '" + k + "' (a rule has select and condition)";
        }
      }
      if (!has_select || !has_condition) return where + ": a rule needs both select and condition";
      rules.push_back(rule);
    }
    *f = std::move(rules);
    return "";
  }, [f] {
    json list = json::array();
    for (const auto& r : *f)
      list.push_back({{"select", SelectorToJson(r.select)}, {"condition", BoundaryConditionName(r.condition)}});
    return list;
  }});
}

KeyTable::KeyTable(Config* c) {
  Integer("threads", &c->threads, 1, 256,
          "threads of Ceres, OpenBLAS and OpenMP; 1 (default) gives bit-identical results on every machine, more may not");
  auto& s = c->surface;
  Path("surface.file", &s.file, "reference mesh (OBJ, PLY, OFF or STL; metres); relative paths are relative to the config file");
  Choice("surface.generator", &s.generator, {"", "great_court", "dome", "hypar", "barrel", "plane", "disk", "annulus"},
         "built-in reference surface, used when surface.file is empty");
  Number("surface.edge_length", &s.edge_length, kPositive, "generator: target triangle edge length, m");
  Number("surface.width", &s.width, kPositive, "generator: x extent, m (disk, annulus: outer diameter)");
  Number("surface.depth", &s.depth, kPositive, "generator: y extent, m (annulus: inner diameter)");
  Number("surface.rise", &s.rise, kNonNegative, "generator: crown height above the supports, m (dome, hypar, barrel)");

  Condition("boundary.default", &c->boundary.default_condition, "support of every boundary vertex unless a rule overrides it");
  Rules("boundary.rules", &c->boundary.rules,
        "list of {select, condition}, applied in order; select: all | outer | inner | corners | {loop: N} | "
        "{box: [xmin, ymin, zmin, xmax, ymax, zmax]} | {ids: [...]} | {ids_file: PATH}");

  Number("load.q", &c->load.q, kPositive, "dead load per area for the membrane solve, N/m²");
  Number("membrane.stiffness", &c->membrane.stiffness, kPositive, "λ_m, membrane stiffness, N/m: v scales with 1/λ_m; the strain directions depend on it only through ε's quadratic term ½∇v∇vᵀ");
  Number("membrane.bending", &c->membrane.bending, kNonNegative, "λ_b, bending stiffness, N·m (0 = pure membrane, as in the paper)");

  auto& g = c->guidance;
  Choice("guidance.source", &g.source, {"strain", "curvature", "file"},
         "guidance field: principal strain (the paper), principal curvature (the reference layout) or a CSV file");
  Number("guidance.threshold", &g.threshold, kFraction, "no alignment where |ε_max| < threshold × max |ε_max|");
  Number("guidance.ramp", &g.ramp, kFraction, "alignment weight ramps from 0 to 1 over [threshold, threshold + ramp] × max");
  Path("guidance.file", &g.file, "guidance.source = file: per-face CSV id,dx,dy,dz[,weight]");

  Number("layout.spacing", &c->layout.spacing, kPositive, "h, distance between neighbouring level lines, m");
  Choice("layout.density", &c->layout.density, {"auto", "spacing", "panel_area"},
         "spacing: level lines h apart; panel_area: φ, ψ then scaled together so that the mean panel area is h² (equal node counts for layouts that cross at different angles); auto: panel_area in `compare`, spacing otherwise");

  auto& lw = c->levelset.weights;
  Number("levelset.weights.alignment", &lw.alignment, kNonNegative, "φ's level lines follow the guidance field");
  Number("levelset.weights.spacing", &lw.spacing, kNonNegative, "even spacing: h|∇φ| = 1, h|∇ψ| = 1");
  Number("levelset.weights.smoothness", &lw.smoothness, kNonNegative, "gradient difference across interior edges");
  Number("levelset.weights.conjugacy", &lw.conjugacy, kNonNegative, "the two families are conjugate: II(n×∇φ, n×∇ψ) = 0");
  Number("levelset.weights.transversality", &lw.transversality, kNonNegative, "crossing angle of the families ≥ levelset.min_angle");
  Number("levelset.min_angle", &c->levelset.min_angle, Range{0.0, 90.0, true, true}, "minimum crossing angle of the two families, degrees");
  Integer("levelset.max_iterations", &c->levelset.max_iterations, 1, 100000, "Ceres iterations of the φ solve and of the ψ solve");
  Integer("levelset.joint_iterations", &c->levelset.joint_iterations, 0, 100000,
          "Ceres iterations of the final solve of φ and ψ together (0: none)");
  Integer("levelset.crossing_rounds", &c->levelset.crossing_rounds, 0, 100,
          "local re-solves after it that raise transversality on the faces still crossing below levelset.min_angle (0: none)");
  Bool("levelset.seams", &c->levelset.seams,
       "cut seams from the guidance's ±½ singularities and from holes to the boundary; φ, ψ jump by whole levels "
       "across them (branch points, as in the paper's curvature reference); false: single-valued φ, ψ");
  Number("levelset.working_edge", &c->levelset.working_edge, kNonNegative,
         "edge length of the mesh φ, ψ are solved on, m (0: 0.4 h); a reference finer than 0.7 × this is remeshed");

  Number("extract.corner_angle", &c->extract.corner_angle, Range{0.0, 180.0, true, true}, "boundary turning angle above which a vertex is a corner, degrees");
  Number("extract.min_edge", &c->extract.min_edge, Range{0.0, 1.0, false, true}, "edges shorter than min_edge × h are merged");
  Number("extract.boundary_tolerance", &c->extract.boundary_tolerance, Range{0.0, 1.0, false, true}, "mesh boundary edges further than this × h from a curved reference boundary get an extra boundary vertex (0: never)");

  auto& pw = c->planarize.weights;
  Number("planarize.weights.planarity", &pw.planarity, kNonNegative, "faces planar");
  Number("planarize.weights.closeness", &pw.closeness, kNonNegative, "vertices stay on the reference surface");
  Number("planarize.weights.boundary", &pw.boundary, kNonNegative, "boundary vertices stay on the reference boundary");
  Number("planarize.weights.fairness", &pw.fairness, kNonNegative, "second differences along the mesh polylines");
  Number("planarize.weights.anchor", &pw.anchor, kNonNegative, "vertices stay near where the layout put them");
  Number("planarize.weights.edge_length", &pw.edge_length, kNonNegative,
         "× the planarity weight: no edge shrinks below a quarter of its extracted length (or of h); 0: off");
  Number("planarize.target_delta", &c->planarize.target_delta, kPositive, "stop when max planarity δ ≤ target_delta");
  Integer("planarize.max_rounds", &c->planarize.max_rounds, 1, 1000, "outer rounds (planarity weight raised after each)");

  auto& a = c->analysis;
  Number("analysis.panel_load", &a.panel_load, kNonNegative, "panel dead load, N/m² of face area");
  Number("analysis.gravity", &a.gravity, kNonNegative, "g, m/s²");
  Bool("analysis.export_calculix", &a.export_calculix, "also write analysis/model.inp for CalculiX");
  Choice("analysis.calculix_element", &a.calculix_element, {"u1", "b32r"},
         "CalculiX beam: u1 = ccx's 2-node beam with the model's Euler–Bernoulli stiffness; b32r = 3-node beam ccx expands to bricks of the true section");
  Integer("analysis.calculix_subdivisions", &a.calculix_subdivisions, 1, 64, "CalculiX elements per member (b32r converges as this grows)");
  Number("analysis.material.youngs_modulus", &a.material.youngs_modulus, kPositive, "E, Pa");
  Number("analysis.material.poisson_ratio", &a.material.poisson_ratio, Range{-1.0, 0.5, true, true}, "ν; G = E / (2(1+ν))");
  Number("analysis.material.density", &a.material.density, kNonNegative, "ρ, kg/m³");
  Choice("analysis.section.shape", &a.section.shape, {"circular_hollow", "rectangular_hollow"}, "member cross-section");
  Number("analysis.section.diameter", &a.section.diameter, kPositive, "circular hollow: outside diameter D, m");
  Number("analysis.section.thickness", &a.section.thickness, kPositive, "wall thickness t, m");
  Number("analysis.section.width", &a.section.width, kPositive, "rectangular hollow: width (in the surface), m");
  Number("analysis.section.height", &a.section.height, kPositive, "rectangular hollow: height (along the surface normal), m");
}

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

// Walks a YAML mapping, setting every leaf it finds; records the keys it set.
Status ApplyMapping(const YAML::Node& node, const std::string& prefix, const std::string& source,
                    KeyTable* table, std::set<std::string>* set_keys) {
  std::set<std::string> seen;
  for (const auto& kv : node) {
    const std::string where = source + ":" + std::to_string(kv.first.Mark().line + 1);
    if (!kv.first.IsScalar()) return Status::InvalidInput(where + ": keys must be plain names");
    const std::string name = kv.first.Scalar();
    const std::string key = prefix.empty() ? name : prefix + "." + name;
    if (!seen.insert(name).second) return Status::InvalidInput(where + ": " + key + ": duplicate key");
    if (const KeyEntry* entry = table->Find(key)) {
      const std::string error = entry->set(kv.second);
      if (!error.empty()) return Status::InvalidInput(where + ": " + key + ": " + error);
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
    const std::string what = table->IsSection(key) ? "is a section, not a key" : "unknown key";
    return Status::InvalidInput(where + ": " + key + ": " + what + table->Suggest(key));
  }
  YAML::Node value;
  try {
    value = YAML::Load(assignment.substr(eq + 1));
  } catch (const YAML::Exception& e) {
    return Status::InvalidInput(where + ": " + key + ": value is not valid YAML: " + e.msg);
  }
  const std::string error = entry->set(value);
  if (!error.empty()) return Status::InvalidInput(where + ": " + key + ": " + error);
  *key_out = key;
  return Status::Ok();
}

}  // namespace

Status ParseConfig(const std::string& yaml_text, const std::string& source_name,
                   const std::string& base_dir, const std::vector<std::string>& overrides,
                   Config* config) {
  *config = Config();
  KeyTable table(config);
  table.set_base_dir(base_dir);
  YAML::Node root;
  try {
    root = YAML::Load(yaml_text);
  } catch (const YAML::ParserException& e) {
    return Status::InvalidInput(source_name + ":" + std::to_string(e.mark.line + 1) + ": YAML syntax error: " + e.msg);
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
  for (const auto& assignment : overrides) {
    std::string key;
    PQ_RETURN_IF_ERROR(ApplyOverride(assignment, &table, &key));
    // The surface comes from one source: setting one of the two clears the other.
    if (key == "surface.file" && !surface.file.empty()) surface.generator.clear();
    if (key == "surface.generator" && !surface.generator.empty()) surface.file.clear();
  }
  if (surface.file.empty() && surface.generator.empty())
    return Status::InvalidInput(source_name + ": surface: set surface.file or surface.generator");
  return Status::Ok();
}

Status LoadConfig(const std::string& path, const std::vector<std::string>& overrides, Config* config) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) return Status::InvalidInput(path + ": config file not found");
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

std::string ConfigReferenceMarkdown() {
  Config defaults;
  KeyTable table(&defaults);
  std::ostringstream s;
  s << "| key | type | default | meaning |\n|---|---|---|---|\n";
  for (const auto& e : table.entries()) {
    std::string type = e.type;
    std::replace(type.begin(), type.end(), '|', '/');
    s << "| `" << e.key << "` | " << type << " | `" << e.get().dump() << "` | " << e.comment << " |\n";
  }
  return s.str();
}

}  // namespace pqlayout

#include "pipeline/config_rules.h"

#include <cmath>
#include <limits>
#include <map>

#include "pipeline/config_yaml.h"

namespace pqlayout {

using config_yaml::Describe;
using config_yaml::KeyName;
using config_yaml::ScalarAs;
using nlohmann::json;

const char* const kConditionList = "fixed | free | clamped | sliding";

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

namespace {

// Vertex ids are checked element by element: yaml-cpp would turn -1 into an int, and a
// negative id once indexed the per-vertex conditions out of bounds (heap corruption).
std::string ParseIds(const YAML::Node& v, std::vector<int>* ids) {
  if (!v.IsSequence()) return ".ids: expected a list of vertex ids, got " + Describe(v);
  for (size_t i = 0; i < v.size(); ++i) {
    long long id = -1;
    if (!ScalarAs(v[i], &id) || id < 0 || id > std::numeric_limits<int>::max())
      return ".ids: " + Describe(v[i]) + " is not a vertex id (ids are whole numbers from 0)";
    ids->push_back(static_cast<int>(id));
  }
  return "";
}

std::string ParseBox(const YAML::Node& v, BoundarySelector* s) {
  const std::string expected = ".box: expected [xmin, ymin, zmin, xmax, ymax, zmax]";
  if (!v.IsSequence() || v.size() != 6) return expected + ", got " + Describe(v);
  double b[6];
  for (size_t i = 0; i < 6; ++i)
    if (!ScalarAs(v[i], &b[i]) || !std::isfinite(b[i])) return expected + ": " + Describe(v[i]) + " is not a finite number";
  s->box_min = Eigen::Vector3d(b[0], b[1], b[2]);
  s->box_max = Eigen::Vector3d(b[3], b[4], b[5]);
  if ((s->box_min.array() > s->box_max.array()).any()) return ".box: min corner exceeds max corner";
  s->kind = BoundarySelector::Kind::kBox;
  return "";
}

// Messages about a selector's value start with its key (".ids: ..."), others do not.
// select: all | outer | inner | corners | {loop: N} | {box: [x0,y0,z0,x1,y1,z1]} |
//         {ids: [...]} | {ids_file: PATH}
std::string ParseSelector(const YAML::Node& n, const RuleSource& source, BoundarySelector* s) {
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
  std::string kind;
  if (!n.IsMap() || n.size() != 1) return expected + ", got " + Describe(n);
  if (!KeyName(n.begin()->first, &kind)) return expected + ", got " + Describe(n.begin()->first) + " as a key";
  const YAML::Node v = n.begin()->second;
  if (kind == "loop") {
    if (ScalarAs(v, &s->loop) && s->loop >= 0) { s->kind = K::kLoop; return ""; }
    return ".loop: expected a loop index >= 0, got " + Describe(v);
  }
  if (kind == "box") return ParseBox(v, s);
  if (kind == "ids") {
    s->kind = K::kIds;
    return ParseIds(v, &s->ids);
  }
  if (kind == "ids_file") {
    if (!v.IsScalar()) return ".ids_file: expected a file path, got " + Describe(v);
    s->ids_file = source.resolve_path(v.Scalar());
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

std::string ParseRule(const YAML::Node& item, const RuleSource& source, BoundaryRule* rule) {
  if (!item.IsMap()) return ": expected {select: ..., condition: ...}, got " + Describe(item);
  rule->origin = source.name + (source.with_lines ? ":" + std::to_string(item.Mark().line + 1) : "");
  bool has_select = false, has_condition = false;
  for (const auto& kv : item) {
    std::string k;
    if (!KeyName(kv.first, &k)) return ": expected the keys select and condition, got " + Describe(kv.first);
    if (k == "select") {
      const std::string err = ParseSelector(kv.second, source, &rule->select);
      if (!err.empty()) return ".select" + std::string(err[0] == '.' ? "" : ": ") + err;
      has_select = true;
    } else if (k == "condition") {
      if (!ParseCondition(kv.second, &rule->condition))
        return ".condition: expected one of " + std::string(kConditionList) + ", got " + Describe(kv.second);
      has_condition = true;
    } else {
      return ": unknown key '" + k + "' (a rule has select and condition)";
    }
  }
  if (!has_select || !has_condition) return ": a rule needs both select and condition";
  return "";
}

}  // namespace

std::string ParseBoundaryRules(const YAML::Node& n, const RuleSource& source, std::vector<BoundaryRule>* rules) {
  if (n.IsNull()) {
    rules->clear();
    return "";
  }
  if (!n.IsSequence()) return "expected a list of {select: ..., condition: ...}, got " + Describe(n);
  std::vector<BoundaryRule> parsed(n.size());
  for (size_t i = 0; i < n.size(); ++i) {
    const std::string error = ParseRule(n[i], source, &parsed[i]);
    if (!error.empty()) return "[" + std::to_string(i) + "]" + error;
  }
  *rules = std::move(parsed);
  return "";
}

json BoundaryRulesToJson(const std::vector<BoundaryRule>& rules) {
  json list = json::array();
  for (const auto& r : rules)
    list.push_back({{"select", SelectorToJson(r.select)}, {"condition", BoundaryConditionName(r.condition)}});
  return list;
}

}  // namespace pqlayout

// Internal to the config parser (pipeline/config.cc; the public interface is pipeline/config.h):
// the key table, i.e. every config key bound to its field with its type, range and meaning,
// and the typed registrations (Number, Integer, Bool, Path, Choice, Condition, Rules) that
// parse and check one YAML value each. Split from config.cc to keep each file under ~500 lines.
#pragma once

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "pipeline/config.h"
#include "pipeline/config_rules.h"
#include "pipeline/config_yaml.h"

namespace pqlayout {
namespace config_internal {

using config_yaml::Describe;
using config_yaml::FormatNumber;
using config_yaml::KeyName;
using config_yaml::ScalarAs;
using nlohmann::json;
constexpr double kInf = std::numeric_limits<double>::infinity();

// A closed or open interval for numeric keys. A `cap` interval is a one-sided range whose
// upper end only keeps out absurd values: its messages name the bound that was crossed.
struct Range {
  double lo = -kInf, hi = kInf;
  bool lo_open = false, hi_open = false;
  bool cap = false;
  bool AboveLow(double v) const { return lo_open ? v > lo : v >= lo; }
  bool Contains(double v) const { return AboveLow(v) && (hi_open ? v < hi : v <= hi); }
  std::string Describe(double v) const {
    std::ostringstream s;
    if (hi == kInf || (cap && !AboveLow(v))) s << (lo_open ? "> " : ">= ") << lo;
    else if (lo == -kInf || cap) s << (hi_open ? "< " : "<= ") << hi;
    else s << "in " << (lo_open ? "(" : "[") << lo << ", " << hi << (hi_open ? ")" : "]");
    return s.str();
  }
};
// Every number has a finite upper bound: a value like 1e300 is a typo, and downstream it
// overflows (v_z = q L² / λ_m, costs of weight × residual²) or reaches a float-to-int cast.
inline Range Positive(double hi) { return {0.0, hi, true, false, true}; }
inline Range NonNegative(double hi) { return {0.0, hi, false, false, true}; }
inline Range AtLeast(double lo, double hi) { return {lo, hi, false, false, true}; }
inline const Range kFraction{0.0, 1.0, false, false};
constexpr double kMaxLength = 1e5;     // m: 100 km, no roof is larger
constexpr double kMaxWeight = 1e6;     // residual weights (the README's sweeps stay below 1e4)
constexpr double kMaxPressure = 1e7;   // N/m²: 1000 t per m²
constexpr double kMaxModulus = 1e15;   // Pa, N/m, N·m
constexpr double kMinSection = 1e-4;   // m: thinner members make the frame singular, not light

// "key: reason", or "key[1].select: reason" when the reason starts with a list index.
inline std::string KeyError(const std::string& key, const std::string& reason) {
  return key + (reason.rfind('[', 0) == 0 ? "" : ": ") + reason;
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
  // "; its keys: a.b.c, a.b.d, …" — the keys and sections one level below a section (the
  // first eight), for a `--set` that names a section.
  std::string ChildKeys(const std::string& section) const {
    std::vector<std::string> children;
    for (const auto& e : entries_) {
      if (e.key.rfind(section + ".", 0) != 0) continue;
      const std::string child = e.key.substr(0, e.key.find('.', section.size() + 1));
      if (std::find(children.begin(), children.end(), child) == children.end()) children.push_back(child);
    }
    std::string list;
    for (size_t k = 0; k < children.size() && k < 8; ++k) list += (k > 0 ? ", " : "") + children[k];
    return "; its keys: " + list + (children.size() > 8 ? ", …" : "");
  }
  std::string Suggest(const std::string& key) const;
  const std::vector<KeyEntry>& entries() const { return entries_; }
  void set_base_dir(std::string dir) { base_dir_ = std::move(dir); }
  // Where values come from, for the origin of boundary rules ("cfg.yaml" with lines, or "--set").
  void set_source(std::string name, bool with_lines) {
    source_name_ = std::move(name);
    source_lines_ = with_lines;
  }
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
      if (!r.Contains(v)) return "must be " + r.Describe(v) + " (got " + FormatNumber(v) + ")";
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
  std::string base_dir_, source_name_;
  bool source_lines_ = false;
};

inline void KeyTable::Condition(const std::string& key, BoundaryCondition* f, const std::string& comment) {
  entries_.push_back({key, kConditionList, comment, [f](const YAML::Node& n) -> std::string {
    if (!ParseCondition(n, f)) return "expected one of " + std::string(kConditionList) + ", got " + Describe(n);
    return "";
  }, [f] { return json(BoundaryConditionName(*f)); }});
}

inline void KeyTable::Rules(const std::string& key, std::vector<BoundaryRule>* f, const std::string& comment) {
  entries_.push_back({key, "list", comment, [this, f](const YAML::Node& n) -> std::string {
    const RuleSource source{source_name_, source_lines_, [this](const std::string& p) { return ResolvePath(p); }};
    return ParseBoundaryRules(n, source, f);
  }, [f] { return BoundaryRulesToJson(*f); }});
}

}  // namespace config_internal
}  // namespace pqlayout

// Parsing of `boundary.default` and `boundary.rules` (the supports), split from config.cc.
// Internal to the config parser: the public interface is pipeline/config.h.
#pragma once

#include <functional>
#include <string>

#include <nlohmann/json.hpp>
#include <yaml-cpp/yaml.h>

#include "problems/options.h"

namespace pqlayout {

extern const char* const kConditionList;  // "fixed | free | clamped | sliding"

// false if n is not one of the condition names.
bool ParseCondition(const YAML::Node& n, BoundaryCondition* c);

// Where a list of rules comes from, for BoundaryRule::origin.
struct RuleSource {
  std::string name;         // "cfg.yaml" or "--set boundary.rules"
  bool with_lines = false;  // append ":LINE" of each rule (a file; not a --set value)
  std::function<std::string(const std::string&)> resolve_path;  // for ids_file
};

// Parses a list of {select, condition}. Returns "" or the reason it is refused, starting with
// the offending element ("[1].select.ids: -1 is not a vertex id ...").
std::string ParseBoundaryRules(const YAML::Node& n, const RuleSource& source, std::vector<BoundaryRule>* rules);

nlohmann::json BoundaryRulesToJson(const std::vector<BoundaryRule>& rules);

}  // namespace pqlayout

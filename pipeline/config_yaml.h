// Small YAML helpers shared by the config parser (config.cc) and the boundary-rule parser
// (config_rules.cc). Every conversion reports failure instead of throwing, so that a wrong
// type becomes one line naming the key, never an uncaught yaml-cpp exception.
#pragma once

#include <yaml-cpp/yaml.h>

#include <sstream>
#include <string>
#include <vector>

namespace pqlayout::config_yaml {

// How a node reads in a message: 'value', "a list", "a mapping" or "nothing".
inline std::string Describe(const YAML::Node& n) {
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

// A mapping key as a plain name; false for a list or mapping used as a key (`[a]: 1`).
inline bool KeyName(const YAML::Node& key, std::string* name) {
  if (!key.IsScalar()) return false;
  *name = key.Scalar();
  return true;
}

inline std::string FormatNumber(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

}  // namespace pqlayout::config_yaml

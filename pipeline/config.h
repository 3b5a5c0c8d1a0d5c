// The run configuration: Config gathers the options struct of every stage (problems/options.h,
// one field per key with its default and comment); the table in config.cc binds each key to
// its field, type, range and comment, and is the single source for parsing, `--set`, the
// resolved config in report.json and the config reference (`pqlayout keys`).
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "base/status.h"
#include "problems/options.h"

namespace pqlayout {

struct Config {
  // Threads of every numerical library (Ceres, OpenBLAS, OpenMP). 1 gives the same bits on
  // every machine and every run; more can change the last bits and, through the non-convex
  // stages, the layout (solver/numerics.h).
  int threads = 1;
  SurfaceOptions surface;
  BoundaryOptions boundary;
  LoadOptions load;
  MembraneOptions membrane;
  GuidanceOptions guidance;
  LayoutOptions layout;
  LevelsetOptions levelset;
  ExtractOptions extract;
  PlanarizeOptions planarize;
  StiffenOptions stiffen;
  AnalysisOptions analysis;
  OutputOptions output;
};

// Reads a YAML config file and applies `--set KEY=VALUE` overrides (VALUE is YAML) after
// it, so overrides win. Relative paths in the file are resolved against the file's folder,
// those in overrides against the working directory. Unknown keys, wrong types and values
// out of range are InvalidInput naming the file, line and key.
Status LoadConfig(const std::string& path, const std::vector<std::string>& overrides, Config* config);

// Same from YAML text; source_name stands in for the file name in messages and
// base_dir is where relative paths are resolved from.
Status ParseConfig(const std::string& yaml_text, const std::string& source_name,
                   const std::string& base_dir, const std::vector<std::string>& overrides,
                   Config* config);

// The resolved config as nested JSON (every key, defaults included).
nlohmann::json ConfigToJson(const Config& config);

// The config reference: one object per key, {key, type, default, meaning}, in table order.
nlohmann::json ConfigReference();

// The config reference as a Markdown table: key, type, default, meaning.
std::string ConfigReferenceMarkdown();

}  // namespace pqlayout

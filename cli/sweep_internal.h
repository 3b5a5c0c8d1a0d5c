// Internal to cli/sweep.cc and cli/sweep_collect.cc: what both halves of the sweep use.
#pragma once

#include <filesystem>
#include <string>

namespace pqlayout {
namespace sweep_internal {

// The shortest text that reads back as exactly v ("0.1", "10", "1e-05").
std::string ShortestNumber(double v);

// A file's whole content ("" if it cannot be read).
std::string ReadText(const std::filesystem::path& path);

}  // namespace sweep_internal
}  // namespace pqlayout

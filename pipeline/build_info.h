// Version of pqlayout, the git revision it was built from and the versions of the libraries
// it was built against (generated at build time by cmake/WriteBuildInfo.cmake).
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace pqlayout {

struct BuildInfo {
  std::string version;
  std::string git_revision;
  std::vector<std::pair<std::string, std::string>> libraries;
};

const BuildInfo& GetBuildInfo();

}  // namespace pqlayout

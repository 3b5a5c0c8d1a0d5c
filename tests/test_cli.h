// Running the pqlayout executable from a test to its end: its exit code, stdout and stderr
// (tests/run_helpers.h: one the test can signal while it runs).
#pragma once

#include <sys/wait.h>

#include <algorithm>
#include <cstdlib>
#include <string>

#include "tests/run_helpers.h"

namespace pqlayout::testing {

struct CliResult {
  int exit_code = -1;
  std::string out, err;
};

// Runs a shell command in dir (stdout and stderr go to dir/stdout.txt and dir/stderr.txt).
inline CliResult RunInDir(const std::string& dir, const std::string& command) {
  const int status = std::system(("cd '" + dir + "' && " + command + " > stdout.txt 2> stderr.txt").c_str());
  CliResult r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = ReadFile(dir + "/stdout.txt");
  r.err = ReadFile(dir + "/stderr.txt");
  return r;
}

// Runs `pqlayout ARGS` in dir.
inline CliResult RunPqlayout(const std::string& dir, const std::string& args) {
  return RunInDir(dir, "'" PQLAYOUT_BINARY "' " + args);
}

inline int CountLines(const std::string& text) { return static_cast<int>(std::count(text.begin(), text.end(), '\n')); }

}  // namespace pqlayout::testing

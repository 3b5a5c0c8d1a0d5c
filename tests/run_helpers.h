// Helpers for tests of whole runs: pqlayout as a child process the test can signal (start
// it, wait for a file it writes, find its own children from /proc, wait for it), and
// snapshots of output folders.
#pragma once

#include <fcntl.h>
#include <signal.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace pqlayout::testing {

// Starts PQLAYOUT_BINARY with args in dir, stdout into dir/stdout.txt and stderr into
// dir/stderr.txt; returns its pid.
inline pid_t StartPqlayout(const std::string& dir, const std::vector<std::string>& args) {
  std::vector<std::string> all{PQLAYOUT_BINARY};
  all.insert(all.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : all) argv.push_back(a.data());
  argv.push_back(nullptr);
  const std::string out = dir + "/stdout.txt", err = dir + "/stderr.txt";
  const pid_t pid = ::fork();
  if (pid == 0) {  // only async-signal-safe calls until exec
    if (::chdir(dir.c_str()) != 0) ::_exit(126);
    const int o = ::open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int e = ::open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (o < 0 || e < 0 || ::dup2(o, STDOUT_FILENO) < 0 || ::dup2(e, STDERR_FILENO) < 0) ::_exit(126);
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }
  return pid;
}

// Waits for pid and returns its wait status.
inline int WaitFor(pid_t pid) {
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  return status;
}

// Whether pid has exited (then reaped, its wait status in *status); does not block.
inline bool Exited(pid_t pid, int* status) { return ::waitpid(pid, status, WNOHANG) == pid; }

// Polls predicate every 50 ms until it holds (true) or `attempts` polls have failed (false):
// a bound against a hang, not a time measurement.
inline bool WaitUntil(const std::function<bool()>& predicate, int attempts = 4000) {
  for (int i = 0; i < attempts; ++i) {
    if (predicate()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  return predicate();
}

// The live processes whose parent is `parent`, from /proc/PID/stat (field 4, after the
// parenthesised command name, which may itself hold spaces and parentheses).
inline std::vector<pid_t> ChildrenOf(pid_t parent) {
  std::vector<pid_t> children;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator("/proc", ec)) {
    const std::string name = entry.path().filename().string();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    std::ifstream in(entry.path() / "stat");
    std::string stat;
    std::getline(in, stat);
    const size_t close = stat.rfind(')');
    if (close == std::string::npos) continue;
    char state = 0;
    long ppid = 0;
    if (std::sscanf(stat.c_str() + close + 1, " %c %ld", &state, &ppid) == 2 && ppid == parent && state != 'Z')
      children.push_back(static_cast<pid_t>(std::stol(name)));
  }
  return children;
}

// Whether a process with this pid exists (a zombie counts: it has not been waited for).
inline bool ProcessExists(pid_t pid) { return ::kill(pid, 0) == 0 || errno == EPERM; }

// The first folder in `dir` whose name starts with `prefix`, or "".
inline std::string FindEntry(const std::string& dir, const std::string& prefix) {
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(dir, ec))
    if (entry.path().filename().string().rfind(prefix, 0) == 0) return entry.path().string();
  return "";
}

inline std::string ReadFile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Every file below dir (relative path → content); staging folders beside dir are not in it.
using Files = std::map<std::string, std::string>;
inline Files Snapshot(const std::string& dir) {
  Files files;
  std::error_code ec;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(dir, ec))
    if (entry.is_regular_file()) files[std::filesystem::relative(entry.path(), dir).string()] = ReadFile(entry.path());
  return files;
}

}  // namespace pqlayout::testing

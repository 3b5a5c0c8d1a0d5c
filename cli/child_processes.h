// The runs of `pqlayout sweep` as child processes: started and waited for by the sweep's
// worker threads, and stopped with the sweep. After SIGINT or SIGTERM (base/interrupt.h)
// the thread that waits for the workers calls ForwardInterrupt: every run in progress gets
// the same signal, exactly once, and no new run starts; the workers then wait for their runs
// to finish winding down, so an interrupted sweep leaves no orphans. Runs stay in the sweep's
// process group, so Ctrl-C in a terminal reaches them directly too; they count only the
// first signal, so the forwarded copy changes nothing.
#pragma once

#include <sys/types.h>

#include <mutex>
#include <set>
#include <string>
#include <vector>

namespace pqlayout {

class ChildProcesses {
 public:
  // Runs `executable args...` with stdout and stderr into log_path and waits for it. Returns
  // the wait status, or -1 if it did not run (*error says why: it could not be started, or
  // the sweep has been interrupted).
  int Run(const std::string& executable, const std::vector<std::string>& args, const std::string& log_path,
          std::string* error);

  // After SIGINT/SIGTERM: sends it to every child still running, once. Cheap otherwise, so
  // the waiting thread may call it in a polling loop.
  void ForwardInterrupt();

 private:
  std::mutex mutex_;
  std::set<pid_t> running_;  // started and not yet reaped
  bool forwarded_ = false;
};

// "pqlayout run exited with code 2", "... was killed by signal 9 (Killed)", ...
std::string DescribeExit(int status);

}  // namespace pqlayout

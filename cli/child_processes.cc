#include "cli/child_processes.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "base/interrupt.h"

extern char** environ;

namespace pqlayout {

int ChildProcesses::Run(const std::string& executable, const std::vector<std::string>& args,
                        const std::string& log_path, std::string* error) {
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  std::vector<std::string> all{executable};
  all.insert(all.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : all) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  int spawned = 0;
  {
    // Checked and started under the lock that ForwardInterrupt takes: a run starts before the
    // signal is forwarded (and receives it) or not at all.
    std::lock_guard<std::mutex> lock(mutex_);
    if (InterruptSignal() == 0) {
      spawned = posix_spawn(&pid, executable.c_str(), &actions, nullptr, argv.data(), environ);
      if (spawned == 0) running_.insert(pid);
    }
  }
  posix_spawn_file_actions_destroy(&actions);
  if (pid == 0) {
    *error = spawned != 0 ? "cannot start " + executable + ": " + std::strerror(spawned) : "interrupted";
    return -1;
  }
  // Wait for the exit without reaping (WNOWAIT), forget the pid, then reap: until it is
  // reaped the pid cannot be reused, so a forwarded signal never hits an unrelated process.
  siginfo_t info;
  while (waitid(P_PID, static_cast<id_t>(pid), &info, WEXITED | WNOWAIT) < 0 && errno == EINTR) {
  }
  {
    std::lock_guard<std::mutex> lock(mutex_);
    running_.erase(pid);
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) {
      *error = std::string("waitpid: ") + std::strerror(errno);
      return -1;
    }
  }
  return status;
}

void ChildProcesses::ForwardInterrupt() {
  const int signal = InterruptSignal();
  if (signal == 0) return;
  std::lock_guard<std::mutex> lock(mutex_);
  if (forwarded_) return;
  forwarded_ = true;
  for (const pid_t pid : running_) ::kill(pid, signal);
}

std::string DescribeExit(int status) {
  if (WIFEXITED(status)) {
    const int code = WEXITSTATUS(status);
    const std::string text = "pqlayout run exited with code " + std::to_string(code);
    return code == 128 + SIGINT || code == 128 + SIGTERM ? text + " (interrupted)" : text;
  }
  if (WIFSIGNALED(status)) {
    const int signal = WTERMSIG(status);
    return "pqlayout run was killed by signal " + std::to_string(signal) + " (" + strsignal(signal) + ")";
  }
  return "pqlayout run ended abnormally";
}

}  // namespace pqlayout

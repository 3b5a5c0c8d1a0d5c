#include "base/interrupt.h"

#include <signal.h>

#include <atomic>
#include <cstring>
#include <string>

namespace pqlayout {
namespace {

std::atomic<int> g_signal{0};
std::atomic<InterruptPoll> g_poll{nullptr};
thread_local const std::atomic<bool>* t_cancel = nullptr;
static_assert(std::atomic<int>::is_always_lock_free, "the handler may only touch a lock-free atomic");

extern "C" void RecordSignal(int signal) {
  int none = 0;
  g_signal.compare_exchange_strong(none, signal);  // the first signal wins; repeats are ignored
}

}  // namespace

void InstallInterruptHandlers() {
  for (const int signal : {SIGINT, SIGTERM}) {
    struct sigaction previous {};
    if (sigaction(signal, nullptr, &previous) == 0 && previous.sa_handler == SIG_IGN) continue;
    struct sigaction action {};
    action.sa_handler = &RecordSignal;
    sigemptyset(&action.sa_mask);
    action.sa_flags = SA_RESTART;  // file I/O and waitpid carry on; the flag is polled
    sigaction(signal, &action, nullptr);
  }
}

int InterruptSignal() { return g_signal.load(); }

void SetInterruptPoll(InterruptPoll poll) { g_poll.store(poll); }

int PollInterrupt() {
  if (g_signal.load() == 0) {
    if (const InterruptPoll poll = g_poll.load()) {
      if (const int signal = poll()) RecordSignal(signal);
    }
  }
  return g_signal.load();
}

void ClearInterrupt() { g_signal.store(0); }

Status CheckInterrupt() {
  const int signal = PollInterrupt();
  if (signal == 0) return Status::Ok();
  return Status::Internal("interrupted by signal " + std::to_string(signal) + " (" + strsignal(signal) + ")");
}

void SetThreadCancelFlag(const std::atomic<bool>* flag) { t_cancel = flag; }

bool ThreadCancelled() { return t_cancel != nullptr && t_cancel->load(); }

void SetInterruptForTesting(int signal) { g_signal.store(signal); }

}  // namespace pqlayout

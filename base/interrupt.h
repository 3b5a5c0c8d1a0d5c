// Interrupts: SIGINT and SIGTERM stop a run cleanly instead of killing it mid-write.
//
// The signal handler only records the signal: one compare-and-swap on a lock-free atomic,
// which is async-signal-safe (C++17 [support.signal]); it allocates nothing, takes no lock,
// touches no file and does not even change errno. Everything else happens on the main thread,
// in ordinary code: the long stages poll the flag (every Ceres iteration through
// solver/ceres_options.h, and the pipeline before each stage), return a failed Status, the
// stack unwinds, OutputFiles' destructor removes the staging folder, and main() prints
// `pqlayout: interrupted` and exits with 128 + the signal (130 for SIGINT, 143 for SIGTERM).
// The process exits normally with that code rather than re-raising the signal: a shell
// shows the same $?, and the output folder is in a known state when it does. A signal that
// arrives once the outputs are being moved into place (OutputFiles::Commit, milliseconds)
// is too late: the run completes and exits 0, so the exit code always matches the folder.
//
// Only the first signal counts; later ones are ignored while the run winds down. That is
// deliberate: Ctrl-C in a terminal reaches `sweep` and its runs (one process group), and
// `sweep` forwards it to them as well, so every run sees it twice. To stop at once use
// SIGKILL; the staging folder it leaves is removed by the next run into the same folder.
#pragma once

#include <atomic>

#include "base/status.h"

namespace pqlayout {

// Installs the handler for SIGINT and SIGTERM, except for a signal that is ignored
// (nohup, a background job of a non-interactive shell), which stays ignored. Only for
// commands that poll: a command that never looks at the flag would become unstoppable.
void InstallInterruptHandlers();

// The first SIGINT or SIGTERM received since InstallInterruptHandlers, or 0.
int InterruptSignal();

// Ok, or (after a signal) Internal "interrupted by signal N (NAME)". Callers return it
// like any failure; main() recognises the interrupt by InterruptSignal(), not by the text.
Status CheckInterrupt();

// An embedding that hears stop requests its own way (the Python module: Ctrl-C, which Python
// catches itself, or an exception raised in a progress callback) installs a poll. PollInterrupt
// calls it when no signal has been recorded yet and records a nonzero return like a signal;
// CheckInterrupt and the Ceres callback (solver/ceres_options.h) go through PollInterrupt, so
// the poll runs before each stage and at every solver iteration, on the thread of the run.
// nullptr removes it.
using InterruptPoll = int (*)();
void SetInterruptPoll(InterruptPoll poll);

// The recorded signal after asking the poll (if any); 0 if none.
int PollInterrupt();

// Forgets a recorded signal, so that the next run in the same process starts afresh
// (the Python module, between runs; tests).
void ClearInterrupt();

// One thread's own stop request, not a signal: a solve started on a second thread in case its
// result is needed (levelset.alongside) is cancelled once it is not (AlongsideSolve). While a
// flag is installed on a thread, ThreadCancelled() there returns its value; the Ceres callback
// (solver/ceres_options.h) ends that thread's solves within one iteration of it being set.
// Nothing is recorded: the other threads and the run carry on. nullptr removes it.
void SetThreadCancelFlag(const std::atomic<bool>* flag);
bool ThreadCancelled();

// Tests: behave as if `signal` had been received (0: as if none had).
void SetInterruptForTesting(int signal);

}  // namespace pqlayout

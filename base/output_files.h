// OutputFiles: a run's outputs are written into a private staging folder beside the output
// folder, `.<DIR name>.partial-<pid>`, and moved into it (one rename per entry) only when the
// whole run succeeded, so a failed or interrupted run leaves no partial output files and a
// reader never sees a half-written one. Outputs of an earlier run in the same folder that
// this run does not produce (e.g. after --until) are removed, so the folder holds one run;
// files that are not outputs of pqlayout (a sweep's run.log and error.txt, the user's own)
// are kept.
//
// Commit protocol: report.json is the completion marker. `sweep` counts a run as finished by
// its report.json alone (cli/sweep.h, InspectRun), and a reader takes the folder for a
// complete run when it holds one. So Commit
//   1. removes the old report.json (unlink),
//   2. replaces every other entry (removes the old one, renames the staged one in),
//   3. renames the new report.json in, last.
// Every step is one unlink(2) or rename(2), atomic under a kill. Killed before step 1 the
// folder still holds the previous run, complete with its report; killed during step 2 it
// holds a mix of old and new files but no report.json, which nothing counts as finished
// (sweep reruns it; the next run into the folder replaces the mix); after step 3 it holds the
// new run, complete. Never a report.json beside another run's files.
// Why not stage the whole folder and swap it in with renameat2(RENAME_EXCHANGE)? The folder
// also holds files that are not ours, one of them (a sweep's run.log) open for writing by
// the running process itself; they would have to be carried across, and the swap is
// Linux-only. Nothing is fsync'ed: the protocol holds against a killed process, not
// against a power cut.
//
// A staging folder whose process is gone (SIGKILL, a crash) is removed by the next Open for
// the same folder; one whose process still runs is left alone.
//
// Test hook: with PQLAYOUT_TEST_FAIL_COMMIT_AFTER=N in the environment, Commit ends the
// process with _exit(137), as a SIGKILL would, before its (N+1)th unlink or rename (N = 0:
// before the first). Read only by Commit; tests/output_files_test.cc kills a commit at every
// step with it.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "base/background_writer.h"
#include "base/status.h"

namespace pqlayout {

class OutputFiles {
 public:
  // Prepares staging for final_dir (creates final_dir's parent folders if needed) and removes
  // stale staging folders of final_dir left by processes that no longer exist.
  static Status Open(const std::string& final_dir, std::unique_ptr<OutputFiles>* out);
  ~OutputFiles();  // waits for the background writes, removes the staging folder unless committed

  // Where to write `relative` (e.g. "fields/faces.csv"); its folders are created.
  std::string Path(const std::string& relative);
  Status WriteText(const std::string& relative, const std::string& content);
  // Runs `write` (it writes files under paths from Path, taken before it is added, and owns
  // what it reads) on the background writer (base/background_writer.h); a failure comes back
  // from WaitForWrites, which Commit calls first.
  void WriteInBackground(std::function<Status()> write) { writer_.Add(std::move(write)); }
  Status WaitForWrites() { return writer_.Wait(); }
  // Writes added from now on wait until ReleaseWrites (or WaitForWrites): BackgroundWriter::Hold.
  void HoldWrites() { writer_.Hold(); }
  void ReleaseWrites() { writer_.Release(); }
  // Moves every staged entry into the output folder (protocol above). Refuses, leaving the
  // folder as it was, if SIGINT/SIGTERM has been received (base/interrupt.h); once
  // started it runs to the end.
  Status Commit();
  // status with the staging folder's path in its message replaced by the output folder's:
  // a failed run's message names the output file as the user knows it, not a staging path
  // that is deleted when the run ends.
  Status InFinalFolder(const Status& status) const;

  const std::string& final_dir() const { return final_dir_; }
  const std::string& staging_dir() const { return staging_dir_; }

 private:
  OutputFiles(std::string final_dir, std::string staging_dir)
      : final_dir_(std::move(final_dir)), staging_dir_(std::move(staging_dir)) {}
  std::string final_dir_, staging_dir_;
  std::vector<std::string> created_parents_;  // made by Open, removed again unless committed
  bool committed_ = false;
  BackgroundWriter writer_;  // waited for by the destructor's body, before the staging folder goes
};

}  // namespace pqlayout

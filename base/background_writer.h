// BackgroundWriter: output files formatted and written on one thread of their own, one task
// after another in the order given, while the run goes on computing. At a million reference
// triangles the field files (fields/*.csv, fields.vtk: ~300 MB) took ~4 s of a ~30 s run on
// the main thread, with the second core idle through the single-threaded level-set solve.
//
// A task owns everything it reads (copies made by the caller when it is added), so nothing it
// touches can change under it; it only writes its own files, so the outputs are byte for byte
// those written in line. Wait returns the first failure (e.g. a full disk) with the file's
// name, once every task added so far has ended; the destructor waits too, so that the staged
// folder is never removed under a task still writing into it. An exception thrown in a task
// (std::bad_alloc) becomes its Status.
//
// Hold keeps the tasks added from starting until Release (or Wait, or the destructor): the
// pipeline holds them while its own stages keep both cores busy (the membrane's factor, the
// closest-point index, the second level-set layout alongside) and lets them run once the level
// sets are solved, beside the single-threaded stages after.
#pragma once

#include <condition_variable>
#include <deque>
#include <functional>
#include <mutex>
#include <thread>

#include "base/status.h"

namespace pqlayout {

class BackgroundWriter {
 public:
  BackgroundWriter() = default;
  BackgroundWriter(const BackgroundWriter&) = delete;
  BackgroundWriter& operator=(const BackgroundWriter&) = delete;
  ~BackgroundWriter();

  // Queues `task`; the thread starts with the first one.
  void Add(std::function<Status()> task);
  // Blocks until every task added so far has ended; the first failure among them, then
  // forgotten (Ok if none failed).
  Status Wait();
  void Hold();
  void Release();

 private:
  void Run();

  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<std::function<Status()>> queue_;
  bool running_task_ = false;
  bool stopping_ = false;
  bool held_ = false;
  Status first_failure_;
  std::thread thread_;
};

}  // namespace pqlayout

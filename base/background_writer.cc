#include "base/background_writer.h"

#include <exception>
#include <string>
#include <utility>

namespace pqlayout {

BackgroundWriter::~BackgroundWriter() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;  // the queue is still worked off first: a task half done would leave a partial file
  }
  changed_.notify_all();
  if (thread_.joinable()) thread_.join();
}

void BackgroundWriter::Add(std::function<Status()> task) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    queue_.push_back(std::move(task));
    if (!thread_.joinable()) thread_ = std::thread([this] { Run(); });
  }
  changed_.notify_all();
}

void BackgroundWriter::Hold() {
  std::lock_guard<std::mutex> lock(mutex_);
  held_ = true;
}

void BackgroundWriter::Release() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    held_ = false;
  }
  changed_.notify_all();
}

Status BackgroundWriter::Wait() {
  Release();
  std::unique_lock<std::mutex> lock(mutex_);
  changed_.wait(lock, [this] { return queue_.empty() && !running_task_; });
  Status failure = std::move(first_failure_);
  first_failure_ = Status::Ok();
  return failure;
}

void BackgroundWriter::Run() {
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    changed_.wait(lock, [this] { return (!queue_.empty() && !held_) || stopping_; });
    if (queue_.empty()) return;  // stopping, and nothing left to write
    std::function<Status()> task = std::move(queue_.front());
    queue_.pop_front();
    running_task_ = true;
    lock.unlock();
    Status status;
    try {
      status = task();
    } catch (const std::exception& e) {
      status = Status::Internal(std::string("writing an output file in the background failed: ") + e.what());
    }
    lock.lock();
    running_task_ = false;
    if (!status.ok() && first_failure_.ok()) first_failure_ = std::move(status);
    changed_.notify_all();
  }
}

}  // namespace pqlayout

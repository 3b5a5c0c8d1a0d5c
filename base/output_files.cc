#include "base/output_files.h"

#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <climits>
#include <cstdlib>
#include <filesystem>
#include <vector>

#include "base/atomic_file.h"
#include "base/interrupt.h"

namespace pqlayout {
namespace fs = std::filesystem;
namespace {

// The completion marker, moved in last (see the commit protocol in the header).
const char kMarker[] = "report.json";

// Every top-level entry a run may produce (SPEC "CLI and outputs"), the marker excepted.
const std::vector<std::string>& OwnedEntries() {
  static const std::vector<std::string> kEntries{
      "report.html", "surface.obj", "fields", "fields.vtk", "quads_initial.obj", "quads_initial.ply",
      "quads.obj", "quads.ply", "quads_planarized.obj", "quads_planarized.ply", "analysis", "figures", "compare", "compare.json"};
  return kEntries;
}

const char kStagingInfix[] = ".partial-";

fs::path StagingFolder(const fs::path& target, pid_t pid) {
  return target.parent_path() / ("." + target.filename().string() + kStagingInfix + std::to_string(pid));
}

// True unless `pid_text` names a process that exists (kill(pid, 0) succeeds, or fails only
// for want of permission). Text that cannot be a process id counts as gone.
bool ProcessIsGone(const std::string& pid_text) {
  if (pid_text.empty() || pid_text.find_first_not_of("0123456789") != std::string::npos) return false;
  errno = 0;
  const long long pid = std::strtoll(pid_text.c_str(), nullptr, 10);
  if (errno == ERANGE || pid > INT_MAX || pid <= 0) return true;
  return ::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH;
}

// Staging folders of `target` left by processes that were killed (SIGKILL, a crash), and
// our own from an earlier run with the same process id.
void RemoveStaleStaging(const fs::path& target) {
  const std::string prefix = "." + target.filename().string() + kStagingInfix;
  std::error_code ec;
  std::vector<fs::path> stale;
  for (const auto& entry : fs::directory_iterator(target.parent_path(), ec)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind(prefix, 0) != 0) continue;
    const std::string pid = name.substr(prefix.size());
    if (pid == std::to_string(::getpid()) || ProcessIsGone(pid)) stale.push_back(entry.path());
  }
  for (const auto& path : stale) fs::remove_all(path, ec);
}

// Counts the unlinks and renames of a commit and, under PQLAYOUT_TEST_FAIL_COMMIT_AFTER=N,
// ends the process before the (N+1)th, without unwinding, as a SIGKILL would.
class CommitSteps {
 public:
  CommitSteps() {
    const char* text = std::getenv("PQLAYOUT_TEST_FAIL_COMMIT_AFTER");
    if (text != nullptr && *text != '\0') fail_after_ = std::atol(text);
  }
  void Next() {
    if (done_ == fail_after_) ::_exit(137);
    ++done_;
  }

 private:
  long done_ = 0, fail_after_ = -1;
};

// Replaces target by staged: removes target if it exists, then moves staged (if any) in.
Status Replace(const fs::path& staged, const fs::path& target, CommitSteps* steps) {
  std::error_code ec;
  if (fs::exists(fs::symlink_status(target, ec))) {
    steps->Next();
    fs::remove_all(target, ec);
    if (ec) return Status::Internal(target.string() + ": cannot remove the earlier run's output: " + ec.message());
  }
  if (!fs::exists(fs::symlink_status(staged, ec))) return Status::Ok();
  steps->Next();
  fs::rename(staged, target, ec);
  if (ec) return Status::Internal(target.string() + ": cannot move output into place: " + ec.message());
  return Status::Ok();
}

}  // namespace

Status OutputFiles::Open(const std::string& final_dir, std::unique_ptr<OutputFiles>* out) {
  std::error_code ec;
  const fs::path target = fs::absolute(final_dir, ec).lexically_normal();
  if (fs::exists(target, ec) && !fs::is_directory(target, ec))
    return Status::InvalidInput(final_dir + ": output path exists and is not a folder");
  const fs::path parent = target.parent_path();
  // The folders this creates above the output folder, deepest first: a failed run removes
  // them again (if still empty), so that it leaves nothing behind.
  std::vector<std::string> created;
  for (fs::path p = parent; !p.empty() && !fs::exists(p, ec); p = p.parent_path()) created.push_back(p.string());
  fs::create_directories(parent, ec);
  if (ec) return Status::InvalidInput(final_dir + ": cannot create output folder: " + ec.message());
  RemoveStaleStaging(target);
  const fs::path staging = StagingFolder(target, ::getpid());
  fs::create_directories(staging, ec);
  if (ec) return Status::InvalidInput(final_dir + ": cannot write in " + parent.string() + ": " + ec.message());
  out->reset(new OutputFiles(target.string(), staging.string()));
  (*out)->created_parents_ = std::move(created);
  return Status::Ok();
}

OutputFiles::~OutputFiles() {
  std::error_code ec;
  (void)writer_.Wait();  // a failed run's writes end before their folder is removed
  if (committed_) return;
  fs::remove_all(staging_dir_, ec);
  for (const auto& dir : created_parents_) fs::remove(dir, ec);  // only if empty
}

std::string OutputFiles::Path(const std::string& relative) {
  const fs::path p = fs::path(staging_dir_) / relative;
  std::error_code ec;
  fs::create_directories(p.parent_path(), ec);
  return p.string();
}

Status OutputFiles::WriteText(const std::string& relative, const std::string& content) {
  return WriteTextFileAtomically(Path(relative), content);
}

Status OutputFiles::Commit() {
  PQ_RETURN_IF_ERROR(InFinalFolder(WaitForWrites()));
  PQ_RETURN_IF_ERROR(CheckInterrupt());
  std::error_code ec;
  fs::create_directories(final_dir_, ec);
  if (ec) return Status::Internal(final_dir_ + ": cannot create output folder: " + ec.message());
  const fs::path staging(staging_dir_), final_dir(final_dir_);
  CommitSteps steps;
  // 1. The old marker goes first: from here on the folder holds no complete run.
  if (fs::exists(fs::symlink_status(final_dir / kMarker, ec))) {
    steps.Next();
    fs::remove(final_dir / kMarker, ec);
    if (ec)
      return Status::Internal((final_dir / kMarker).string() + ": cannot remove the earlier run's report: " +
                              ec.message());
  }
  // 2. Every other entry. Anything staged that is not in the owned list is a programming
  // error; it is moved too, to stay visible.
  std::vector<std::string> names = OwnedEntries();
  for (const auto& entry : fs::directory_iterator(staging, ec)) {
    const std::string name = entry.path().filename().string();
    if (name != kMarker && std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
  }
  for (const auto& name : names) PQ_RETURN_IF_ERROR(Replace(staging / name, final_dir / name, &steps));
  // 3. The new marker last: the folder now holds this run, complete.
  PQ_RETURN_IF_ERROR(Replace(staging / kMarker, final_dir / kMarker, &steps));
  committed_ = true;
  fs::remove_all(staging, ec);
  return Status::Ok();
}

Status OutputFiles::InFinalFolder(const Status& status) const {
  if (status.ok()) return status;
  std::string message = status.message();
  for (size_t at = message.find(staging_dir_); at != std::string::npos;
       at = message.find(staging_dir_, at + final_dir_.size()))
    message.replace(at, staging_dir_.size(), final_dir_);
  return status.code() == StatusCode::kInvalidInput ? Status::InvalidInput(message) : Status::Internal(message);
}

}  // namespace pqlayout

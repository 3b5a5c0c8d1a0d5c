#include "problems/output_files.h"

#include <unistd.h>

#include <filesystem>
#include <vector>

#include "geometry/atomic_file.h"

namespace pqlayout {
namespace fs = std::filesystem;
namespace {

// Every top-level entry a run may produce (SPEC "CLI and outputs").
const std::vector<std::string>& OwnedEntries() {
  static const std::vector<std::string> kEntries{
      "report.json", "report.html", "surface.obj", "fields", "fields.vtk", "quads_initial.obj",
      "quads_initial.ply", "quads.obj", "quads.ply", "analysis", "figures", "compare", "compare.json"};
  return kEntries;
}

}  // namespace

Status OutputFiles::Open(const std::string& final_dir, std::unique_ptr<OutputFiles>* out) {
  std::error_code ec;
  const fs::path target = fs::absolute(final_dir, ec).lexically_normal();
  if (fs::exists(target, ec) && !fs::is_directory(target, ec))
    return Status::InvalidInput(final_dir + ": output path exists and is not a folder");
  const fs::path parent = target.parent_path();
  fs::create_directories(parent, ec);
  if (ec) return Status::InvalidInput(final_dir + ": cannot create output folder: " + ec.message());
  const fs::path staging = parent / ("." + target.filename().string() + ".partial-" + std::to_string(::getpid()));
  fs::remove_all(staging, ec);
  fs::create_directories(staging, ec);
  if (ec) return Status::InvalidInput(final_dir + ": cannot write in " + parent.string() + ": " + ec.message());
  out->reset(new OutputFiles(target.string(), staging.string()));
  return Status::Ok();
}

OutputFiles::~OutputFiles() {
  std::error_code ec;
  if (!committed_) fs::remove_all(staging_dir_, ec);
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
  std::error_code ec;
  fs::create_directories(final_dir_, ec);
  if (ec) return Status::Internal(final_dir_ + ": cannot create output folder: " + ec.message());
  for (const auto& name : OwnedEntries()) {
    const fs::path staged = fs::path(staging_dir_) / name;
    const fs::path target = fs::path(final_dir_) / name;
    fs::remove_all(target, ec);
    if (!fs::exists(staged)) continue;
    fs::rename(staged, target, ec);
    if (ec) return Status::Internal(target.string() + ": cannot move output into place: " + ec.message());
  }
  // Anything staged that is not in the owned list is a programming error; keep it visible.
  for (const auto& entry : fs::directory_iterator(staging_dir_, ec)) {
    fs::rename(entry.path(), fs::path(final_dir_) / entry.path().filename(), ec);
  }
  fs::remove_all(staging_dir_, ec);
  committed_ = true;
  return Status::Ok();
}

}  // namespace pqlayout

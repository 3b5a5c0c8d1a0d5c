#include "base/atomic_file.h"

#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>

namespace pqlayout {

Status WriteFileAtomically(const std::string& path,
                           const std::function<bool(const std::string&)>& writer) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path target(path);
  if (target.has_parent_path()) {
    fs::create_directories(target.parent_path(), ec);
    if (ec) return Status::Internal(path + ": cannot create directory: " + ec.message());
  }
  // Keep the real extension last: OpenMesh's writers choose the format by extension.
  const fs::path temporary = target.parent_path() /
      (".tmp-" + std::to_string(::getpid()) + "-" + target.filename().string());
  bool written = false;
  std::string reason;
  try {
    written = writer(temporary.string());
  } catch (const std::exception& e) {
    reason = std::string(": ") + e.what();
  }
  if (!written) {
    fs::remove(temporary, ec);
    return Status::Internal(path + ": could not write file" + reason);
  }
  fs::rename(temporary, target, ec);
  if (ec) {
    fs::remove(temporary, ec);
    return Status::Internal(path + ": could not move file into place: " + ec.message());
  }
  return Status::Ok();
}

Status WriteTextFileAtomically(const std::string& path, const std::string& content) {
  return WriteFileAtomically(path, [&](const std::string& temporary) {
    std::ofstream out(temporary, std::ios::binary);
    out << content;
    out.close();
    return static_cast<bool>(out);
  });
}

}  // namespace pqlayout

// Atomic file output: content is written to a temporary file beside the target and renamed
// over it only when complete, so a reader never sees a half-written file.
#pragma once

#include <functional>
#include <string>

#include "base/status.h"

namespace pqlayout {

// Calls writer(temporary_path); on success renames the temporary onto path. The writer
// returns false (or throws) on failure, in which case the temporary is removed and an
// Internal status names path.
Status WriteFileAtomically(const std::string& path,
                           const std::function<bool(const std::string& temporary_path)>& writer);

// Writes text content atomically.
Status WriteTextFileAtomically(const std::string& path, const std::string& content);

}  // namespace pqlayout

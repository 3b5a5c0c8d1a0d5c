#include "base/allocator.h"

#include <dlfcn.h>

#include <cstddef>

namespace pqlayout {

std::string AllocatorDescription() {
  using Mallctl = int (*)(const char*, void*, size_t*, void*, size_t);
  const auto mallctl = reinterpret_cast<Mallctl>(dlsym(RTLD_DEFAULT, "mallctl"));
  if (mallctl == nullptr) return "glibc malloc";
  const char* version = nullptr;
  const char* thp = nullptr;
  size_t size = sizeof(const char*);
  std::string text = "jemalloc";
  if (mallctl("version", &version, &size, nullptr, 0) == 0 && version != nullptr) text += std::string(" ") + version;
  size = sizeof(const char*);
  if (mallctl("opt.thp", &thp, &size, nullptr, 0) == 0 && thp != nullptr) text += std::string(" (thp ") + thp + ")";
  return text;
}

}  // namespace pqlayout

// libFuzzer target for one mesh format, whose extension (".obj", ".ply", ".off" or ".stl")
// the build gives as PQ_FUZZ_EXTENSION. It does what `pqlayout run` does with a surface
// file: ReadPolygonSoup (which picks the reader by extension, hence the file), then
// PrepareSurfaceSoup (quads split, CAD repairs, validation) and BuildTriMesh when those
// succeed. Any crash, sanitizer report, hang or runaway allocation is a finding; so is a validated soup that OpenMesh refuses, because
// OpenMesh must only ever get input that has been checked. See fuzz/README.md.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "geometry/mesh_io.h"
#include "geometry/mesh_validation.h"

namespace {

// One file per process, rewritten for every input and removed at exit.
const std::string& InputPath() {
  static const std::string path = [] {
    const char* tmp = std::getenv("TMPDIR");
    std::string pattern = std::string(tmp && *tmp ? tmp : "/tmp") + "/pqlayout_fuzz_XXXXXX" PQ_FUZZ_EXTENSION;
    const int fd = mkstemps(pattern.data(), sizeof(PQ_FUZZ_EXTENSION) - 1);
    if (fd < 0) {
      std::perror("mkstemps");
      std::abort();
    }
    close(fd);
    return pattern;
  }();
  return path;
}

void RemoveInput() { std::remove(InputPath().c_str()); }

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  InputPath();
  std::atexit(RemoveInput);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  FILE* file = std::fopen(InputPath().c_str(), "wb");
  if (!file || std::fwrite(data, 1, size, file) != size || std::fclose(file) != 0) std::abort();
  pqlayout::PolygonSoup soup;
  if (!pqlayout::ReadPolygonSoup(InputPath(), &soup).ok()) return 0;
  if (!pqlayout::PrepareSurfaceSoup(InputPath(), &soup).ok()) return 0;  // as ReadSurfaceMesh does
  pqlayout::TriMesh mesh;
  const pqlayout::Status built = pqlayout::BuildTriMesh(soup, &mesh, nullptr);
  if (!built.ok()) {
    std::fprintf(stderr, "a validated soup was refused by BuildTriMesh: %s\n", built.message().c_str());
    std::abort();
  }
  return 0;
}

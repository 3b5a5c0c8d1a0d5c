// JavaScript compiled into the binary for report.html's 3D view (report/report_view3d.h):
// three.js r111 (three.min.js) and its OrbitControls (examples/js/controls/OrbitControls.js)
// from the Debian package libjs-three, and the view's own script report/report_view3d.js.
// CMake runs cmake/EmbedFiles.cmake on them at build time (problems/CMakeLists.txt), which
// generates the definitions: the page needs no network, the binary no file at run time.
#pragma once

#include <cstddef>
#include <string_view>

namespace pqlayout {
namespace embedded {

extern const unsigned char kThreeJs[];
extern const std::size_t kThreeJsSize;
extern const unsigned char kOrbitControlsJs[];
extern const std::size_t kOrbitControlsJsSize;
extern const unsigned char kView3dJs[];
extern const std::size_t kView3dJsSize;

inline std::string_view Text(const unsigned char* bytes, std::size_t size) {
  return {reinterpret_cast<const char*>(bytes), size};
}
inline std::string_view ThreeJs() { return Text(kThreeJs, kThreeJsSize); }
inline std::string_view OrbitControlsJs() { return Text(kOrbitControlsJs, kOrbitControlsJsSize); }
inline std::string_view View3dJs() { return Text(kView3dJs, kView3dJsSize); }

}  // namespace embedded
}  // namespace pqlayout

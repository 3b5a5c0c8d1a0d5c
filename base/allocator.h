// Which malloc the running process uses, for --version and report.json: the pqlayout executable
// links jemalloc with transparent huge pages (cli/allocator_config.cc); the tests, the benchmarks'
// kernels and the Python module (loaded into an interpreter that already has its malloc) keep
// glibc's. Found at run time (jemalloc's mallctl, looked up by name), so this layer links nothing.
#pragma once

#include <string>

namespace pqlayout {

// "jemalloc 5.3.0-0-g54eaed1d8b56 (thp always)" or "glibc malloc".
std::string AllocatorDescription();

}  // namespace pqlayout

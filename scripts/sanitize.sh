#!/usr/bin/env bash
# The whole test suite under AddressSanitizer and UndefinedBehaviorSanitizer (with
# float-cast-overflow), in build-asan/. Every finding aborts the process that made it, so a
# finding fails its test. Ceres, CHOLMOD and OpenMesh are Debian's uninstrumented builds;
# EIGEN_MALLOC_ALREADY_ALIGNED=1 keeps Eigen's allocations plain malloc/free on both sides
# of that boundary. About 4x slower than the Release suite. The Python module is left out: an
# instrumented extension cannot be loaded into Debian's uninstrumented python3 (the ASan
# runtime must come first); python/tests runs in the Release suite.
#
#   bash scripts/sanitize.sh                  # build and run every test
#   bash scripts/sanitize.sh -R Cli           # extra arguments go to ctest
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install_deps.sh
flags="-fsanitize=address,undefined,float-cast-overflow -fno-sanitize-recover=all -fno-omit-frame-pointer"
flags="$flags -DEIGEN_MALLOC_ALREADY_ALIGNED=1"
cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DPQLAYOUT_BUILD_BENCHMARKS=OFF -DPQLAYOUT_BUILD_PYTHON=OFF \
  -DPQLAYOUT_TEST_TIMEOUT=3600 -DPQLAYOUT_JEMALLOC=OFF \
  -DCMAKE_CXX_FLAGS="$flags" -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" > build-asan.log 2>&1 \
  || { cat build-asan.log; exit 1; }
ninja -C build-asan -j "$(nproc)"
export ASAN_OPTIONS=${ASAN_OPTIONS:-abort_on_error=1:detect_leaks=1:suppressions=$PWD/scripts/lsan.supp}
export LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$PWD/scripts/lsan.supp}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
cd build-asan
ctest --output-on-failure -j "$(nproc)" "$@"

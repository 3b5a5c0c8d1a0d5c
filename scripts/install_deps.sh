#!/usr/bin/env bash
# Installs the Debian packages pqlayout needs, if any is missing. Safe to run repeatedly.
set -euo pipefail
packages=(
  build-essential cmake ninja-build git pkg-config
  libceres-dev libeigen3-dev libsuitesparse-dev libopenmesh-dev libgoogle-glog-dev libgflags-dev
  libyaml-cpp-dev libcgal-dev libgmp-dev libmpfr-dev nlohmann-json3-dev libcli11-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  libspectra-dev         # Lanczos eigensolver on Eigen: the buckling factors (solver/frame_buckling.h)
  calculix-ccx           # ccx: the CalculiX cross-check in tests/calculix_test.cc (skipped without it)
  libjs-three            # three.js r111 + OrbitControls, compiled into the binary for report.html's 3D view (report/report_view3d.h)
  chromium               # headless browser for the report check (tests/report_check_test, scripts/check_report.sh)
  libjemalloc-dev        # the pqlayout executable's malloc, with transparent huge pages (cli/allocator_config.cc)
  libopenblas-dev        # the one BLAS/LAPACK pqlayout links (CMake BLA_VENDOR=OpenBLAS); see solver/numerics.h
  python3-dev pybind11-dev python3-numpy python3-pytest  # `import pqlayout` (python/) and its pytest suite
  clang libclang-rt-14-dev  # scripts/fuzz.sh: clang with libFuzzer and the sanitizer runtimes
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi
echo "pqlayout: installing ${missing[*]}"
sudo=""
if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"

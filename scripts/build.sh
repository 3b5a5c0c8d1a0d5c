#!/usr/bin/env bash
# Configures and builds pqlayout (Release) in build/. Extra arguments go to the build tool
# (e.g. a target name).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install_deps.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release > build.log 2>&1 || { cat build.log; exit 1; }
jobs=$(nproc)
ninja -C build -j "$jobs" "$@"

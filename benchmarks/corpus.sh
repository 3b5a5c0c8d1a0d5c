#!/usr/bin/env bash
# The roof corpus (issue 17): builds pqlayout and its Python module, then runs every roof of
# examples/corpus and the Great Court with strain and with curvature guidance (defaults only)
# and writes benchmarks/corpus.md and benchmarks/corpus.csv, and the gallery's thumbnails in
# docs/corpus (benchmarks/corpus.py says what).
#
#   bash benchmarks/corpus.sh [--set KEY=VALUE ...] [--roofs a,b] [--out STEM]
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh _pqlayout > /dev/null
need=()  # the gallery's thumbnails (docs/corpus)
command -v rsvg-convert >/dev/null || need+=(librsvg2-bin)
command -v pngquant >/dev/null || need+=(pngquant)
if [ ${#need[@]} -gt 0 ]; then
  sudo=""; [ "$(id -u)" -ne 0 ] && sudo=sudo
  $sudo apt-get install -y -qq "${need[@]}" > /dev/null
fi
PYTHONPATH=build/python exec /usr/bin/python3 benchmarks/corpus.py "$@"

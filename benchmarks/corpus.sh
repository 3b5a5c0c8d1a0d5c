#!/usr/bin/env bash
# The roof corpus (issue 17): builds pqlayout and its Python module, then runs every roof of
# examples/corpus and the Great Court with strain and with curvature guidance (defaults only)
# and writes benchmarks/corpus.md and benchmarks/corpus.csv (benchmarks/corpus.py says what).
#
#   bash benchmarks/corpus.sh [--set KEY=VALUE ...] [--roofs a,b] [--out STEM]
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh _pqlayout > /dev/null
PYTHONPATH=build/python exec /usr/bin/python3 benchmarks/corpus.py "$@"

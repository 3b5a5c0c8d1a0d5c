#!/usr/bin/env bash
# The main job end to end: installs what is missing, builds, and lays out the British Museum
# Great Court roof in the paper's setting (examples/great_court.yaml) into out/great_court.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh pqlayout
build/cli/pqlayout run examples/great_court.yaml --out out/great_court "$@"

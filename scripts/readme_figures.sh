#!/usr/bin/env bash
# Regenerates the PNG figures the README shows, from runs of examples/great_court.yaml.
# Needs rsvg-convert (Debian package librsvg2-bin; installed here if missing).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh pqlayout
command -v rsvg-convert >/dev/null || { sudo=""; [ "$(id -u)" -ne 0 ] && sudo=sudo; $sudo apt-get install -y -qq librsvg2-bin; }
build/cli/pqlayout run examples/great_court.yaml --out out/readme --until levelset -q
build/cli/pqlayout run examples/great_court.yaml --out out/readme_curvature --until guidance -q --set guidance.source=curvature
rsvg-convert -w 700 out/readme/figures/displacement.svg -o docs/figures/displacement.png
rsvg-convert -w 700 out/readme/figures/guidance.svg -o docs/figures/guidance.png
rsvg-convert -w 700 out/readme_curvature/figures/guidance.svg -o docs/figures/guidance_curvature.png
rsvg-convert -w 700 out/readme/figures/levelsets.svg -o docs/figures/levelsets.png
build/cli/pqlayout compare examples/great_court.yaml --out out/readme_compare -q
rsvg-convert -w 600 out/readme_compare/figures/compliance_strain.svg -o docs/figures/compliance_strain.png
rsvg-convert -w 600 out/readme_compare/figures/compliance_curvature.svg -o docs/figures/compliance_curvature.png

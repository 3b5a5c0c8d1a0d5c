#!/usr/bin/env bash
# Regenerates the PNG figures the README shows, from runs of examples/great_court.yaml, and
# the screenshot of report.html (checked by scripts/check_report.sh on the way).
# Needs rsvg-convert (librsvg2-bin) and pngquant (installed here if missing) and chromium
# (scripts/install_deps.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh pqlayout
need=()
command -v rsvg-convert >/dev/null || need+=(librsvg2-bin)
command -v pngquant >/dev/null || need+=(pngquant)
if [ ${#need[@]} -gt 0 ]; then
  sudo=""; [ "$(id -u)" -ne 0 ] && sudo=sudo
  $sudo apt-get install -y -qq "${need[@]}"
fi
png() {  # SVG → PNG of the given width, colours quantised to keep the file small
  rsvg-convert -w "$2" "$1" -o "$3"
  pngquant --quality=70-90 --speed 1 -f -o "$3" "$3"
}
build/cli/pqlayout run examples/great_court.yaml --out out/readme -q
build/cli/pqlayout run examples/great_court.yaml --out out/readme_curvature --until extract -q --set guidance.source=curvature
# The paper's strain field (alignment only where the strain is strong) beside the default's,
# whose weak zones follow the curvature lines (guidance.fallback).
build/cli/pqlayout run examples/great_court.yaml --out out/readme_paper --until guidance -q --set guidance.fallback=none
png out/readme_paper/figures/guidance.svg 700 docs/figures/guidance.png
png out/readme/figures/guidance.svg 700 docs/figures/guidance_fallback.png
for f in displacement levelsets; do png out/readme/figures/$f.svg 700 docs/figures/$f.png; done
png out/readme_curvature/figures/guidance.svg 700 docs/figures/guidance_curvature.png
png out/readme_curvature/figures/levelsets.svg 700 docs/figures/levelsets_curvature.png
for f in planarity_initial planarity shell_3d; do png out/readme/figures/$f.svg 600 docs/figures/$f.png; done
for f in buckling utilisation; do png out/readme/figures/$f.svg 600 docs/figures/${f}_strain.png; done
SCREENSHOT_SCALE=0.5 bash scripts/check_report.sh out/readme/report.html docs/figures/report_screenshot.png
pngquant --quality=60-85 --speed 1 -f -o docs/figures/report_screenshot.png docs/figures/report_screenshot.png
# The paper's comparison (strain without the fallback) and the default's.
build/cli/pqlayout compare examples/great_court.yaml --out out/readme_compare -q --set stiffen.tolerance=0 --set guidance.fallback=none
build/cli/pqlayout compare examples/great_court.yaml --out out/readme_compare_fallback -q --set stiffen.tolerance=0
build/cli/pqlayout compare examples/great_court.yaml --out out/readme_compare_stiffened -q
bash scripts/check_report.sh out/readme_compare/report.html
png out/readme_compare/figures/compliance_strain.svg 600 docs/figures/compliance_strain.png
png out/readme_compare/figures/compliance_curvature.svg 600 docs/figures/compliance_curvature.png
png out/readme_compare_fallback/figures/compliance_strain.svg 600 docs/figures/compliance_strain_fallback.png
for g in strain curvature; do png out/readme_compare_stiffened/$g/figures/offset.svg 600 docs/figures/offset_$g.png; done
# The circular dome of the corpus with strain guidance, without and with a pole (issue 17); the
# paper's strain field (with the curvature fallback its crown is a weak zone and gets no pole).
build/cli/pqlayout run examples/corpus/dome_circular.yaml --out out/readme_dome_nopole --until planarize -q --set levelset.poles=false --set guidance.fallback=none
build/cli/pqlayout run examples/corpus/dome_circular.yaml --out out/readme_dome_pole --until planarize -q --set guidance.fallback=none
png out/readme_dome_nopole/figures/levelsets.svg 500 docs/figures/dome_without_pole.png
png out/readme_dome_pole/figures/levelsets.svg 500 docs/figures/dome_with_pole.png

#!/usr/bin/env bash
# Cross-checks a run's frame analysis with CalculiX: runs ccx on RUN_DIR/analysis/model.inp
# (written by `pqlayout run ... --set analysis.export_calculix=true`) in a scratch folder and
# prints ccx's compliance fᵀu (the deck's *CLOAD forces times ccx's displacements of the
# frame nodes), its max |u| over the frame nodes, and pqlayout's numbers from report.json.
#   scripts/calculix_check.sh out/great_court
set -euo pipefail
run=${1:?usage: calculix_check.sh RUN_DIR}
deck="$run/analysis/model.inp"
[ -f "$deck" ] || { echo "calculix_check: $deck not found (run with --set analysis.export_calculix=true)" >&2; exit 2; }
command -v ccx > /dev/null || { echo "calculix_check: ccx not found (Debian package calculix-ccx)" >&2; exit 2; }
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
cp "$deck" "$scratch/model.inp"
start=$(date +%s.%N)
(cd "$scratch" && OMP_NUM_THREADS=${OMP_NUM_THREADS:-1} ccx -i model > ccx.log 2>&1) ||
  { tail -20 "$scratch/ccx.log" >&2; exit 1; }
end=$(date +%s.%N)
awk -v seconds="$(echo "$end - $start" | bc)" '
  FNR == 1 { file++ }
  file == 1 && /^\*/ { cload = ($0 ~ /^\*CLOAD/); next }
  file == 1 && cload { split($0, f, ","); load[f[1] "," f[2]] += f[3]; next }
  file == 2 && /displacements/ { block = 1; next }
  file == 2 && block && NF == 0 { if (seen) block = 0; next }
  file == 2 && block {
    seen = 1
    for (d = 1; d <= 3; d++) c += load[$1 "," d] * $(d + 1)
    u = sqrt($2 * $2 + $3 * $3 + $4 * $4); if (u > umax) umax = u
  }
  END { printf "ccx: compliance %.7g J, max |u| %.7g m (frame nodes), %.1f s\n", c, umax, seconds }
' "$scratch/model.inp" "$scratch/model.dat"
sed -n '/"analyze": {/,/^ *}/p' "$run/report.json" | grep -E '"(compliance_total|max_displacement)"' |
  sed 's/^ */pqlayout: /; s/,$//'
# The buckling deck (analysis/model_buckle.inp, written with the other when the frame
# buckles): ccx's first factors (B32R bricks, a little above the beam model's) and pqlayout's.
buckle="$run/analysis/model_buckle.inp"
if [ -f "$buckle" ]; then
  cp "$buckle" "$scratch/buckle.inp"
  (cd "$scratch" && OMP_NUM_THREADS=${OMP_NUM_THREADS:-1} ccx -i buckle > ccx_buckle.log 2>&1) ||
    { tail -20 "$scratch/ccx_buckle.log" >&2; exit 1; }
  awk '/B U C K L I N G/ { block = 1; next } block && $1 ~ /^[0-9]+$/ && NF == 2 { printf "%s%.6g", (n++ ? ", " : "ccx: buckling factors "), $2 }
       block && n && NF == 0 { exit } END { print "" }' "$scratch/buckle.dat"
  sed -n '/"analyze": {/,/^ *}/p' "$run/report.json" | tr -d '\n' | grep -oE '"buckling_factors": \[[^]]*\]' |
    sed 's/^/pqlayout: /; s/  */ /g'
fi

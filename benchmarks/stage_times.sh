#!/usr/bin/env bash
# Per-stage time regression check (issue 19): the Great Court at its default reference (12k
# triangles) with both guidance sources, at 112k triangles (surface.edge_length 0.5, the
# remeshed working-mesh path) with strain guidance, and the 12k draft (--draft: levelset.draft and stiffen's
# early stop), each run PQ_REPEAT times (default 3); the
# median wall seconds of every stage (report.json `stages.<stage>.seconds`) and of the whole
# run are compared with benchmarks/stage_baseline.csv.
#
#   bash benchmarks/stage_times.sh [BUILD_DIR]            # compare; exit 1 on a regression
#   bash benchmarks/stage_times.sh [BUILD_DIR] --update   # measure and write the baseline
#
# A regression: a stage at more than 1.5 × its baseline and more than 0.3 s above it (timings
# on a shared machine wander by ~20 %; sub-second stages by more). Such a check would have
# caught the poles' doubling of the Great Court's level-set stage (7.1 → 15.3 s, 2026-12-02).
# The baseline is machine-specific: update it (and say on which machine) when the machine or
# a deliberate trade changes. Needs jq (installed if missing). The committed baseline: the
# project's 2-core machine, idle, 2026-12-06, after 8baa834 (the joint solve from the initial
# guess; the one before: 2026-12-03, after fe70fcb, the pole gate); the draft's rows 2026-12-07,
# after --draft began to stop stiffen early, in a slower hour (the 12k strain run took 8.3 s then
# against its 6.6 s here, so the draft's 2.46 s is a lenient baseline; 2.2 s idle).
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
update=${2:-}
repeat=${PQ_REPEAT:-3}
baseline=benchmarks/stage_baseline.csv
name=stage_times
source benchmarks/common.sh
current="$work/current.csv"
echo "case,stage,seconds" > "$current"

measure() {  # case name, then pqlayout --set arguments
  local case_=$1
  shift
  local samples="$work/samples.csv"
  : > "$samples"
  for ((i = 1; i <= repeat; i++)); do
    rm -rf "$work/run"
    if ! "$pqlayout" run examples/great_court.yaml "$@" --out "$work/run" -q > "$work/log" 2>&1; then
      cat "$work/log" >&2
      echo "$name: $case_: the run failed" >&2
      exit 2
    fi
    jq -r '(.run.completed_stages[] as $s | "\($s),\(.stages[$s].seconds)"), "total,\(.run.total_seconds)"' \
      "$work/run/report.json" >> "$samples"
  done
  # Median per stage, in the order the stages ran.
  awk -F, -v c="$case_" '{ if (!($1 in n)) order[++k] = $1; v[$1, ++n[$1]] = $2 }
    END { for (i = 1; i <= k; i++) { s = order[i]; m = n[s];
            for (a = 1; a <= m; a++) x[a] = v[s, a];
            for (a = 1; a <= m; a++) for (b = a + 1; b <= m; b++) if (x[b] < x[a]) { t = x[a]; x[a] = x[b]; x[b] = t }
            printf "%s,%s,%.3f\n", c, s, (m % 2 ? x[(m + 1) / 2] : 0.5 * (x[m / 2] + x[m / 2 + 1])) } }' \
    "$samples" >> "$current"
  echo "$name: $case_ measured ($repeat runs)" >&2
}

measure gc12k_strain --set guidance.source=strain
measure gc12k_curvature --set guidance.source=curvature
measure gc112k_strain --set guidance.source=strain --set surface.edge_length=0.5
measure gc12k_draft --set guidance.source=strain --draft

if [[ "$update" == "--update" ]]; then
  cp "$current" "$baseline"
  echo "$name: wrote $baseline" >&2
  column -t -s, "$baseline"
  exit 0
fi
[[ -f "$baseline" ]] || { echo "$name: $baseline not found; run with --update first" >&2; exit 2; }
awk -F, 'NR == FNR { if (FNR > 1) base[$1 "," $2] = $3; next }
  FNR == 1 { printf "%-16s %-10s %10s %10s %7s\n", "case", "stage", "baseline", "now", "ratio"; next }
  { key = $1 "," $2; b = (key in base) ? base[key] : -1
    ratio = b > 0 ? $3 / b : 0
    flag = (b >= 0 && $3 > 1.5 * b && $3 > b + 0.3) ? "  REGRESSION" : ""
    if (flag != "") bad++
    shown = (b >= 0) ? sprintf("%.3f", b) : "new"
    printf "%-16s %-10s %10s %10.3f %7s%s\n", $1, $2, shown, $3, (b > 0) ? sprintf("%.2f", ratio) : "-", flag }
  END { if (bad) { printf "%d stage(s) regressed\n", bad; exit 1 } print "no stage regressed" }' "$baseline" "$current"

#!/usr/bin/env bash
# End-to-end benchmark: every stage of the Great Court pipeline (examples/great_court.yaml,
# h = 3 m) on generated reference meshes from ~10k to ~1M triangles.
#
#   bash benchmarks/run_e2e.sh [BUILD_DIR] [OUT_CSV]
#   PQ_E2E_EDGES="1.5 0.5" bash benchmarks/run_e2e.sh      # a subset of reference edge lengths
#   PQ_E2E_SOURCE=curvature bash benchmarks/run_e2e.sh ...  # the other guidance source
#
# Writes OUT_CSV (default benchmarks/results.csv): one row per stage and size with the stage's
# wall time and the process's peak resident memory after it (report.json `seconds` and
# `peak_memory_mb`), then prints per stage the growth exponent b of seconds ≈ a · triangles^b
# (least squares in log–log over all sizes). Beside it, OUT_CSV with "_layouts" before .csv:
# one row per size with what makes the timing worth quoting, the layout's validity (working
# mesh, alignment where weight > 0.5, spacing CV, min crossing, fold-overs, quad fraction,
# δ max, closeness / h, report.json targets met of 11). Needs jq (installed here if missing).
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
csv=${2:-benchmarks/results.csv}
edges=${PQ_E2E_EDGES:-"1.5 0.8 0.5 0.3 0.17"}
source_=${PQ_E2E_SOURCE:-strain}
layouts="${csv%.csv}_layouts.csv"
name=run_e2e
source benchmarks/common.sh
rows="$work/rows.csv"
: > "$rows"
echo "triangles,source,working_triangles,alignment_deg,spacing_cv,min_crossing_deg,foldovers,quad_fraction,planarity_max,closeness_over_h,targets_met,total_seconds" > "$layouts"
for edge in $edges; do
  echo "run_e2e: reference edge length $edge m ..." >&2
  "$pqlayout" run examples/great_court.yaml --set surface.edge_length="$edge" --set guidance.source="$source_" \
    --out "$work/run" -q
  jq -r --arg edge "$edge" '
    .stages.surface.n_faces as $n
    | .run.completed_stages[] as $s
    | [$s, $n, ($edge | tonumber), .stages[$s].seconds, (.stages[$s].peak_memory_mb // "")] | @csv' \
    "$work/run/report.json" | tr -d '"' >> "$rows"
  jq -r '"run_e2e:   \(.stages.surface.n_faces) triangles, total \(.run.total_seconds | . * 10 | round / 10) s, targets met \(.targets.met) of 11"' \
    "$work/run/report.json" >&2
  jq -r --arg source "$source_" '
    .stages as $s | .config.layout.spacing as $h
    | [$s.surface.n_faces, $source, $s.levelset.working_mesh_triangles,
       $s.levelset.alignment_rms_deg_weight_above_half,
       ([$s.levelset.spacing_cv_phi, $s.levelset.spacing_cv_psi] | max),
       $s.levelset.min_crossing_angle_deg, $s.levelset.foldovers, $s.extract.quad_fraction,
       $s.planarize.planarity_max, ($s.planarize.closeness_max / $h), .targets.met, .run.total_seconds] | @csv' \
    "$work/run/report.json" | tr -d '"' >> "$layouts"
  rm -rf "$work/run"
done
{ echo "stage,triangles,edge_length,seconds,peak_memory_mb"; cat "$rows"; } > "$csv"
echo "wrote $csv and $layouts"
echo "growth exponents (seconds ∝ triangles^b):"
awk -F, '{ x = log($2); y = log($4 > 1e-6 ? $4 : 1e-6); n[$1]++; sx[$1] += x; sy[$1] += y; sxx[$1] += x * x;
           sxy[$1] += x * y; if (!($1 in order)) { order[$1] = ++k; name[k] = $1 } }
     END { for (i = 1; i <= k; i++) { s = name[i]; d = n[s] * sxx[s] - sx[s] * sx[s];
           if (n[s] > 1 && d > 0) printf "  %-10s b = %.2f\n", s, (n[s] * sxy[s] - sx[s] * sy[s]) / d } }' "$rows"

#!/usr/bin/env bash
# Benchmark of the stiffen stage (issue 16): the Great Court (examples/great_court.yaml) at
# h = 3 m and 1.25 m, strain and curvature guidance, stiffen.tolerance 0.1 m; one run at a
# time. Prints the markdown table of benchmarks/RESULTS.md "Stiffen": vertices, L-BFGS
# iterations, frame solves (evaluations), time per evaluation, stage time, C after / before;
# then the roofs with free edges (examples/corpus barrel, canopy), where stiffen also tries
# bracing each free stretch (extract.brace_free_edges = paying): stiffen runs, stretches
# braced, stage time, C after with the bracing / without.
#
#   bash benchmarks/stiffen.sh [BUILD_DIR]
# Needs jq (installed here if missing). Targets (issue 16): stage ≤ 10 s at h = 3 m and
# ≤ 60 s at h = 1.25 m; the ratio at 1.25 m within 0.1 of that at 3 m.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
name=stiffen.sh
source benchmarks/common.sh
echo "| grid | vertices | iterations | evaluations | per evaluation | stage | ratio |"
echo "|---|---:|---:|---:|---:|---:|---:|"
for h in 3 1.25; do
  for guidance in strain curvature; do
    "$pqlayout" run examples/great_court.yaml --until stiffen -q --set layout.spacing="$h" \
      --set guidance.source="$guidance" --out "$work/run"
    jq -r --arg g "$guidance" --arg h "$h" '.stages.stiffen as $s
      | ($s.frame_seconds / $s.evaluations * 1000 | . * 10 | round / 10) as $per
      | "| \($g), h = \($h) m | \(.stages.extract.n_vertices) | \($s.iterations) | \($s.evaluations) | \($per) ms | \($s.seconds | . * 10 | round / 10) s | \($s.compliance_ratio | . * 1000 | round / 1000) |"' \
      "$work/run/report.json"
    rm -rf "$work/run"
  done
done
echo
echo "| roof with free edges | stiffen runs | stretches braced | quads cut | stage | C braced / unbraced |"
echo "|---|---:|---:|---:|---:|---:|"
for roof in barrel canopy; do
  for guidance in strain curvature; do
    "$pqlayout" run "examples/corpus/$roof.yaml" --until stiffen -q --set guidance.source="$guidance" --out "$work/run"
    jq -r --arg g "$guidance" --arg r "$roof" '.stages.stiffen as $s | $s.bracing as $b
      | "| \($r), \($g) | \($b.trials) | \($b.braced_stretches) of \($b.free_stretches) | \($b.braced_quads) | \($s.seconds | . * 10 | round / 10) s | \($b.compliance_ratio | . * 1000 | round / 1000) |"' \
      "$work/run/report.json"
    rm -rf "$work/run"
  done
done

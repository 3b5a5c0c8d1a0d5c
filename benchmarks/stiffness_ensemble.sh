#!/usr/bin/env bash
# What a roof's grid shell is worth over an ensemble of meshes (the Great Court unless --config),
# whole runs: each reference edge length × each guidance source, the compliance of the planarised shell and
# after stiffen, the panels planarisation built, the targets met. One CSV row per run and a
# summary per source (median, range, ratio max/min).
#
# Why: the level sets land in a different minimum on every mesh (layout_ensemble.sh), and the
# planarisation and stiffen amplify it: on 2026-12-04 the strain layout's compliance after
# stiffen was 151,990 J at the default 12k-triangle reference and 291,350 J at 44k, while the
# curvature layout stayed within 56–60k J. A change meant to make the shell stiffer is judged
# by this distribution, never by one run.
#
#   bash benchmarks/stiffness_ensemble.sh [--config examples/great_court.yaml] [--sources "strain curvature"]
#                                         [--edges "1.4 1.45 1.5 1.55 1.6 0.8 0.5"]
#                                         [--set KEY=VALUE]... [--jobs 2] [--out FILE.csv] [--bin PQLAYOUT]
# ~4 min on 2 cores at the defaults (14 whole runs of 10k–112k reference triangles).
set -euo pipefail
cd "$(dirname "$0")/.."
config=examples/great_court.yaml sources="strain curvature" edges="1.4 1.45 1.5 1.55 1.6 0.8 0.5" jobs=2 out=benchmarks/ensemble/stiffness_ensemble.csv bin=""
sets=()
while [ $# -gt 0 ]; do
  case "$1" in
    --config) config=$2; shift 2 ;;
    --sources) sources=$2; shift 2 ;;
    --edges) edges=$2; shift 2 ;;
    --set) sets+=(--set "$2"); shift 2 ;;
    --jobs) jobs=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    --bin) bin=$2; shift 2 ;;
    *) echo "stiffness_ensemble.sh: unknown argument '$1'" >&2; exit 2 ;;
  esac
done
name=stiffness_ensemble.sh
source benchmarks/ensemble_setup.sh
run_one() {  # source edge
  local dir="$tmp/$1_$2"
  "$bin" run "$config" --set surface.edge_length="$2" --set guidance.source="$1" \
    --set output.fields=false "${sets[@]}" --out "$dir" -q > /dev/null 2>&1 ||
    { echo "stiffness_ensemble: run failed ($1, edge $2)" >&2; return 1; }
  jq -r --arg s "$1" --arg e "$2" '.stages as $st | [$s, $e, $st.surface.n_faces,
    $st.levelset.alignment_rms_deg_weight_above_half, ($st.levelset.alignment_rms_deg_source_above_half // $st.levelset.alignment_rms_deg_weight_above_half), $st.levelset.min_crossing_angle_deg,
    $st.extract.quad_fraction, $st.planarize.quad_fraction, $st.planarize.warped_split, $st.planarize.folded_split,
    $st.planarize.closed_edges, $st.stiffen.compliance_before, $st.stiffen.compliance_after,
    .targets.met, $st.levelset.seconds + $st.planarize.seconds + $st.stiffen.seconds] | @csv' "$dir/report.json" > "$dir/row.csv"
  rm -rf "$dir/figures" "$dir"/*.obj "$dir"/*.vtk 2> /dev/null || true
}
export -f run_one
export bin tmp config
export sets_string="${sets[*]:-}"
pairs=()
for s in $sources; do for e in $edges; do pairs+=("$s $e"); done; done
printf '%s\n' "${pairs[@]}" | xargs -P "$jobs" -L 1 bash -c 'sets=($sets_string); run_one "$0" "$1"'
echo "source,reference_edge,reference_triangles,alignment_deg_w05,alignment_to_source_deg_w05,min_crossing_deg,extract_quads,planarized_quads,warped_split,folded_split,closed_edges,compliance_before_J,compliance_after_J,targets_met,solve_s" > "$out"
for s in $sources; do for e in $edges; do cat "$tmp/${s}_${e}/row.csv" >> "$out"; done; done
/usr/bin/python3 - "$out" <<'EOF'
import csv, statistics, sys
rows = list(csv.DictReader(open(sys.argv[1])))
for source in dict.fromkeys(r["source"] for r in rows):
    rs = [r for r in rows if r["source"] == source]
    after = [float(r["compliance_after_J"]) for r in rs]
    before = [float(r["compliance_before_J"]) for r in rs]
    quads = [float(r["planarized_quads"]) for r in rs]
    print(f"{source}: {len(rs)} runs; compliance after stiffen median {statistics.median(after):,.0f} J "
          f"(range {min(after):,.0f}-{max(after):,.0f}, max/min {max(after) / min(after):.2f}); before "
          f"median {statistics.median(before):,.0f} J; planarised quads median {statistics.median(quads):.3f}; "
          f"folded panels split median {statistics.median(float(r['folded_split']) for r in rs):.0f}; "
          f"targets met {sum(int(r['targets_met']) for r in rs)} of {11 * len(rs)}")
EOF

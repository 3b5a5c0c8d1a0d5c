#!/usr/bin/env bash
# Same answer on every machine: runs the Great Court example (and its curvature-guided
# variant) once per BLAS setting and checks that every output is identical to the first
# setting's, byte for byte, apart from report.json's timings, dates, paths and the name of
# the BLAS kernel. OpenBLAS picks a different kernel per CPU; OPENBLAS_CORETYPE makes one
# machine stand in for another. Settings the CPU cannot run (SkylakeX without AVX-512,
# Haswell without AVX2) are skipped with a note.
#
#   bash scripts/check_reproducible.sh                      # all settings below
#   bash scripts/check_reproducible.sh default Nehalem      # just these
#
# Settings: default (the machine's own choice), Haswell, SkylakeX, Nehalem (an
# OPENBLAS_CORETYPE), threads1 (OPENBLAS_NUM_THREADS=1). Needs build/cli/pqlayout
# (bash scripts/build.sh pqlayout). Exit 0 when everything agrees.
set -euo pipefail
cd "$(dirname "$0")/.."
binary=build/cli/pqlayout
[ -x "$binary" ] || { echo "check_reproducible: $binary not built (bash scripts/build.sh pqlayout)" >&2; exit 2; }
settings=("$@")
[ ${#settings[@]} -gt 0 ] || settings=(default Haswell SkylakeX Nehalem threads1)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

cpu_has() { grep -qw "$1" /proc/cpuinfo; }

# report.json without what legitimately differs between two runs of the same computation.
normalised_report() {
  grep -v -E '"([a-z_]*seconds|peak_memory_mb|started_at|output_folder|command|blas_core|blas)":' "$1"
}

run_setting() {  # setting variant out_dir
  local setting=$1 variant=$2 out=$3
  local -a env_args=(env -u OPENBLAS_CORETYPE -u OPENBLAS_NUM_THREADS)
  case "$setting" in
    default) env_args=(env) ;;
    threads1) env_args=(env OPENBLAS_NUM_THREADS=1) ;;
    *) env_args+=("OPENBLAS_CORETYPE=$setting") ;;
  esac
  local -a extra=()
  [ "$variant" = curvature ] && extra=(--set guidance.source=curvature)
  "${env_args[@]}" "$binary" run examples/great_court.yaml -q --out "$out" "${extra[@]}"
}

failures=0
reference=""
for setting in "${settings[@]}"; do
  case "$setting" in
    SkylakeX) cpu_has avx512f || { echo "skip SkylakeX: this CPU has no AVX-512"; continue; } ;;
    Haswell) cpu_has avx2 || { echo "skip Haswell: this CPU has no AVX2"; continue; } ;;
  esac
  for variant in strain curvature; do
    out="$work/$setting-$variant"
    start=$(date +%s%N)
    run_setting "$setting" "$variant" "$out"
    core=$(grep -o '"blas_core": "[^"]*"' "$out/report.json" | cut -d'"' -f4)
    compliance=$(grep -o '"compliance_total": [^,]*' "$out/report.json" | head -1 | cut -d' ' -f2)
    printf '%-9s %-9s kernel %-10s compliance %s J  (%d ms)\n' "$setting" "$variant" "$core" "$compliance" \
      $((($(date +%s%N) - start) / 1000000))
    first="$work/${reference:-$setting}-$variant"
    [ -n "$reference" ] || continue
    if ! diff <(normalised_report "$first/report.json") <(normalised_report "$out/report.json") > "$work/diff"; then
      echo "DIFFERENT: report.json of $setting ($variant) vs $reference:"; head -20 "$work/diff"; failures=$((failures + 1))
    fi
    while IFS= read -r file; do
      if ! cmp -s "$first/$file" "$out/$file"; then
        echo "DIFFERENT: $file of $setting ($variant) vs $reference"; failures=$((failures + 1))
      fi
    done < <(cd "$first" && find . -type f ! -name report.json ! -name report.html ! -name '*.svg' | sort)
  done
  reference=${reference:-$setting}
done
if [ "$failures" -gt 0 ]; then
  echo "check_reproducible: $failures outputs differ between BLAS settings" >&2
  exit 1
fi
echo "check_reproducible: every output identical across: ${settings[*]}"

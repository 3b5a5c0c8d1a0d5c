#!/usr/bin/env bash
# Fuzzes the mesh readers with libFuzzer (see fuzz/README.md): builds fuzz_obj, fuzz_ply,
# fuzz_off and fuzz_stl with clang, AddressSanitizer and UBSan in build-fuzz/, runs each
# format for SECONDS on a copy of its seed corpus (fuzz/corpus/FORMAT), and exits 1 if any
# run found a crash or sanitizer report, a hang (one input taking over 10 s) or an input
# needing over 2 GB. Findings are kept in build-fuzz/runs/FORMAT/artifacts/, each run's log
# in build-fuzz/runs/FORMAT/fuzz.log.
# Usage: scripts/fuzz.sh [SECONDS_PER_FORMAT]   (default 60)
set -euo pipefail
seconds="${1:-60}"
if ! [[ "$seconds" =~ ^[1-9][0-9]*$ ]]; then
  echo "usage: scripts/fuzz.sh [SECONDS_PER_FORMAT]" >&2
  exit 2
fi
root="$(cd "$(dirname "$0")/.." && pwd)"
build="$root/build-fuzz"
formats=(obj ply off stl)

mkdir -p "$build"
if ! CC=clang CXX=clang++ cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DPQLAYOUT_BUILD_FUZZERS=ON -DPQLAYOUT_BUILD_TESTS=OFF -DPQLAYOUT_BUILD_BENCHMARKS=OFF \
    > "$build/configure.log" 2>&1; then
  cat "$build/configure.log" >&2
  exit 1
fi
ninja -C "$build" -j2 "${formats[@]/#/fuzz_}" > "$build/build.log" 2>&1 || { cat "$build/build.log" >&2; exit 1; }

# The targets write each input to a temporary file (the readers take a path): keep it in memory.
if [ -d /dev/shm ] && [ -w /dev/shm ]; then export TMPDIR=/dev/shm; fi

failed=0
for format in "${formats[@]}"; do
  run="$build/runs/$format"
  rm -rf "$run"
  mkdir -p "$run/corpus" "$run/artifacts"
  cp "$root/fuzz/corpus/$format/"* "$run/corpus/"   # libFuzzer adds what it finds to this copy
  # One process (one core): -jobs/-fork would lose the plain exit status.
  status=0
  "$build/fuzz/fuzz_$format" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
    -dict="$root/fuzz/dict/$format.dict" -artifact_prefix="$run/artifacts/" -print_final_stats=1 \
    "$run/corpus" > "$run/fuzz.log" 2>&1 || status=$?
  # A run that crashes on its first input prints neither line: these must not stop the script.
  executed=$(sed -n 's/^stat::number_of_executed_units: *//p' "$run/fuzz.log" || true)
  coverage=$(grep -o 'cov: [0-9]*' "$run/fuzz.log" | tail -1 | cut -d' ' -f2 || true)
  findings=$(find "$run/artifacts" -type f | wc -l)
  if [ "$status" -eq 0 ] && [ "$findings" -eq 0 ]; then
    echo "fuzz $format: ok, ${executed:-?} inputs in ${seconds} s, coverage ${coverage:-?} edges, corpus $(ls "$run/corpus" | wc -l) files"
  else
    failed=1
    echo "fuzz $format: FAILED (exit $status) after ${executed:-?} inputs; findings in $run/artifacts:" >&2
    ls "$run/artifacts" >&2
    grep -E 'ERROR|SUMMARY|ALARM|out-of-memory|Test unit written' "$run/fuzz.log" | head -20 >&2 || true
  fi
done
exit "$failed"

#!/usr/bin/env bash
# Cornell box end to end (load, mesh, rows, solve to 1e-4, write a 512x512 picture) with
# default settings at PATCHES patches: median wall time of 3 runs, and the area-weighted
# relative RMS error of B (non-emitting patches) against an analytic (s=16) + cg (1e-9)
# reference on the same mesh. Run with OMP_WAIT_POLICY=passive on a shared machine.
# Usage: bench/cornell_end_to_end.sh [PATCHES] [extra radflux solve flags...]
set -euo pipefail
cd "$(dirname "$0")/.."
patches=${1:-8500}
shift || true
bin=build/release/client/radflux
out=${BENCH_OUT:-/tmp/radflux-bench}
mkdir -p "$out"
ref="$out/ref$patches.csv"
if [ ! -f "$ref" ]; then
  "$bin" solve scenes/cornell_box.obj --patches "$patches" --form-factors analytic --samples 16 \
    --solver cg --tolerance 1e-9 --max-iterations 5000 --patch-values "$ref" -q
fi
times=()
for run in 1 2 3; do
  start=$(date +%s.%N)
  "$bin" solve scenes/cornell_box.obj --patches "$patches" --render "$out/c.png" \
    --patch-values "$out/run.csv" -q "$@"
  times+=("$(awk -v s="$start" -v e="$(date +%s.%N)" 'BEGIN{printf "%.3f", e-s}')")
done
median=$(printf '%s\n' "${times[@]}" | sort -n | sed -n 2p)
echo "patches $patches flags [$*] median wall ${median}s (runs: ${times[*]})"
build/release/bench/compare_patch_values "$out/run.csv" "$ref" scenes/cornell_box.obj

#!/usr/bin/env bash
# Worker nodes (issue 5): rows per second of one job with the server alone on C cores
# against the server on 1 core plus C-1 local workers of 1 thread each (same cores in all),
# and the bytes per row the workers sent. Rows time = PHASE_ROWS -> PHASE_SOLVE in the
# server log. Usage: bench/workers.sh BUILD_DIR [CORES] [PATCHES]
set -euo pipefail
build=${1:-build/workers}
cores=${2:-2}
patches=${3:-6000}
radfluxd=$build/server/radfluxd
cli=$build/client/radflux
scene=$(dirname "$0")/../scenes/cornell_box.obj
work=$(mktemp -d)
trap 'kill $(jobs -p) 2>/dev/null || true; rm -rf "$work"' EXIT

# Runs one job; $1 = server threads, $2 = workers (1 thread each). Prints rows seconds.
run() {
  local threads=$1 workers=$2 log=$work/server_$1_$2.log
  rm -rf "$work/data"
  "$radfluxd" --listen 127.0.0.1:0 --data-dir "$work/data" --threads "$threads" \
    --worker-token bench-worker-token >"$log" 2>&1 &
  local server=$!
  local addr=""
  for _ in $(seq 100); do
    addr=$(sed -n 's/^radfluxd listening on //p' "$log")
    [ -n "$addr" ] && break
    sleep 0.1
  done
  local pids=()
  for i in $(seq "$workers"); do
    "$radfluxd" --worker --server "$addr" --threads 1 --worker-token bench-worker-token \
      >"$work/worker_$i.log" 2>&1 &
    pids+=($!)
  done
  for i in $(seq "$workers"); do
    until grep -q "registered with" "$work/worker_$i.log"; do sleep 0.1; done
  done
  "$cli" submit --server "$addr" --watch --patches "$patches" --rays 256 \
    --max-iterations 5 "$scene" >/dev/null 2>&1
  for p in "${pids[@]}"; do kill "$p"; wait "$p" 2>/dev/null || true; done
  kill "$server"; wait "$server" 2>/dev/null || true
  python3 - "$log" <<'PY'
import re, sys, datetime
text = open(sys.argv[1]).read()
def at(pattern):
    m = re.search(r"\[(\d+-\d+-\d+ \d+:\d+:\d+\.\d+)\][^\n]*" + pattern, text)
    return datetime.datetime.strptime(m.group(1), "%Y-%m-%d %H:%M:%S.%f")
rows = (at("PHASE_SOLVE") - at("PHASE_ROWS")).total_seconds()
farm = re.search(r"row farm: (.*)", text)
print(f"{rows:.3f}\t{farm.group(1) if farm else ''}")
PY
}

echo "cores=$cores patches~$patches (cornell box, monte_carlo 256 rays, 64-row blocks)"
echo "server alone, $cores thread(s):"
run "$cores" 0
echo "server 1 thread + $((cores - 1)) worker(s) x 1 thread:"
run 1 $((cores - 1))
echo "server 1 thread alone (for the per-core rate):"
run 1 0

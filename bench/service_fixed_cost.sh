#!/bin/bash
# The service's fixed cost per round trip (issue 4), paired and alternated between builds:
# for each build a warm radfluxd (--threads 2 --jobs 1, loopback); then RUNS rounds, each
# running for every build in turn `radflux solve` and `radflux submit --watch --report` of
# the Cornell box at ~8,500 patches. Per run: wall time, and the job's compute
# (mesh+embree+rows+solve from its report). The extra fixed cost of the service is
#   (service wall - service compute) - (solve wall - solve compute)
# of the same round; printed per run, then per build the median and quartiles of it, of
# the two walls, and of the wall overhead (service wall / solve wall - 1).
# Usage: bash bench/service_fixed_cost.sh RUNS BUILD_DIR...   (OMP_WAIT_POLICY=passive)
set -euo pipefail
RUNS=$1; shift
BUILDS=("$@")
SCENE=$(cd "$(dirname "$0")/.." && pwd)/scenes/cornell_box.obj
DIR=$(mktemp -d /tmp/radflux_fixed_XXXXXX)
export OMP_WAIT_POLICY=${OMP_WAIT_POLICY:-passive}
PIDS=(); ADDRS=()
trap 'for p in "${PIDS[@]}"; do kill "$p" 2>/dev/null || true; done; wait 2>/dev/null; rm -rf "$DIR"' EXIT
source "$(dirname "$0")/radfluxd_start.sh"
for k in "${!BUILDS[@]}"; do
  start_radfluxd "$DIR" "$k" "${BUILDS[$k]}/server/radfluxd" --threads 2 --jobs 1
  PIDS+=("$RADFLUXD_PID")
  ADDRS+=("$RADFLUXD_ADDR")
  # Warm-up: the scene stored, the server's caches and the client's files warm.
  "${BUILDS[$k]}/client/radflux" submit "$SCENE" --patches 8500 --server "${ADDRS[$k]}" --watch \
    --report "$DIR/w.json" >/dev/null 2>&1
  "${BUILDS[$k]}/client/radflux" solve "$SCENE" --patches 8500 --threads 2 -q --report "$DIR/w.json"
done
echo "load at start: $(cut -d' ' -f1-3 /proc/loadavg)"
now() { date +%s.%N; }
compute() {
  python3 -c "import json,sys; s=json.load(open(sys.argv[1]))['seconds']; \
print(s['mesh']+s['embree']+s['rows']+s['solve'])" "$1"
}
for i in $(seq "$RUNS"); do
  for k in "${!BUILDS[@]}"; do
    R=${BUILDS[$k]}/client/radflux
    t0=$(now); "$R" solve "$SCENE" --patches 8500 --threads 2 -q --report "$DIR/s.json"; t1=$(now)
    "$R" submit "$SCENE" --patches 8500 --server "${ADDRS[$k]}" --watch --report "$DIR/r.json" \
      >/dev/null 2>&1
    t2=$(now)
    echo "$k $t0 $t1 $t2 $(compute "$DIR/s.json") $(compute "$DIR/r.json")" >>"$DIR/runs.txt"
  done
done
echo "load at end: $(cut -d' ' -f1-3 /proc/loadavg)"
python3 - "$DIR/runs.txt" "${BUILDS[@]}" <<'PY'
import sys, statistics
rows = [l.split() for l in open(sys.argv[1])]
builds = sys.argv[2:]
def q(v):
    v = sorted(v); n = len(v)
    qs = statistics.quantiles(v, n=4) if n > 1 else [v[0]] * 3
    return f"{statistics.median(v):7.1f} ({qs[0]:.1f}..{qs[2]:.1f})"
for k, b in enumerate(builds):
    r = [[float(x) for x in row[1:]] for row in rows if row[0] == str(k)]
    solve = [1e3 * (t1 - t0) for t0, t1, t2, sc, rc in r]
    svc = [1e3 * (t2 - t1) for t0, t1, t2, sc, rc in r]
    extra = [1e3 * ((t2 - t1 - rc) - (t1 - t0 - sc)) for t0, t1, t2, sc, rc in r]
    over = [100 * ((t2 - t1) / (t1 - t0) - 1) for t0, t1, t2, sc, rc in r]
    print(f"{b}: runs {len(r)}; ms solve wall {q(solve)}, service wall {q(svc)}, "
          f"extra fixed cost {q(extra)}; wall overhead % {q(over)}")
PY

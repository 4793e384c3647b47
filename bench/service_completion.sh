#!/bin/bash
# The service's completion path and client tail (issue 4), alternated between builds: one
# radfluxd per build (SPDLOG_LEVEL=debug, --threads 2 --jobs 1, loopback), then N rounds of
# `radflux submit --watch --report` of the Cornell box at ~8,500 patches to each build in
# turn. Per build, from the server's log and the client's start and end: the time from the
# end of the solve to SUCCEEDED (report, encoding, result storage, final state), from
# SUCCEEDED to the client's exit (final event, GetResult, outputs, exit), and from the
# client's start to QUEUED; medians and quartiles.
# Usage: bash bench/service_completion.sh N BUILD_DIR...   (OMP_WAIT_POLICY=passive)
set -euo pipefail
N=$1; shift; SCENE=$(cd "$(dirname "$0")/.." && pwd)/scenes/cornell_box.obj
D=$(mktemp -d /tmp/radflux_completion_XXXXXX); PIDS=(); ADDRS=()
BUILDS=("$@")
export OMP_WAIT_POLICY=${OMP_WAIT_POLICY:-passive}
source "$(dirname "$0")/radfluxd_start.sh"
for k in "${!BUILDS[@]}"; do
  start_radfluxd $D $k env SPDLOG_LEVEL=debug ${BUILDS[$k]}/server/radfluxd --threads 2 --jobs 1
  PIDS+=($RADFLUXD_PID); ADDRS+=("$RADFLUXD_ADDR")
  ${BUILDS[$k]}/client/radflux submit $SCENE --patches 8500 --server ${ADDRS[$k]} --watch --report $D/r.json >/dev/null 2>&1
done
for i in $(seq $N); do for k in "${!BUILDS[@]}"; do
  t0=$(date +%s.%N); J=$(${BUILDS[$k]}/client/radflux submit $SCENE --patches 8500 --server ${ADDRS[$k]} --watch --report $D/r.json 2>/dev/null | tail -1); t1=$(date +%s.%N)
  echo "$J $t0 $t1" >> $D/runs$k
done; done
for p in "${PIDS[@]}"; do kill $p; done; wait 2>/dev/null || true
for k in "${!BUILDS[@]}"; do python3 - $D/runs$k $D/server_$k.log ${BUILDS[$k]} <<'PY'
import sys, re, datetime, statistics
def ts(l): return datetime.datetime.strptime(l[1:24], "%Y-%m-%d %H:%M:%S.%f").timestamp()
log = open(sys.argv[2]).read().splitlines()
ev = {}
for l in log:
    m = re.search(r"job (job-\w+): (.*)", l)
    if not m: continue
    j, what = m.groups(); e = ev.setdefault(j, {})
    if "QUEUED (scene" in what: e['queued'] = ts(l)
    if "-> JOB_STATE_RUNNING PHASE_SOLVE" in what: e['solve'] = ts(l)
    if "-> JOB_STATE_SUCCEEDED" in what: e['done'] = ts(l)
    m2 = re.search(r"solve ([0-9.]+), result encoding", what)
    if m2: e['solve_ms'] = float(m2.group(1))
a, b, c = [], [], []
for line in open(sys.argv[1]):
    j, t0, t1 = line.split(); e = ev[j]
    a.append(1e3*(e['done']-e['solve'])-e['solve_ms']); b.append(1e3*(float(t1)-e['done'])); c.append(1e3*(e['queued']-float(t0)))
q = lambda v: "%.1f (%.1f..%.1f)" % (statistics.median(v), *[statistics.quantiles(v, n=4)[i] for i in (0, 2)])
print(f"{sys.argv[3]}: n {len(a)}; ms solve end -> SUCCEEDED {q(a)}; SUCCEEDED -> client exit {q(b)}; client start -> QUEUED {q(c)}")
PY
done
rm -rf $D

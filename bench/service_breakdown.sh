#!/bin/bash
# Where the service's time goes (issue 4): one radfluxd (--threads 2), N runs of the Cornell
# box at ~8,500 patches, each: `radflux solve`, `radflux list` (a client process start plus
# one call), `radflux submit` (upload of the stored scene + SubmitJob), `radflux watch`,
# `radflux result`, then the same round trip in one process (`radflux submit --watch
# --report`), with the wall time of each and the phase seconds of both reports; then
# the server's phase transitions from its log. Run with SPDLOG_LEVEL=debug to get radfluxd's
# per-step timings (limits check, job row, state updates, result encoding/storing/reading)
# in $SERVER_LOG (default /tmp/radflux_breakdown_server.log).
# Usage: bash bench/service_breakdown.sh BUILD_DIR [N] ["extra radfluxd flags"]
set -euo pipefail
BUILD=$1; N=${2:-5}; EXTRA=${3:-}
SERVER_LOG=${SERVER_LOG:-/tmp/radflux_breakdown_server.log}
R=$BUILD/client/radflux; D=$BUILD/server/radfluxd
SCENE=$(cd "$(dirname "$0")/.." && pwd)/scenes/cornell_box.obj
DIR=$(mktemp -d /tmp/radflux_breakdown_XXXXXX)
export OMP_WAIT_POLICY=passive
source "$(dirname "$0")/radfluxd_start.sh"
start_radfluxd "$DIR" main $D --threads 2 --jobs 1 $EXTRA
PID=$RADFLUXD_PID; ADDR=$RADFLUXD_ADDR
trap 'kill $PID; wait $PID 2>/dev/null; rm -rf $DIR' EXIT
now() { date +%s.%N; }
$R submit $SCENE --patches 8500 --server $ADDR --watch >/dev/null 2>&1  # warm-up, scene stored
for i in $(seq $N); do
  t0=$(now); $R solve $SCENE --patches 8500 --threads 2 -q --report $DIR/s.json; t1=$(now)
  $R list --server $ADDR >/dev/null; t2=$(now)
  JOB=$($R submit $SCENE --patches 8500 --server $ADDR 2>/dev/null | tail -1); t3=$(now)
  $R watch $JOB --server $ADDR 2>/dev/null; t4=$(now)
  $R result $JOB --server $ADDR --report $DIR/r.json >/dev/null; t5=$(now)
  $R submit $SCENE --patches 8500 --server $ADDR --watch --report $DIR/o.json >/dev/null 2>&1; t6=$(now)
  python3 - "$t0" "$t1" "$t2" "$t3" "$t4" "$t5" "$t6" $DIR/s.json $DIR/r.json <<'PY'
import sys, json
t = [float(x) for x in sys.argv[1:8]]
s = json.load(open(sys.argv[8]))['seconds']; r = json.load(open(sys.argv[9]))['seconds']
c = lambda x: x['mesh'] + x['embree'] + x['rows'] + x['solve']
print(f"solve_wall {t[1]-t[0]:.3f} list_wall {t[2]-t[1]:.3f} submit_wall {t[3]-t[2]:.3f} "
      f"watch_wall {t[4]-t[3]:.3f} result_wall {t[5]-t[4]:.3f} one_process_wall {t[6]-t[5]:.3f} | solve: mesh {s['mesh']:.3f} embree {s['embree']:.3f} "
      f"rows {s['rows']:.3f} solve {s['solve']:.3f} | svc: mesh {r['mesh']:.3f} embree {r['embree']:.3f} rows {r['rows']:.3f} solve {r['solve']:.3f}")
PY
done
cp $DIR/server_main.log "$SERVER_LOG"; grep -E "QUEUED|->" $DIR/server_main.log | tail -$((10*N)) > $DIR/phases.txt
python3 - $DIR/phases.txt <<'PY'
import sys, re, datetime, collections
rows = [l for l in open(sys.argv[1])]
jobs = collections.defaultdict(list)
for l in rows:
    m = re.match(r"\[([\d\- :.]+)\].*job (job-\w+): (.*)", l)
    if not m: continue
    t = datetime.datetime.strptime(m.group(1), "%Y-%m-%d %H:%M:%S.%f").timestamp()
    what = m.group(3)
    key = "QUEUED" if what.startswith("QUEUED") else what.split("-> ")[1].split(":")[0].strip()
    jobs[m.group(2)].append((key, t))
for j, ev in jobs.items():
    out = []
    for (a, ta), (b, tb) in zip(ev, ev[1:]):
        out.append(f"{a.split()[-1]}->{b.split()[-1]} {1000*(tb-ta):.0f}ms")
    print(j, " ".join(out))
PY

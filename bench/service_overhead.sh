#!/bin/bash
# Service overhead (issue 4), on the Cornell box at ~8,500 patches, one radfluxd on loopback:
#  A. `radflux solve` in-process vs the service path `radflux submit --watch` + `radflux result`
#     (upload, queue, rows stored block by block with fsync, checkpointed solve, result stored
#     and streamed back): wall time, and the job's compute time (mesh+embree+rows+solve from
#     each report). Median of 3 of each, interleaved.
#  B. Snapshot streaming: the same job with 0 watchers vs 50 watchers asking a float32
#     snapshot every iteration (`radflux watch --snapshot-every 1`, niced so that the clients'
#     own decoding competes less with the server on this 2-core machine): the job's solve
#     seconds and compute seconds from its report. Median of 3 of each, interleaved. A
#     blocker job runs first so the watchers connect while the measured job is queued.
# Usage: bench/service_overhead.sh [BUILD_DIR]   (default build/svc2; needs radflux, radfluxd)
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
BUILD=${1:-$ROOT/build/svc2}
RADFLUX=$BUILD/client/radflux
RADFLUXD=$BUILD/server/radfluxd
SERVICE=$RADFLUX
"$RADFLUX" submit --help >/dev/null 2>&1 || SERVICE=$BUILD/tests/integration/radflux_service_cli
SCENE=$ROOT/scenes/cornell_box.obj
JOB_OPTS=(--patches 8500)
THREADS=2
DIR=$(mktemp -d /tmp/radflux_bench_XXXXXX)
trap 'kill $PID 2>/dev/null || true; wait $PID 2>/dev/null || true; rm -rf "$DIR"' EXIT
mkfifo "$DIR/out"
"$RADFLUXD" --listen 127.0.0.1:0 --data-dir "$DIR/data" --threads $THREADS --jobs 1 \
  >"$DIR/out" 2>"$DIR/server.log" &
PID=$!
read -r LINE <"$DIR/out"
ADDR=${LINE#radfluxd listening on }
now() { date +%s.%N; }
TICKS=$(getconf CLK_TCK)
server_cpu() { awk -v t="$TICKS" '{printf "%.3f", ($14 + $15) / t}' "/proc/$PID/stat"; }
LOAD_START=$(cut -d' ' -f1-3 /proc/loadavg)
compute() {  # mesh+embree+rows+solve seconds and solve seconds of a report
  python3 -c "import json,sys; s=json.load(open(sys.argv[1]))['seconds']; \
print(s['mesh']+s['embree']+s['rows']+s['solve'], s['solve'])" "$1"
}

echo "# part A: solve vs service (median of 3)" >&2
for i in 1 2 3; do
  t0=$(now)
  TIMEFORMAT='%U %S'
  solve_cpu=$( { time "$RADFLUX" solve "$SCENE" "${JOB_OPTS[@]}" --threads $THREADS -q \
                   --report "$DIR/solve_$i.json" ; } 2>&1 | awk '{print $1 + $2}')
  t1=$(now)
  c0=$(server_cpu)
  JOB=$("$SERVICE" submit "$SCENE" "${JOB_OPTS[@]}" --watch --server "$ADDR" 2>/dev/null | tail -n 1)
  "$SERVICE" result "$JOB" --server "$ADDR" --report "$DIR/svc_$i.json" >/dev/null
  t2=$(now)
  c1=$(server_cpu)
  echo "A $i solve_wall $(echo "$t1 - $t0" | bc) service_wall $(echo "$t2 - $t1" | bc)" \
       "solve_compute $(compute "$DIR/solve_$i.json") service_compute $(compute "$DIR/svc_$i.json")" \
       "solve_cpu $solve_cpu server_cpu $(echo "$c1 - $c0" | bc)" \
    | tee -a "$DIR/a.txt" >&2
done

echo "# part B: 0 vs 50 snapshot watchers (median of 3)" >&2
for i in 1 2 3; do
  for watchers in 0 50; do
    # A blocker job runs first (--jobs 1) so that the 50 watcher processes start and
    # connect while the measured job is still queued: their start-up does not land on it.
    c0=$(server_cpu)
    "$SERVICE" submit "$SCENE" --patches 4000 --server "$ADDR" >/dev/null 2>&1
    JOB=$("$SERVICE" submit "$SCENE" "${JOB_OPTS[@]}" --server "$ADDR" 2>/dev/null | tail -n 1)
    pids=()
    for ((w = 0; w < watchers; ++w)); do
      nice -n 10 "$SERVICE" watch "$JOB" --server "$ADDR" --snapshot-every 1 \
        2>"$DIR/w_${i}_$w.err" >/dev/null &
      pids+=($!)
    done
    connected=0
    while ((connected < watchers)); do
      connected=$( (grep -l "JOB_STATE_QUEUED" "$DIR"/w_"${i}"_*.err 2>/dev/null || true) | wc -l)
      sleep 0.05
    done
    started=$("$SERVICE" list --server "$ADDR" | grep -c "^$JOB .*JOB_STATE_QUEUED" || true)
    "$SERVICE" watch "$JOB" --server "$ADDR" 2>/dev/null
    for p in "${pids[@]}"; do wait "$p" || { echo "a watcher failed:" >&2; cat "$DIR"/w_"${i}"_*.err | grep radflux: | sort | uniq -c >&2; exit 1; }; done
    c1=$(server_cpu)
    "$SERVICE" result "$JOB" --server "$ADDR" --report "$DIR/b_${i}_$watchers.json" >/dev/null
    got=0
    if ((watchers > 0)); then
      got=$(cat "$DIR"/w_"${i}"_*.err | awk '/snapshots received/ {s += $1} END {print s / '"$watchers"'}')
    fi
    echo "B $i watchers $watchers compute_solve $(compute "$DIR/b_${i}_$watchers.json")" \
         "snapshots_per_watcher $got still_queued_when_all_connected $started" \
         "server_cpu_blocker_and_job $(echo "$c1 - $c0" | bc)" \
      | tee -a "$DIR/b.txt" >&2
  done
done

echo "load average (1/5/15 min) at start: $LOAD_START, at end: $(cut -d' ' -f1-3 /proc/loadavg)"
python3 - "$DIR" <<'PY'
import statistics as st, sys
d = sys.argv[1]
a = [l.split() for l in open(f"{d}/a.txt")]
med = lambda xs: st.median(float(x) for x in xs)
sw, vw = med(r[3] for r in a), med(r[5] for r in a)
sc, vc = med(r[7] for r in a), med(r[10] for r in a)
print("| measure (median of 3) | radflux solve | service | overhead |")
print("|---|---|---|---|")
print(f"| wall time, s | {sw:.3f} | {vw:.3f} | {100 * (vw / sw - 1):+.1f}% |")
print(f"| job compute (mesh+embree+rows+solve), s | {sc:.3f} | {vc:.3f} | {100 * (vc / sc - 1):+.1f}% |")
pc, vpc = med(r[13] for r in a), med(r[15] for r in a)
print(f"| CPU s (solve process / server process) | {pc:.3f} | {vpc:.3f} | {100 * (vpc / pc - 1):+.1f}% |")
ratio = st.median(float(r[5]) / float(r[3]) for r in a)
print(f"| median of paired wall-time ratios | | | {100 * (ratio - 1):+.1f}% |")
b = [l.split() for l in open(f"{d}/b.txt")]
zero = [r for r in b if r[3] == "0"]
fifty = [r for r in b if r[3] == "50"]
c0, c50 = med(r[5] for r in zero), med(r[5] for r in fifty)
s0, s50 = med(r[6] for r in zero), med(r[6] for r in fifty)
snaps = med(r[8] for r in fifty)
print()
print("| measure (median of 3) | 0 watchers | 50 watchers | cost |")
print("|---|---|---|---|")
print(f"| job compute (mesh+embree+rows+solve), s | {c0:.3f} | {c50:.3f} | {100 * (c50 / c0 - 1):+.1f}% |")
print(f"| solve phase, s | {s0:.3f} | {s50:.3f} | {100 * (s50 / s0 - 1):+.1f}% |")
print(f"| snapshots received per watcher | - | {snaps:.1f} | |")
u0, u50 = med(r[12] for r in zero), med(r[12] for r in fifty)
print(f"| server CPU s, blocker + job | {u0:.3f} | {u50:.3f} | {u50 - u0:+.3f} s |")
ratio = st.median(float(f[5]) / float(z[5]) for z, f in zip(zero, fifty))
print(f"| median of paired job-compute ratios | | | {100 * (ratio - 1):+.1f}% |")
PY

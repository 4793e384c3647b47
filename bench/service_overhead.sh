#!/bin/bash
# Service overhead (issue 4), on the Cornell box at ~8,500 patches, radfluxd on loopback:
#  A. `radflux solve` in-process vs the service path in one client process, `radflux submit
#     --watch --report` (upload, queue, rows checkpointed by time, checkpointed solve, result
#     stored and streamed back), and in two (`submit --watch` then `radflux result`, the path
#     before submit took output options): wall time, and the job's compute time
#     (mesh+embree+rows+solve from each report). RUNS of each, interleaved; medians and the
#     median of paired ratios.
#  B. Snapshot streaming, unpinned: the same job with 0 watchers vs 50 watchers asking a
#     snapshot every iteration (`radflux watch --snapshot-every 1`, niced: float16 since
#     commit "watch asks float16", float32 before), all on the same cores as the server:
#     the job's compute seconds from its report.
#  C. Snapshot streaming as in production, where watchers are other machines: a second
#     radfluxd pinned to CPU 0 (`taskset -c 0`, --threads 1), the 50 watcher processes
#     pinned to CPU 1; the job's compute seconds with 0 vs 50 watchers, and `radflux solve
#     --threads 1` on CPU 0 for reference.
#  In B and C a blocker job (30,000 patches, seconds long) runs first and is cancelled once
#  every watcher has connected, so the watchers connect while the measured job is queued:
#  their start-up does not land on it (with the 4,000-patch blocker used before svc8 the
#  blocker ended first, and late watchers connected during, or after, the measured job,
#  getting its history and one snapshot). radfluxd runs with SPDLOG_LEVEL=debug and
#  logs, per job, the CPU time of the job's own thread and of the whole server process
#  while the job ran (ns clocks): C's "server CPU during the job" with 0 vs 50 watchers is
#  what streaming to the watchers cost the server's core, the job's own thread excluded.
# Usage: bash bench/service_overhead.sh [BUILD_DIR] [RUNS]   (default build/release, 5;
# needs radflux and radfluxd; set OMP_WAIT_POLICY=passive on a shared machine)
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
BUILD=${1:-$ROOT/build/release}
RUNS=${2:-5}
RADFLUX=$BUILD/client/radflux
RADFLUXD=$BUILD/server/radfluxd
SERVICE=$RADFLUX
"$RADFLUX" submit --help >/dev/null 2>&1 || SERVICE=$BUILD/tests/integration/radflux_service_cli
SCENE=$ROOT/scenes/cornell_box.obj
JOB_OPTS=(--patches 8500)
THREADS=2
DIR=$(mktemp -d /tmp/radflux_bench_XXXXXX)
PIDS=()
trap 'for p in "${PIDS[@]}"; do kill "$p" 2>/dev/null || true; wait "$p" 2>/dev/null || true; done; rm -rf "$DIR"' EXIT
# start_server NAME THREADS [taskset prefix...]: a radfluxd on its own data dir; sets
# ADDR_<NAME> and PID_<NAME>.
source "$(dirname "$0")/radfluxd_start.sh"
start_server() {
  local name=$1 threads=$2
  shift 2
  start_radfluxd "$DIR" "$name" env SPDLOG_LEVEL=debug "$@" "$RADFLUXD" --threads "$threads" \
    --jobs 1
  PIDS+=("$RADFLUXD_PID")
  printf -v "ADDR_$name" '%s' "$RADFLUXD_ADDR"
  printf -v "PID_$name" '%s' "$RADFLUXD_PID"
}
start_server main $THREADS
start_server pinned 1 taskset -c 0
now() { date +%s.%N; }
TICKS=$(getconf CLK_TCK)
server_cpu() { awk -v t="$TICKS" '{printf "%.3f", ($14 + $15) / t}' "/proc/$1/stat"; }
LOAD_START=$(cut -d' ' -f1-3 /proc/loadavg)
compute() {  # mesh+embree+rows+solve seconds and solve seconds of a report
  python3 -c "import json,sys; s=json.load(open(sys.argv[1]))['seconds']; \
print(s['mesh']+s['embree']+s['rows']+s['solve'], s['solve'])" "$1"
}

# job_cpu NAME JOB: "job thread ms" and "process ms" of JOB from server NAME's debug log.
job_cpu() {
  grep "job $2: cpu ms" "$DIR/server_$1.log" | sed -E 's/.*job thread ([0-9.]+), process ([0-9.]+).*/\1 \2/'
}

# watched_job PART RUN WATCHERS NAME [taskset prefix for the watchers...]: one measured
# job with that many snapshot watchers on server NAME; appends a line to $DIR/PART.txt.
watched_job() {
  local part=$1 i=$2 watchers=$3 name=$4
  local addr_var=ADDR_$4 pid_var=PID_$4
  local addr=${!addr_var} pid=${!pid_var}
  shift 4
  local c0 c1 blocker job got started connected pids=()
  c0=$(server_cpu "$pid")
  blocker=$("$SERVICE" submit "$SCENE" --patches 30000 --server "$addr" 2>/dev/null | tail -n 1)
  job=$("$SERVICE" submit "$SCENE" "${JOB_OPTS[@]}" --server "$addr" 2>/dev/null | tail -n 1)
  rm -f "$DIR"/w_*.err
  for ((w = 0; w < watchers; ++w)); do
    "$@" nice -n 10 "$SERVICE" watch "$job" --server "$addr" --snapshot-every 1 \
      2>"$DIR/w_$w.err" >/dev/null &
    pids+=($!)
  done
  connected=0
  while ((connected < watchers)); do
    if grep -q "^radflux: " "$DIR"/w_*.err 2>/dev/null; then
      echo "a watcher failed:" >&2; grep -h "^radflux: " "$DIR"/w_*.err | sort | uniq -c >&2; exit 1
    fi
    connected=$( (grep -l "^\[[0-9]*\] queued" "$DIR"/w_*.err 2>/dev/null || true) | wc -l)
    sleep 0.05
  done
  started=$("$SERVICE" list --server "$addr" | grep -c "^$job .*JOB_STATE_QUEUED" || true)
  "$SERVICE" cancel "$blocker" --server "$addr" >/dev/null
  "$SERVICE" watch "$job" --server "$addr" 2>/dev/null
  for p in "${pids[@]}"; do wait "$p" || { echo "a watcher failed:" >&2; cat "$DIR"/w_*.err | grep radflux: | sort | uniq -c >&2; exit 1; }; done
  c1=$(server_cpu "$pid")
  "$SERVICE" result "$job" --server "$addr" --report "$DIR/${part}_${i}_$watchers.json" >/dev/null
  got=0 events=0
  if ((watchers > 0)); then
    got=$(cat "$DIR"/w_*.err | awk '/snapshots received/ {s += $1} END {print s / '"$watchers"'}')
    events=$(cat "$DIR"/w_*.err | grep -c '^\[' || true)
    events=$(echo "$events / $watchers" | bc -l)
  fi
  echo "$part $i watchers $watchers compute_solve $(compute "$DIR/${part}_${i}_$watchers.json")" \
       "snapshots_per_watcher $got still_queued_when_all_connected $started" \
       "server_cpu_blocker_and_job $(echo "$c1 - $c0" | bc) events_per_watcher $events" \
       "cpu_ms_job_thread_process $(job_cpu "$name" "$job")" \
    | tee -a "$DIR/$part.txt" >&2
}

for i in $(seq "$RUNS"); do
  echo "# run $i of $RUNS, load average $(cut -d' ' -f1-3 /proc/loadavg)" >&2
  # A: solve vs service, 2 threads each.
  t0=$(now)
  TIMEFORMAT='%U %S'
  solve_cpu=$( { time "$RADFLUX" solve "$SCENE" "${JOB_OPTS[@]}" --threads $THREADS -q \
                   --report "$DIR/solve_$i.json" ; } 2>&1 | awk '{print $1 + $2}')
  t1=$(now)
  c0=$(server_cpu "$PID_main")
  "$SERVICE" submit "$SCENE" "${JOB_OPTS[@]}" --watch --server "$ADDR_main" \
    --report "$DIR/svc_$i.json" >/dev/null 2>&1
  t2=$(now)
  c1=$(server_cpu "$PID_main")
  JOB=$("$SERVICE" submit "$SCENE" "${JOB_OPTS[@]}" --watch --server "$ADDR_main" 2>/dev/null | tail -n 1)
  "$SERVICE" result "$JOB" --server "$ADDR_main" --report "$DIR/svc2_$i.json" >/dev/null
  t3=$(now)
  echo "A $i solve_wall $(echo "$t1 - $t0" | bc) service_wall $(echo "$t2 - $t1" | bc)" \
       "solve_compute $(compute "$DIR/solve_$i.json") service_compute $(compute "$DIR/svc_$i.json")" \
       "solve_cpu $solve_cpu server_cpu $(echo "$c1 - $c0" | bc)" \
       "two_process_wall $(echo "$t3 - $t2" | bc)" \
    | tee -a "$DIR/A.txt" >&2
  # B: 0 vs 50 watchers, unpinned.
  watched_job B "$i" 0 main
  watched_job B "$i" 50 main
  # C: server on CPU 0 (1 thread), watchers on CPU 1; solve --threads 1 on CPU 0.
  taskset -c 0 "$RADFLUX" solve "$SCENE" "${JOB_OPTS[@]}" --threads 1 -q \
    --report "$DIR/C_solve_$i.json"
  echo "Csolve $i compute_solve $(compute "$DIR/C_solve_$i.json")" | tee -a "$DIR/Csolve.txt" >&2
  watched_job C "$i" 0 pinned taskset -c 1
  watched_job C "$i" 50 pinned taskset -c 1
done

echo "load average (1/5/15 min) at start: $LOAD_START, at end: $(cut -d' ' -f1-3 /proc/loadavg)"
python3 - "$DIR" "$RUNS" <<'PY'
import statistics as st, sys
d, runs = sys.argv[1], sys.argv[2]
med = lambda xs: st.median(float(x) for x in xs)
pct = lambda a, b: f"{100 * (b / a - 1):+.1f}%"
a = [l.split() for l in open(f"{d}/A.txt")]
sw, vw = med(r[3] for r in a), med(r[5] for r in a)
sc, vc = med(r[7] for r in a), med(r[10] for r in a)
print(f"| A: measure (median of {runs}) | radflux solve | service | overhead |")
print("|---|---|---|---|")
print(f"| wall time, s (service: `submit --watch --report`, one process) | {sw:.3f} | {vw:.3f} | {pct(sw, vw)} |")
tw = med(r[17] for r in a)
print(f"| wall time, s (service: `submit --watch` + `result`, two processes) | {sw:.3f} | {tw:.3f} | {pct(sw, tw)} |")
print(f"| job compute (mesh+embree+rows+solve), s | {sc:.3f} | {vc:.3f} | {pct(sc, vc)} |")
pc, vpc = med(r[13] for r in a), med(r[15] for r in a)
print(f"| CPU s (solve process / server process) | {pc:.3f} | {vpc:.3f} | {pct(pc, vpc)} |")
print(f"| median of paired wall-time ratios (one process) | | | {pct(1, st.median(float(r[5]) / float(r[3]) for r in a))} |")
print(f"| median of paired wall-time ratios (two processes) | | | {pct(1, st.median(float(r[17]) / float(r[3]) for r in a))} |")
print(f"| median of paired job-compute ratios | | | {pct(1, st.median(float(r[10]) / float(r[7]) for r in a))} |")
def watchers(part, title, solve_ref=None):
    b = [l.split() for l in open(f"{d}/{part}.txt")]
    zero = [r for r in b if r[3] == "0"]
    fifty = [r for r in b if r[3] == "50"]
    c0, c50 = med(r[5] for r in zero), med(r[5] for r in fifty)
    print()
    print(f"| {title} (median of {runs}) | 0 watchers | 50 watchers | cost |")
    print("|---|---|---|---|")
    if solve_ref:
        print(f"| `radflux solve --threads 1` on CPU 0, compute s | {solve_ref:.3f} | | |")
    print(f"| job compute (mesh+embree+rows+solve), s | {c0:.3f} | {c50:.3f} | {pct(c0, c50)} |")
    print(f"| solve phase, s | {med(r[6] for r in zero):.3f} | {med(r[6] for r in fifty):.3f} | |")
    print(f"| snapshots / events received per watcher | - | {med(r[8] for r in fifty):.1f} / {med(r[14] for r in fifty):.1f} | |")
    u0, u50 = med(r[12] for r in zero), med(r[12] for r in fifty)
    print(f"| server CPU s, blocker + job | {u0:.3f} | {u50:.3f} | {u50 - u0:+.3f} s |")
    ratio = st.median(float(f[5]) / float(z[5]) for z, f in zip(zero, fifty))
    print(f"| median of paired job-compute ratios | | | {pct(1, ratio)} |")
    t0, t50 = med(r[16] for r in zero), med(r[16] for r in fifty)
    print(f"| CPU ms of the job's own thread | {t0:.1f} | {t50:.1f} | {pct(t0, t50)} |")
    p0, p50 = med(r[17] for r in zero), med(r[17] for r in fifty)
    print(f"| server CPU ms during the job (all threads) | {p0:.1f} | {p50:.1f} | {p50 - p0:+.1f} ms |")
    extra = st.median((float(f[17]) - float(z[17])) / float(z[17]) for z, f in zip(zero, fifty))
    print(f"| watchers' extra server CPU / server CPU of the job, paired median | | | {100 * extra:+.1f}% |")
watchers("B", "B: unpinned, watchers on the server's cores")
cs = med(l.split()[3] for l in open(f"{d}/Csolve.txt"))
watchers("C", "C: server on CPU 0 (1 thread), watchers on CPU 1", cs)
PY

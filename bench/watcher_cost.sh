#!/bin/bash
# What 50 snapshot watchers cost a radfluxd, alternated between server binaries (issue 4).
# For each SERVER a radfluxd pinned to CPU 0 (--threads 1 --jobs 1, loopback, debug log);
# then RUNS rounds, each running for every server in turn one job with 0 watchers and one
# with 50 (`radflux watch --snapshot-every $SNAP`, niced, pinned to CPU 1). A blocker job
# runs first and is cancelled once every watcher has connected, so their start-up does not
# land on the measured job. Per server, medians of the job thread's CPU and the whole
# process's CPU while the job ran (the server's debug log), and of the paired "other
# threads" extra: (process - job thread) with 50 watchers minus the same with 0. The log's
# window ends before the job's final event; "to the last watcher" also counts that event,
# the last snapshot and the streams' teardown: the server's process CPU clock (less the job
# thread's) from the job's start to the end of its last watch stream (debug log), 50
# watchers minus 0 (where the bench's own watcher is the last).
# With VIEW_TABS=N, the measured job's watchers are instead one `radflux view` (itself one
# watch stream) and N clients of its page (bench/view_tabs.py: the page's event stream and
# newest-snapshot fetches, no rendering), all niced on CPU 1; the table's "50" is then N.
# Usage: bash bench/watcher_cost.sh RUNS SERVER...   (SERVER: a radfluxd binary)
#   env: CLIENT (default build/release/client/radflux), JOB_PATCHES (8500),
#        BLOCKER_PATCHES (30000), SNAP (1; 0 = no snapshots), VIEW_TABS (unset)
set -eu
RUNS=$1; shift; SERVERS=("$@")
ROOT=$(cd "$(dirname "$0")/.." && pwd)
R=${CLIENT:-$ROOT/build/release/client/radflux}; SCENE=$ROOT/scenes/cornell_box.obj
D=$(mktemp -d); ADDRS=(); SPIDS=()
trap 'kill ${SPIDS[@]} 2>/dev/null; rm -rf $D' EXIT
source "$(dirname "$0")/radfluxd_start.sh"
for k in "${!SERVERS[@]}"; do
  start_radfluxd "$D" "$k" env SPDLOG_LEVEL=debug taskset -c 0 "${SERVERS[$k]}" --threads 1 --jobs 1
  SPIDS+=("$RADFLUXD_PID"); ADDRS+=("$RADFLUXD_ADDR")
done
WATCHERS=${VIEW_TABS:-50}
one() {  # SERVER_INDEX WATCHERS: "index watchers job_thread_ms process_ms to_last_watcher_ms"
  local k=$1 n=$2 A=${ADDRS[$1]} pids=() blocker job view=""
  blocker=$("$R" submit "$SCENE" --patches "${BLOCKER_PATCHES:-30000}" --server "$A" 2>/dev/null | tail -1)
  job=$("$R" submit "$SCENE" --patches "${JOB_PATCHES:-8500}" --server "$A" 2>/dev/null | tail -1)
  rm -f "$D"/w_*.err
  if [ -n "${VIEW_TABS:-}" ] && [ "$n" -gt 0 ]; then
    rm -f "$D/view.out"
    taskset -c 1 nice -n 10 "$R" view "$job" --server "$A" >"$D/view.out" 2>/dev/null &
    view=$!
    until [ -s "$D/view.out" ]; do sleep 0.05; done
    taskset -c 1 nice -n 10 python3 "$(dirname "$0")/view_tabs.py" "$(head -n 1 "$D/view.out")" \
      "$n" "$D/w_" &
    pids+=($!)
  fi
  for ((w = 0; w < n; ++w)); do
    [ -z "${VIEW_TABS:-}" ] || break
    taskset -c 1 nice -n 10 "$R" watch "$job" --server "$A" --snapshot-every "${SNAP:-1}" \
      2>"$D/w_$w.err" >/dev/null &
    pids+=($!)
  done
  while [ "$( (grep -l "^\[[0-9]*\] queued" "$D"/w_*.err 2>/dev/null || true) | wc -l)" -lt "$n" ]; do
    sleep 0.05
  done
  "$R" cancel "$blocker" --server "$A" >/dev/null
  "$R" watch "$job" --server "$A" >/dev/null 2>&1
  for p in "${pids[@]}"; do wait "$p"; done
  [ -z "$view" ] || { kill "$view"; wait "$view" 2>/dev/null || true; }
  # The server logs each stream's end once it is done with it: wait for all n + 1 (30 s at
  # most; with VIEW_TABS, the view's one stream + 1).
  local waited=0 streams=$((n + 1))
  [ -z "${VIEW_TABS:-}" ] || [ "$n" -eq 0 ] || streams=2
  until [ "$(grep -c "job $job: watch ended" "$D/server_$k.log")" -ge "$streams" ]; do
    waited=$((waited + 1))
    [ "$waited" -le 1500 ] || { echo "job $job: $streams watch ends not logged in 30 s" >&2; exit 1; }
    sleep 0.02
  done
  echo "$k $n $(grep "job $job: cpu ms" "$D/server_$k.log" |
    sed -E 's/.*job thread ([0-9.]+), process ([0-9.]+), process clock at start ([0-9.]+)/\1 \2 \3/') $(
    grep "job $job: watch ended" "$D/server_$k.log" | sed -E 's/.*process cpu clock //' |
      sort -g | tail -1)"
}
for i in $(seq "$RUNS"); do
  for k in "${!SERVERS[@]}"; do one "$k" 0; one "$k" "$WATCHERS"; done
done >"$D/res.txt"
python3 - "$D/res.txt" "${SERVERS[@]}" <<'PY'
import statistics as st, sys
rows = [l.split() for l in open(sys.argv[1])]
for k, name in enumerate(sys.argv[2:]):
    z = [(float(r[2]), float(r[3]), float(r[5]) - float(r[4]))
         for r in rows if int(r[0]) == k and r[1] == "0"]
    w = [(float(r[2]), float(r[3]), float(r[5]) - float(r[4]))
         for r in rows if int(r[0]) == k and r[1] != "0"]
    extra = [(b[1] - b[0]) - (a[1] - a[0]) for a, b in zip(z, w)]
    share = [e / a[1] * 100 for e, a in zip(extra, z)]
    whole = [(b[2] - b[0]) - (a[2] - a[0]) for a, b in zip(z, w)]
    whole_share = [e / a[1] * 100 for e, a in zip(whole, z)]
    print(f"{name}: job thread ms {st.median(x[0] for x in z):.1f} -> {st.median(x[0] for x in w):.1f}; "
          f"process ms {st.median(x[1] for x in z):.1f} -> {st.median(x[1] for x in w):.1f}; "
          f"other threads +{st.median(extra):.1f} ms ({', '.join(f'{e:.1f}' for e in sorted(extra))}), "
          f"{st.median(share):.1f}% of the job's server CPU; to the last watcher "
          f"+{st.median(whole):.1f} ms ({', '.join(f'{e:.1f}' for e in sorted(whole))}), "
          f"{st.median(whole_share):.1f}%")
PY

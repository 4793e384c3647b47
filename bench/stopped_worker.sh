#!/usr/bin/env bash
# Stopped workers (issue 22): what one worker frozen with SIGSTOP mid-block costs a job.
# The server (1 thread) and two 1-thread workers build one job's rows, default lease
# (300 s); in the second run one worker holds its first block (--testing-block-delay-ms)
# and is SIGSTOPped as soon as it starts it. Rows time = PHASE_ROWS -> PHASE_SOLVE in the
# server log; the log lines of the backup or of the release for silence are printed.
# Usage: bench/stopped_worker.sh BUILD_DIR [PATCHES]   (default build/ci, 3000)
set -euo pipefail
build=${1:-build/ci}
patches=${2:-3000}
radfluxd=$build/server/radfluxd
cli=$build/client/radflux
scene=$(dirname "$0")/../scenes/cornell_box.obj
work=$(mktemp -d)
trap 'kill -CONT $(jobs -p) 2>/dev/null || true; kill -9 $(jobs -p) 2>/dev/null || true; rm -rf "$work"' EXIT

# Runs one job; $1 = "stop" to freeze the second worker mid-block. Prints the rows seconds.
run() {
  local log=$work/server_$1.log
  rm -rf "$work/data"
  "$radfluxd" --listen 127.0.0.1:0 --data-dir "$work/data" --threads 1 \
    --worker-token bench-token >"$log" 2>&1 &
  local server=$! addr=""
  until [ -n "$addr" ]; do sleep 0.1; addr=$(sed -n 's/^radfluxd listening on //p' "$log"); done
  local delay=0
  [ "$1" = stop ] && delay=600000
  "$radfluxd" --worker --server "$addr" --threads 1 --worker-token bench-token \
    >"$work/a.log" 2>&1 &
  local a=$!
  "$radfluxd" --worker --server "$addr" --threads 1 --worker-token bench-token \
    --testing-block-delay-ms "$delay" >"$work/b.log" 2>&1 &
  local b=$!
  until grep -q "registered with" "$work/a.log" && grep -q "registered with" "$work/b.log"; do
    sleep 0.1
  done
  "$cli" submit --server "$addr" --watch --patches "$patches" --rays 256 --max-iterations 5 \
    "$scene" >/dev/null 2>&1 &
  local client=$!
  if [ "$1" = stop ]; then
    until grep -q "building row block" "$work/b.log"; do sleep 0.01; done
    kill -STOP "$b"
  fi
  wait "$client"
  kill -9 "$a" "$b" "$server"
  wait "$a" "$b" "$server" 2>/dev/null || true
  python3 - "$log" <<'PY'
import re, sys, datetime
text = open(sys.argv[1]).read()
def at(pattern):
    m = re.search(r"\[(\d+-\d+-\d+ \d+:\d+:\d+\.\d+)\][^\n]*" + pattern, text)
    return datetime.datetime.strptime(m.group(1), "%Y-%m-%d %H:%M:%S.%f")
print(f"rows {(at('PHASE_SOLVE') - at('PHASE_ROWS')).total_seconds():.3f} s")
for line in re.findall(r".*(?:as a backup|stopped answering).*", text):
    print("  " + line)
PY
}

echo "patches~$patches (cornell box, monte_carlo 256 rays), server 1 thread + 2 workers x 1 thread"
echo "no worker stopped:"
run go
echo "one worker SIGSTOPped mid-block (lease 300 s):"
run stop

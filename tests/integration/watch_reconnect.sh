#!/bin/bash
# `radflux watch` across a server restart: while the watch follows a solving job, radfluxd
# is killed (-9) and started again on the same port and job store. The watch reconnects by
# itself after the last event it saw and ends with the job's success (exit 0), its event
# numbers only growing. Waits on the watch's output, never on a clock (ctest's timeout
# bounds it).
set -euo pipefail
RADFLUXD=$1 CLI=$2 SCENE=$3
source "$(dirname "$0")/radfluxd_fixture.sh"
SERVER_FLAGS=(--checkpoint-seconds 0 --solve-delay-ms 50)
start_radfluxd "$RADFLUXD" /tmp/radflux_reconnect_XXXXXX "${SERVER_FLAGS[@]}"
echo "server at $ADDR"
JOB=$("$CLI" submit "$SCENE" --patches 600 --rays 64 --solver southwell --tolerance 1e-5 \
  --server "$ADDR" | tail -n 1)
"$CLI" watch "$JOB" --server "$ADDR" 2>"$DIR/watch.err" &
WATCH=$!
until grep -q "solving: iteration" "$DIR/watch.err"; do sleep 0.05; done
kill -9 "$PID"
wait "$PID" || true
restart_radfluxd "$RADFLUXD" "${SERVER_FLAGS[@]}"
echo "restarted at $ADDR"
wait "$WATCH" || { echo "watch failed:"; cat "$DIR/watch.err"; exit 1; }
grep -q "radflux: watch of $JOB dropped after event [0-9]*.*reconnecting" "$DIR/watch.err"
[ "$(grep '^\[' "$DIR/watch.err" | tail -n 1 | cut -d" " -f2)" = succeeded ]
# Event numbers grow across the restart (the rebuilt history is numbered above the old).
grep -o '^\[[0-9]*\]' "$DIR/watch.err" | tr -d '[]' | sort -n -c
echo "watch reconnect ok"

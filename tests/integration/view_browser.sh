#!/bin/bash
# `radflux view` in a real browser: radfluxd (one job at a time) solves the Cornell box
# slowly (row blocks and solver iterations held); `radflux view JOB` serves its page while
# the job is queued behind a blocker; headless Chromium (view_browser.py) opens the page,
# lets the job start (cancels the blocker) and checks the page's own state and screenshots
# against the final B (`radflux result --patch-values`). Waits on conditions only (ctest's
# timeout bounds it). The view and the browser each run in their own process group, which
# the exit trap kills: nothing is left behind.
set -euo pipefail
RADFLUXD=$1 CLI=$2 SCENE=$3 PY=$4
HERE=$(cd "$(dirname "$0")" && pwd)
source "$HERE/radfluxd_fixture.sh"
start_radfluxd "$RADFLUXD" /tmp/radflux_view_XXXXXX --jobs 1 --checkpoint-seconds 0 \
  --testing-block-delay-ms 20 --solve-delay-ms 400
GROUPS_STARTED=()
cleanup() {
  for g in "${GROUPS_STARTED[@]}"; do kill -- -"$g" 2>/dev/null || true; done
  kill "$PID" 2>/dev/null || true
  wait 2>/dev/null || true
  rm -rf "$DIR"
}
trap cleanup EXIT
submit() { "$CLI" submit "$SCENE" --server "$ADDR" "$@" 2>/dev/null | tail -n 1; }
BLOCKER=$(submit --patches 20000)
JOB=$(submit --patches 1500 --tolerance 1e-6)
set -m  # each background job below gets its own process group (its pid)
"$CLI" view "$JOB" --server "$ADDR" >"$DIR/view.out" 2>"$DIR/view.err" &
GROUPS_STARTED+=($!)
until [ -s "$DIR/view.out" ]; do
  kill -0 "${GROUPS_STARTED[0]}" 2>/dev/null || { echo "radflux view exited:"; cat "$DIR/view.err"; exit 1; }
  sleep 0.05
done
URL=$(head -n 1 "$DIR/view.out")
echo "view of $JOB at $URL"
"$PY" "$HERE/view_browser.py" "$URL" "$DIR" "$CLI cancel $BLOCKER --server $ADDR" \
  "$CLI result $JOB --server $ADDR --patch-values $DIR/final.csv" &
GROUPS_STARTED+=($!)
wait "${GROUPS_STARTED[1]}"
set +m
[ -z "${VIEW_SCREENSHOT:-}" ] || cp "$DIR/mid_solve.png" "$VIEW_SCREENSHOT"
echo "view browser ok"

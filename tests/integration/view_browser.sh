#!/bin/bash
# `radflux view` in a real browser: radfluxd (one job at a time) solves the Cornell box
# slowly (row blocks and solver iterations held); `radflux view JOB` serves its page while
# the job is queued behind blockers; headless Chromium (view_browser.py) opens the page,
# lets the job start (cancels the blockers) and checks the page's own state and screenshots
# against the final B (`radflux result --patch-values`); then `radflux view` of the saved
# result (the GLB the page links) shows the box in the browser. Waits on conditions only (ctest's
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
# Blockers hold the queue until the browser cancels them, however slowly Chromium starts
# under load: each runs ~36 s towards a tolerance of 1e-30 (iterations held 400 ms),
# three of them longer than the browser's 120 s wait for the queued page.
BLOCKERS=()
for _ in 1 2 3; do
  BLOCKERS+=("$(submit --patches 20000 --solver jacobi --tolerance 1e-30 --max-iterations 100000)")
done
CANCEL_BLOCKERS=""
for b in "${BLOCKERS[@]}"; do CANCEL_BLOCKERS+="$CLI cancel $b --server $ADDR && "; done
JOB=$(submit --patches 1500 --tolerance 1e-6)
set -m  # each background job below gets its own process group (its pid)
"$CLI" view "$JOB" --server "$ADDR" >"$DIR/view.out" 2>"$DIR/view.err" &
GROUPS_STARTED+=($!)
# view_url OUT: waits until the view just started (the last group) prints its URL to OUT.
view_url() {
  until [ -s "$1" ]; do
    kill -0 "${GROUPS_STARTED[-1]}" 2>/dev/null || { echo "radflux view exited"; exit 1; }
    sleep 0.05
  done
  head -n 1 "$1"
}
URL=$(view_url "$DIR/view.out")
echo "view of $JOB at $URL"
"$PY" "$HERE/view_browser.py" "$URL" "$DIR" "${CANCEL_BLOCKERS}true" \
  "$CLI result $JOB --server $ADDR --patch-values $DIR/final.csv --out $DIR/final.glb" &
GROUPS_STARTED+=($!)
wait "${GROUPS_STARTED[-1]}"
# The saved result, `radflux view RESULT.glb`.
"$CLI" view "$DIR/final.glb" >"$DIR/glb.out" 2>"$DIR/glb.err" &
GROUPS_STARTED+=($!)
GLB_URL=$(view_url "$DIR/glb.out")
"$PY" "$HERE/view_browser.py" --glb "$GLB_URL" &
GROUPS_STARTED+=($!)
wait "${GROUPS_STARTED[-1]}"
set +m
[ -z "${VIEW_SCREENSHOT:-}" ] || cp "$DIR/mid_solve.png" "$VIEW_SCREENSHOT"
echo "view browser ok"

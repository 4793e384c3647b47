#!/bin/bash
# A view-factor job resumed after kill -9 (issue 23): radfluxd is killed while the job's
# blocks of rows are being built (a testing delay after each block keeps it there); started
# again on the same store, it reuses the blocks it had stored, builds the rest, and the
# job's files are byte for byte those of `radflux viewfactors` on the same model. Waits on
# the store's files and the job's state, never on a clock (ctest's timeout bounds it).
set -euo pipefail
RADFLUXD=$1 CLI=$2
source "$(dirname "$0")/radfluxd_fixture.sh"
start_radfluxd "$RADFLUXD" /tmp/radflux_vf_resume_XXXXXX --testing-block-delay-ms 300
# A 20 x 20 grid of ground squares and a wall: 802 surfaces, 13 blocks of 64 rows.
python3 "$(dirname "$0")/write_stl.py" yard "$DIR/yard.stl"
ARGS=(--by face --format sparse --min-vf 0.0001)
"$CLI" viewfactors "$DIR/yard.stl" "${ARGS[@]}" -q -o "$DIR/local.txt" --svf "$DIR/local.svf" \
  2>/dev/null
JOB=$("$CLI" submit "$DIR/yard.stl" --viewfactors "${ARGS[@]}" --server "$ADDR" 2>/dev/null | tail -n 1)
blocks() { ls "$DIR/data/jobs/$JOB"/vf_block.*.rfb 2>/dev/null | wc -l; }
until [ "$(blocks)" -ge 3 ]; do sleep 0.05; done
kill -9 "$PID"
wait "$PID" || true
stored=$(blocks)
[ "$stored" -lt 13 ] || { echo "all 13 blocks were stored before the kill"; exit 1; }
restart_radfluxd "$RADFLUXD"
"$CLI" watch "$JOB" --server "$ADDR" >/dev/null 2>"$DIR/watch.err" ||
  { echo "watch after restart:"; cat "$DIR/watch.err"; exit 1; }
"$CLI" result "$JOB" -o "$DIR/service.txt" --svf "$DIR/service.svf" --report "$DIR/report.json" \
  --server "$ADDR" >/dev/null
cmp "$DIR/local.txt" "$DIR/service.txt" || { echo "resumed job's view factors differ"; exit 1; }
cmp "$DIR/local.svf" "$DIR/service.svf" || { echo "resumed job's sky view factors differ"; exit 1; }
# The restart reused the stored blocks (64 rows each) and built the others.
reused=$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["reused_rows"])' \
  "$DIR/report.json")
[ "$reused" -ge $((64 * 3)) ] && [ "$reused" -lt 802 ] ||
  { echo "reused $reused rows after $stored blocks were stored"; exit 1; }
grep -q "job $JOB: reused $reused stored view-factor rows of 802" "$DIR/server.log" ||
  { echo "no reuse line in the server log"; exit 1; }
echo "view-factor resume ok: $stored blocks stored at the kill, $reused rows reused"

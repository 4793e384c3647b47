#!/bin/bash
# A view-factor job partitioned over worker nodes (issue 23): radfluxd and two `radfluxd
# --worker` processes on loopback share the job's blocks of surface rows; the server checks
# every worker block and recomputes half of its rows (--verify-fraction 0.5). The job's files
# are byte for byte those of the same job with no worker and of `radflux viewfactors`, when
# each pair is integrated once (reciprocal rows) and when rows are built one by one (a
# --memory-limit below the pair triangle: the workers build what the server chose).
set -euo pipefail
RADFLUXD=$1 CLI=$2
source "$(dirname "$0")/radfluxd_fixture.sh"
TOKEN=worker-secret
start_radfluxd "$RADFLUXD" /tmp/radflux_vf_workers_XXXXXX --worker-token "$TOKEN" \
  --verify-fraction 0.5 --testing-block-delay-ms 100
WORKERS=()
trap 'kill "${WORKERS[@]}" $PID 2>/dev/null || true; wait 2>/dev/null || true; rm -rf "$DIR"' EXIT
# A 20 x 20 grid of ground squares and a wall: 802 surfaces, 13 blocks of 64 rows.
python3 "$(dirname "$0")/write_stl.py" yard "$DIR/yard.stl"
# run NAME ARGS...: the service job's files and report (submit --watch, then result).
run() {
  local name=$1
  shift
  local job
  job=$("$CLI" submit "$DIR/yard.stl" --viewfactors "$@" --watch -o "$DIR/$name.txt" \
    --svf "$DIR/$name.svf" --server "$ADDR" 2>"$DIR/$name.err" | tail -n 1)
  "$CLI" result "$job" --report "$DIR/$name.json" --server "$ADDR" >/dev/null
}
remote_rows() { python3 -c 'import json,sys; w=json.load(open(sys.argv[1]))["workers"]
assert w["rejected_blocks"] == 0, w
print(w["remote_rows"], w["verified_rows"])' "$1"; }
RECIPROCAL=(--by face --format sparse --min-vf 0.0001)
ROW_BY_ROW=(--by face --format view3d --memory-limit 1M)
for kind in RECIPROCAL ROW_BY_ROW; do
  declare -n args=$kind
  "$CLI" viewfactors "$DIR/yard.stl" "${args[@]}" -q -o "$DIR/$kind.local.txt" \
    --svf "$DIR/$kind.local.svf" 2>/dev/null
  run "$kind.alone" "${args[@]}"
done
[ "$(remote_rows "$DIR/RECIPROCAL.alone.json")" = "0 0" ] || { echo "rows from no worker?"; exit 1; }

for k in 1 2; do
  "$RADFLUXD" --worker --server "$ADDR" --worker-token "$TOKEN" --threads 1 \
    --testing-block-delay-ms 100 2>"$DIR/worker$k.log" &
  WORKERS+=($!)
done
until [ "$(grep -l "registered with" "$DIR"/worker*.log 2>/dev/null | wc -l)" -eq 2 ]; do
  sleep 0.05
done
for kind in RECIPROCAL ROW_BY_ROW; do
  declare -n args=$kind
  run "$kind.workers" "${args[@]}"
  for ext in txt svf; do
    cmp "$DIR/$kind.local.$ext" "$DIR/$kind.alone.$ext" ||
      { echo "$kind: no-worker job's .$ext differs from radflux viewfactors"; exit 1; }
    cmp "$DIR/$kind.alone.$ext" "$DIR/$kind.workers.$ext" ||
      { echo "$kind: 2-worker job's .$ext differs from the no-worker job's"; exit 1; }
  done
  read -r remote verified < <(remote_rows "$DIR/$kind.workers.json")
  [ "$remote" -gt 0 ] && [ "$verified" -gt 0 ] ||
    { echo "$kind: workers built $remote rows, $verified verified"; cat "$DIR"/worker*.log; exit 1; }
  echo "$kind: $remote rows built by workers, $verified of them recomputed by the server"
done
python3 -c 'import json,sys
assert json.load(open(sys.argv[1]))["adaptive"]["reciprocal"] is True
assert json.load(open(sys.argv[2]))["adaptive"]["reciprocal"] is False' \
  "$DIR/RECIPROCAL.workers.json" "$DIR/ROW_BY_ROW.workers.json"
echo "view-factor workers ok"

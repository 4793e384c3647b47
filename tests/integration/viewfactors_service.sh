#!/bin/bash
# A view-factor job through the service (issue 23): `radflux submit MODEL --viewfactors ...`
# then `radflux result JOB -o OUT --svf SVF` (and `submit --watch -o OUT --svf SVF`) give
# the bytes `radflux viewfactors MODEL ... -o OUT --svf SVF` writes, for an STL and an OBJ
# model in each format (adaptive per-pair integration) and for patch-row integration; the
# job shows in `list` as SUCCEEDED; options that do nothing are refused naming the option,
# by the client where the model is not needed, by the server (INVALID_ARGUMENT) where it is.
set -euo pipefail
RADFLUXD=$1 CLI=$2
source "$(dirname "$0")/radfluxd_fixture.sh"
start_radfluxd "$RADFLUXD" /tmp/radflux_vf_service_XXXXXX
M="$DIR/models"
mkdir -p "$M"
# A unit room, each wall its own object (faces inward), and a floating box's top and side.
cat >"$M/room.obj" <<'OBJ'
mtllib room.mtl
usemtl grey
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
v 0 0 1
v 1 0 1
v 1 1 1
v 0 1 1
v 0.3 0.3 0.4
v 0.6 0.3 0.4
v 0.6 0.6 0.4
v 0.3 0.6 0.4
v 0.3 0.3 0.2
v 0.6 0.3 0.2
o floor
f 1 2 3 4
o ceiling
f 5 8 7 6
o south
f 1 5 6 2
o east
f 2 6 7 3
o north
f 3 7 8 4
o west
f 4 8 5 1
o box_top
f 9 10 11 12
o box_side
f 9 13 14 10
OBJ
printf 'newmtl grey\nKd 0.5 0.5 0.5\n' >"$M/room.mtl"
# A street canyon: ground and two facing walls, two triangles each.
python3 "$(dirname "$0")/write_stl.py" canyon "$M/canyon.stl"
server=(--server "$ADDR")
# same_bytes NAME MODEL ARGS...: local viewfactors, submit --watch, and result of that job
# write the same two files.
same_bytes() {
  local name=$1 model=$2
  shift 2
  "$CLI" viewfactors "$model" "$@" -q -o "$DIR/$name.local" --svf "$DIR/$name.local.svf" \
    2>"$DIR/$name.local.err"
  "$CLI" submit "$model" --viewfactors "$@" --watch -o "$DIR/$name.watch" \
    --svf "$DIR/$name.watch.svf" "${server[@]}" >"$DIR/$name.job" 2>"$DIR/$name.submit.err"
  local job
  job=$(tail -n 1 "$DIR/$name.job")
  "$CLI" result "$job" -o "$DIR/$name.result" --svf "$DIR/$name.result.svf" \
    --report "$DIR/$name.json" "${server[@]}" >/dev/null
  for kind in watch result; do
    cmp "$DIR/$name.local" "$DIR/$name.$kind" ||
      { echo "$name: $kind file differs from radflux viewfactors"; exit 1; }
    cmp "$DIR/$name.local.svf" "$DIR/$name.$kind.svf" ||
      { echo "$name: $kind sky view factors differ"; exit 1; }
  done
  [ -s "$DIR/$name.local" ] || { echo "$name: empty view-factor file"; exit 1; }
  "$CLI" list "${server[@]}" | grep -q "^$job  JOB_STATE_SUCCEEDED  PHASE_DONE" ||
    { echo "$name: job $job not listed SUCCEEDED"; "$CLI" list "${server[@]}"; exit 1; }
  echo "$job"
}
for model in room.obj canyon.stl; do
  same_bytes "${model%.*}-csv" "$M/$model" --by face --format csv >/dev/null
  same_bytes "${model%.*}-sparse" "$M/$model" --by face --format sparse --min-vf 0.01 >/dev/null
  same_bytes "${model%.*}-view3d" "$M/$model" --by face --format view3d >/dev/null
done
# Patch rows (Monte Carlo, seeded per patch): the same bytes too.
same_bytes room-patches "$M/room.obj" --integration patches --patches 64 --rays 32 >/dev/null

# The report says what ran: 8 surfaces of the room, adaptive, its row sums.
python3 - "$DIR/room-csv.json" "$DIR/room-patches.json" <<'PY'
import json, sys
adaptive, patches = (json.load(open(p)) for p in sys.argv[1:3])
assert adaptive["surfaces"] == 8 and adaptive["integration"] == "adaptive", adaptive
assert adaptive["adaptive"]["reciprocal"] is True, adaptive["adaptive"]
assert patches["integration"] == "patches" and patches["patches"] > 8, patches
PY
# `result` without files names the job's surfaces.
room_job=$(tail -n 1 "$DIR/room-csv.job")
"$CLI" result "$room_job" "${server[@]}" | grep -q "^8 surfaces" ||
  { echo "result of a view-factor job without -o: $("$CLI" result "$room_job" "${server[@]}")"; exit 1; }
# One sky view factor per surface after the header line.
[ "$(wc -l <"$DIR/room-csv.local.svf")" -eq 9 ] && [ "$(wc -l <"$DIR/canyon-csv.local.svf")" -eq 7 ] ||
  { echo "sky view factor files: $(wc -l "$DIR"/*-csv.local.svf)"; exit 1; }

# Refusals. The client: a solver option, an import rule on an STL, a view-factor option
# without --viewfactors, a file without --watch.
refused() {  # refused WHAT EXPECTED-TEXT ARGS...: the command fails, its stderr has the text
  local what=$1 text=$2
  shift 2
  local code=0
  "$CLI" "$@" "${server[@]}" >/dev/null 2>"$DIR/refused.err" || code=$?
  [ "$code" -ne 0 ] && grep -qF -- "$text" "$DIR/refused.err" ||
    { echo "$what: exit $code, stderr: $(cat "$DIR/refused.err")"; exit 1; }
}
refused "--solver" "--solver is for radflux solve only" \
  submit "$M/room.obj" --viewfactors --solver jacobi
refused "--two-sided on STL" "--two-sided is an import rule" \
  submit "$M/canyon.stl" --viewfactors --two-sided
refused "--by alone" "--by needs --viewfactors" submit "$M/room.obj" --by face
refused "-o without --watch" "--output needs --watch" \
  submit "$M/room.obj" --viewfactors -o "$DIR/x.csv"
refused "--out with --viewfactors" "--out is for radiosity jobs" \
  submit "$M/room.obj" --viewfactors --out "$DIR/x.ply" --watch
# The server (it reads the model): by object, the box is one surface of two faces, so the
# run integrates patch rows and an adaptive knob does nothing.
sed -i 's/^o box_side$//' "$M/room.obj"
refused "--vf-tolerance on patch rows" \
  "INVALID_ARGUMENT: --vf-tolerance applies to adaptive integration; this run uses patch rows (a surface with several faces: try --by face)" \
  submit "$M/room.obj" --viewfactors --vf-tolerance 0.01
echo "view-factor service ok"

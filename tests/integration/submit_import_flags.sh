#!/bin/bash
# `radflux submit`'s import flags reach radfluxd (issue 19). The server, not the client,
# reads the scene, so each flag is seen in what the server did with it: the report's import
# list (--max-reflectance's value in its line, --two-sided's twins), the refusal it sends
# back (--strict, a scene without emitters), the job it runs (--emit) and its face count
# (--curve-segments on an MGF sphere).
set -euo pipefail
RADFLUXD=$1 CLI=$2
source "$(dirname "$0")/radfluxd_fixture.sh"
start_radfluxd "$RADFLUXD" /tmp/radflux_import_flags_XXXXXX
S="$DIR/scenes"
mkdir -p "$S"
# A lamp (facing down at z = 1) over a floor whose Kd is 1 in every band.
cat >"$S/room.obj" <<'OBJ'
mtllib room.mtl
v 0 0 1
v 0 1 1
v 1 1 1
v 1 0 1
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
o lamp
usemtl lamp
f 1 2 3 4
o floor
usemtl chalk
f 5 6 7 8
OBJ
printf 'newmtl lamp\nKd 0.5 0.5 0.5\nKe 1 1 1\nnewmtl chalk\nKd 1 1 1\n' >"$S/room.mtl"
submit() { "$CLI" submit "$@" --patches 20 --rays 64 --watch --server "$ADDR"; }
imports() {  # the report's import list as "kind count message" lines
  python3 -c 'import json,sys
for f in json.load(open(sys.argv[1]))["import"]: print(f["kind"], f["count"], f["message"])' "$1"
}

submit "$S/room.obj" --report "$DIR/default.json" >/dev/null
[ "$(imports "$DIR/default.json")" = "reflectance_clamped 1 material with reflectance >= 1 clamped to 0.98" ] ||
  { echo "default import: $(imports "$DIR/default.json")"; exit 1; }

submit "$S/room.obj" --max-reflectance 0.9 --two-sided --report "$DIR/flags.json" >/dev/null
expected="reflectance_clamped 1 material with reflectance >= 1 clamped to 0.9
two_sided 2 two-sided faces given a back-face twin (each side lit on its own)"
[ "$(imports "$DIR/flags.json")" = "$expected" ] ||
  { echo "--max-reflectance 0.9 --two-sided import: $(imports "$DIR/flags.json")"; exit 1; }
python3 -c 'import json,sys; assert json.load(open(sys.argv[1]))["mesh"]["faces"] == 4' "$DIR/flags.json"

code=0
"$CLI" submit "$S/room.obj" --strict --server "$ADDR" 2>"$DIR/strict.err" >/dev/null || code=$?
[ "$code" -ne 0 ] || { echo "--strict submit of a Kd 1 scene succeeded"; exit 1; }
grep -q "material 'chalk': reflectance Kd 1 is outside \[0,1)" "$DIR/strict.err" ||
  { echo "--strict: $(cat "$DIR/strict.err")"; exit 1; }

# Without its lamp's Ke the room has no emitter: refused naming --emit; lit by --emit
# (the lamp, black, keeps B = E = pi L_e exactly).
printf 'newmtl lamp\nKd 0 0 0\nnewmtl chalk\nKd 0.5 0.5 0.5\n' >"$S/room.mtl"
code=0
"$CLI" submit "$S/room.obj" --server "$ADDR" 2>"$DIR/dark.err" >/dev/null || code=$?
[ "$code" -ne 0 ] && grep -q "light it with --emit MATERIAL=R,G,B" "$DIR/dark.err" ||
  { echo "dark scene: exit $code, $(cat "$DIR/dark.err")"; exit 1; }
submit "$S/room.obj" --emit lamp=2,2,2 --patch-values "$DIR/lit.csv" >/dev/null
python3 - "$DIR/lit.csv" <<'PY'
import csv, math, sys
rows = list(csv.DictReader(open(sys.argv[1])))
lamp = [r for r in rows if r["object"] == "lamp"]
assert lamp and all(abs(float(r["r"]) - 2 * math.pi) < 1e-6 for r in lamp), lamp
PY

# A sphere of 10 x 5 faces and a cylinder of 10 (16 x 8 and 16 by default).
submit "$(dirname "$0")/../data/curved_lamps.mgf" --curve-segments 10 --report "$DIR/ball.json" >/dev/null
python3 -c 'import json,sys; f = json.load(open(sys.argv[1]))["mesh"]["faces"]; assert f == 60, f' \
  "$DIR/ball.json"
echo "submit import flags ok"

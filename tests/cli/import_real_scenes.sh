#!/usr/bin/env bash
# Issue 19's import rules from the command line, on the public holodeck scene as downloaded
# (../shared/scenes/holodeck): `radflux solve` prints one line per kind of fix-up (count and
# first file:line), solves with the scene's own emitters (exit 0) and lists every fix-up in
# the report; -q silences the lines; --strict refuses (exit 2) naming what it would fix; a
# scene without emitters is refused naming --emit. Fails (never skips) without ../shared.
set -uo pipefail
radflux=$1
source_dir=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

holodeck="$source_dir/../shared/scenes/holodeck/holodeck.obj"
[ -f "$holodeck" ] || { echo "FAIL: $holodeck is missing"; exit 1; }

"$radflux" solve "$holodeck" --patches 3000 --report "$tmp/h.json" 2>"$tmp/err" ||
  fail "holodeck solve exited $?"
grep '^import: ' "$tmp/err" >"$tmp/lines"
h="$holodeck"
cat >"$tmp/expected" <<LINES
import: 161 faces took their reflectance from textures (map_Kd) (first at $h:616)
import: 3 faces took their emission from textures (map_Ke) (first at $h:9680)
import: 1 material with reflectance >= 1 clamped to 0.98 (first at material 'door')
import: 4 faces with a repeated vertex simplified (first at $h:7693)
import: 4 zero-area faces dropped (first at $h:7719)
import: 44 non-planar faces split into triangles (first at $h:6267)
import: 79 non-convex faces triangulated (first at $h:621)
import: 39 pairs of coplanar faces overlap (each hides the other; not changed) (first at $h:616 and $h:652)
LINES
diff "$tmp/expected" "$tmp/lines" >/dev/null || { fail "import lines differ:"; diff "$tmp/expected" "$tmp/lines"; }
python3 - "$tmp/h.json" <<'PY' || fail "report's import list"
import json, sys
report = json.load(open(sys.argv[1]))
counts = {f["kind"]: f["count"] for f in report["import"]}
assert counts == {"reflectance_from_textures": 161, "emission_from_textures": 3,
                  "reflectance_clamped": 1, "repeated_vertices_removed": 4, "zero_area_dropped": 4,
                  "non_planar_split": 44, "non_convex_triangulated": 79, "coplanar_overlap": 39}, counts
assert report["energy_balance"]["ok"], report["energy_balance"]
PY

"$radflux" solve "$holodeck" --patches 3000 -q 2>"$tmp/quiet" || fail "quiet solve exited $?"
! grep -q '^import: ' "$tmp/quiet" || fail "-q still prints import lines"

"$radflux" solve "$holodeck" --strict -q 2>"$tmp/strict"
code=$?
[ "$code" -eq 2 ] || fail "--strict exited $code, not 2"
grep -q "material 'door': reflectance Kd 1 is outside \[0,1)" "$tmp/strict" || fail "--strict message: $(cat "$tmp/strict")"

"$radflux" solve "$holodeck" --emit nosuch=1,1,1 -q 2>"$tmp/emit"
code=$?
[ "$code" -eq 2 ] && grep -q "no material 'nosuch'" "$tmp/emit" || fail "--emit of an unknown material: exit $code, $(cat "$tmp/emit")"

printf 'mtllib dark.mtl\no a\nusemtl grey\nv 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 3\n' >"$tmp/dark.obj"
printf 'newmtl grey\nKd 0.5 0.5 0.5\n' >"$tmp/dark.mtl"
"$radflux" solve "$tmp/dark.obj" -q 2>"$tmp/dark"
code=$?
[ "$code" -eq 2 ] && grep -q "light it with --emit MATERIAL=R,G,B .*'grey' (0.5)" "$tmp/dark" ||
  fail "no-emitter scene: exit $code, $(cat "$tmp/dark")"

[ "$failures" -eq 0 ] && echo "import CLI tests passed"
exit "$failures"

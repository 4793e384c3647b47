#!/usr/bin/env bash
# Issue 19's "Done when": every OBJ scene of ../shared/scenes as downloaded and every
# RenderPark MGF scene solves with its documented lights (../shared/scenes/README.md) through
# `radflux solve` at the defaults: exit 0, at most one `import:` line per kind of fix-up (and
# the report lists each kind once, with the same count of entries), the solve converged, the
# energy balance ok, and the default picture (80 x 60, linear PFM) shows the lit scene: at
# least the stated fraction of its pixels is lit (radiance > 0). Fails (never skips) without
# ../shared. Label "real_scenes" (about 30 s: the conference room and Lost Empire are big).
set -uo pipefail
radflux=$1
scenes="$2/../shared/scenes"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

# name, file, least lit fraction of the default picture, flags
check() {
  local name=$1 file=$scenes/$2 lit=$3
  shift 3
  [ -f "$file" ] || { fail "$file is missing"; return; }
  "$radflux" solve "$file" "$@" --report "$tmp/$name.json" --render "$tmp/$name.pfm" \
    --size 80x60 2>"$tmp/$name.err"
  local code=$?
  [ "$code" -eq 0 ] || { fail "$name: exit $code: $(tail -3 "$tmp/$name.err")"; return; }
  grep '^import: ' "$tmp/$name.err" >"$tmp/$name.lines"
  python3 - "$name" "$tmp/$name.json" "$tmp/$name.lines" "$tmp/$name.pfm" "$lit" <<'PY' ||
import json, struct, sys
name, report_path, lines_path, pfm_path, least_lit = sys.argv[1:]
report = json.load(open(report_path))
kinds = [f["kind"] for f in report["import"]]
assert len(kinds) == len(set(kinds)), f"{name}: a kind listed twice: {kinds}"
lines = open(lines_path).read().splitlines()
assert len(lines) == len(kinds), f"{name}: {len(lines)} import lines for {len(kinds)} kinds"
for f in report["import"]:  # a part a diffuse solve leaves out comes with its share
    if f["kind"].endswith("_left_out"):
        share = f["share"]
        assert 0 < share["mean"] <= share["max"] <= 1, f"{name}: {f}"
        assert "of the light" in f["message"], f"{name}: {f['message']}"
assert report["solve"]["converged"], f"{name}: not converged"
assert report["energy_balance"]["ok"], f"{name}: energy balance off: {report['energy_balance']}"
with open(pfm_path, "rb") as f:
    assert f.readline().strip() == b"PF"
    w, h = map(int, f.readline().split())
    endian = "<" if float(f.readline()) < 0 else ">"
    rgb = struct.unpack(endian + "f" * (3 * w * h), f.read(12 * w * h))
lit = sum(1 for i in range(w * h) if max(rgb[3 * i:3 * i + 3]) > 0) / (w * h)
print(f"{name}: {len(kinds)} import kinds, converged, balance ok "
      f"({report['energy_balance']['relative_imbalance']:.4f}), default picture {lit:.1%} lit")
assert lit >= float(least_lit), f"{name}: default picture {lit:.1%} lit, under {least_lit}"
PY
    fail "$name"
}

check holodeck holodeck/holodeck.obj 0.95
check conference conference/conference.obj 0.95 --emit mesh16_SG=20,20,20
check lost_empire lost_empire/lost_empire.obj 0.9 --emit Torch=20,15,8
# cube and corridor are framed from outside (open scenes): the room fills part of the picture.
check cube renderpark/cube.mgf 0.35
check corridor renderpark/corridor.mgf 0.4
check office2 renderpark/office2/office2.mgf 0.7
check classroom renderpark/salon/classroom.mgf 0.9
# Open scenes, seen from outside (solver/output/default_view.h): examp1 is a lone luminaire
# (the lamps between its vanes are what is lit: 3.8% of the picture), floor_gloss a floor
# with a lamp, a ball and a box (27%).
check examp1 renderpark/examp1.mgf 0.03
check floor_gloss renderpark/floor_gloss.mgf 0.2
# Materials/test.mgf: the library's test scene (a face under a small lamp; 37%). The other
# files there are material libraries with no faces.
check materials_test renderpark/Materials/test.mgf 0.3

[ "$failures" -eq 0 ] && echo "real scene solves passed"
exit "$failures"

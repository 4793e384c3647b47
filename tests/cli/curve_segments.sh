#!/usr/bin/env bash
# --curve-segments N (issue 19) reaches the MGF tessellation from `radflux solve` and
# `radflux viewfactors`: a unit sphere (sph) gets N x ceil(N/2) faces and a cylinder (cyl,
# radius 1, length 2) N; their areas approach the closed forms (4 pi each) as N grows, the
# sphere's from below by less than (pi/N)^2 relative, the cylinder's exactly by the factor
# sin(pi/N)/(pi/N) (mgf_primitives.h), tests/data/curved_lamps.mgf. A count outside
# [3, 1024] is one line, exit 2.
set -uo pipefail
radflux=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

shapes="$(dirname "$0")/../data/curved_lamps.mgf"
for n in 8 13 64 256; do
  "$radflux" solve "$shapes" --curve-segments "$n" --patches 1 -q \
    --report "$tmp/r$n.json" --patch-values "$tmp/p$n.csv" || fail "solve --curve-segments $n exited $?"
  "$radflux" viewfactors "$shapes" --curve-segments "$n" --format view3d -q \
    -o "$tmp/v$n.vs3" || fail "viewfactors --curve-segments $n exited $?"
done
python3 - "$tmp" <<'PY' || fail "faces or areas"
import csv, json, math, sys
tmp = sys.argv[1]
last = None
for n in (8, 13, 64, 256):
    faces = json.load(open(f"{tmp}/r{n}.json"))["mesh"]["faces"]
    assert faces == n * math.ceil(n / 2) + n, (n, faces)
    area = {"ball": 0.0, "tube": 0.0}
    for row in csv.DictReader(open(f"{tmp}/p{n}.csv")):
        area[row["object"]] += float(row["area"])
    sphere_error = 1 - area["ball"] / (4 * math.pi)
    assert 0 < sphere_error < (math.pi / n) ** 2, (n, area["ball"], sphere_error)
    assert last is None or sphere_error < last, (n, sphere_error, last)
    last = sphere_error
    chord = math.sin(math.pi / n) / (math.pi / n)
    assert abs(area["tube"] / (4 * math.pi * chord) - 1) < 1e-7, (n, area["tube"])
    # viewfactors tessellates the same way: its View3D header lists the two areas.
    vs3 = sorted(float(a) for a in open(f"{tmp}/v{n}.vs3").read().splitlines()[1].split())
    for a, b in zip(vs3, sorted(area.values())):
        assert abs(a / b - 1) < 1e-5, (n, vs3, area)
    print(f"n={n}: {faces} faces, sphere area {area['ball']:.9g} "
          f"(error {sphere_error:.3g} < {(math.pi / n) ** 2:.3g}), cylinder {area['tube']:.9g}")
PY

"$radflux" solve "$shapes" --curve-segments 2 -q 2>"$tmp/err"
code=$?
[ "$code" -eq 2 ] && [ "$(cat "$tmp/err")" = "radflux solve: --curve-segments must be in [3, 1024], not 2" ] ||
  fail "--curve-segments 2: exit $code, $(cat "$tmp/err")"

[ "$failures" -eq 0 ] && echo "curve segments ok"
exit "$failures"

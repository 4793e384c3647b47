#!/bin/bash
# `radflux result` writes what `radflux solve` writes, and `radflux watch --snapshots` writes
# rendered PNGs. radfluxd on a loopback port it picks itself; the client re-loads the job's
# scene (GetScene) and re-meshes it. Checks:
#  - the PNG, PLY, GLB, PFM and patch-values CSV of `result`, and those `submit --watch` writes
#    in one process, equal those of `solve` with the same options byte for byte;
#  - the report JSONs agree on patches, non-zeros, rays, iterations, residual and energy
#    balance (timings differ);
#  - `watch --snapshots DIR` leaves at least one PNG in DIR, and every PNG decodes (chunk
#    CRCs, zlib stream, size of the raw scanlines = height * (1 + 3 * width)).
set -euo pipefail
RADFLUXD=$1 RADFLUX=$2 SCENE=$3  # radflux runs solve itself and the service verbs via radflux-service
source "$(dirname "$0")/radfluxd_fixture.sh"
start_radfluxd "$RADFLUXD" /tmp/radflux_result_XXXXXX

OPTS=(--patches 500 --rays 96 --seed 3 --solver southwell --tolerance 1e-5)
CAMERA=(--size 96x72 --camera-pos 278,273,-800 --camera-look-at 278,273,0 --fov-deg 40)
"$RADFLUX" submit "$SCENE" "${OPTS[@]}" --server "$ADDR" >"$DIR/submit.out" 2>/dev/null
JOB=$(tail -n 1 "$DIR/submit.out")
# Watch from the start with snapshots; then the outputs of the finished job.
"$RADFLUX" watch "$JOB" --server "$ADDR" --snapshots "$DIR/snaps" "${CAMERA[@]}" 2>"$DIR/watch.err"
"$RADFLUX" result "$JOB" --server "$ADDR" --render "$DIR/r.png" --out "$DIR/r.ply" \
  --patch-values "$DIR/r.csv" --report "$DIR/r.json" "${CAMERA[@]}" >/dev/null
"$RADFLUX" result "$JOB" --server "$ADDR" --render "$DIR/r.pfm" --out "$DIR/r.glb" \
  "${CAMERA[@]}" >/dev/null
"$RADFLUX" solve "$SCENE" "${OPTS[@]}" -q --render "$DIR/s.png" --out "$DIR/s.ply" \
  --patch-values "$DIR/s.csv" --report "$DIR/s.json" "${CAMERA[@]}"
"$RADFLUX" solve "$SCENE" "${OPTS[@]}" -q --render "$DIR/s.pfm" --out "$DIR/s.glb" "${CAMERA[@]}"
# One process: submit, watch, then the same outputs as `result` writes.
"$RADFLUX" submit "$SCENE" "${OPTS[@]}" --server "$ADDR" --watch --render "$DIR/w.png" \
  --out "$DIR/w.ply" --patch-values "$DIR/w.csv" --report "$DIR/w.json" "${CAMERA[@]}" \
  >"$DIR/submit_watch.out" 2>/dev/null
[[ "$(tail -n 1 "$DIR/submit_watch.out")" =~ ^job-[0-9a-f]{16}$ ]] || {
  echo "submit --watch with outputs: last line is not the job id"; exit 1; }
for f in png ply csv pfm glb; do
  cmp "$DIR/r.$f" "$DIR/s.$f" || { echo "result .$f differs from solve .$f"; exit 1; }
done
for f in png ply csv; do
  cmp "$DIR/w.$f" "$DIR/s.$f" || { echo "submit --watch .$f differs from solve .$f"; exit 1; }
done
# Output options without --watch are refused before anything is submitted.
if "$RADFLUX" submit "$SCENE" "${OPTS[@]}" --server "$ADDR" --render "$DIR/x.png" 2>"$DIR/err"; then
  echo "submit --render without --watch succeeded"; exit 1
fi
grep -q -- "--render needs --watch" "$DIR/err" || { cat "$DIR/err"; exit 1; }
[ "$("$RADFLUX" list --server "$ADDR" | wc -l)" -eq 2 ] || { echo "a refused submit made a job"; exit 1; }

python3 - "$DIR" <<'PY'
import json, struct, sys, zlib, glob, os
d = sys.argv[1]
s = json.load(open(f"{d}/s.json"))
for name in ("r", "w"):
    r = json.load(open(f"{d}/{name}.json"))
    for path in (("mesh", "patches"), ("matrix", "nnz"), ("rays",), ("solve", "iterations"),
                 ("solve", "residual"), ("energy_balance", "relative_imbalance")):
        a, b = r, s
        for k in path: a, b = a[k], b[k]
        assert a == b, f"report {'.'.join(path)}: {name}.json {a} != solve {b}"

def decode_png(path):
    data = open(path, "rb").read()
    assert data[:8] == b"\x89PNG\r\n\x1a\n", "signature"
    at, idat, width = 8, b"", None
    while at < len(data):
        n, kind = struct.unpack(">I4s", data[at:at + 8])
        body = data[at + 8:at + 8 + n]
        assert zlib.crc32(kind + body) == struct.unpack(">I", data[at + 8 + n:at + 12 + n])[0], "crc"
        if kind == b"IHDR": width, height, depth, colour = struct.unpack(">IIBB", body[:10])
        if kind == b"IDAT": idat += body
        at += 12 + n
    assert depth == 8 and colour == 2, "8-bit RGB"
    assert len(zlib.decompress(idat)) == height * (1 + 3 * width), "scanlines"
    return width, height

snaps = sorted(glob.glob(f"{d}/snaps/*.png"))
assert snaps, "watch --snapshots wrote no PNG"
for p in snaps: assert decode_png(p) == (96, 72), p
assert decode_png(f"{d}/r.png") == (96, 72)
print(f"{len(snaps)} snapshot PNGs decode; result outputs equal solve outputs")
PY
echo "result outputs ok"

#!/usr/bin/env bash
# CLI contract smoke tests: `radflux solve` and `radflux viewfactors` on the Cornell box,
# their output files, and one clear line with a non-zero exit for bad arguments/scenes.
set -uo pipefail
radflux=$1
source_dir=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

cornell="$source_dir/scenes/cornell_box.obj"
"$radflux" solve "$cornell" --patches 300 --quiet --render "$tmp/c.png" --out "$tmp/c.ply" \
  --report "$tmp/c.json" --patch-values "$tmp/c.csv" --size 64x64 || fail "solve exited $?"
[ "$(head -c 8 "$tmp/c.png" | od -An -c | tr -d ' ')" = "211PNG\r\n032\n" ] || fail "PNG signature"
head -1 "$tmp/c.ply" | grep -qx ply || fail "PLY header"
[ "$(head -1 "$tmp/c.csv")" = "patch,face,object,area,cx,cy,cz,r,g,b" ] || fail "CSV header"
rows=$(($(wc -l <"$tmp/c.csv") - 1))
[ "$rows" -ge 270 ] && [ "$rows" -le 330 ] || fail "CSV has $rows patch rows for --patches 300"
grep -q '"relative_imbalance"' "$tmp/c.json" || fail "report lacks the energy balance"
grep -q '"rays_per_second"' "$tmp/c.json" || fail "report lacks rays_per_second"

"$radflux" solve "$cornell" --patches 300 --quiet --render "$tmp/c.pfm" --size 32x16 || fail "pfm solve"
[ "$(head -c 3 "$tmp/c.pfm" | od -An -c | tr -d ' ')" = 'PF\n' ] || fail "PFM header"
# --gather 0 is today's picture, bit for bit; --gather N reports its time beside the solve's.
"$radflux" solve "$cornell" --patches 300 --quiet --render "$tmp/g0.pfm" --size 32x16 --gather 0 ||
  fail "gather 0 solve"
cmp -s "$tmp/c.pfm" "$tmp/g0.pfm" || fail "--gather 0 changes the picture"
"$radflux" solve "$cornell" --patches 300 --quiet --render "$tmp/g4.pfm" --size 32x16 --gather 4 \
  --report "$tmp/g4.json" || fail "gather 4 solve"
grep -q '"gather"' "$tmp/g4.json" || fail "report lacks the gather's seconds"
cmp -s "$tmp/c.pfm" "$tmp/g4.pfm" && fail "--gather 4 gives the default picture"
# --direct-light patch is the Gouraud picture of B, not the default's; --seed seeds the default.
"$radflux" solve "$cornell" --patches 300 --quiet --render "$tmp/dp.pfm" --size 32x16 \
  --direct-light patch || fail "direct-light patch solve"
cmp -s "$tmp/c.pfm" "$tmp/dp.pfm" && fail "--direct-light patch gives the default picture"
"$radflux" solve "$cornell" --patches 300 --quiet --render "$tmp/c1.pfm" --size 32x16 ||
  fail "second default solve"
cmp -s "$tmp/c.pfm" "$tmp/c1.pfm" || fail "the default picture differs run to run"
"$radflux" solve "$cornell" --patches 300 --quiet --render "$tmp/s2.pfm" --size 32x16 --seed 2 ||
  fail "seed 2 solve"
cmp -s "$tmp/c.pfm" "$tmp/s2.pfm" && fail "--seed 2 gives seed 1's picture"
# --lightmap SIZE: a GLB with a second UV set and an emissive lightmap texture.
"$radflux" solve "$cornell" --patches 300 --quiet --out "$tmp/lm.glb" --lightmap 128 || fail "lightmap"
[ "$(head -c 4 "$tmp/lm.glb")" = glTF ] || fail "lightmap GLB magic"
for key in TEXCOORD_1 KHR_materials_emissive_strength image/png; do
  grep -aq "$key" "$tmp/lm.glb" || fail "lightmap GLB lacks $key"
done

# --memory-limit: rows spill to disk and B is the same as in memory (same CSV, byte for byte).
"$radflux" solve "$cornell" --patches 300 --quiet --memory-limit 1K --patch-values "$tmp/s.csv" \
  --report "$tmp/s.json" || fail "spilled solve exited $?"
cmp -s "$tmp/c.csv" "$tmp/s.csv" || fail "spilled solve gives a different B"
grep -q '"spilled_bytes"' "$tmp/s.json" || fail "report lacks spilled_bytes"

"$radflux" viewfactors "$cornell" --by object --patches 300 -o "$tmp/vf.csv" || fail "viewfactors"
head -1 "$tmp/vf.csv" | grep -q '^from,floor,ceiling,back_wall,red_wall' || fail "view-factor header"
[ "$(wc -l <"$tmp/vf.csv")" -eq 9 ] || fail "view-factor rows (8 objects + header)"

# The refining solvers report what they built: hierarchical its links, adaptive its passes.
"$radflux" solve "$cornell" --solver hierarchical --link-epsilon 1e-3 --quiet --report "$tmp/h.json" ||
  fail "hierarchical solve exited $?"
grep -q '"links_per_leaf"' "$tmp/h.json" || fail "hierarchical report lacks its links"
grep -q '"error": "not computed for --solver hierarchical' "$tmp/h.json" ||
  fail "hierarchical report does not say why it has no energy balance"
"$radflux" solve "$cornell" --patches 100 --adaptive-passes 1 --quiet --report "$tmp/a.json" ||
  fail "adaptive solve exited $?"
grep -q '"rows_recomputed"' "$tmp/a.json" || fail "adaptive report lacks its passes"

# A solve that stops short of --tolerance exits 3 with one line giving the residual reached,
# and still writes what was asked.
out=$("$radflux" solve "$cornell" --patches 300 --quiet --max-iterations 2 --report "$tmp/n.json" \
  --patch-values "$tmp/n.csv" 2>&1 >/dev/null)
code=$?
[ "$code" -eq 3 ] || fail "unconverged solve exited $code, not 3"
[ "$(printf '%s\n' "$out" | wc -l)" -eq 1 ] || fail "unconverged solve: not one line: $out"
printf '%s' "$out" | grep -q "radflux solve: not converged: residual .* after 2 iterations" ||
  fail "unconverged solve: '$out' lacks the residual reached"
grep -q '"converged": false' "$tmp/n.json" || fail "unconverged solve: report not written"
[ "$(wc -l <"$tmp/n.csv")" -gt 270 ] || fail "unconverged solve: patch values not written"

# A converged solve whose energy balance is off (two coplanar floors that overlap make light
# from nothing) exits 4 with one line saying by how much and why, and writes its outputs;
# the same cube without the overlay closes its balance and exits 0.
overlap="$source_dir/tests/data/overlapping_floor.obj"
out=$("$radflux" solve "$overlap" --quiet --report "$tmp/o.json" 2>&1 >/dev/null)
code=$?
[ "$code" -eq 4 ] || fail "solve with overlapping floors exited $code, not 4"
[ "$(printf '%s\n' "$out" | wc -l)" -eq 1 ] || fail "balance off: not one line: $out"
printf '%s' "$out" | grep -q "radflux solve: energy balance off by [0-9.]*% of the emitted power (tolerance [0-9.]*%): absorbed + escaped exceed emitted" ||
  fail "balance off: '$out'"
grep -q '"ok": false' "$tmp/o.json" || fail "balance off: report not written"
grep -v overlay "$overlap" | sed 's/^f 9 10 11 12$//' >"$tmp/closed.obj"
cp "$source_dir/tests/data/overlapping_floor.mtl" "$tmp/"
"$radflux" solve "$tmp/closed.obj" --quiet || fail "the cube without the overlay exited $?"

# Bad input: non-zero exit and exactly one line naming the problem.
expect_error() {
  local what=$1 pattern=$2
  shift 2
  out=$("$radflux" "$@" 2>&1 >/dev/null)
  code=$?
  [ "$code" -ne 0 ] || fail "$what: exit code 0"
  [ "$(printf '%s\n' "$out" | wc -l)" -eq 1 ] || fail "$what: not one line: $out"
  printf '%s' "$out" | grep -q -- "$pattern" || fail "$what: '$out' lacks '$pattern'"
}
expect_error "missing scene" "cannot open" solve "$tmp/none.obj"
expect_error "bad rays" "rays" solve "$cornell" --rays -3
expect_error "odd hemicube" "hemicube-res" solve "$cornell" --form-factors hemicube --hemicube-res 7
expect_error "render extension" "render" solve "$cornell" --render "$tmp/x.bmp"
expect_error "gather range" "--gather" solve "$cornell" --render "$tmp/x.png" --gather -1
expect_error "direct-light value" "direct-light" solve "$cornell" --render "$tmp/x.png" \
  --direct-light vertex
expect_error "pixel-samples range" "pixel-samples" solve "$cornell" --render "$tmp/x.png" \
  --pixel-samples 0
expect_error "lightmap without glb" "--lightmap" solve "$cornell" --out "$tmp/x.ply" --lightmap 64
expect_error "unknown solver" "solver" solve "$cornell" --solver magic
printf 'o a\nusemtl nothing\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' >"$tmp/bad.obj"
expect_error "unknown material" "bad.obj:6: unknown material 'nothing'" solve "$tmp/bad.obj"
"$radflux" --version | grep -qx "radflux [0-9]*\.[0-9]*\.[0-9]*" || fail "--version prints 'radflux X.Y.Z'"
expect_error "unknown verb" "unknown verb 'solv'" solv "$cornell"
expect_error "no verb" "A subcommand is required"
expect_error "element floor" "min-element-area must be in (0, 1)" solve "$cornell" \
  --solver hierarchical --min-element-area 0
expect_error "link epsilon" "link-epsilon must be" solve "$cornell" --solver hierarchical \
  --link-epsilon -1
expect_error "cg cannot stream" "memory-limit" solve "$cornell" --memory-limit 1M --solver cg
expect_error "spill dir is a file" "cannot create a spill file in" solve "$cornell" --patches 300 -q \
  --memory-limit 1K --spill-dir "$tmp/c.csv"
# viewfactors: a flag that would do nothing is refused, by name (issue 23).
expect_error "viewfactors solver flag" "--solver is for radflux solve only" viewfactors "$cornell" \
  -o "$tmp/vf2.csv" --solver cg
expect_error "viewfactors adaptive flag on patches" "--far-ratio applies to adaptive" viewfactors \
  "$cornell" -o "$tmp/vf2.csv" --far-ratio 4
expect_error "viewfactors patch flag on adaptive" "--samples applies to --integration patches" \
  viewfactors "$cornell" --by face -o "$tmp/vf2.csv" --samples 16
# grep reads the whole help (no -q): an early exit would SIGPIPE radflux once the help
# outgrows one pipe write, and pipefail would report that.
"$radflux" solve --help | grep -- "--hemicube-res" >/dev/null || fail "--help lists options"
"$radflux" solve --help | grep -- "--memory-limit" >/dev/null || fail "--help lists --memory-limit"

# `radflux` only dispatches (client/service_dispatch.h): alone, without its siblings, it says
# which executable it could not run.
cp "$radflux" "$tmp/radflux"
expect_missing_sibling_for() {
  "$tmp/radflux" "${@:2}" >"$tmp/alone.out" 2>&1 && fail "radflux alone: ${*:2} exited 0"
  grep -q "cannot run $tmp/$1 " "$tmp/alone.out" || fail "radflux alone: ${*:2} does not name $1"
}
expect_missing_sibling_for radflux-local solve "$cornell"
expect_missing_sibling_for radflux-service --server 127.0.0.1:1 list

checks=37
# The service verbs run in radflux-service next to radflux (client/service_dispatch.h): the same
# command line reaches them, connection flags before or after the verb.
if [ -x "$(dirname "$radflux")/radflux-service" ]; then
  checks=$((checks + 4))
  expect_error "server down" "cannot reach radfluxd at 127.0.0.1:1" --server 127.0.0.1:1 list
  expect_error "server down, flag after verb" "cannot reach radfluxd" list --server=127.0.0.1:1
  "$radflux" submit --help | grep -- "--request-id" >/dev/null ||
    fail "submit --help lists --request-id"
  "$radflux" --help | grep "submit" >/dev/null || fail "--help lists the service verbs"
fi

echo "$((checks - failures)) passed, $failures failed"
[ "$failures" -eq 0 ]

#!/usr/bin/env bash
# Speed against error on the Cornell box for uniform, adaptive and hierarchical (issue 7).
# Error: RMS over scene objects (light excluded) of the relative error of each object's
# area-weighted mean B (r+g+b), against a fine uniform monte_carlo reference; works across
# different meshes. Usage: OMP_WAIT_POLICY=passive bench/issue7_sweep.sh RADFLUX OUTDIR
set -euo pipefail
RADFLUX=$1; OUT=$2; SCENE=$(dirname "$0")/../scenes/cornell_box.obj
mkdir -p "$OUT"
[ -f "$OUT/ref.csv" ] || "$RADFLUX" solve "$SCENE" --patches 4000 --rays 4096 --tolerance 1e-6 \
  --patch-values "$OUT/ref.csv" -q
err() { python3 - "$1" "$OUT/ref.csv" <<'PY'
import csv, sys, math
def means(path):
    s, a = {}, {}
    for r in csv.DictReader(open(path)):
        o = r['object']; ar = float(r['area'])
        s[o] = s.get(o, 0) + ar * (float(r['r']) + float(r['g']) + float(r['b'])); a[o] = a.get(o, 0) + ar
    return {o: s[o] / a[o] for o in s}
run, ref = means(sys.argv[1]), means(sys.argv[2])
e = [(run[o] / ref[o] - 1) ** 2 for o in ref if o != 'light']
print('%.3e' % math.sqrt(sum(e) / len(e)))
PY
}
run() {  # name, then flags
  local name=$1; shift
  local t0=$(date +%s.%N)
  "$RADFLUX" solve "$SCENE" "$@" --patch-values "$OUT/$name.csv" --render "$OUT/$name.png" -q \
    > "$OUT/$name.log" 2>&1
  local t1=$(date +%s.%N)
  local n=$(($(wc -l < "$OUT/$name.csv") - 1))
  # hierarchical: leaves, links and link memory from its log line
  local links=$(sed -n 's/.* \([0-9]*\) leaves .*; \([0-9]*\) links (\([0-9.]*\) MB links.*/\1 \/ \2 \/ \3 MB/p' "$OUT/$name.log")
  printf "| %s | %s | %d | %.2f | %s | %s |\n" "$name" "$*" "$n" "$(echo "$t1 - $t0" | bc)" \
    "$(err "$OUT/$name.csv")" "${links:--}"
}
echo "| run | flags | patches | seconds | object-mean error | leaves / links / link MB |"
echo "|---|---|---|---|---|---|"
for p in 250 1000 2500; do run uniform_mc_$p --patches $p; done
for p in 250 1000; do run uniform_analytic_$p --patches $p --form-factors analytic; done
for k in 1 2; do run adaptive_$k --patches 100 --form-factors analytic --adaptive-passes $k --adaptive-threshold 0.3; done
for e in 1e-3 3e-4 1e-4 3e-5 1e-5; do run hier_$e --solver hierarchical --link-epsilon $e; done

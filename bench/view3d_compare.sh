#!/bin/bash
# Builds View3D 3.2 from ../shared/peers/View3D (its one-line build, into /tmp, never into the
# repository) and compares radflux viewfactors against it on the grid rooms of issue 23
# (bench/view3d_compare.py). usage: bench/view3d_compare.sh [RADFLUX] [N ...]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
radflux=${1:-$root/build/ci/client/radflux}
shift || true
sizes=${*:-20}
src=$root/../shared/peers/View3D/src
view3d=/tmp/view3d_bench/view3d
if [ ! -x "$view3d" ]; then
  mkdir -p /tmp/view3d_bench
  gcc -O2 -D_MAX_PATH=260 -Dstrcmpi=strcasecmp -include strings.h \
    "$src"/ctrans.c "$src"/getdat.c "$src"/heap.c "$src"/misc.c "$src"/polygn.c \
    "$src"/savevf.c "$src"/test3d.c "$src"/v3main.c "$src"/view3d.c "$src"/viewobs.c \
    "$src"/viewpp.c "$src"/viewunob.c -lm -o "$view3d" 2>/dev/null
fi
for n in $sizes; do
  python3 "$root/bench/view3d_compare.py" --view3d "$view3d" --radflux "$radflux" --n "$n" \
    --workdir "/tmp/view3d_compare"
done

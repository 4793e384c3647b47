#!/usr/bin/env bash
# Spilling rows to disk (issue 6): the Cornell box at PATCHES patches solved (1) in memory,
# (2) in memory inside a memory cgroup capped at CAP bytes (below the in-memory peak), and
# (3) with --memory-limit LIMIT in the same cgroup. Prints time per phase, spill and read
# statistics, peak RSS, and whether B (--patch-values CSV) is identical to run (1).
# Needs root for the cgroup (v2 at /sys/fs/cgroup, else v1 under the caller's memory cgroup).
#
#   OMP_WAIT_POLICY=passive bench/spill.sh OUT_DIR [PATCHES] [CAP] [LIMIT] [BIN]
# RUNS="spill" runs only some of the three (the comparison then uses OUT_DIR/memory.csv).
set -uo pipefail
out=$1
patches=${2:-1000000}
cap=${3:-1200M}
limit=${4:-256M}
root=$(cd "$(dirname "$0")/.." && pwd)
bin=${5:-$root/build/release/client/radflux}
scene=$root/scenes/cornell_box.obj
mkdir -p "$out"

cap_bytes=$(numfmt --from=iec "$cap")
if [ -f /sys/fs/cgroup/cgroup.controllers ]; then
  cg=/sys/fs/cgroup/radflux_spill
  mkdir -p "$cg" && echo "$cap_bytes" >"$cg/memory.max" && echo 0 >"$cg/memory.swap.max"
else
  cg=/sys/fs/cgroup/memory$(awk -F: '$2 == "memory" {print $3}' /proc/self/cgroup)/radflux_spill
  mkdir -p "$cg" && echo "$cap_bytes" >"$cg/memory.limit_in_bytes"
fi
# Runs radflux solve with the given extra flags; $1 = name, $2 = "cg" to run in the cgroup.
run() {
  local name=$1 where=$2
  shift 2
  local start=$(date +%s.%N)
  if [ "$where" = cg ]; then
    (echo $BASHPID >"$cg/cgroup.procs" && exec "$bin" solve "$scene" --patches "$patches" -q \
      --report "$out/$name.json" --patch-values "$out/$name.csv" "$@")
  else
    "$bin" solve "$scene" --patches "$patches" -q --report "$out/$name.json" \
      --patch-values "$out/$name.csv" "$@"
  fi
  local code=$?
  echo "$name: exit $code, wall $(echo "$(date +%s.%N) - $start" | bc) s"
  rm -f "$out/$name.failed"
  [ "$code" -eq 0 ] || touch "$out/$name.failed"
}
runs=${RUNS:-memory memory_capped spill}
[[ " $runs " == *" memory "* ]] && run memory free
[[ " $runs " == *" memory_capped "* ]] && run memory_capped cg
[[ " $runs " == *" spill "* ]] && run spill cg --memory-limit "$limit"
rmdir "$cg"

python3 - "$out" <<'PY'
import json, os, sys
out = sys.argv[1]
for name in ["memory", "memory_capped", "spill"]:
    path = os.path.join(out, name + ".json")
    if os.path.exists(os.path.join(out, name + ".failed")) or not os.path.exists(path):
        print(f"{name}: did not finish"); continue
    r = json.load(open(path)); s = r["seconds"]; sp = r["matrix"]["spill"]
    line = (f"{name}: patches {r['mesh']['patches']} rows {s['rows']:.1f} s solve {s['solve']:.2f} s "
            f"({r['solve']['iterations']} it, {r['solve']['method']}) matrix {r['matrix']['bytes']/1e6:.0f} MB "
            f"peak RSS {r['peak_rss_bytes']/1e6:.0f} MB")
    if sp:
        mb = sp["read_bytes"] / 1e6
        line += (f"\n  spilled {sp['spilled_bytes']/1e6:.0f} MB, in memory {sp['memory_bytes']/1e6:.0f} MB; "
                 f"{sp['read_passes']} read passes, {mb:.0f} MB read in {sp['read_seconds']:.2f} s "
                 f"({mb/max(sp['read_seconds'],1e-9):.0f} MB/s, {sp['read_bytes']/sp['read_passes']/1e6:.0f} MB "
                 f"per pass), solve waited {sp['wait_seconds']:.2f} s for reads")
    print(line)
ref = os.path.join(out, "memory.csv")
for name in ["memory_capped", "spill"]:
    csv = os.path.join(out, name + ".csv")
    if os.path.exists(ref) and os.path.exists(csv) and not os.path.exists(os.path.join(out, name + ".failed")):
        same = open(ref, "rb").read() == open(csv, "rb").read()
        print(f"{name}: B {'bit-identical to' if same else 'DIFFERS from'} the in-memory run")
PY

#!/usr/bin/env bash
# The cost of verifying workers' rows (issue 22): radfluxd (1 thread) + one worker (1 thread)
# solve the Cornell box; the server recomputes a sample of every worker block's rows. Prints
# the server's own account: rows verified of rows received, the seconds spent, and that as a
# % of the workers' build time of those rows (an upper bound of the % of the job's CPU).
# Usage: bench/verify_cost.sh BUILD_DIR [PATCHES] [VERIFY_FRACTION]
set -euo pipefail
build=${1:?build dir}
patches=${2:-4000}
fraction=${3:-0.015}
radfluxd=$build/server/radfluxd
cli=$build/client/radflux
scene=$(cd "$(dirname "$0")/.." && pwd)/scenes/cornell_box.obj
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
log=$work/server.log
"$radfluxd" --listen 127.0.0.1:0 --data-dir "$work/data" --threads 1 --worker-token bench \
  --verify-fraction "$fraction" >"$log" 2>&1 &
server=$!
addr=""
for _ in $(seq 100); do
  addr=$(sed -n 's/^radfluxd listening on //p' "$log")
  [ -n "$addr" ] && break
  sleep 0.1
done
"$radfluxd" --worker --server "$addr" --threads 1 --worker-token bench >"$work/worker.log" 2>&1 &
worker=$!
until grep -q "registered with" "$work/worker.log"; do sleep 0.1; done
"$cli" submit --server "$addr" --watch --patches "$patches" --rays 256 --max-iterations 5 \
  "$scene" >/dev/null 2>&1
kill "$worker" "$server"
wait "$worker" "$server" 2>/dev/null || true
echo "patches~$patches verify-fraction $fraction (64-row blocks, monte_carlo 256 rays):"
grep -o "verified .*" "$log"

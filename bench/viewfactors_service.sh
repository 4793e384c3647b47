#!/usr/bin/env bash
# View-factor jobs through the service (issue 23): a city of FACETS STL facets
# (bench/city_stl.py), sparse output, computed by `radflux viewfactors` (local), by radfluxd
# alone (C threads), and by radfluxd on 1 thread plus C-1 workers of 1 thread each (the
# same cores). Prints wall seconds of each (the service's: submit --watch, upload to files
# written) and the CPU seconds (user + sys) of the processes doing the work; checks that
# the three files are the same bytes. Usage: bench/viewfactors_service.sh BUILD_DIR [CORES]
# [FACETS]
set -euo pipefail
build=${1:-build/ci}
cores=${2:-2}
facets=${3:-6000}
radfluxd=$build/server/radfluxd
cli=$build/client/radflux
work=$(mktemp -d)
trap 'kill $(jobs -p) 2>/dev/null || true; rm -rf "$work"' EXIT
python3 "$(dirname "$0")/city_stl.py" "$work/city.stl" --facets "$facets" >/dev/null
args=(--by face --format sparse --min-vf 0.01)

# cpu PID: user + sys seconds of a process and its reaped children so far (from /proc).
cpu() { awk -v hz="$(getconf CLK_TCK)" '{print ($14 + $15 + $16 + $17) / hz}' "/proc/$1/stat"; }

start=$(date +%s.%N)
/usr/bin/time -f "%U %S" -o "$work/local.time" "$cli" viewfactors "$work/city.stl" \
  "${args[@]}" --threads "$cores" -q -o "$work/local.txt" 2>/dev/null
local_wall=$(echo "$(date +%s.%N) - $start" | bc)
local_cpu=$(awk '{print $1 + $2}' "$work/local.time")

# Runs the job on a fresh server; $1 = server threads, $2 = workers (1 thread each).
run() {
  local threads=$1 workers=$2 log=$work/server_$1_$2.log
  rm -rf "$work/data"
  "$radfluxd" --listen 127.0.0.1:0 --data-dir "$work/data" --threads "$threads" \
    --worker-token bench-worker-token >"$log" 2>&1 &
  local server=$! addr=""
  until [ -n "$addr" ]; do addr=$(sed -n 's/^radfluxd listening on //p' "$log"); sleep 0.05; done
  local pids=()
  for i in $(seq "$workers"); do
    "$radfluxd" --worker --server "$addr" --threads 1 --worker-token bench-worker-token \
      >"$work/worker_$i.log" 2>&1 &
    pids+=($!)
  done
  for i in $(seq "$workers"); do
    until grep -q "registered with" "$work/worker_$i.log"; do sleep 0.05; done
  done
  local before=0 p
  for p in "$server" "${pids[@]}"; do before=$(echo "$before + $(cpu "$p")" | bc); done
  local t0
  t0=$(date +%s.%N)
  "$cli" submit "$work/city.stl" --viewfactors "${args[@]}" --watch -o "$work/service_$2.txt" \
    --server "$addr" >/dev/null 2>&1
  local wall after=0
  wall=$(echo "$(date +%s.%N) - $t0" | bc)
  for p in "$server" "${pids[@]}"; do after=$(echo "$after + $(cpu "$p")" | bc); done
  echo "$wall $(echo "$after - $before" | bc)"
  for p in "${pids[@]}"; do kill "$p"; wait "$p" 2>/dev/null || true; done
  kill "$server"; wait "$server" 2>/dev/null || true
}
read -r alone_wall alone_cpu < <(run "$cores" 0)
read -r farm_wall farm_cpu < <(run 1 $((cores - 1)))
cmp "$work/local.txt" "$work/service_0.txt"
cmp "$work/local.txt" "$work/service_$((cores - 1)).txt"
printf "%d facets, %d cores: wall s / cpu s\n" "$facets" "$cores"
printf "  radflux viewfactors (local)          %6.2f / %6.2f\n" "$local_wall" "$local_cpu"
printf "  radfluxd alone (%d threads)           %6.2f / %6.2f\n" "$cores" "$alone_wall" "$alone_cpu"
printf "  radfluxd 1 thread + %d worker(s)      %6.2f / %6.2f\n" $((cores - 1)) "$farm_wall" "$farm_cpu"
echo "  the three files are the same bytes"

# Sourced by the service benches (bench/service_*.sh, bench/watcher_cost.sh).
# start_radfluxd DIR NAME COMMAND...: runs `COMMAND... --listen 127.0.0.1:0 --data-dir
# DIR/data_NAME` in the background (COMMAND: radfluxd's path and flags, after any env or
# taskset prefix), its log in DIR/server_NAME.log; once it listens, sets RADFLUXD_ADDR
# (HOST:PORT, the port it picked) and RADFLUXD_PID.
start_radfluxd() {
  local dir=$1 name=$2 line
  shift 2
  mkfifo "$dir/out_$name"
  "$@" --listen 127.0.0.1:0 --data-dir "$dir/data_$name" >"$dir/out_$name" \
    2>"$dir/server_$name.log" &
  RADFLUXD_PID=$!
  read -r line <"$dir/out_$name"
  RADFLUXD_ADDR=${line#radfluxd listening on }
}

# Sourced by the CLI integration scripts (cli_round_trip.sh, result_outputs.sh,
# watch_reconnect.sh).
# start_radfluxd RADFLUXD TEMPLATE [FLAGS...]: makes a scratch directory DIR (mktemp -d
# TEMPLATE; it is removed on exit, after the server is killed) and starts RADFLUXD with FLAGS
# and its job store in it on a loopback port the server picks itself. Sets DIR, PID (the
# server) and ADDR (HOST:PORT).
start_radfluxd() {
  local radfluxd=$1
  DIR=$(mktemp -d "$2")
  shift 2
  trap 'kill $PID 2>/dev/null || true; wait $PID 2>/dev/null || true; rm -rf "$DIR"' EXIT
  mkfifo "$DIR/out"
  ADDR=127.0.0.1:0
  restart_radfluxd "$radfluxd" "$@"
}

# restart_radfluxd RADFLUXD [FLAGS...]: starts RADFLUXD again on DIR's job store and on ADDR
# (after the previous one stopped or was killed); sets PID and ADDR.
restart_radfluxd() {
  local radfluxd=$1
  shift
  "$radfluxd" --listen "$ADDR" --data-dir "$DIR/data" --threads 2 "$@" >"$DIR/out" \
    2>>"$DIR/server.log" &
  PID=$!
  local line
  read -r line <"$DIR/out"
  ADDR=${line#radfluxd listening on }
}

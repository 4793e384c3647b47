#!/bin/bash
# CLI smoke test of the service verbs: radfluxd on a loopback port it picks itself,
# submit --watch, result, list, --server after and before the verb, server-down message.
set -euo pipefail
RADFLUXD=$1 CLI=$2 SCENE=$3
source "$(dirname "$0")/radfluxd_fixture.sh"
start_radfluxd "$RADFLUXD" /tmp/radflux_cli_XXXXXX
echo "server at $ADDR"

"$CLI" submit "$SCENE" --patches 200 --rays 64 --watch --server "$ADDR" >"$DIR/submit.out"
JOB=$(tail -n 1 "$DIR/submit.out")
[[ "$JOB" =~ ^job-[0-9a-f]{16}$ ]] || { echo "bad job id line: $JOB"; exit 1; }
"$CLI" --server "$ADDR" result "$JOB" --patch-values "$DIR/b.csv" --report "$DIR/report.json"
[ "$(head -n 1 "$DIR/b.csv")" = "patch,face,object,area,cx,cy,cz,r,g,b" ]
[ "$(wc -l <"$DIR/b.csv")" -gt 150 ]
grep -q '"iterations"' "$DIR/report.json"
"$CLI" list --server "$ADDR" | grep -q "$JOB.*JOB_STATE_SUCCEEDED"
# Options the service cannot carry are refused, not silently dropped.
if "$CLI" submit "$SCENE" --solver hierarchical --server "$ADDR" 2>"$DIR/err"; then
  echo "submit --solver hierarchical succeeded"; exit 1
fi
grep -q "run in \`radflux solve\` only" "$DIR/err"

kill -TERM $PID
wait $PID
if "$CLI" list --server "$ADDR" 2>"$DIR/err"; then echo "list succeeded without a server"; exit 1; fi
grep -q "cannot reach radfluxd at $ADDR" "$DIR/err"
[ "$(wc -l <"$DIR/err")" -eq 1 ]
echo "cli round trip ok"

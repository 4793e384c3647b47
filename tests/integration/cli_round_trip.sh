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
# list's columns: id, state, phase, patches, message, and last the owner (on a server
# without tokens everyone is the principal 'default').
"$CLI" list --server "$ADDR" | grep -q "^$JOB  JOB_STATE_SUCCEEDED  PHASE_DONE  patches [0-9]*  .*  owner default$" \
  || { "$CLI" list --server "$ADDR"; echo "list line without its owner last"; exit 1; }
# watch speaks to people: on a terminal (script(1) gives it one) a bar redrawn in place with
# the phase in words; piped, plain lines with the event number.
script -qec "$CLI watch $JOB --server $ADDR" /dev/null >"$DIR/tty.out"
grep -q $'\rsucceeded  *\[#*\] 100.0%' "$DIR/tty.out" || { cat -v "$DIR/tty.out"; exit 1; }
"$CLI" watch "$JOB" --server "$ADDR" 2>"$DIR/piped.err"
grep -qx '\[[0-9]*\] succeeded' "$DIR/piped.err" || { cat -v "$DIR/piped.err"; exit 1; }
! grep -q $'\r' "$DIR/piped.err"
# A job whose solve stops short of its tolerance has its result, but watch, result and list
# say so at once, and watch and result exit 3 (one line with the residual reached).
code=0
"$CLI" submit "$SCENE" --patches 200 --rays 64 --max-iterations 1 --watch --server "$ADDR" \
  >"$DIR/short.out" 2>"$DIR/short.err" || code=$?
[ "$code" -eq 3 ] || { echo "submit --watch of a job short of its tolerance exited $code"; exit 1; }
grep -q "radflux watch: job job-[0-9a-f]* not converged: residual .* after 1 iterations" \
  "$DIR/short.err"
SHORT=$(tail -n 1 "$DIR/short.out")
code=0
"$CLI" --server "$ADDR" result "$SHORT" --patch-values "$DIR/short.csv" 2>"$DIR/short.err" || code=$?
[ "$code" -eq 3 ] || { echo "result of a job short of its tolerance exited $code"; exit 1; }
[ "$(wc -l <"$DIR/short.err")" -eq 1 ]
grep -q "radflux result: job $SHORT not converged: residual" "$DIR/short.err"
[ "$(wc -l <"$DIR/short.csv")" -gt 150 ]
"$CLI" list --server "$ADDR" | grep -q "$SHORT.*JOB_STATE_SUCCEEDED NOT_CONVERGED.*not converged"
"$CLI" list --server "$ADDR" | grep "$JOB" | grep -qv "NOT_CONVERGED"
# A job whose energy balance is off (two coplanar floors that overlap) has its result, but
# watch, result and list say so, and watch and result exit 4.
OVERLAP="$(dirname "$0")/../data/overlapping_floor.obj"
code=0
"$CLI" submit "$OVERLAP" --watch --server "$ADDR" >"$DIR/off.out" 2>"$DIR/off.err" || code=$?
[ "$code" -eq 4 ] || { echo "submit --watch of a job whose balance is off exited $code"; exit 1; }
grep -q "radflux watch: job job-[0-9a-f]* energy balance off by .* absorbed + escaped exceed" \
  "$DIR/off.err"
OFF=$(tail -n 1 "$DIR/off.out")
code=0
"$CLI" --server "$ADDR" result "$OFF" --report "$DIR/off.json" 2>"$DIR/off.err" || code=$?
[ "$code" -eq 4 ] || { echo "result of a job whose balance is off exited $code"; exit 1; }
grep -q "radflux result: job $OFF energy balance off by" "$DIR/off.err"
grep -q '"ok": false' "$DIR/off.json"
"$CLI" list --server "$ADDR" | grep -q "$OFF.*JOB_STATE_SUCCEEDED ENERGY_BALANCE_OFF.*energy balance off"
"$CLI" list --server "$ADDR" | grep "$JOB" | grep -qv "ENERGY_BALANCE_OFF"
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

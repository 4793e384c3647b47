#!/bin/bash
# `radflux solve SCENE --view`: `radflux` hands it to radflux-service, which solves in-process
# and serves the view page (/job/local/). Its event stream ends with the job's end; its lit
# mesh (result.glb) is byte for byte the GLB `radflux solve --out` writes without --view (the
# view does not change the solve); its last snapshot is float16 RGB per patch; radflux-local
# itself refuses --view with one line. The view runs in its own process group, killed on exit.
set -euo pipefail
CLI=$1 SCENE=$2
DIR=$(mktemp -d /tmp/radflux_solve_view_XXXXXX)
GROUP=""
trap '[ -z "$GROUP" ] || kill -- -"$GROUP" 2>/dev/null || true; wait 2>/dev/null || true; rm -rf "$DIR"' EXIT
OPTS=(--patches 600 --rays 64)
"$CLI" solve "$SCENE" "${OPTS[@]}" --quiet --out "$DIR/plain.glb"
set -m
"$CLI" solve "$SCENE" "${OPTS[@]}" --view >/dev/null 2>"$DIR/view.err" &
GROUP=$!
set +m
until grep -q "view at http" "$DIR/view.err"; do
  kill -0 "$GROUP" 2>/dev/null || { echo "solve --view exited:"; cat "$DIR/view.err"; exit 1; }
  sleep 0.05
done
URL=$(grep -o 'http://[^ ]*' "$DIR/view.err")
python3 - "$URL" "$DIR/plain.glb" <<'PY'
import json, sys, urllib.request
url, plain = sys.argv[1], sys.argv[2]
with urllib.request.urlopen(url + "events", timeout=120) as events:
    for raw in events:
        line = raw.decode().strip()
        if line.startswith("data: ") and json.loads(line[6:])["ended"]:
            last = json.loads(line[6:])
            break
assert last["state"] == "JOB_STATE_SUCCEEDED" and last["has_glb"] and last["has_report"], last
info = json.load(urllib.request.urlopen(url + "info"))
with urllib.request.urlopen(url + "snapshot") as r:
    assert len(r.read()) == 6 * info["patches"], "snapshot is not float16 RGB per patch"
report = json.load(urllib.request.urlopen(url + "report"))
assert report["solve"]["iterations"] == last["iteration"], (report["solve"], last)
glb = urllib.request.urlopen(url + "result.glb").read()
assert glb == open(plain, "rb").read(), "the view's GLB differs from solve --out's"
print(f"solve --view ok: {info['patches']} patches, {last['iteration']} iterations")
PY
if "$(dirname "$(readlink -f "$CLI")")/radflux-local" solve "$SCENE" --view 2>"$DIR/local.err"; then
  echo "radflux-local accepted --view"; exit 1
fi
grep -q "is served by radflux-service" "$DIR/local.err"

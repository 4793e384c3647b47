#!/bin/bash
# The lightmapped GLB in three.js (issue 24): one Cornell solve written as a lightmapped GLB
# (`--out lm.glb --lightmap 512`) and as the default vertex-coloured GLB; `radflux view` serves
# each and headless Chromium (view_browser.py --lightmap) checks that both load without
# console errors and that the lightmap is drawn with its baked texture (the two pictures agree
# within the texture's quantisation). Each view runs in its own process group, killed on exit.
set -euo pipefail
CLI=$1 SCENE=$2 PY=$3
HERE=$(cd "$(dirname "$0")" && pwd)
DIR=$(mktemp -d /tmp/radflux_lightmap_XXXXXX)
GROUPS_STARTED=()
cleanup() {
  for g in "${GROUPS_STARTED[@]}"; do kill -- -"$g" 2>/dev/null || true; done
  wait 2>/dev/null || true
  rm -rf "$DIR"
}
trap cleanup EXIT
"$CLI" solve "$SCENE" -q --out "$DIR/lm.glb" --lightmap 512
"$CLI" solve "$SCENE" -q --out "$DIR/vc.glb"
set -m  # each view below gets its own process group (its pid)
for name in lm vc; do
  "$CLI" view "$DIR/$name.glb" >"$DIR/$name.out" 2>"$DIR/$name.err" &
  GROUPS_STARTED+=($!)
done
set +m
# url NAME: the URL `radflux view DIR/NAME.glb` prints once it is up.
url() {
  until [ -s "$DIR/$1.out" ]; do
    [ ! -s "$DIR/$1.err" ] || { echo "radflux view $1: $(cat "$DIR/$1.err")" >&2; exit 1; }
    sleep 0.05
  done
  head -n 1 "$DIR/$1.out"
}
LM_URL=$(url lm)
VC_URL=$(url vc)
"$PY" "$HERE/view_browser.py" --lightmap "$LM_URL" "$VC_URL"
echo "lightmap browser ok"

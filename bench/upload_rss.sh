#!/usr/bin/env bash
# Peak RSS (VmHWM) of radfluxd for one upload of a ~MB-megabyte scene and for three at once
# (issue 22: 857 MiB and 2.4 GiB for 200 MB while uploads were held in memory; now they
# stream to disk, and what remains is the scene's text while it is parsed). The scenes are
# the Cornell box padded with comment lines to MB megabytes (each a different pad, so three
# distinct scenes).
#   bench/upload_rss.sh [MB=200] [BUILD=build/ci]
set -euo pipefail
mb=${1:-200}
build=${2:-build/ci}
tmp=$(mktemp -d /tmp/radflux_upload_rss.XXXXXX)
trap 'kill $server 2>/dev/null; rm -rf "$tmp"' EXIT
for k in 1 2 3; do
  mkdir -p "$tmp/s$k"
  cp scenes/cornell_box.mtl "$tmp/s$k/"
  { cat scenes/cornell_box.obj
    head -c $((mb * 1000000)) /dev/zero | tr '\0' 'x' | fold -w 99 | sed "s/^/#$k/"; } \
    >"$tmp/s$k/cornell_box.obj"
done
peak() {  # starts radfluxd, submits the given scenes at once, prints its VmHWM
  rm -rf "$tmp/data" "$tmp/log" && mkdir "$tmp/data"  # no earlier server's log to match
  "$build/server/radfluxd" --listen 127.0.0.1:0 --data-dir "$tmp/data" \
    --max-upload $(((mb + 10) * 1000000)) >"$tmp/log" 2>&1 &
  server=$!
  until grep -q "listening on" "$tmp/log"; do sleep 0.1; done
  local address
  address=$(grep -o "listening on [^ ]*" "$tmp/log" | awk '{print $3}')
  for scene in "$@"; do
    "$build/client/radflux" submit "$scene" --server "$address" --patches 100 >/dev/null &
  done
  wait $(jobs -p | grep -v "^$server$")
  grep VmHWM /proc/$server/status
  kill $server && wait $server || true
}
echo "one ${mb} MB upload:"; peak "$tmp/s1/cornell_box.obj"
echo "three at once:"; peak "$tmp/s1/cornell_box.obj" "$tmp/s2/cornell_box.obj" "$tmp/s3/cornell_box.obj"

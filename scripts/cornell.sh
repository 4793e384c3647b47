#!/usr/bin/env bash
# Sets everything up, builds radflux, and solves the Cornell box in-process, writing
# cornell.png (the picture), cornell.glb (the lit mesh) and cornell.json (the report).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
cmake --preset release >/dev/null
cmake --build --preset release -j "$(nproc)" --target radflux
build/release/client/radflux solve scenes/cornell_box.obj \
  --render cornell.png --out cornell.glb --report cornell.json "$@"
echo "wrote cornell.png, cornell.glb and cornell.json"

#!/bin/sh
# Load + mesh of the conference room (issue 19: <= 1.5 s on the project machine), as the
# median of 5 runs of bench/load_mesh (parse, import rules, subdivision at the CLI's default
# 2000 patches). Usage: bench/load_mesh_conference.sh [BUILD_DIR] (default build/release).
set -eu
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build/release}
exec "$build/bench/load_mesh" "$root/../shared/scenes/conference/conference.obj" 2000 5

#!/usr/bin/env bash
# RenderPark's classroom (issue 21) against Cycles: the scene as radflux loads it written as OBJ
# (bench/scene_obj; both sides of a two-sided face reflect, and the tubes emit from both sides:
# bench/obj_emitter_twins.py), rendered by Cycles (two seeds, SPP samples, default 1024, ~1 min
# a seed on 2 cores; skipped when present) from a corner under the ceiling, and radflux's
# picture from the same camera once per job seed of SEEDS (default "1 2 3") with EXTRA flags
# (e.g. EXTRA="--gather 32"); prints bench/image_regions.py's regions for each (the lamps in
# view left out).
#
#   [SEEDS="1 2 3"] [EXTRA="..."] [SPP=1024] bench/classroom_vs_cycles.sh OUT_DIR
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(dirname "$here")
out=${1:?usage: classroom_vs_cycles.sh OUT_DIR}
mkdir -p "$out"
build=${BUILD:-$root/build/ci}
scene=$root/../shared/scenes/renderpark/salon/classroom.mgf
command -v blender > /dev/null && /usr/bin/python3 -c "import numpy" 2> /dev/null || {
  echo "classroom_vs_cycles.sh: needs Debian's blender and python3-numpy" \
       "(apt-get install blender python3-numpy)" >&2
  exit 1
}
[ -f "$out/classroom.obj" ] || "$build/bench/scene_obj" "$scene" "$out/classroom.obj"
[ -f "$out/classroom_twins.obj" ] ||
  /usr/bin/python3 "$here/obj_emitter_twins.py" "$out/classroom.obj" "$out/classroom_twins.obj"
spp=${SPP:-1024}
refs=()
for seed in 1 2; do
  refs+=("$out/classroom_ref_${spp}_seed$seed.npy")
  [ -f "${refs[-1]}" ] || blender -b --factory-startup -noaudio \
    --python "$root/../shared/tools/cycles_reference.py" -- "$out/classroom_twins.obj" \
    "${refs[-1]%.npy}" --pos 6.5,10.8,2.8 --look 1,2,0.8 --up 0,0,1 --fov 70 --size 160x120 \
    --samples "$spp" --seed $seed --two-sided 1 --threads 2 > "$out/render_${spp}_seed$seed.log" 2>&1
  [ -f "${refs[-1]}" ] || { echo "Cycles wrote no ${refs[-1]}: see $out/render_${spp}_seed$seed.log" >&2; exit 1; }
done
read -r -a extra <<< "${EXTRA:-}"
for seed in ${SEEDS:-1 2 3}; do
  echo "== radflux defaults ${extra[*]:-} --seed $seed"
  OMP_WAIT_POLICY=passive "$build/client/radflux-local" solve "$scene" -q --seed "$seed" \
    --camera-pos 6.5,10.8,2.8 --camera-look-at 1,2,0.8 --camera-up 0,0,1 --fov-deg 70 \
    --size 640x480 --render "$out/radflux_seed$seed.pfm" "${extra[@]}"
  /usr/bin/python3 "$here/image_regions.py" --view classroom "$out/radflux_seed$seed.pfm" "${refs[@]}"
done

#!/usr/bin/env bash
# The conference room (issue 21) against Cycles: clean the scene, render the Cycles reference
# (two seeds; ~2 min a seed at 2,048 samples on 2 quiet cores, ~12 loaded; skipped when
# present), solve with radflux at its defaults and at each extra --patches given, once per job
# seed of SEEDS (default "1"), with EXTRA flags added (e.g. EXTRA="--gather 16"), and print the
# issue's region means for each, the phases' seconds from the report, and wall and CPU
# (user + sys) seconds. A cleaned scene and references are kept in /work/notes/cluster.
# radflux's picture is SS (default 4) times the references' 160x120 in both directions and
# box-averaged down in the comparison, as Cycles' box filter spans the pixel (SS=1: pixel
# centres; the screen's one-pixel emitting frame then reads 20-30% off in its rows).
# Cycles gets the scene and camera in metres (times 0.01, bench/obj_scaled.py; radiance does
# not depend on the scale): Blender 3.4 samples a triangle light by solid angle when its
# longest edge exceeds (distance to its plane) / (twice its area), not scale-free; in the scene's
# centimetres it picked solid-angle sampling, which drops directions towards an emitter seen
# edge-on, and the references came out dark (ceiling 2.2%, floor 2.8%, left wall 4.4%; the
# same as bench/cornell_vs_cycles.sh found on the Cornell box). SPP (default 2048): Cycles'
# samples per pixel.
#
#   [SEEDS="1 2 3"] [EXTRA="..."] [SS=4] [SPP=2048] bench/conference_vs_cycles.sh OUT_DIR [PATCHES ...]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(dirname "$here")
out=${1:?usage: conference_vs_cycles.sh OUT_DIR [PATCHES ...]}
shift
mkdir -p "$out"
radflux=${RADFLUX:-$root/build/ci/client/radflux}
ss=${SS:-4}
cam=(--camera-pos 1550,400,-300 --camera-look-at 0,200,-200 --camera-up 0,1,0 --fov-deg 60
     --size $((160 * ss))x$((120 * ss)))
[ -f "$out/conf.obj" ] || python3 "$here/clean_real_scene.py" \
  "$root/../shared/scenes/conference/conference.obj" "$out/conf" --emit mesh16_SG --ke 20 --max-kd 0.98
spp=${SPP:-2048}
# Blender runs the references; its Python needs NumPy (neither is a radflux dependency).
command -v blender > /dev/null && /usr/bin/python3 -c "import numpy" 2> /dev/null || {
  echo "conference_vs_cycles.sh: needs Debian's blender and python3-numpy" \
       "(apt-get install blender python3-numpy)" >&2
  exit 1
}
[ -f "$out/conf_m.obj" ] || /usr/bin/python3 "$here/obj_scaled.py" "$out/conf.obj" "$out/conf_m.obj" 0.01
refs=()
for seed in 1 2; do
  refs+=("$out/conf_ref_m_${spp}_seed$seed.npy")
  [ -f "${refs[-1]}" ] || blender -b --factory-startup -noaudio \
    --python "$root/../shared/tools/cycles_reference.py" -- "$out/conf_m.obj" "${refs[-1]%.npy}" \
    --pos 15.5,4,-3 --look 0,2,-2 --up 0,1,0 --fov 60 --size 160x120 --samples "$spp" \
    --seed $seed --max-refl 0.98 --threads 2 > "$out/render_m_${spp}_seed$seed.log" 2>&1
  [ -f "${refs[-1]}" ] || { echo "Cycles wrote no ${refs[-1]}: see $out/render_m_${spp}_seed$seed.log" >&2; exit 1; }
done
read -r -a extra <<< "${EXTRA:-}"
for patches in default "$@"; do
  flags=()
  [ "$patches" = default ] || flags=(--patches "$patches")
  for job_seed in ${SEEDS:-1}; do
    run="${patches}_seed$job_seed"
    # Exit 4 (energy balance off) still writes the outputs; it is said on stderr.
    OMP_WAIT_POLICY=passive /usr/bin/time \
      -f "patches $patches, seed $job_seed: wall %e s, cpu %U + %S s, max RSS %M KB" \
      "$radflux" solve "$out/conf.obj" -q --seed "$job_seed" "${flags[@]}" "${extra[@]}" \
      "${cam[@]}" --report "$out/r_$run.json" --render "$out/conf_$run.pfm" || [ $? = 4 ]
    /usr/bin/python3 -c 'import json, sys
print("phases (s):", ", ".join(f"{k} {v:.2f}" for k, v in json.load(open(sys.argv[1]))["seconds"].items()))' \
      "$out/r_$run.json"
    /usr/bin/python3 "$here/image_regions.py" "$out/conf_$run.pfm" "${refs[@]}"
  done
done

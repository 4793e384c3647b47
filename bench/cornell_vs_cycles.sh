#!/usr/bin/env bash
# The Cornell box's defaults against an independent path tracer (Blender's Cycles):
# per-surface mean radiance of radflux's linear pictures against Cycles' picture from the same
# camera, over several radflux seeds (the mean difference is the bias, their spread the noise,
# so that one lucky seed cannot decide), and the whole process's time (median of RUNS runs).
#
# Needs Blender (a bench tool, not a build dependency; not in scripts/setup.sh):
#   apt-get install -y --no-install-recommends blender python3-numpy
# and optionally hyperfine for the timing (else a loop of `date`).
#
# Usage: bench/cornell_vs_cycles.sh [extra radflux solve flags...]
#   OUT=dir (default /tmp/radflux-cycles), SIZE=128x128, SPP=4096 (Cycles samples per pixel),
#   RUNS=20 (0: no timing), BIN=build/ci/client/radflux, SEEDS="1 2 3 4 5 6" (radflux --seed
#   per picture; one seed, e.g. SEEDS=1, is the single-run mode). The two Cycles renders (seeds
#   1 and 2, ~6-9 min each here; OUT/cycles_m_SIZE_SPP_seedN) are reused when OUT has them.
#   SS=4: radflux's pictures are rendered SS times larger and box-averaged down in the comparison
#   (SS x SS samples per pixel, as Cycles' box filter spans the pixel: a pixel across an edge
#   inside one object, such as a block's front and side faces, then means the same in both;
#   SS=1 takes each pixel's centre, which put a block's one-pixel-wide side column 50% off).
#
# Cycles gets the scene in metres (every vertex and the camera times 0.001; radiance does not
# depend on the scale). Blender 3.4 samples a triangle light by solid angle when its longest
# edge exceeds (distance to its plane) / (twice its area), a test that is not scale-free: in
# millimetres it picked solid-angle sampling everywhere, whose directions towards a lamp seen
# edge-on (the walls' tops) miss the triangle and are dropped, so the reference lost 0.6-1.5%
# of the direct light on the top quarter of the walls (direct light alone against Lambert's
# closed form: back / green wall 0.994 / 0.985; in metres 1.007 / 1.006, as BSDF sampling
# alone). In metres it samples by area but within ~2 mm of the lamp's plane.
set -euo pipefail
cd "$(dirname "$0")/.."
out=${OUT:-/tmp/radflux-cycles}
size=${SIZE:-128x128}
ss=${SS:-4}
spp=${SPP:-4096}
runs=${RUNS:-20}
read -r -a seeds <<< "${SEEDS:-1 2 3 4 5 6}"
bin=${BIN:-build/ci/client/radflux}
scene=scenes/cornell_box.obj
mkdir -p "$out"

# The box fitted in the picture from -z (radflux's default before the default view filled the
# picture with the opening), spelled out so that Cycles gets the same one.
pos=278,274.4,-778.4
look=278,274.4,279.6
fov=39.3077
camera=(--camera-pos "$pos" --camera-look-at "$look" --fov-deg "$fov" --size "$size")

# The scene and camera in metres for Cycles (see above; bench/obj_scaled.py), the MTL beside it.
{ read -r pos_m; read -r look_m; } < <(/usr/bin/python3 bench/obj_scaled.py "$scene" \
  "$out/cycles_scene.obj" 0.001 "$pos" "$look")
cp "${scene%.obj}.mtl" "$out/"
for seed in 1 2; do
  ref="$out/cycles_m_${size}_${spp}_seed$seed"
  if [ ! -f "$ref.npy" ]; then
    blender -b --factory-startup -noaudio --python ../shared/tools/cycles_reference.py -- \
      "$out/cycles_scene.obj" "$ref" --pos "$pos_m" --look "$look_m" \
      --up 0,1,0 --fov "$fov" --size "$size" --samples "$spp" --seed "$seed" --threads 2 \
      > "$ref.log" 2>&1
  fi
done

# The masks: the same scene with every object emitting its code k (radiance k) and
# reflecting nothing, rendered by radflux with the same camera.
/usr/bin/python3 - "$scene" "$out/flat" <<'EOF'
import os, sys
scene, flat = sys.argv[1], sys.argv[2]
codes = ["floor", "ceiling", "back_wall", "red_wall", "green_wall", "light", "short_block",
         "tall_block"]
lines, obj = [], None
for line in open(scene):
    p = line.split()
    if p and p[0] == "mtllib":
        line = f"mtllib {os.path.basename(flat)}.mtl\n"
    elif p and p[0] == "o":
        obj = p[1]
    elif p and p[0] == "usemtl":
        line = f"usemtl code_{obj}\n"
    lines.append(line)
open(flat + ".obj", "w").writelines(lines)
with open(flat + ".mtl", "w") as f:
    for k, name in enumerate(codes, start=1):
        f.write(f"newmtl code_{name}\nKd 0 0 0\nKe {k} {k} {k}\n")
EOF
"$bin" solve "$out/flat.obj" --render "$out/mask.pfm" "${camera[@]}" -q --direct-light patch

# radflux's pictures at the defaults (plus any flags given), one per seed, SS times larger,
# and the comparison.
w=${size%x*} h=${size#*x}
big=(--camera-pos "$pos" --camera-look-at "$look" --fov-deg "$fov" --size $((w * ss))x$((h * ss)))
pictures=()
for seed in "${seeds[@]}"; do
  pictures+=("$out/radflux_seed$seed.pfm")
  "$bin" solve "$scene" --render "${pictures[-1]}" "${big[@]}" -q --seed "$seed" "$@"
done
/usr/bin/python3 bench/cornell_vs_cycles.py "$out/mask.pfm" \
  "$out/cycles_m_${size}_${spp}_seed1.npy" "$out/cycles_m_${size}_${spp}_seed2.npy" \
  "${pictures[@]}" --json "$out/compare.json"

# The whole process at the defaults, no outputs: median of RUNS runs.
if [ "$runs" -eq 0 ]; then
  exit 0
elif command -v hyperfine > /dev/null; then
  hyperfine -N -w 2 -r "$runs" --export-json "$out/time.json" \
    "$bin solve $scene -q $*" | grep -E "Time|Range"
  /usr/bin/python3 -c "import json,sys; r=json.load(open(sys.argv[1]))['results'][0]; \
print(f\"median {r['median']*1000:.1f} ms over {len(r['times'])} runs\")" "$out/time.json"
else
  for ((r = 0; r < runs; ++r)); do
    s=$(date +%s.%N); "$bin" solve "$scene" -q "$@"; e=$(date +%s.%N)
    echo "$s $e"
  done | awk '{print ($2 - $1) * 1000}' | sort -n | awk '{t[NR] = $1} END {
    printf "median %.1f ms over %d runs\n", (NR % 2 ? t[(NR + 1) / 2] : (t[NR / 2] + t[NR / 2 + 1]) / 2), NR}'
fi

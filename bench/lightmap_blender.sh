#!/usr/bin/env bash
# Slow check (not a test): Debian's Blender imports radflux's lightmapped GLB headless and
# sees the second UV set and the lightmap image on an emissive material.
# Needs: apt-get install -y --no-install-recommends blender
# Usage: bench/lightmap_blender.sh [SIZE]   (BIN=build/ci/client/radflux, OUT=/tmp/radflux-lightmap)
set -euo pipefail
cd "$(dirname "$0")/.."
size=${1:-512}
bin=${BIN:-build/ci/client/radflux}
out=${OUT:-/tmp/radflux-lightmap}
mkdir -p "$out"
"$bin" solve scenes/cornell_box.obj -q --out "$out/cornell_lightmap.glb" --lightmap "$size"
blender -b --factory-startup -noaudio --python-expr "
import bpy, sys, numpy
# Debian's Blender 3.4 importer still says np.bool, which NumPy >= 1.24 removed (not our GLB).
if not hasattr(numpy, 'bool'): numpy.bool = bool
bpy.ops.import_scene.gltf(filepath='$out/cornell_lightmap.glb')
meshes = [o for o in bpy.context.selected_objects if o.type == 'MESH']  # the imported ones
uv = [len(o.data.uv_layers) for o in meshes]
images = [i for i in bpy.data.images if i.size[0] > 0]
emissive = [m for m in bpy.data.materials if m.use_nodes and any(
    n.type == 'TEX_IMAGE' for n in m.node_tree.nodes)]
print('LIGHTMAP_CHECK meshes', len(meshes), 'uv_layers', uv, 'images',
      [(i.name, tuple(i.size)) for i in images], 'materials_with_texture', len(emissive))
ok = meshes and min(uv) >= 2 and any(tuple(i.size) == ($size, $size) for i in images) and emissive
print('LIGHTMAP_OK' if ok else 'LIGHTMAP_FAIL')
sys.exit(0 if ok else 1)
" 2>&1 | grep -E "LIGHTMAP_|Error|error" 

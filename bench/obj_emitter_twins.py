#!/usr/bin/python3
"""An OBJ whose two-sided emitters emit from both sides in a renderer that emits from fronts only.

Usage: obj_emitter_twins.py IN.obj OUT.obj

bench/scene_obj writes a two-sided face once (material suffix _2s) and Cycles
(../shared/tools/cycles_reference.py --two-sided 1) then reflects on both sides but emits from
the front alone, where radflux's twin emits too (RenderPark's classroom: each tube's upper side
lights its housing). Each face of an emitting _2s material (Ke > 0 in IN's MTL) becomes two
faces 0.05 mm either side of it, back to back, each facing out: every ray meets one of them
from its front. Other lines are copied; the new vertices go at the end (the faces keep their
positive indices). OUT uses IN's MTL.
"""
import os
import sys

OFFSET = 5e-5  # scene units (metres in RenderPark's scenes)


def emitting_materials(obj_path, lines):
    out, name = set(), None
    for line in lines:
        if line.startswith("mtllib"):
            for entry in open(os.path.join(os.path.dirname(obj_path), line.split(None, 1)[1].strip())):
                parts = entry.split()
                if parts[:1] == ["newmtl"]:
                    name = parts[1]
                elif parts[:1] == ["Ke"] and any(float(v) > 0 for v in parts[1:4]):
                    out.add(name)
    return {m for m in out if m.endswith("_2s")}


def main():
    if len(sys.argv) != 3:
        raise SystemExit(__doc__)
    lines = open(sys.argv[1]).read().split("\n")
    emitting = emitting_materials(sys.argv[1], lines)
    vertices = [[float(v) for v in line.split()[1:4]] for line in lines if line.startswith("v ")]
    out, extra, material = [], [], None
    for line in lines:
        parts = line.split()
        if parts[:1] == ["usemtl"]:
            material = parts[1]
        if parts[:1] != ["f"] or material not in emitting:
            out.append(line)
            continue
        corners = [vertices[int(p.split("/")[0]) - 1] for p in parts[1:]]
        a = [corners[1][k] - corners[0][k] for k in range(3)]
        b = [corners[2][k] - corners[0][k] for k in range(3)]
        n = [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
        length = sum(v * v for v in n) ** 0.5
        for side in (1, -1):
            first = len(vertices) + 1
            for c in corners:
                vertices.append([c[k] + side * OFFSET * n[k] / length for k in range(3)])
                extra.append("v %.9g %.9g %.9g" % tuple(vertices[-1]))
            ids = [str(first + k) for k in range(len(corners))]
            out.append("f " + " ".join(ids if side > 0 else ids[::-1]))
    with open(sys.argv[2], "w") as f:
        f.write("\n".join(out + extra) + "\n")


if __name__ == "__main__":
    main()

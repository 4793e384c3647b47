#!/usr/bin/python3
"""An OBJ scene scaled for Cycles: every vertex (and any X,Y,Z points given) times a factor.

Blender 3.4 samples a triangle light by solid angle when its longest edge exceeds (distance to
its plane) / (twice its area), a test that is not scale-free: in millimetres or centimetres it
picks solid-angle sampling, whose directions towards a lamp seen edge-on are dropped, and the
reference loses grazing direct light (the Cornell box's wall tops 0.6-1.5%, the conference's
left wall 4.4%). Radiance does not depend on the scale, so the Cycles references of bench/ are
rendered in metres.

Usage: bench/obj_scaled.py SRC.obj DST.obj FACTOR [X,Y,Z ...]
Writes DST.obj (same lines, vertices scaled; the MTL it names must sit beside it) and prints
each point, scaled, one per line.
"""
import sys


def main():
    src, dst, factor = sys.argv[1], sys.argv[2], float(sys.argv[3])
    with open(dst, "w") as out:
        for line in open(src):
            p = line.split()
            if p and p[0] == "v":
                line = "v " + " ".join("%.9g" % (float(v) * factor) for v in p[1:4]) + "\n"
            out.write(line)
    for point in sys.argv[4:]:
        print(",".join("%.9g" % (float(v) * factor) for v in point.split(",")))


if __name__ == "__main__":
    main()

#!/usr/bin/env python3
"""Cleans a third-party OBJ (../shared/scenes/) so that today's loader takes it, until the
import rules of issue 19 (--emit, clamping, triangulation) land: every face becomes
triangles (a fan from the vertex that keeps every triangle turning the face's way, so
non-convex quads split along the right diagonal), zero-area triangles are dropped, Kd is
clamped to --max-kd, and the materials named by --emit get Ke. Writes OUT.obj and OUT.mtl;
never changes the input.

    bench/clean_real_scene.py ../shared/scenes/conference/conference.obj /tmp/conf \\
        --emit mesh16_SG --ke 10
"""
import argparse
import os
import re


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def newell(points):
    n = [0.0, 0.0, 0.0]
    for k, p in enumerate(points):
        q = points[(k + 1) % len(points)]
        n[0] += (p[1] - q[1]) * (p[2] + q[2])
        n[1] += (p[2] - q[2]) * (p[0] + q[0])
        n[2] += (p[0] - q[0]) * (p[1] + q[1])
    return tuple(n)


def triangulate(tokens, points, min_area2):
    """Fan triangles of one face (token lists), trying each start vertex until every
    triangle turns the face's way; triangles with twice-area below min_area2 are dropped."""
    normal = newell(points)
    m = len(tokens)
    best = None
    for start in range(m):
        tris = []
        ok = True
        for k in range(1, m - 1):
            a, b, c = start, (start + k) % m, (start + k + 1) % m
            n = cross(sub(points[b], points[a]), sub(points[c], points[a]))
            if dot(n, normal) < 0:
                ok = False
            if dot(n, n) ** 0.5 > min_area2:
                tris.append((a, b, c))
        if ok:
            best = tris
            break
        if best is None:
            best = tris
    return [[tokens[a], tokens[b], tokens[c]] for a, b, c in best]


def clean_obj(src, dst, mtl_name, min_area2):
    positions = []
    faces_in = faces_out = dropped = 0
    with open(src) as f, open(dst, "w") as out:
        for line in f:
            if line.startswith("v "):
                positions.append(tuple(float(x) for x in line.split()[1:4]))
            elif line.startswith("mtllib"):
                out.write("mtllib %s\n" % mtl_name)
                continue
            elif line.startswith("f "):
                tokens = line.split()[1:]
                idx = [int(t.split("/")[0]) for t in tokens]
                points = [positions[i - 1] if i > 0 else positions[len(positions) + i] for i in idx]
                faces_in += 1
                tris = triangulate(tokens, points, min_area2)
                dropped += (len(tokens) - 2) - len(tris)
                for t in tris:
                    out.write("f %s\n" % " ".join(t))
                faces_out += len(tris)
                continue
            out.write(line)
    return faces_in, faces_out, dropped


def clean_mtl(src, dst, max_kd, emit, ke):
    material = None
    with open(src) as f, open(dst, "w") as out:
        for line in f:
            s = line.strip()
            if s.startswith("newmtl"):
                material = s.split(None, 1)[1]
            if re.match(r"^Kd\s", s):
                kd = [min(float(x), max_kd) for x in s.split()[1:4]]
                line = "Kd %g %g %g\n" % tuple(kd)
            if re.match(r"^Ke\s", s) and material in emit:
                continue  # replaced below
            out.write(line)
            if s.startswith("newmtl") and material in emit:
                out.write("Ke %g %g %g\n" % (ke, ke, ke))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("obj")
    ap.add_argument("out", help="output path without extension (writes OUT.obj, OUT.mtl)")
    ap.add_argument("--max-kd", type=float, default=0.95)
    ap.add_argument("--emit", action="append", default=[], help="material to light (repeat)")
    ap.add_argument("--ke", type=float, default=10.0, help="radiance Ke of --emit materials")
    ap.add_argument("--min-area", type=float, default=1e-12,
                    help="drop triangles below this area (scene units^2)")
    args = ap.parse_args()
    src_mtl = None
    with open(args.obj) as f:
        for line in f:
            if line.startswith("mtllib"):
                src_mtl = os.path.join(os.path.dirname(args.obj), line.split(None, 1)[1].strip())
                break
    mtl_name = os.path.basename(args.out) + ".mtl"
    faces_in, faces_out, dropped = clean_obj(args.obj, args.out + ".obj", mtl_name,
                                             2 * args.min_area)
    clean_mtl(src_mtl, args.out + ".mtl", args.max_kd, set(args.emit), args.ke)
    print("%s: %d faces -> %d triangles (%d zero-area dropped)" % (args.out + ".obj", faces_in,
                                                                   faces_out, dropped))


if __name__ == "__main__":
    main()

#!/usr/bin/env python3
"""Cost per row against the number of emitter patches (issue 20: direct light at any number
of emitters). A closed 4 x 3 x 4 room whose walls and floor are 48 x 48 faces each (one patch
per face: --max-edge 1e9), lit by (a) one small lamp patch, (b) a luminous ceiling of one
face, (c) the ceiling as N x N faces, (d) the same split into 2 N^2 triangles; every run has
the same non-emitter rows, and (b)-(d) the same light, so their cost per row compares the
number of emitter patches alone. Prints,
per case and binary: emitter patches, rows (the white faces; the lamp case has a white ceiling
too), rays per row, the rows' wall seconds (the report's seconds.rows) and microseconds per row,
and the whole solve's CPU time (user + sys of the process: mesh, rows, solve) in microseconds
per row; medians of RUNS runs. CPU time is the measure to compare under load (wall grows with
the machine's load, CPU time far less); a change to the rows alone changes the solve's CPU
time by what it changes the rows'. With
several --bin, each case runs them in turn, run after run (before and after a change in one
run, under the same load).

Usage: bench/emitter_count_cost.py [--bin build/ci/client/radflux ...] [--n 64] [--runs 5]
       [--threads 1] [--out /tmp/radflux-emitters]
"""
import argparse
import json
import os
import resource
import statistics
import subprocess

MTL = "newmtl white\nKd 0.7 0.7 0.7\nnewmtl lamp\nKd 0 0 0\nKe 5 5 5\n"


def grid(material, origin, ex, ey, g, out, triangles=False, fill=1.0):
    """g x g faces on origin + a ex + b ey, front side ex x ey, each `fill` of its cell's side
    (about the cell's centre); appends OBJ lines to out."""
    for a in range(g):
        for b in range(g):
            p = [origin[k] + ex[k] * (a + (1 - fill) / 2) / g + ey[k] * (b + (1 - fill) / 2) / g
                 for k in range(3)]
            q = [[p[k] + ex[k] * da * fill / g + ey[k] * db * fill / g for k in range(3)]
                 for da, db in ((0, 0), (1, 0), (1, 1), (0, 1))]
            first = out["next"]
            out["lines"].append(f"usemtl {material}")
            out["lines"] += [f"v {v[0]:.9g} {v[1]:.9g} {v[2]:.9g}" for v in q]
            out["next"] += 4
            if triangles:
                out["lines"].append(f"f {first} {first + 1} {first + 2}")
                out["lines"].append(f"f {first} {first + 2} {first + 3}")
            else:
                out["lines"].append(f"f {first} {first + 1} {first + 2} {first + 3}")


def room(path, ceiling, n):
    """The room with ceiling 'lamp' (one small lamp patch under a white ceiling), 'face' (one
    emitting face), 'quads' (N x N emitting faces), 'triangles' (2 N^2) or 'panels' (N x N
    faces at 80% of their cells' side under a white ceiling: they tile nothing)."""
    out = {"lines": [f"mtllib {os.path.basename(path)[:-4]}.mtl"], "next": 1}
    w, h, d, g = 4.0, 3.0, 4.0, 48
    grid("white", (0, 0, 0), (0, 0, d), (w, 0, 0), g, out)        # floor, facing +y
    grid("white", (0, 0, 0), (w, 0, 0), (0, h, 0), g, out)        # z = 0, facing +z
    grid("white", (0, 0, d), (0, h, 0), (w, 0, 0), g, out)        # z = d, facing -z
    grid("white", (0, 0, 0), (0, h, 0), (0, 0, d), g, out)        # x = 0, facing +x
    grid("white", (w, 0, 0), (0, 0, d), (0, h, 0), g, out)        # x = w, facing -x
    if ceiling == "lamp":
        grid("white", (0, h, 0), (w, 0, 0), (0, 0, d), g, out)    # white ceiling, facing -y
        grid("lamp", (1.8, h - 0.01, 1.8), (0.4, 0, 0), (0, 0, 0.4), 1, out)
    elif ceiling == "panels":
        grid("white", (0, h, 0), (w, 0, 0), (0, 0, d), g, out)
        grid("lamp", (0, h - 0.01, 0), (w, 0, 0), (0, 0, d), n, out, fill=0.8)
    else:
        faces = 1 if ceiling == "face" else n
        grid("lamp", (0, h, 0), (w, 0, 0), (0, 0, d), faces, out, ceiling == "triangles")
    with open(path, "w") as f:
        f.write("\n".join(out["lines"]) + "\n")
    with open(path[:-4] + ".mtl", "w") as f:
        f.write(MTL)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--bin", action="append",
                    help="radflux binary; repeat to compare (default build/ci/client/radflux)")
    ap.add_argument("--n", type=int, default=64)
    ap.add_argument("--runs", type=int, default=5)
    ap.add_argument("--threads", type=int, default=1)
    ap.add_argument("--out", default="/tmp/radflux-emitters")
    a = ap.parse_args()
    bins = a.bin or ["build/ci/client/radflux"]
    os.makedirs(a.out, exist_ok=True)
    print(f"{'case':20s} {'bin':>3s} {'emitters':>8s} {'rows':>6s} {'rays/row':>9s} "
          f"{'rows s':>8s} {'us/row':>7s} {'solve cpu us/row':>16s}")
    for ceiling in ("lamp", "face", "quads", "triangles", "panels"):
        scene = os.path.join(a.out, f"room_{ceiling}.obj")
        room(scene, ceiling, a.n)
        seconds = [[] for _ in bins]
        cpu = [[] for _ in bins]
        rays = [0 for _ in bins]
        for _ in range(a.runs):
            for b, binary in enumerate(bins):
                report = os.path.join(a.out, f"room_{ceiling}_{b}.json")
                before = resource.getrusage(resource.RUSAGE_CHILDREN)
                subprocess.run([binary, "solve", scene, "-q", "--threads", str(a.threads),
                                "--max-edge", "1e9", "--report", report], check=True)
                r = json.load(open(report))
                seconds[b].append(r["seconds"]["rows"])
                after = resource.getrusage(resource.RUSAGE_CHILDREN)
                cpu[b].append(after.ru_utime + after.ru_stime - before.ru_utime - before.ru_stime)
                rays[b] = r["rays"]
        emitters = {"lamp": 1, "face": 1, "quads": a.n * a.n, "triangles": 2 * a.n * a.n,
                    "panels": a.n * a.n}[ceiling]
        rows = (6 if ceiling in ("lamp", "panels") else 5) * 48 * 48  # white faces: a row each
        for b in range(len(bins)):
            median = statistics.median(seconds[b])
            median_cpu = statistics.median(cpu[b])
            print(f"{ceiling + ' ceiling':20s} {b:3d} {emitters:8d} {rows:6d} "
                  f"{rays[b] / rows:9.2f} {median:8.3f} {1e6 * median / rows:7.1f} "
                  f"{1e6 * median_cpu / rows:16.1f}", flush=True)


if __name__ == "__main__":
    main()

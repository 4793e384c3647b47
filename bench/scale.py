#!/usr/bin/env python3
"""Scale: `radflux solve` on the Cornell box from 1k to 1M patches (monte_carlo, cg),
one run each: seconds per phase, matrix bytes, peak memory; then the growth exponent of
each (least-squares slope of log(value) against log(n)). Writes CSV and prints a table.

  bench/scale.py --out bench/results/scale [--max 1000000] [--bin build/release/client/radflux]
"""
import argparse, csv, json, math, os, subprocess, tempfile, time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def slope(xs, ys):
    pts = [(math.log(x), math.log(y)) for x, y in zip(xs, ys) if x > 0 and y > 0]
    if len(pts) < 2:
        return float("nan")
    mx = sum(p[0] for p in pts) / len(pts)
    my = sum(p[1] for p in pts) / len(pts)
    return sum((x - mx) * (y - my) for x, y in pts) / sum((x - mx) ** 2 for x, _ in pts)


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--out", required=True)
    p.add_argument("--max", type=int, default=1_000_000)
    p.add_argument("--bin", default=os.path.join(ROOT, "build/release/client/radflux"))
    p.add_argument("--extra", default="", help="extra radflux solve flags")
    a = p.parse_args()
    sizes = [n for n in [1000, 4000, 16000, 64000, 256000, 1000000] if n <= a.max]
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for n in sizes:
            rep = os.path.join(tmp, "r.json")
            start = time.perf_counter()
            subprocess.run([a.bin, "solve", os.path.join(ROOT, "scenes/cornell_box.obj"),
                            "--patches", str(n), "-q", "--report", rep, *a.extra.split()], check=True)
            wall = time.perf_counter() - start
            r = json.load(open(rep))
            s = r["seconds"]
            rows.append({"patches": r["mesh"]["patches"], "wall": round(wall, 3),
                         "mesh": round(s["mesh"], 4), "embree": round(s["embree"], 4),
                         "rows": round(s["rows"], 3), "solve": round(s["solve"], 3),
                         "iterations": r["solve"]["iterations"], "nnz": r["matrix"]["nnz"],
                         "matrix_mb": round(r["matrix"]["bytes"] / 1e6, 1),
                         "peak_mb": round(r["peak_rss_bytes"] / 1e6, 1),
                         "rays_per_s": round(r["rays_per_second"] / 1e6, 2)})
            print(rows[-1], flush=True)
    with open(a.out + ".csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    ns = [r["patches"] for r in rows]
    for key in ["wall", "embree", "rows", "solve", "nnz", "matrix_mb", "peak_mb"]:
        print(f"{key:10s} grows as n^{slope(ns, [r[key] for r in rows]):.2f}")


if __name__ == "__main__":
    main()

#!/usr/bin/python3
"""Speed against per-object error on RenderPark's scenes, per method and knob (issue 21).

Usage: bench/real_scenes_sweep.py [--build build/ci] [--cache /tmp/radflux-real]
           [--scenes classroom,corridor,office2] [--out bench/results/real] [--timeout 600]

For each scene, radflux-local solve runs once per setting (SETTINGS: the defaults; --patches;
--rays; --form-factors hemicube and analytic; every --solver including hierarchical, which
meshes on its own) and is judged as bench/real_scenes.py judges it, against the same cached
references (bench/object_reference, two seeds). Writes OUT_SCENE.csv (one row per setting:
wall and CPU seconds, peak memory, rays, unknowns, the per-object error over the judged
objects and over those the reference knows within 0.25%) and OUT_SCENE.png (gnuplot: CPU
seconds against the median error of the sharp objects, log-log, one point per setting, the
defaults marked, rpkCpp's time as a vertical line). A setting that runs out of --timeout
seconds gets a row that says so.
"""
import csv
import os
import subprocess
import sys

import real_scenes as rs

SETTINGS = [("defaults", [])] + \
    [(f"patches {n}", ["--patches", str(n)]) for n in (500, 1000, 4000, 8000, 16000)] + \
    [(f"rays {k}", ["--rays", str(k)]) for k in (16, 32, 128, 256)] + \
    [("hemicube", ["--form-factors", "hemicube"]), ("analytic", ["--form-factors", "analytic"])] + \
    [(f"solver {s}", ["--solver", s]) for s in ("jacobi", "gauss_seidel", "southwell", "cg",
                                                "hierarchical")]
COLUMNS = ["scene", "setting", "status", "wall_s", "cpu_s", "peak_rss_mib", "rays", "unknowns",
           "objects", "err_max_pct", "err_median_pct", "above_1pct", "sharp_objects",
           "sharp_max_pct", "sharp_median_pct", "sharp_above_1pct"]


def measure(opt, name, ref, label, flags):
    """One CSV row (dict) for `flags` on scene `name`."""
    run = rs.radflux(opt["--build"], opt["--cache"], name, flags, timeout=float(opt["--timeout"]))
    if run is None:
        return {"scene": name, "setting": label, "status": "timeout"}
    err, sharp = rs.errors(ref, run)
    e, s = rs.stats(list(err.values())), rs.stats(list(sharp.values()))
    report = run["report"]
    fmt = lambda v: "" if v is None else f"{v:.3f}"
    return {"scene": name, "setting": label, "status": run["status"], "wall_s": f"{run['wall']:.3f}",
            "cpu_s": f"{run['cpu']:.3f}", "peak_rss_mib": f"{report.get('peak_rss_bytes', 0) / 2**20:.1f}",
            "rays": report.get("rays", ""), "unknowns": report["mesh"]["unknowns"]["unknowns"],
            "objects": len(err), "err_max_pct": fmt(e[0]), "err_median_pct": fmt(e[1]),
            "above_1pct": e[2], "sharp_objects": len(sharp), "sharp_max_pct": fmt(s[0]),
            "sharp_median_pct": fmt(s[1]), "sharp_above_1pct": s[2]}


def plot(csv_path, png_path, name):
    """CPU seconds against the sharp objects' median error, the defaults marked."""
    rpk = rs.RPK_SECONDS.get(name)
    peer = (f"set arrow from {rpk}, graph 0 to {rpk}, graph 1 nohead dt 2\n"
            f"set label 'rpkCpp (wall)' at {rpk}, graph 0.95 offset 0.5,0\n" if rpk else "")
    script = f"""set terminal pngcairo size 900,600 noenhanced
set output '{png_path}'
set datafile separator ','
set logscale xy
set xlabel 'CPU seconds of radflux solve (user + sys)'
set ylabel 'median |error| of object mean B, % (objects known within 0.25%)'
set title '{name}: radflux settings against the per-object path-traced reference'
set grid
{peer}plot '< grep -v timeout {csv_path}' every ::1 using 5:15:2 with labels left offset 0.5,0 font ',8' notitle, \\
     '' every ::1 using 5:15 with points pt 7 title 'settings', \\
     '< grep ",defaults," {csv_path}' using 5:15 with points pt 6 ps 3 lw 2 title 'defaults'
"""
    subprocess.run(["gnuplot"], input=script, text=True, check=True)


def main():
    args = sys.argv[1:]
    opt = {"--build": os.path.join(rs.ROOT, "build", "ci"), "--cache": "/tmp/radflux-real",
           "--paths": "", "--relative-error": "0.001", "--scenes": rs.DEFAULT_SCENES,
           "--out": os.path.join(rs.ROOT, "bench", "results", "real"), "--timeout": "600"}
    for i in range(0, len(args), 2):
        opt[args[i]] = args[i + 1]
    for name in opt["--scenes"].split(","):
        _, _, ref = rs.references(opt, name)
        path = f"{opt['--out']}_{name}.csv"
        with open(path, "w", newline="") as f:
            out = csv.DictWriter(f, fieldnames=COLUMNS)
            out.writeheader()
            for label, flags in SETTINGS:
                row = measure(opt, name, ref, label, flags)
                out.writerow(row)
                f.flush()
                print(",".join(str(row.get(c, "")) for c in COLUMNS), flush=True)
        plot(path, f"{opt['--out']}_{name}.png", name)


if __name__ == "__main__":
    main()

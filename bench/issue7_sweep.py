#!/usr/bin/env python3
"""Speed against error of uniform, adaptive and hierarchical meshes (issue 7).

    OMP_WAIT_POLICY=passive bench/issue7_sweep.py BUILD OUTDIR {cornell,hall} [--only NAME...]

BUILD is a build directory with client/radflux and bench/field_error. Each run is
`radflux solve SCENE FLAGS` timed by /usr/bin/time (wall, CPU = user + sys, peak RSS). Its
error is measured by field_error against a reference that has no mesh of its own (exact
direct light plus one bounce of final gather into a fine uniform solve; see
bench/field_error.cc): rms / l1 of B with each patch constant (what was solved), rms_smooth
with per-vertex interpolation (what the picture shows). Also the older object-mean error
(RMS over objects of the relative error of each object's area-weighted mean B) against the
fine solve. Prints a Markdown table; every run's files stay in OUTDIR, and its numbers in
OUTDIR/runs.csv (a re-run replaces its row).

    bench/issue7_sweep.py BUILD OUTDIR SCENE --plot

draws OUTDIR/runs.csv (gnuplot): field rms against CPU seconds and against peak memory, one
line per family of runs (uniform k 64, uniform analytic, adaptive, hierarchical, ...), and
prints each adaptive and hierarchical run's gain in time and memory over every uniform family
at equal field rms (interpolated log-log; "-" outside the family's range).
"""
import argparse
import csv
import json
import math
import os
import re
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
SCENES = {
    "cornell": os.path.join(HERE, "..", "scenes", "cornell_box.obj"),
    "hall": os.path.join(HERE, "..", "scenes", "large", "hall.obj"),
}
# The fine uniform solve the reference gathers from: its discretisation only enters the
# reference through one bounce of indirect light.
FINE = {
    "cornell": ["--patches", "60000", "--rays", "1024"],
    "hall": ["--patches", "50000", "--rays", "256"],
}
RUNS = {
    "cornell": [("uniform_%d" % n, ["--patches", str(n)]) for n in (1000, 4000, 8000, 16000, 32000, 64000)]
    + [("uniform_analytic_%d" % n, ["--patches", str(n), "--form-factors", "analytic"]) for n in (1000, 2000, 3000, 4000, 8000, 16000)]
    + [("adaptive_t%s_p%d" % (t, p), ["--patches", "1000", "--adaptive-passes", str(p), "--adaptive-threshold", t])
       for t in ("0.1", "0.2") for p in (2, 3, 4)]
    + [("hierarchical_%s" % e, ["--solver", "hierarchical", "--link-epsilon", e]) for e in ("1e-3", "1e-4", "1e-5")]
    + [("uniform_k%d_%d" % (k, n), ["--patches", str(n), "--rays", str(k)]) for k in (16, 256) for n in (8000, 16000, 32000)]
    + [("adaptive_k%d_t0.1_p%d" % (k, p), ["--patches", "1000", "--adaptive-passes", str(p), "--adaptive-threshold", "0.1",
                                           "--rays", str(k)]) for k in (16, 256) for p in (2, 3)],
    "hall": [("uniform_%d" % n, ["--patches", str(n)]) for n in (5000, 12500, 25000, 50000, 100000)]
    + [("adaptive_t%s_p%d" % (t, p), ["--patches", "2000", "--adaptive-passes", str(p), "--adaptive-threshold", t])
       for t in ("0.1", "0.2") for p in (2, 3, 4)]
    + [("uniform_analytic_%d" % n, ["--patches", str(n), "--form-factors", "analytic"]) for n in (2000, 4000, 8000, 16000, 32000)]
    + [("hierarchical_%s" % e, ["--solver", "hierarchical", "--link-epsilon", e])
       for e in ("1e-3", "1e-4", "1e-5", "3e-6", "1e-6")]
    # Finer element floors (`--min-element-area`, default 2e-5 of the scene's area): the default
    # stops the hall's leaves at ~23k whatever the epsilon.
    + [("hierarchical_a%s_%s" % (a, e), ["--solver", "hierarchical", "--link-epsilon", e, "--min-element-area", a])
       for a, e in (("5e-6", "1e-5"), ("5e-6", "3e-6"), ("5e-6", "1e-6"), ("2e-6", "1e-6"))]
    + [("uniform_k%d_%d" % (k, n), ["--patches", str(n), "--rays", str(k)]) for k in (16, 256) for n in (12500, 25000, 50000)]
    + [("adaptive_k%d_t0.1_p%d" % (k, p), ["--patches", "2000", "--adaptive-passes", str(p), "--adaptive-threshold", "0.1",
                                           "--rays", str(k)]) for k in (16, 256) for p in (2, 3)],
}


def solve(build, scene, out, name, flags):
    """Runs one solve; returns (wall s, cpu s, peak MB, its log)."""
    base = os.path.join(out, name)
    timing = base + ".time"
    cmd = ["/usr/bin/time", "-f", "%e %U %S %M", "-o", timing, os.path.join(build, "client", "radflux"),
           "solve", scene, *flags, "--patch-values", base + ".csv", "--out", base + ".ply",
           "--render", base + ".png", "--report", base + ".json"]
    log = subprocess.run(cmd, capture_output=True, text=True)
    if log.returncode != 0:
        sys.exit(f"{name}: radflux failed:\n{log.stderr}")
    with open(base + ".log", "w") as f:
        f.write(log.stderr)
    wall, user, system, rss = open(timing).read().split()[-4:]
    return float(wall), float(user) + float(system), int(rss) / 1024, log.stderr


def object_means(path):
    s, a = {}, {}
    for r in csv.DictReader(open(path)):
        o, ar = r["object"], float(r["area"])
        s[o] = s.get(o, 0) + ar * (float(r["r"]) + float(r["g"]) + float(r["b"]))
        a[o] = a.get(o, 0) + ar
    return {o: s[o] / a[o] for o in s}


def object_mean_error(run, ref):
    run, ref = object_means(run), object_means(ref)
    e = [(run[o] / ref[o] - 1) ** 2 for o in ref if not o.startswith("light") and ref[o] > 0]
    return math.sqrt(sum(e) / len(e))


COLUMNS = ["name", "patches", "wall_s", "cpu_s", "peak_mb", "rms", "l1", "rms_smooth", "object_mean_error", "leaves",
           "links"]
# A run's family (one line in the plots) from its name, with the legend it gets.
FAMILIES = [
    (r"uniform_\d+", "uniform, monte_carlo k 64 (the default)"),
    (r"uniform_k16_\d+", "uniform, monte_carlo k 16"),
    (r"uniform_k256_\d+", "uniform, monte_carlo k 256"),
    (r"uniform_analytic_\d+", "uniform, analytic rows (n^2)"),
    (r"adaptive_t0.1_p\d+", "adaptive, t 0.1"),
    (r"adaptive_t0.2_p\d+", "adaptive, t 0.2"),
    (r"adaptive_k16_t0.1_p\d+", "adaptive k 16, t 0.1"),
    (r"adaptive_k256_t0.1_p\d+", "adaptive k 256, t 0.1"),
    (r"hierarchical_[0-9.e-]+", "hierarchical"),
    (r"hierarchical_a5e-6_[0-9.e-]+", "hierarchical, element floor 5e-6"),
    (r"hierarchical_a2e-6_[0-9.e-]+", "hierarchical, element floor 2e-6"),
]

COLORS = ["#1f77b4", "#9ecae1", "#08519c", "#7f7f7f", "#2ca02c", "#98df8a", "#bcbd22", "#006d2c", "#d62728",
          "#ff7f0e", "#8c564b"]


def save_row(path, row):
    rows = list(csv.DictReader(open(path), restval="")) if os.path.exists(path) else []
    rows = [r for r in rows if r["name"] != row["name"]] + [row]
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, COLUMNS)
        w.writeheader()
        w.writerows(rows)


def at_rms(family, rms, column):
    """The family's `column` at field rms `rms`, interpolated log-log between its two runs
    around it; None outside their range."""
    pts = sorted((float(r["rms"]), float(r[column])) for r in family)
    for (e0, v0), (e1, v1) in zip(pts, pts[1:]):
        if e0 <= rms <= e1:
            t = 0 if e1 == e0 else math.log(rms / e0) / math.log(e1 / e0)
            return math.exp(math.log(v0) + t * (math.log(v1) - math.log(v0)))
    return None


def by_family(rows):
    """Legend -> the family's runs sorted by CPU seconds, in FAMILIES' order, empty ones left out."""
    families = {title: sorted((r for r in rows if re.fullmatch(pattern, r["name"])), key=lambda r: float(r["cpu_s"]))
                for pattern, title in FAMILIES}
    return {title: runs for title, runs in families.items() if runs}


def equal_error_table(families, rows):
    """Each adaptive and hierarchical run against the uniform families at its field rms:
    how many times less CPU time and peak memory it takes (uniform / run)."""
    baselines = [t for t in families if t.startswith("uniform")]
    print("| run | patches | field rms | CPU s | peak MB | " + " | ".join(f"{b}: time, memory" for b in baselines) + " |")
    print("|---" * (5 + len(baselines)) + "|")
    for r in rows:
        if r["name"].startswith("uniform"):
            continue
        cells = []
        for b in baselines:
            t, m = at_rms(families[b], float(r["rms"]), "cpu_s"), at_rms(families[b], float(r["rms"]), "peak_mb")
            cells.append("-" if t is None else f"{t / float(r['cpu_s']):.2g}x, {m / float(r['peak_mb']):.2g}x")
        print(f"| {r['name']} | {r['patches']} | {r['rms']} | {r['cpu_s']} | {r['peak_mb']} | " + " | ".join(cells) + " |")


def plot(out, scene):
    """Draws runs.csv: one gnuplot data block per family, sorted by CPU seconds."""
    rows = list(csv.DictReader(open(os.path.join(out, "runs.csv"))))
    families = by_family(rows)
    equal_error_table(families, rows)
    data, curves = os.path.join(out, "runs.dat"), list(families)
    rms = [float(r["rms"]) for r in rows]
    with open(data, "w") as f:
        for family in families.values():
            for r in family:
                f.write(f"{r['cpu_s']} {r['peak_mb']} {r['rms']}\n")
            f.write("\n\n")
    for x, column, label in (("time", 1, "CPU seconds of radflux solve"), ("memory", 2, "peak RSS, MB")):
        lines = [f"'{data}' index {i} using {column}:3 with linespoints lw 2 lc rgb '{COLORS[i % len(COLORS)]}' "
                 f"title '{t}'" for i, t in enumerate(curves)]
        script = f"""set terminal pngcairo size 900,600 noenhanced
set output '{os.path.join(out, f"field_error_{x}.png")}'
set logscale xy
set title '{scene}: speed against error (field rms, lower is better)'
set xlabel '{label}'
set ylabel 'field rms of B against the reference'
set yrange [{min(rms) / 1.1}:{max(rms) * 1.1}]
set ytics (0.02, 0.03, 0.04, 0.05, 0.06, 0.08, 0.1, 0.12, 0.15, 0.2)
set grid xtics ytics
set key top right box opaque font ',9'
plot {', '.join(lines)}
"""
        subprocess.run(["gnuplot"], input=script, text=True, check=True)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("build")
    ap.add_argument("out")
    ap.add_argument("scene", choices=sorted(SCENES))
    ap.add_argument("--only", nargs="*", help="run only these names")
    ap.add_argument("--plot", action="store_true", help="only draw OUTDIR/runs.csv")
    args = ap.parse_args()
    if args.plot:
        return plot(args.out, args.scene)
    os.makedirs(args.out, exist_ok=True)
    scene = SCENES[args.scene]
    field_error = os.path.join(args.build, "bench", "field_error")
    points = os.path.join(args.out, "reference.points")
    fine = os.path.join(args.out, "fine")
    if not os.path.exists(points):
        solve(args.build, scene, args.out, "fine", FINE[args.scene])
        subprocess.run([field_error, "reference", scene, fine + ".ply", fine + ".csv", points], check=True,
                       stdout=subprocess.DEVNULL)
    print("| run | flags | patches | wall s | CPU s | peak MB | field rms | field l1 | rms smooth "
          "| object-mean error |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for name, flags in RUNS[args.scene]:
        if args.only and name not in args.only:
            continue
        wall, cpu, mb, _ = solve(args.build, scene, args.out, name, flags)
        base = os.path.join(args.out, name)
        hierarchical = json.load(open(base + ".json")).get("hierarchical", {})
        e = json.loads(subprocess.run([field_error, "compare", points, base + ".ply", base + ".csv"],
                                      check=True, capture_output=True, text=True).stdout)
        object_error = object_mean_error(base + ".csv", fine + ".csv")
        save_row(os.path.join(args.out, "runs.csv"),
                 {"name": name, "patches": e["run_patches"], "wall_s": f"{wall:.2f}", "cpu_s": f"{cpu:.2f}",
                  "peak_mb": f"{mb:.0f}", "rms": f"{e['rms']:.4f}", "l1": f"{e['l1']:.4f}",
                  "rms_smooth": f"{e['rms_smooth']:.4f}", "object_mean_error": f"{object_error:.2e}",
                  "leaves": hierarchical.get("leaves", ""), "links": hierarchical.get("links", "")})
        print(f"| {name} | `{' '.join(flags)}` | {e['run_patches']} | {wall:.2f} | {cpu:.2f} | {mb:.0f} | "
              f"{e['rms']:.4f} | {e['l1']:.4f} | {e['rms_smooth']:.4f} | {object_error:.2e} |", flush=True)


if __name__ == "__main__":
    main()

#!/usr/bin/env python3
"""Speed against error: drives `radflux solve` over every form-factor method and its
knob, and over the solvers, on one scene and mesh, and records wall time (whole
process, median of --repeat runs), time per phase, rays, nnz, peak memory and the
error against a reference (bench/compare_patch_values). Writes CSV and a log-log
plot (gnuplot): one line per method.

  bench/sweep.py --scene scenes/cornell_box.obj --patches 2000 --out bench/results/cornell_2000
  bench/sweep.py --patches 8500 --knobs "monte_carlo=16,64,256,1024;hemicube=4,8,16,32;analytic=1" \
      --repeat 1 --reference-samples 8 --out bench/results/cornell_8500

The reference (analytic rows with many samples + direct for n <= 4000, else cg to
1e-9) is computed once per scene and patch count and kept beside the CSV. Where analytic
rows are impractical (O(n^2): ~1 h at 30k patches) --reference-rays K makes it
monte_carlo rows with K rays and --reference-samples points for the emitter columns.
"""
import argparse, csv, json, os, statistics, subprocess, sys, tempfile, time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BIN = os.path.join(ROOT, "build/release/client/radflux")
COMPARE = os.path.join(ROOT, "build/release/bench/compare_patch_values")

SWEEPS = {
    "monte_carlo": ("--rays", [16, 32, 64, 128, 256, 512, 1024, 2048]),
    "hemicube": ("--hemicube-res", [4, 8, 16, 32, 64, 128]),
    "analytic": ("--samples", [1, 2, 4, 8]),
}
SOLVERS = ["jacobi", "gauss_seidel", "southwell", "cg"]


def run(args, repeat):
    """Median wall seconds of `radflux solve args` and the last run's report."""
    walls, report = [], None
    with tempfile.TemporaryDirectory() as tmp:
        for _ in range(repeat):
            rep, vals = os.path.join(tmp, "r.json"), os.path.join(tmp, "v.csv")
            start = time.perf_counter()
            subprocess.run([BIN, "solve", *args, "-q", "--report", rep, "--patch-values", vals],
                           check=True)
            walls.append(time.perf_counter() - start)
            report = json.load(open(rep))
        errors = json.loads(subprocess.run([COMPARE, vals, REFERENCE, SCENE], check=True,
                                           capture_output=True, text=True).stdout)
    return statistics.median(walls), report, errors


def row(label, method, knob, solver, wall, report, errors):
    s = report["seconds"]
    return {"label": label, "method": method, "knob": knob, "solver": solver,
            "wall": f"{wall:.4f}", "rows_s": f"{s['rows']:.4f}", "solve_s": f"{s['solve']:.4f}",
            "embree_s": f"{s['embree']:.4f}", "rays": report["rays"],
            "nnz": report["matrix"]["nnz"], "peak_mb": f"{report.get('peak_rss_bytes', 0) / 1e6:.1f}",
            "iterations": report["solve"]["iterations"],
            "rms": f"{max(errors['rms_r'], errors['rms_g'], errors['rms_b']):.5f}",
            "max": f"{max(errors['max_r'], errors['max_g'], errors['max_b']):.4f}",
            "surfaces_rms": f"{errors.get('surfaces_rms', 0):.5f}"}


def plot(csv_path, png_path, column, ylabel):
    lines = []
    for m in SWEEPS:
        lines.append(f"'< grep -E \"^{m} [0-9]+,\" {csv_path}' using 5:{column} with linespoints title '{m}'")
    script = f"""set terminal pngcairo size 900,600 noenhanced
set output '{png_path}'
set datafile separator ','
set logscale xy
set xlabel 'wall time of radflux solve, s (median)'
set ylabel '{ylabel}'
set grid
set key top right
plot {', '.join(lines)}
"""
    subprocess.run(["gnuplot"], input=script, text=True, check=True)


def main():
    global REFERENCE, SCENE, BIN, COMPARE
    p = argparse.ArgumentParser()
    p.add_argument("--scene", default=os.path.join(ROOT, "scenes/cornell_box.obj"))
    p.add_argument("--patches", type=int, default=2000)
    p.add_argument("--out", required=True)
    p.add_argument("--repeat", type=int, default=3)
    p.add_argument("--reference-samples", type=int, default=32)
    p.add_argument("--methods", default="monte_carlo,hemicube,analytic")
    p.add_argument("--knobs", default="",
                   help="override knob lists, e.g. 'monte_carlo=16,64;hemicube=4,8' (methods listed run)")
    p.add_argument("--reference-rays", type=int, default=0,
                   help="monte_carlo reference with this many rays instead of analytic rows")
    p.add_argument("--solver-rays", type=int, default=256, help="monte_carlo k of the solver sweep")
    p.add_argument("--plot-only", action="store_true", help="redraw the plots from the CSV")
    p.add_argument("--bin", default=BIN, help="radflux binary (copy it when rebuilding meanwhile)")
    p.add_argument("--compare", default=COMPARE, help="compare_patch_values binary")
    a = p.parse_args()
    BIN, COMPARE = a.bin, a.compare
    if a.plot_only:
        return plots(a.out)
    SCENE = a.scene
    base = ["--patches", str(a.patches), a.scene]
    REFERENCE = a.out + "_reference.csv"
    if not os.path.exists(REFERENCE):
        solver = ["--solver", "direct"] if a.patches <= 4000 else ["--solver", "cg", "--tolerance", "1e-9", "--max-iterations", "10000"]
        rows = (["--form-factors", "monte_carlo", "--rays", str(a.reference_rays)] if a.reference_rays
                else ["--form-factors", "analytic"])
        subprocess.run([BIN, "solve", *base, *rows, "--samples", str(a.reference_samples), *solver,
                        "-q", "--patch-values", REFERENCE], check=True)
    sweeps = {m: SWEEPS[m] for m in a.methods.split(",")}
    if a.knobs:
        sweeps = {}
        for part in a.knobs.split(";"):
            method, values = part.split("=")
            sweeps[method] = (SWEEPS[method][0], [int(v) for v in values.split(",")])
    rows = []
    for method, (flag, knobs) in sweeps.items():
        for knob in knobs:
            wall, report, errors = run([*base, "--form-factors", method, flag, str(knob)], a.repeat)
            rows.append(row(f"{method} {knob}", method, knob, "auto", wall, report, errors))
            print(rows[-1], flush=True)
    for solver in SOLVERS:
        for tol in ["1e-2", "1e-3", "1e-4", "1e-6"]:
            wall, report, errors = run([*base, "--rays", str(a.solver_rays), "--solver", solver,
                                        "--tolerance", tol, "--max-iterations", "100000"], a.repeat)
            rows.append(row(f"{solver} {tol}", "monte_carlo", a.solver_rays, solver, wall, report, errors))
            rows[-1]["knob"] = tol
            print(rows[-1], flush=True)
    with open(a.out + ".csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    plots(a.out)


def plots(out):
    plot(out + ".csv", out + "_patch_error.png", 13, "area-weighted relative RMS of B (non-emitters)")
    plot(out + ".csv", out + "_surface_error.png", 15, "RMS relative error of surface means")


if __name__ == "__main__":
    main()

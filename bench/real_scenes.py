#!/usr/bin/python3
"""RenderPark scenes against an independent per-object reference (issue 21).

Usage: bench/real_scenes.py [--build build/ci] [--cache /tmp/radflux-real] [--paths N]
                            [--scenes classroom,corridor,office2] [-- extra radflux solve flags]

For each scene: the reference is bench/object_reference (path tracing, no radiosity machinery)
with N paths per object (default 65,536) and seeds 1 and 2, cached in CACHE as
SCENE_ref_seedS_N.csv (computed only when missing); radflux-local solve runs once with its
defaults (plus any extra flags) and the report's phase times and the --patch-values CSV give,
per object, the area-weighted mean of (r+g+b)/3 over the object's full face area (the part
contact meshing leaves out, covered by another face, counted as dark, as it is in the
reference). Prints one line per scene: wall time, phases,
and |radflux / reference - 1| over the objects (max, median, and how many exceed 1%); the
reference's own noise is the two seeds' difference (max, median), and the same error
statistics are given over the objects whose reference mean has a standard error <= 0.25%.
Objects whose reference mean is below 1% of the median object's are left out (nothing to be
relative to), and so are emitters that reflect nothing (their B is their E in both); an
emitter that reflects is kept (its error is small against its E).
The reference cache is keyed by scene, seed and N only: delete it when object_reference
changes.
"""
import csv
import json
import os
import statistics
import subprocess
import sys
import time

SCENES = {"classroom": "salon/classroom.mgf", "corridor": "corridor.mgf",
          "office2": "office2/office2.mgf"}
RPK_SECONDS = {"classroom": 9.8, "corridor": 0.56, "office2": 0.90}  # issue 21's rpkCpp figures
ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SHARED = os.path.join(ROOT, "..", "shared", "scenes", "renderpark")


def reference(build, cache, name, paths, seed):
    """Object -> (area, mean B, stderr, emits) from the cached or freshly computed reference."""
    path = os.path.join(cache, f"{name}_ref_seed{seed}_{paths}.csv")
    if not os.path.exists(path):
        with open(path + ".tmp", "w") as out:
            subprocess.run([os.path.join(build, "bench", "object_reference"),
                            os.path.join(SHARED, SCENES[name]), str(paths), str(seed)],
                           stdout=out, check=True, env=dict(os.environ, OMP_WAIT_POLICY="passive"))
        os.replace(path + ".tmp", path)
    with open(path) as f:
        return {r["object"]: (float(r["area"]), (float(r["r"]) + float(r["g"]) + float(r["b"])) / 3,
                              float(r["stderr"])) for r in csv.DictReader(f)}


def radflux(build, cache, name, extra):
    """(wall seconds, exit status, report, object -> area-weighted mean B) of one radflux solve;
    exit 3 (not converged) and 4 (energy balance off) still write the outputs, and are said."""
    report, values = (os.path.join(cache, f"{name}_run.{x}") for x in ("json", "csv"))
    start = time.monotonic()
    status = subprocess.run([os.path.join(build, "client", "radflux-local"), "solve",
                             os.path.join(SHARED, SCENES[name]), "-q", "--report", report,
                             "--patch-values", values] + extra,
                            env=dict(os.environ, OMP_WAIT_POLICY="passive")).returncode
    if status not in (0, 3, 4):
        raise SystemExit(f"radflux solve {name}: exit {status}")
    wall = time.monotonic() - start
    acc = {}
    with open(values) as f:
        for r in csv.DictReader(f):
            a = float(r["area"])
            s = acc.setdefault(r["object"], [0.0, 0.0])
            s[0] += a * (float(r["r"]) + float(r["g"]) + float(r["b"])) / 3
            s[1] += a
    with open(report) as f:
        return wall, status, json.load(f), {k: (v[0], v[1]) for k, v in acc.items() if v[1] > 0}


def judged(ref):
    """Objects the comparison is about: those that reflect light (the reference's stderr > 0),
    but not the dim ones (below 1% of the median object)."""
    lit = [b for (_, b, se) in ref.values() if se > 0]
    floor = 1e-2 * statistics.median(lit) if lit else 0
    return [k for k, (_, b, se) in ref.items() if se > 0 and b > floor]


def percent_stats(values):
    values = [abs(v) * 100 for v in values]
    return max(values), statistics.median(values)


def main():
    args = sys.argv[1:]
    extra = args[args.index("--") + 1:] if "--" in args else []
    args = args[:args.index("--")] if "--" in args else args
    opt = {"--build": os.path.join(ROOT, "build", "ci"), "--cache": "/tmp/radflux-real",
           "--paths": "65536", "--scenes": ",".join(SCENES)}
    for i in range(0, len(args), 2):
        opt[args[i]] = args[i + 1]
    os.makedirs(opt["--cache"], exist_ok=True)
    for name in opt["--scenes"].split(","):
        ref1, ref2 = (reference(opt["--build"], opt["--cache"], name, int(opt["--paths"]), s)
                      for s in (1, 2))
        wall, status, report, run = radflux(opt["--build"], opt["--cache"], name, extra)
        keys = [k for k in judged(ref1) if k in run]
        mean = {k: (ref1[k][1] + ref2[k][1]) / 2 for k in keys}
        # radflux's power over the object's full face area (the reference's): contact meshing
        # leaves out the part of a face that another covers (a lamp hung just in front of its
        # housing), which the reference counts with the (next to nothing) light it gets there.
        ours = {k: run[k][0] / ref1[k][0] for k in keys}
        cut = sum(run[k][1] < (1 - 1e-3) * ref1[k][0] for k in keys)
        err = [ours[k] / mean[k] - 1 for k in keys]
        noise = [ref1[k][1] / ref2[k][1] - 1 for k in keys]
        worst = max(keys, key=lambda k: abs(ours[k] / mean[k] - 1))
        phases = " ".join(f"{k} {v:.3f}" for k, v in report["seconds"].items() if v >= 0.0005)
        said = {0: "", 3: " NOT CONVERGED", 4: " ENERGY BALANCE OFF"}[status]
        # Well measured: the two seeds' mean has a standard error <= 0.25% (a 1% error is 4 sigma).
        sharp = [ours[k] / mean[k] - 1 for k in keys
                 if max(ref1[k][2], ref2[k][2]) / 2 ** 0.5 <= 0.0025 * mean[k]]
        sharp_text = (f"max {percent_stats(sharp)[0]:.2f}% median {percent_stats(sharp)[1]:.2f}%, "
                      f"{sum(abs(e) > 0.01 for e in sharp)} above 1%" if sharp else "none")
        print(f"{name}{said}: {wall:.2f} s wall (rpkCpp {RPK_SECONDS[name]} s); phases: {phases}; "
              f"{len(keys)} objects ({cut} with faces cut by contact meshing): error max {percent_stats(err)[0]:.2f}% ({worst}) median "
              f"{percent_stats(err)[1]:.2f}%, {sum(abs(e) > 0.01 for e in err)} above 1%; "
              f"reference seeds differ max {percent_stats(noise)[0]:.2f}% "
              f"median {percent_stats(noise)[1]:.2f}%; the {len(sharp)} objects the reference "
              f"knows within 0.25%: {sharp_text}")


if __name__ == "__main__":
    main()

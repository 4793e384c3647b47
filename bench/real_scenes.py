#!/usr/bin/python3
"""RenderPark's scenes and Lost Empire against an independent per-object reference (issue 21).

Usage: bench/real_scenes.py [--build build/ci] [--cache /tmp/radflux-real] [--paths N]
                            [--relative-error R] [--scenes classroom,corridor,office2]
                            [-- extra radflux solve flags]

--scenes takes any of classroom, corridor, office2 (the default) and lost_empire (its torches
lit by --emit Torch=20,15,8, as in bench/RESULTS.md; its objects are its 46 'g' groups, one
per material: the file has a single 'o', so the script reads a copy in CACHE with each 'g'
made an 'o', its MTL and textures linked, not copied).

For each scene: the reference is bench/object_reference (path tracing, no radiosity machinery;
at most N paths an object, default PATHS per scene, fewer once its standard error is R of its
mean, default 0.001) with seeds 1 and 2, cached in CACHE as SCENE_ref_v3_seedS_N.csv (computed only
when missing: delete it when object_reference changes). radflux-local solve runs once with
its defaults (plus any extra flags); the --patch-values CSV gives, per object, the
area-weighted mean of (r+g+b)/3 over the object's full face area (the part contact meshing
leaves out, covered by another face, counted as dark, as it is in the reference). A patch
partly enclosed in a solid (the report's mesh.unknowns.partly_enclosed) shows its exposed
part's B over its whole area, where the reference has the enclosed part dark: such objects
read high here (Lost Empire's Leaves and Detector_Rail, bench/RESULTS.md).

Prints one line per scene: wall and CPU time (user + sys of the solve), phases, and
|radflux / reference - 1| over the judged objects (max, median, how many exceed 1%, and its
mean weighted by the objects' areas: "area-weighted" in bench/RESULTS.md), then the
same over the objects the reference knows within 0.25% (standard error of the two seeds'
mean: a 1% error is 4 of them). Judged: objects that reflect (the reference's standard
error > 0) and are not dim (mean above 1% of the median object's); emitters that reflect are
kept. The reference's own noise is said as the median of its relative standard errors, and
checked: the two seeds' difference over its standard error should have a median near 0.67.
"""
import csv
import json
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time

# name -> (file under ../shared/scenes, import flags given to radflux and to the reference)
SCENES = {"classroom": ("renderpark/salon/classroom.mgf", []),
          "corridor": ("renderpark/corridor.mgf", []),
          "office2": ("renderpark/office2/office2.mgf", []),
          "lost_empire": ("lost_empire/lost_empire.obj", ["--emit", "Torch=20,15,8"])}
DEFAULT_SCENES = "classroom,corridor,office2"
GROUPS_AS_OBJECTS = {"lost_empire"}
RPK_SECONDS = {"classroom": 9.8, "corridor": 0.56, "office2": 0.90}  # issue 21's rpkCpp figures
# Most paths an object per reference seed, within ~10 min each on a loaded 2-core machine:
# the classroom's 629 objects (most of them dim chair and table frames) get fewer.
PATHS = {"classroom": 65536, "corridor": 1048576, "office2": 1048576, "lost_empire": 1048576}
ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SHARED = os.path.join(ROOT, "..", "shared", "scenes")
SHARP = 0.0025  # the reference's relative standard error below which an object is "sharp"


def scene_file(cache, name):
    """The file radflux and the reference read for scene `name` (see GROUPS_AS_OBJECTS)."""
    shared = os.path.join(SHARED, SCENES[name][0])
    if name not in GROUPS_AS_OBJECTS:
        return shared
    folder = os.path.join(cache, f"{name}_groups")
    copy = os.path.join(folder, os.path.basename(shared))
    if not os.path.exists(copy):
        os.makedirs(folder, exist_ok=True)
        source = os.path.dirname(os.path.abspath(shared))
        for entry in os.listdir(source):
            if entry != os.path.basename(shared) and not os.path.exists(os.path.join(folder, entry)):
                os.symlink(os.path.join(source, entry), os.path.join(folder, entry))
        with open(shared) as f, open(copy + ".tmp", "w") as out:
            for line in f:
                out.write("o " + line[2:] if line.startswith("g ") else line)
        os.replace(copy + ".tmp", copy)
    return copy


def reference(build, cache, name, paths, relative, seed):
    """Object -> (area, mean B, standard error) from the cached or fresh reference."""
    path = os.path.join(cache, f"{name}_ref_v3_seed{seed}_{paths}.csv")
    if not os.path.exists(path):
        with open(path + ".tmp", "w") as out:
            subprocess.run([os.path.join(build, "bench", "object_reference"), *SCENES[name][1],
                            scene_file(cache, name), str(paths), str(seed), str(relative)],
                           stdout=out, check=True, env=dict(os.environ, OMP_WAIT_POLICY="passive"))
        os.replace(path + ".tmp", path)
    with open(path) as f:
        return {r["object"]: (float(r["area"]), (float(r["r"]) + float(r["g"]) + float(r["b"])) / 3,
                              float(r["stderr"])) for r in csv.DictReader(f)}


def references(opt, name):
    """The two seeds' references and their mean: object -> (area, B, standard error)."""
    paths = int(opt["--paths"]) if opt["--paths"] else PATHS[name]
    ref1, ref2 = (reference(opt["--build"], opt["--cache"], name, paths,
                            float(opt["--relative-error"]), s) for s in (1, 2))
    mean = {k: (a, (b + ref2[k][1]) / 2, (se * se + ref2[k][2] ** 2) ** 0.5 / 2)
            for k, (a, b, se) in ref1.items() if k in ref2}
    return ref1, ref2, mean


def radflux(build, cache, name, flags, timeout=None):
    """One radflux solve: dict with wall and cpu seconds, exit status, the report, and per
    object (B x area summed, area) from --patch-values; None when it ran out of time.
    Exit 3 (not converged) and 4 (energy balance off) still write the outputs."""
    with tempfile.TemporaryDirectory() as tmp:
        report, values = os.path.join(tmp, "r.json"), os.path.join(tmp, "v.csv")
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        start = time.monotonic()
        try:
            status = subprocess.run(
                [os.path.join(build, "client", "radflux-local"), "solve",
                 scene_file(cache, name), "-q", "--report", report,
                 "--patch-values", values] + SCENES[name][1] + flags, timeout=timeout,
                env=dict(os.environ, OMP_WAIT_POLICY="passive")).returncode
        except subprocess.TimeoutExpired:
            return None
        wall = time.monotonic() - start
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        if status not in (0, 3, 4):
            raise SystemExit(f"radflux solve {name} {' '.join(flags)}: exit {status}")
        acc = {}
        with open(values) as f:
            for r in csv.DictReader(f):
                a = float(r["area"])
                s = acc.setdefault(r["object"], [0.0, 0.0])
                s[0] += a * (float(r["r"]) + float(r["g"]) + float(r["b"])) / 3
                s[1] += a
        with open(report) as f:
            rep = json.load(f)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return {"wall": wall, "cpu": cpu, "status": status, "report": rep,
            "objects": {k: tuple(v) for k, v in acc.items() if v[1] > 0}}


def judged(ref):
    """Objects the comparison is about: those that reflect light (the reference's stderr > 0),
    but not the dim ones (below 1% of the median object)."""
    lit = [b for (_, b, se) in ref.values() if se > 0]
    floor = 1e-2 * statistics.median(lit) if lit else 0
    return [k for k, (_, b, se) in ref.items() if se > 0 and b > floor]


def stats(errors):
    """(max |e| %, median |e| %, count above 1%) of relative errors, or Nones when empty."""
    if not errors:
        return None, None, 0
    values = [abs(e) * 100 for e in errors]
    return max(values), statistics.median(values), sum(v > 1 for v in values)


def errors(ref, run):
    """Per judged object, radflux's mean B over the object's full face area (the reference's)
    relative to the reference, minus 1; and the subset the reference knows within SHARP."""
    keys = [k for k in judged(ref) if k in run["objects"]]
    err = {k: run["objects"][k][0] / ref[k][0] / ref[k][1] - 1 for k in keys}
    sharp = {k: e for k, e in err.items() if ref[k][2] <= SHARP * ref[k][1]}
    return err, sharp


def main():
    args = sys.argv[1:]
    extra = args[args.index("--") + 1:] if "--" in args else []
    args = args[:args.index("--")] if "--" in args else args
    opt = {"--build": os.path.join(ROOT, "build", "ci"), "--cache": "/tmp/radflux-real",
           "--paths": "", "--relative-error": "0.001", "--scenes": DEFAULT_SCENES}
    for i in range(0, len(args), 2):
        opt[args[i]] = args[i + 1]
    os.makedirs(opt["--cache"], exist_ok=True)
    for name in opt["--scenes"].split(","):
        ref1, ref2, ref = references(opt, name)
        run = radflux(opt["--build"], opt["--cache"], name, extra)
        err, sharp = errors(ref, run)
        keys = list(err)
        noise = statistics.median(ref[k][2] / ref[k][1] for k in keys) * 100
        pulls = statistics.median(abs(ref1[k][1] - ref2[k][1]) / (ref1[k][2] ** 2 + ref2[k][2] ** 2) ** 0.5
                                  for k in keys if ref1[k][2] > 0)
        worst = max(keys, key=lambda k: abs(err[k]))
        phases = " ".join(f"{k} {v:.3f}" for k, v in run["report"]["seconds"].items() if v >= 0.0005)
        said = {0: "", 3: " NOT CONVERGED", 4: " ENERGY BALANCE OFF"}[run["status"]]
        e, s = stats(list(err.values())), stats(list(sharp.values()))
        area = sum(ref[k][0] for k in keys)
        weighted = sum(ref[k][0] * abs(err[k]) for k in keys) / area * 100
        sharp_text = (f"max {s[0]:.2f}% median {s[1]:.2f}%, {s[2]} above 1%" if sharp else "none")
        peer = f"rpkCpp {RPK_SECONDS[name]} s" if name in RPK_SECONDS else "no peer figure"
        print(f"{name}{said}: {run['wall']:.2f} s wall, {run['cpu']:.2f} CPU-s ({peer}); phases: {phases}; {len(keys)} objects: error max "
              f"{e[0]:.2f}% ({worst}) median {e[1]:.2f}%, {e[2]} above 1%, area-weighted {weighted:.2f}%; reference: median "
              f"standard error {noise:.3f}%, seeds differ by a median {pulls:.2f} of theirs "
              f"(0.67 if honest); the {len(sharp)} objects it knows within {SHARP:.2%}: {sharp_text}")


if __name__ == "__main__":
    main()

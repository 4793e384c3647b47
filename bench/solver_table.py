#!/usr/bin/env python3
"""The solver table of issue 20: every solver on every scene given (default: scenes/hard/*.obj
and the Cornell box), default options otherwise, one `radflux solve --report` each. Prints a
markdown table: iterations, outcome (converged or not, exit status), final residual, methods
used (a cg fallback shows as "cg>gauss_seidel"), solve seconds, energy balance.

    bench/solver_table.py build/ci/client/radflux [SCENE.obj ...] [--solvers auto,cg]
"""
import argparse
import glob
import json
import os
import subprocess
import tempfile

SOLVERS = ["auto", "jacobi", "gauss_seidel", "southwell", "cg", "direct"]


def run(radflux, scene, solver, extra):
    with tempfile.TemporaryDirectory() as tmp:
        report = os.path.join(tmp, "r.json")
        cmd = [radflux, "solve", scene, "--solver", solver, "--report", report, "-q"] + extra
        proc = subprocess.run(cmd, capture_output=True, text=True)
        if not os.path.exists(report):
            return {"exit": proc.returncode, "error": proc.stderr.strip().splitlines()[-1:]}
        r = json.load(open(report))
    s = r["solve"]
    used = r.get("solver", {}).get("used", [s["method"]])
    e = r["energy_balance"]
    return {
        "exit": proc.returncode,
        "patches": r["mesh"]["patches"],
        "iterations": s["iterations"],
        "converged": s["converged"],
        "residual": s["residual"],
        "used": ">".join(used),
        "solve_s": r["seconds"]["solve"],
        "balance": "%s %.2f%%" % ("ok" if e.get("ok") else "NOT ok",
                                  100 * e.get("relative_imbalance", float("nan"))),
    }


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("radflux")
    ap.add_argument("scenes", nargs="*")
    ap.add_argument("--solvers", default=",".join(SOLVERS))
    ap.add_argument("--extra", default="", help="more solve options, e.g. '--rays 16'")
    args = ap.parse_args()
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    scenes = args.scenes or sorted(glob.glob(os.path.join(root, "scenes/hard/*.obj"))) + [
        os.path.join(root, "scenes/cornell_box.obj")]
    print("| scene | patches | solver | used | iterations | outcome | exit | residual | solve s "
          "| energy balance |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for scene in scenes:
        for solver in args.solvers.split(","):
            r = run(args.radflux, scene, solver, args.extra.split())
            name = os.path.basename(scene)
            if "error" in r:
                print("| %s | | %s | | | refused | %d | | | %s |" % (name, solver, r["exit"],
                                                                    " ".join(r["error"])))
                continue
            print("| %s | %d | %s | %s | %d | %s | %d | %.2e | %.3f | %s |" % (
                name, r["patches"], solver, r["used"], r["iterations"],
                "converged" if r["converged"] else "NOT converged", r["exit"], r["residual"],
                r["solve_s"], r["balance"]))


if __name__ == "__main__":
    main()

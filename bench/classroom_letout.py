#!/usr/bin/python3
"""How much of their light RenderPark's classroom fixtures let into the room (issue 21).

Usage: classroom_letout.py RADFLUX_LOCAL [SEED ...] [-- FLAGS...]

The classroom (../shared/scenes/renderpark/salon/classroom.mgf) is rewritten with every
material's rd set to 0 but the tubes' (tllamp, rd 0.5) and the housings' (lampbakgrijs, rd 0.8):
the room absorbs whatever leaves a fixture. radflux solves it at its defaults (or FLAGS) per
seed; from its --patch-values the light the tubes and housings absorb is A (B - E) (1 - rho) /
rho per patch, and the let-out share is 1 - (absorbed by the fixtures + escaped) / emitted
(band 0). Particle tracing of one fixture (bench/light_losses) and radflux on one fixture at
--max-edge 0.003 both give 0.682, and the tubes absorb 0.137 of the emitted light.
"""
import csv
import json
import os
import subprocess
import sys
import tempfile

KEEP = {"tllamp": 0.5, "lampbakgrijs": 0.8}  # the fixtures' materials and their rd
SCENE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "shared", "scenes",
                     "renderpark", "salon", "classroom.mgf")


def black_room(src, dst):
    """Writes src with every rd but KEEP's set to 0; returns {object: material}."""
    material, objects, out = None, {}, []
    current = None
    for line in open(src):
        token = line.split()
        if token[:1] == ["o"] and len(token) >= 2:
            current = token[1]
        if token[:1] == ["m"] and len(token) >= 2:
            material = token[1]
            if current and current not in objects:
                objects[current] = material
        if token[:1] == ["rd"] and material not in KEEP:
            line = "\trd 0.000000\n"
        out.append(line)
    with open(dst, "w") as f:
        f.write("".join(out))
    return objects


def let_out(radflux, scene, objects, seed, flags, work):
    values, report = os.path.join(work, "v.csv"), os.path.join(work, "r.json")
    subprocess.run([radflux, "solve", scene, "-q", "--seed", str(seed), "--patch-values", values,
                    "--report", report] + flags, check=True, env=dict(os.environ,
                   OMP_WAIT_POLICY="passive"))
    balance = json.load(open(report))["energy_balance"]
    rows = list(csv.DictReader(open(values)))
    emitted = balance["emitted"][0]
    tube_area = sum(float(r["area"]) for r in rows if objects.get(r["object"]) == "tllamp")
    e = emitted / tube_area  # the tubes' E (they are the only emitters)
    absorbed = {m: 0.0 for m in KEEP}
    for r in rows:
        m = objects.get(r["object"])
        if m in KEEP:
            b = float(r["r"]) - (e if m == "tllamp" else 0)
            absorbed[m] += float(r["area"]) * b * (1 - KEEP[m]) / KEEP[m]
    out = 1 - (sum(absorbed.values()) + balance["escaped"][0]) / emitted
    return out, absorbed["tllamp"] / emitted, absorbed["lampbakgrijs"] / emitted


def main():
    args = sys.argv[1:]
    flags = args[args.index("--") + 1:] if "--" in args else []
    args = args[:args.index("--")] if "--" in args else args
    if not args:
        sys.exit(__doc__)
    seeds = [int(s) for s in args[1:]] or [1, 2, 3]
    with tempfile.TemporaryDirectory() as work:
        scene = os.path.join(work, "black_room.mgf")
        objects = black_room(SCENE, scene)
        for seed in seeds:
            out, tubes, housings = let_out(args[0], scene, objects, seed, flags, work)
            print(f"seed {seed}: let out {out:.4f} (truth 0.682), tubes absorb {tubes:.4f} "
                  f"(0.137), housings {housings:.4f}")


if __name__ == "__main__":
    main()

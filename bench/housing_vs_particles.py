#!/usr/bin/python3
"""How much of a lamp's light its housing keeps: radflux against particle tracing (issue 21).

Usage: housing_vs_particles.py --radflux RADFLUX_LOCAL --particles LIGHT_LOSSES
                               [--seeds 1,2] [--tolerance 0.05] [--keep DIR]

The scene is RenderPark's classroom fixture rebuilt by hand (solver/formfactor/near_field_cuts.h): a
two-sided 1.3 m x 4 cm tube 1.8 cm under the top of a trough (8 cm top, sides sloping out to a
20 cm opening 8 cm lower) made of two two-sided shells 2 mm apart, rd 0.8, in a 10 x 7 x 3.5 m
room of 25 cm one-sided tiles that face out: whatever leaves the fixture meets a tile's back
and is lost, so the room only makes the faces many enough to be grouped as the classroom's are
(a* = room area / 2,000, ~0.13 m^2, the housing's faces smaller). The share of the emitted
power the fixture absorbs (tube and housing) is radflux's energy_balance.absorbed / emitted at
its defaults (band 0), against 1 - lost from bench/light_losses (particles from the tube, no
radiosity machinery). Exits 1 when a seed's share is off by more than --tolerance (relative).
Before near-field steps radflux kept 0.285-0.294 against the particles' 0.316.
"""
import json
import os
import subprocess
import sys
import tempfile

ROOM = (10.0, 7.0, 3.5)
TILE = 0.25


class Mgf:
    def __init__(self):
        self.lines, self.count = [], 0

    def face(self, points):
        names = []
        for p in points:
            names.append(f"p{self.count}")
            self.lines.append(f"v p{self.count} =\n\tp {p[0]:.6f} {p[1]:.6f} {p[2]:.6f}")
            self.count += 1
        self.lines.append("f " + " ".join(names))


def trough(mgf, inset):
    """One shell of the trough along y in [inset, 1.4 - inset], its walls moved in by inset."""
    x0, y0, y1 = 5.0, 3.0 + inset, 4.4 - inset
    top, bottom = 3.48 - inset, 3.40
    t, b = 0.04, 0.10 - inset  # half widths of the top and of the opening
    mgf.face([(x0 - t, y0, top), (x0 + t, y0, top), (x0 + t, y1, top), (x0 - t, y1, top)])
    mgf.face([(x0 - b, y0, bottom), (x0 - t, y0, top), (x0 - t, y1, top), (x0 - b, y1, bottom)])
    mgf.face([(x0 + t, y0, top), (x0 + b, y0, bottom), (x0 + b, y1, bottom), (x0 + t, y1, top)])
    for y in (y0, y1):
        mgf.face([(x0 - b, y, bottom), (x0 + b, y, bottom), (x0 + t, y, top), (x0 - t, y, top)])


def scene_text():
    mgf = Mgf()
    mgf.lines += ["o tube", "m tube =", "\tc", "\trd 0.5", "\tc", "\ted 100"]
    mgf.face([(4.98, 3.05, 3.46), (5.02, 3.05, 3.46), (5.02, 4.35, 3.46), (4.98, 4.35, 3.46)])
    mgf.lines += ["o", "o housing", "m housing =", "\tc", "\trd 0.8"]
    trough(mgf, 0.0)
    trough(mgf, 0.002)
    mgf.lines += ["o", "o room", "m tile =", "\tc", "\trd 0.5", "\tsides 1"]
    X, Y, Z = ROOM
    nx, ny, nz = round(X / TILE), round(Y / TILE), round(Z / TILE)

    def wall(origin, du, dv, nu, nv):  # tiles facing du x dv (out of the room)
        for i in range(nu):
            for j in range(nv):
                corner = [origin[k] + du[k] * i + dv[k] * j for k in range(3)]
                mgf.face([corner, [corner[k] + du[k] for k in range(3)],
                          [corner[k] + du[k] + dv[k] for k in range(3)],
                          [corner[k] + dv[k] for k in range(3)]])

    s = TILE
    wall((0, 0, 0), (0, s, 0), (s, 0, 0), ny, nx)
    wall((0, 0, Z), (s, 0, 0), (0, s, 0), nx, ny)
    wall((0, 0, 0), (s, 0, 0), (0, 0, s), nx, nz)
    wall((0, Y, 0), (0, 0, s), (s, 0, 0), nz, nx)
    wall((0, 0, 0), (0, 0, s), (0, s, 0), nz, ny)
    wall((X, 0, 0), (0, s, 0), (0, 0, s), ny, nz)
    mgf.lines.append("o")
    return "\n".join(mgf.lines) + "\n"


def main():
    args = dict(zip(sys.argv[1::2], sys.argv[2::2]))
    if "--radflux" not in args or "--particles" not in args:
        raise SystemExit(__doc__)
    seeds = [int(s) for s in args.get("--seeds", "1,2").split(",")]
    tolerance = float(args.get("--tolerance", "0.05"))
    env = dict(os.environ, OMP_WAIT_POLICY="passive")
    with tempfile.TemporaryDirectory() as tmp:
        folder = args.get("--keep", tmp)
        path = os.path.join(folder, "housing.mgf")
        with open(path, "w") as f:
            f.write(scene_text())
        lost = subprocess.run([args["--particles"], path, "2000000", "1"], env=env, check=True,
                              capture_output=True, text=True).stdout.splitlines()
        truth = 1 - float(lost[1].split(",")[1])  # band 0
        print(f"particles: the fixture absorbs {truth:.4f} of the emitted power")
        failed = False
        for seed in seeds:
            report = os.path.join(folder, f"r{seed}.json")
            subprocess.run([args["--radflux"], "solve", path, "-q", "--seed", str(seed),
                            "--report", report], env=env, check=True)
            with open(report) as f:
                balance = json.load(f)["energy_balance"]
            share = balance["absorbed"][0] / balance["emitted"][0]
            off = share / truth - 1
            failed |= abs(off) > tolerance
            print(f"radflux seed {seed}: {share:.4f} ({100 * off:+.1f}%)")
    if failed:
        print(f"FAIL: radflux off by more than {100 * tolerance:.0f}%")
        sys.exit(1)


if __name__ == "__main__":
    main()

#!/usr/bin/python3
"""Closed-form checks of bench/object_reference (issue 21): a closed unit cube, rho = 0.5
everywhere, seen from inside.

Usage: bench/object_reference_check.py [--binary build/ci/bench/object_reference]
(ctest object_reference_closed_box runs it)

1. Every wall emits E = pi: every wall's B is E / (1 - rho) = 2 pi.
2. Only the floor emits E = pi: the walls differ, but in a closed box all light that leaves a
   wall lands on one, so sum of A B = A_floor E / (1 - rho) = 2 pi; and the four side walls
   agree with each other (symmetry).
3. A lamp (E = pi, rho 0) of 0.4 x 0.4 facing up, 2 cm under a grey square of the same size
   facing down (rho 0.5), nothing else: the square's B is rho E F, F of C-11 (the shadow
   rays from it to the lamp 2 cm away must not meet the lamp as their own blocker).
4. The same with the lamp half transparent (map_d: a grey texel of 128, opacity 128/255)
   and lit by --emit lamp=1,1,1 (no Ke): only its opaque part emits, so the square's B is
   3.'s times 128/255.
Each is asserted within 4 of the reference's own standard errors (plus 0.05% for what the
standard error of a stratified mean can miss); exit 1 and one line per failure otherwise.
"""
import csv
import io
import math
import os
import subprocess
import sys
import struct
import tempfile
import zlib

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
WALLS = {"floor": [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)],
         "ceiling": [(0, 0, 1), (0, 1, 1), (1, 1, 1), (1, 0, 1)],
         "south": [(0, 0, 0), (0, 0, 1), (1, 0, 1), (1, 0, 0)],
         "north": [(0, 1, 0), (1, 1, 0), (1, 1, 1), (0, 1, 1)],
         "west": [(0, 0, 0), (0, 1, 0), (0, 1, 1), (0, 0, 1)],
         "east": [(1, 0, 0), (1, 0, 1), (1, 1, 1), (1, 1, 0)]}


def box(directory, lit):
    """Writes the cube (faces facing inwards) with the walls in `lit` emitting; its path."""
    with open(os.path.join(directory, "box.mtl"), "w") as f:
        f.write("newmtl lit\nKd 0.5 0.5 0.5\nKe 1 1 1\nnewmtl wall\nKd 0.5 0.5 0.5\n")
    lines, first = ["mtllib box.mtl"], 1
    for name, quad in WALLS.items():
        lines += [f"o {name}", "usemtl " + ("lit" if name in lit else "wall")]
        lines += ["v %g %g %g" % v for v in quad] + [f"f {first} {first + 1} {first + 2} {first + 3}"]
        first += 4
    path = os.path.join(directory, "box.obj")
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")
    return path


def parallel_squares(a, c):
    """C-11: F between identical, directly opposed squares of side a at distance c."""
    x = a / c
    r = math.sqrt(1 + x * x)
    return 2 / (math.pi * x * x) * (math.log(r * r / math.sqrt(1 + 2 * x * x))
                                     + 2 * x * r * math.atan(x / r) - 2 * x * math.atan(x))


def grey_png(path, value):
    """Writes a 1 x 1 8-bit greyscale PNG of `value`."""
    def chunk(kind, data):
        return (struct.pack(">I", len(data)) + kind + data
                + struct.pack(">I", zlib.crc32(kind + data) & 0xffffffff))
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", 1, 1, 8, 0, 0, 0, 0))
                + chunk(b"IDAT", zlib.compress(bytes([0, value]))) + chunk(b"IEND", b""))


def lamp_under_square(directory, lamp="Ke 1 1 1"):
    """Writes the lamp 2 cm under a grey square (3. above), `lamp` its material's last line;
    its path."""
    with open(os.path.join(directory, "gap.mtl"), "w") as f:
        f.write(f"newmtl lamp\nKd 0 0 0\n{lamp}\nnewmtl grey\nKd 0.5 0.5 0.5\n")
    with open(os.path.join(directory, "gap.obj"), "w") as f:
        f.write("mtllib gap.mtl\no lamp\nusemtl lamp\nv 0 0 0\nv 0.4 0 0\nv 0.4 0.4 0\n"
                "v 0 0.4 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nf 1/1 2/2 3/3 4/4\no square\n"
                "usemtl grey\nv 0 0 0.02\nv 0 0.4 0.02\nv 0.4 0.4 0.02\nv 0.4 0 0.02\n"
                "f 5 6 7 8\n")
    return os.path.join(directory, "gap.obj")


def run(binary, path, flags=()):
    """Object -> (B, standard error) from object_reference at 65,536 paths an object."""
    out = subprocess.run([binary, *flags, path, "65536", "1",
                          "0.0005"], check=True, capture_output=True, text=True).stdout
    return {r["object"]: ((float(r["r"]) + float(r["g"]) + float(r["b"])) / 3, float(r["stderr"]))
            for r in csv.DictReader(io.StringIO(out))}


def check(what, got, want, se, failures):
    ok = abs(got - want) <= 4 * se + 5e-4 * abs(want)
    print(f"{what}: {got:.5f} against {want:.5f} (standard error {se:.5f}) {'ok' if ok else 'FAILED'}")
    if not ok:
        failures.append(what)


def main():
    binary = (sys.argv[sys.argv.index("--binary") + 1] if "--binary" in sys.argv
              else os.path.join(ROOT, "build", "ci", "bench", "object_reference"))
    failures = []
    with tempfile.TemporaryDirectory() as directory:
        every = run(binary, box(directory, set(WALLS)))
        for name, (b, se) in every.items():
            check(f"all walls emit, {name}", b, 2 * math.pi, se, failures)
        floor = run(binary, box(directory, {"floor"}))
        total = sum(b for b, _ in floor.values())
        check("floor emits, sum of A B", total, 2 * math.pi,
              math.sqrt(sum(se * se for _, se in floor.values())), failures)
        sides = [floor[k] for k in ("south", "north", "west", "east")]
        mean = sum(b for b, _ in sides) / 4
        for name, (b, se) in zip(("south", "north", "west", "east"), sides):
            check(f"floor emits, {name} wall against the side walls' mean", b, mean, se, failures)
        b, se = run(binary, lamp_under_square(directory))["square"]
        gap = 0.5 * math.pi * parallel_squares(0.4, 0.02)
        check("a square 2 cm above a lamp", b, gap, se, failures)
        grey_png(os.path.join(directory, "half.png"), 128)
        b, se = run(binary, lamp_under_square(directory, "map_d half.png"),
                    ("--emit", "lamp=1,1,1"))["square"]
        check("a square 2 cm above a half transparent lamp", b, gap * 128 / 255, se, failures)
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()

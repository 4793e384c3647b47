#!/usr/bin/python3
"""The contact line under the Cornell box's blocks, in radflux's or Cycles' picture.

Usage: contact_band.py IMAGE(.pfm|.npy) [--pos X,Y,Z --look X,Y,Z --fov DEG]

For each block's front bottom edge (the side facing the camera at -z), over the middle 80% of
its length: the floor's mean radiance (mean of the three bands) in bands 0-15, 15-30 and
30-60 mm in front of it, found by intersecting each pixel centre's ray with the floor plane
(y = 0) and leaving out pixels whose ray passes through a block first. Prints the 0-15 mm band
as a fraction of the visible floor's mean (outside the 0-15 mm bands) and of the 30-60 mm band
beside it: what tests/unit/output_contact_cornell_test.cc asserts. The default camera is
bench/cornell_vs_cycles.sh's (the box fitted in the picture from -z); the classic one is
--pos 278,273,-800 --look 278,273,0.
"""
import argparse

import numpy as np

from cornell_vs_cycles import read_pfm

# Footprints (x, z), counter-clockwise from above, and heights, from scenes/cornell_box.obj.
BLOCKS = {"short": ([(130, 65), (82, 225), (240, 272), (290, 114)], 165.0),
          "tall": ([(265, 296), (314, 456), (472, 406), (423, 247)], 330.0)}
FRONT_EDGES = {"short": ((130, 65), (290, 114)), "tall": ((265, 296), (423, 247))}
BANDS_MM = [(0, 15), (15, 30), (30, 60)]


def inside(poly, x, z):
    """Boolean array: (x, z) inside the convex counter-clockwise polygon."""
    ok = np.ones_like(x, dtype=bool)
    for (x1, z1), (x2, z2) in zip(poly, poly[1:] + poly[:1]):
        ok &= (x2 - x1) * (z - z1) - (z2 - z1) * (x - x1) <= 0
    return ok


def floor_points(shape, pos, look, fov):
    """Per pixel: the floor point (x, z) of the centre ray, and whether the floor is seen."""
    h, w = shape
    fwd = (look - pos) / np.linalg.norm(look - pos)
    right = np.cross(fwd, [0, 1, 0])
    right /= np.linalg.norm(right)
    up = np.cross(right, fwd)
    hh = np.tan(np.radians(fov / 2))
    ys, xs = np.mgrid[0:h, 0:w]
    sx, sy = (2 * (xs + 0.5) / w - 1) * hh * w / h, (1 - 2 * (ys + 0.5) / h) * hh
    d = fwd + right * sx[..., None] + up * sy[..., None]
    down = d[..., 1] < 0
    t = np.where(down, -pos[1] / np.where(down, d[..., 1], -1), 0)
    fx, fz = pos[0] + d[..., 0] * t, pos[2] + d[..., 2] * t
    seen = down & (fx > 0) & (fx < 549.6) & (fz > 0) & (fz < 559.2)
    for k in range(1, 120):  # blocked when a point on the ray is inside a block
        s = t * k / 120
        px, py, pz = (pos[i] + d[..., i] * s for i in range(3))
        for poly, height in BLOCKS.values():
            seen &= ~((py >= 0) & (py <= height) & inside(poly, px, pz))
    return fx, fz, seen


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("image")
    ap.add_argument("--pos", default="278,274.4,-778.4")
    ap.add_argument("--look", default="278,274.4,279.6")
    ap.add_argument("--fov", type=float, default=39.3077)
    a = ap.parse_args()
    img = np.load(a.image).astype(np.float64) if a.image.endswith(".npy") else read_pfm(a.image)
    pos, look = (np.array([float(v) for v in s.split(",")]) for s in (a.pos, a.look))
    fx, fz, seen = floor_points(img.shape[:2], pos, look, a.fov)
    v = img.mean(axis=2)
    contact = np.zeros_like(seen)
    means = {}
    for name, ((x1, z1), (x2, z2)) in FRONT_EDGES.items():
        e = np.array([x2 - x1, z2 - z1], dtype=float)
        length = np.hypot(*e)
        u = ((fx - x1) * e[0] + (fz - z1) * e[1]) / length ** 2
        n = np.array([e[1], -e[0]]) / length
        if n[1] > 0:
            n = -n  # towards the camera (-z)
        mm = (fx - x1) * n[0] + (fz - z1) * n[1]
        along = seen & (u >= 0.1) & (u <= 0.9)
        means[name] = [(v[along & (mm >= lo) & (mm <= hi)].mean(), int((along & (mm >= lo) & (mm <= hi)).sum()))
                       for lo, hi in BANDS_MM]
        contact |= along & (mm >= 0) & (mm <= 15)
    floor_mean = v[seen & ~contact].mean()
    print(f"{a.image}: floor mean {floor_mean:.4g} over {int((seen & ~contact).sum())} px")
    for name, bands in means.items():
        text = ", ".join(f"{lo}-{hi} mm {m:.4g} ({n} px)" for (lo, hi), (m, n) in zip(BANDS_MM, bands))
        print(f"  {name} block: {text}; 0-15 mm = {100 * bands[0][0] / floor_mean:.1f}% of the "
              f"floor's mean, {bands[0][0] / bands[2][0]:.2f} x the 30-60 mm band")


if __name__ == "__main__":
    main()

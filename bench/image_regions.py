#!/usr/bin/python3
"""Mean radiance of image regions of a radflux picture against Cycles (issue 21).

Usage: image_regions.py [--view conference|classroom] RADFLUX.pfm CYCLES_SEED1.npy [CYCLES_SEED2.npy ...]

Both pictures are from the same camera (--view conference, the default: issue 21's
--camera-pos 1550,400,-300 --camera-look-at 0,200,-200 --camera-up 0,1,0 --fov-deg 60;
--view classroom: bench/classroom_vs_cycles.sh's); Cycles at --size 160x120 by
../shared/tools/cycles_reference.py. In the classroom the lamps in view (pixels Cycles shows
above 5 times the picture's median) are left out of every region: they are the emitters' own E. A radflux picture n times that size in both directions is
box-averaged down to it (n x n samples per pixel, as Cycles' box filter spans the pixel; at
n = 1 a pixel takes its centre, and a pixel across a thin bright edge, the screen's emitting
frame, reads the edge or the dark beside it, not their mix). For each region of the issue's table and band-mean
radiance: Cycles (the mean of the seeds), radflux, and radflux's relative difference; with two
or more seeds, the seeds' own spread (max relative difference of one seed from their mean).
"""
import sys

import numpy as np

from cornell_vs_cycles import box_down, read_pfm

# view: name: (first row, last row + 1, first column, last column + 1) of the 160x120 picture
REGIONS = {"conference": {
    "ceiling band (rows 0-29)": (0, 30, 0, 160),
    "floor band (rows 90-119)": (90, 120, 0, 160),
    "back wall (rows 40-79, columns 60-99)": (40, 80, 60, 100),
    "left wall (rows 40-79, columns 0-19)": (40, 80, 0, 20),
    "whole image": (0, 120, 0, 160),
}, "classroom": {
    "ceiling band (rows 0-29)": (0, 30, 0, 160),
    "wall x = 7 (rows 40-99, columns 0-14)": (40, 100, 0, 15),
    "back wall y = 0 (rows 40-61, columns 25-69)": (40, 62, 25, 70),
    "wall x = 0 (rows 40-79, columns 110-159)": (40, 80, 110, 160),
    "desks and floor (rows 80-119)": (80, 120, 0, 160),
    "whole image": (0, 120, 0, 160),
}}
MASK_LAMPS = {"classroom"}


def region_mean(image, box, keep):
    r0, r1, c0, c1 = box
    return float(image[r0:r1, c0:c1, :].mean(axis=2)[keep[r0:r1, c0:c1]].mean())


def main():
    args = sys.argv[1:]
    view = "conference"
    if args[:1] == ["--view"]:
        view, args = args[1], args[2:]
    if len(args) < 2 or view not in REGIONS:
        raise SystemExit(__doc__)
    seeds = [np.load(p).astype(np.float64) for p in args[1:]]
    radflux = box_down(read_pfm(args[0]), seeds[0].shape)
    luminance = sum(seeds).mean(axis=2) / len(seeds)
    keep = (luminance < 5 * np.median(luminance) if view in MASK_LAMPS
            else np.ones(luminance.shape, dtype=bool))
    for s in seeds:
        if s.shape != radflux.shape:
            raise SystemExit(f"shapes differ: radflux {radflux.shape}, cycles {s.shape}")
    print(f"{'region':44s} {'cycles':>10s} {'radflux':>10s} {'diff':>8s} {'seeds':>7s}")
    for name, box in REGIONS[view].items():
        per_seed = [region_mean(s, box, keep) for s in seeds]
        ref = sum(per_seed) / len(per_seed)
        spread = max(abs(v - ref) / ref for v in per_seed) if len(seeds) > 1 else float("nan")
        ours = region_mean(radflux, box, keep)
        print(f"{name:44s} {ref:10.4f} {ours:10.4f} {100 * (ours / ref - 1):+7.2f}% "
              f"{100 * spread:6.2f}%")


if __name__ == "__main__":
    main()

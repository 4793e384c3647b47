#!/usr/bin/python3
"""Mean radiance of image regions of radflux's conference-room picture against Cycles (issue 21).

Usage: conference_regions.py RADFLUX.pfm CYCLES_SEED1.npy [CYCLES_SEED2.npy ...]

Both pictures are from the same camera (issue 21: --camera-pos 1550,400,-300
--camera-look-at 0,200,-200 --camera-up 0,1,0 --fov-deg 60; Cycles at --size 160x120 by
../shared/tools/cycles_reference.py). A radflux picture n times that size in both directions is
box-averaged down to it (n x n samples per pixel, as Cycles' box filter spans the pixel; at
n = 1 a pixel takes its centre, and a pixel across a thin bright edge, the screen's emitting
frame, reads the edge or the dark beside it, not their mix). For each region of the issue's table and band-mean
radiance: Cycles (the mean of the seeds), radflux, and radflux's relative difference; with two
or more seeds, the seeds' own spread (max relative difference of one seed from their mean).
"""
import sys

import numpy as np

from cornell_vs_cycles import box_down, read_pfm

# name: (first row, last row + 1, first column, last column + 1) of the 160x120 picture
REGIONS = {
    "ceiling band (rows 0-29)": (0, 30, 0, 160),
    "floor band (rows 90-119)": (90, 120, 0, 160),
    "back wall (rows 40-79, columns 60-99)": (40, 80, 60, 100),
    "left wall (rows 40-79, columns 0-19)": (40, 80, 0, 20),
    "whole image": (0, 120, 0, 160),
}


def region_mean(image, box):
    r0, r1, c0, c1 = box
    return float(image[r0:r1, c0:c1, :].mean())


def main():
    if len(sys.argv) < 3:
        raise SystemExit(__doc__)
    seeds = [np.load(p).astype(np.float64) for p in sys.argv[2:]]
    radflux = box_down(read_pfm(sys.argv[1]), seeds[0].shape)
    for s in seeds:
        if s.shape != radflux.shape:
            raise SystemExit(f"shapes differ: radflux {radflux.shape}, cycles {s.shape}")
    print(f"{'region':40s} {'cycles':>10s} {'radflux':>10s} {'diff':>8s} {'seeds':>7s}")
    for name, box in REGIONS.items():
        per_seed = [region_mean(s, box) for s in seeds]
        ref = sum(per_seed) / len(per_seed)
        spread = max(abs(v - ref) / ref for v in per_seed) if len(seeds) > 1 else float("nan")
        ours = region_mean(radflux, box)
        print(f"{name:40s} {ref:10.4f} {ours:10.4f} {100 * (ours / ref - 1):+7.2f}% "
              f"{100 * spread:6.2f}%")


if __name__ == "__main__":
    main()

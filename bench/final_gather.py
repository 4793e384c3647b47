#!/usr/bin/python3
"""Block error of a final-gathered picture against a path-traced reference.

Usage: final_gather.py RADFLUX.pfm REPORT.json REF_SEED1.npy REF_SEED2.npy [--block 4] [--tol 0.03]
                      [--png PREFIX]

The picture and the reference (two Cycles renders with different seeds, n1 and n2 samples per
pixel read from the .json beside each .npy, linear radiance, row 0 = top, combined as their
sample-weighted mean) are cut into BLOCK x BLOCK pixel blocks (16 pixels at the default). A
block's error is |mean radflux - mean reference| / mean reference of the sum over the three
bands; blocks the reference sees as black (below 1e-3 of the image's mean: outside the box)
are left out and counted. Prints the fraction of blocks within TOL and the error percentiles;
the reference's own noise per block (sigma of the combined reference, from the two renders'
difference: sigma = |h1 - h2| sqrt(n1 n2) / (n1 + n2), as a fraction, its RMS over blocks);
the fraction within TOL against each render alone and against their mean (n1, n2 and n1 + n2
samples), and its straight-line fit in 1/n taken to n = 16,384 (the goal's reference: noise in
the reference only spreads the errors, so the fraction rises as 1/n falls); and the final
gather's and the solve's seconds from REPORT. With --png, writes PREFIX_radflux.png and
PREFIX_reference.png: both pictures at the same exposure (the reference's 95th-percentile
pixel value, over the three bands, is white), sRGB, clipped.
"""
import json
import sys

import numpy as np

from cornell_vs_cycles import read_pfm
from pictures_vs_reference import write_png


def block_means(image, block):
    h, w = image.shape[0] // block * block, image.shape[1] // block * block
    s = image[:h, :w].sum(axis=2)
    return s.reshape(h // block, block, w // block, block).mean(axis=(1, 3))


def errors(test, ref, keep):
    return np.abs(test[keep] - ref[keep]) / ref[keep]


def fraction_at_16k(test, halves, weights, keep, block, tol):
    """Fraction of blocks within tol against references of n samples, n in weights and their
    sum, and its linear fit in 1/n evaluated at 16,384 samples."""
    refs = {n: block_means(h, block) for n, h in zip(weights, halves)}
    refs[sum(weights)] = (weights[0] * refs[weights[0]] + weights[1] * refs[weights[1]]) / sum(weights)
    within = {n: np.mean(errors(test, r, keep) <= tol) for n, r in refs.items()}
    slope, at_infinity = np.polyfit([1 / n for n in within], list(within.values()), 1)
    return within, slope / 16384 + at_infinity


def summary(name, e, tol):
    p = np.percentile(e, [50, 90, 99])
    print(f"{name}: {np.mean(e <= tol) * 100:.1f}% of {e.size} blocks within {tol * 100:g}%; "
          f"error median {p[0] * 100:.2f}%, 90th {p[1] * 100:.2f}%, 99th {p[2] * 100:.2f}%")


def write_pngs(prefix, radflux, ref):
    """The two pictures, one exposure (see the docstring)."""
    white = np.percentile(ref, 95)
    for name, image in (("radflux", radflux), ("reference", ref)):
        write_png(f"{prefix}_{name}.png", image, white)
    print(f"wrote {prefix}_radflux.png and {prefix}_reference.png (white = {white:.4g})")


def main():
    args = sys.argv[1:]
    opts = {"--block": "4", "--tol": "0.03", "--png": ""}
    for k in list(opts):
        if k in args:
            i = args.index(k)
            opts[k] = args[i + 1]
            del args[i:i + 2]
    if len(args) != 4:
        raise SystemExit(__doc__)
    block, tol = int(opts["--block"]), float(opts["--tol"])
    radflux = read_pfm(args[0])
    halves = [np.load(p).astype(np.float64) for p in args[2:4]]
    n1, n2 = (json.load(open(p[:-len(".npy")] + ".json"))["opts"]["samples"] for p in args[2:4])
    n1, n2 = int(n1), int(n2)
    ref = (n1 * halves[0] + n2 * halves[1]) / (n1 + n2)
    if radflux.shape != ref.shape:
        raise SystemExit(f"picture {radflux.shape} and reference {ref.shape} differ in size")
    r, t = block_means(ref, block), block_means(radflux, block)
    h1, h2 = block_means(halves[0], block), block_means(halves[1], block)
    keep = r > 1e-3 * r.mean()
    print(f"{block}x{block}-pixel blocks: {keep.sum()} lit, {(~keep).sum()} black in the reference")
    summary("radflux vs reference", errors(t, r, keep), tol)
    sigma = errors(h1, h2, keep) * np.sqrt(n1 * n2) / (n1 + n2)
    print(f"reference: {n1} + {n2} samples per pixel; its own noise per block (sigma) RMS "
          f"{np.sqrt(np.mean(sigma ** 2)) * 100:.2f}%, 90th percentile "
          f"{np.percentile(sigma, 90) * 100:.2f}%")
    within, at_16k = fraction_at_16k(t, halves, (n1, n2), keep, block, tol)
    print("within " + ", ".join(f"{v * 100:.2f}% at {n} spp" for n, v in within.items()) +
          f" of the reference; fit in 1/n at 16384 spp: {at_16k * 100:.2f}%")
    if opts["--png"]:
        write_pngs(opts["--png"], radflux, ref)
    seconds = json.load(open(args[1]))["seconds"]
    print(f"final gather {seconds.get('gather', 0):.3f} s; rows {seconds['rows']:.3f} s, "
          f"solve {seconds['solve']:.3f} s")


if __name__ == "__main__":
    main()

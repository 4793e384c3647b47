#!/usr/bin/python3
"""radflux's pictures beside a Cycles reference, at one exposure, as PNGs for bench/RESULTS.md.

Usage: pictures_vs_reference.py OUT_PREFIX REFERENCE.npy NAME=RADFLUX.pfm [NAME=RADFLUX.pfm ...]

Each radflux picture is box-averaged down to the reference's size (cornell_vs_cycles.box_down);
every picture, the reference included, is written as OUT_PREFIX_NAME.png (the reference as
OUT_PREFIX_cycles.png) with the reference's 95th percentile white and the sRGB curve, so that
the pictures compare as they are.
"""
import sys

import numpy as np

from cornell_vs_cycles import box_down, read_pfm


def write_png(path, image, white):
    """Linear radiance `image` as an 8-bit sRGB PNG with `white` as 1."""
    from PIL import Image
    x = np.clip(image / white, 0, 1)
    srgb = np.where(x <= 0.0031308, 12.92 * x, 1.055 * x ** (1 / 2.4) - 0.055)
    Image.fromarray(np.round(srgb * 255).astype(np.uint8)).save(path)


def main():
    if len(sys.argv) < 4 or any("=" not in a for a in sys.argv[3:]):
        sys.exit(__doc__)
    prefix, ref = sys.argv[1], np.load(sys.argv[2])
    white = np.percentile(ref, 95)
    write_png(f"{prefix}_cycles.png", ref, white)
    for arg in sys.argv[3:]:
        name, path = arg.split("=", 1)
        write_png(f"{prefix}_{name}.png", box_down(read_pfm(path), ref.shape), white)
    print(f"wrote {prefix}_*.png (white = {white:.4g})")


if __name__ == "__main__":
    main()

#!/usr/bin/python3
"""Per-surface mean radiance of radflux's Cornell box picture against Cycles.

Usage: cornell_vs_cycles.py MASK.pfm RADFLUX.pfm CYCLES_SEED1.npy CYCLES_SEED2.npy [--json OUT]

MASK.pfm is radflux's render of the flat-coded scene (every object emits radiance k, k = 1, 2,
... in the order of CODES, and reflects nothing): a pixel belongs to object k when all three
bands equal k to 1e-4 and so do its 8 neighbours (one pixel of erosion, so that no pixel
straddles an edge in either renderer: Cycles' box filter spans the pixel, radflux takes its
centre). For each surface and band: the mean radiance over its pixels in Cycles (the mean of the
two seeds) and in radflux, and the relative difference; the two seeds' difference measures the
reference's own noise. Prints a table and the RMS over (surface, band) and the worst, excluding
the emitter (its radiance is its Ke in both, plus a little reflected light).
"""
import json
import sys

import numpy as np

CODES = ["floor", "ceiling", "back_wall", "red_wall", "green_wall", "light", "short_block",
         "tall_block"]
EMITTERS = {"light"}
BANDS = "RGB"


def read_pfm(path):
    """Colour PFM as float HxWx3, row 0 = top (PFM stores bottom row first)."""
    with open(path, "rb") as f:
        if f.readline().strip() != b"PF":
            raise SystemExit(f"{path}: not a colour PFM")
        w, h = (int(v) for v in f.readline().split())
        scale = float(f.readline())
        data = np.frombuffer(f.read(), dtype="<f4" if scale < 0 else ">f4")
    return data.reshape(h, w, 3)[::-1].astype(np.float64)


def masks(code_image):
    """Object name -> boolean mask of its interior pixels."""
    out = {}
    for k, name in enumerate(CODES, start=1):
        exact = np.all(np.abs(code_image - k) < 1e-4, axis=2)
        eroded = exact.copy()
        eroded[0, :] = eroded[-1, :] = eroded[:, 0] = eroded[:, -1] = False
        for dy in (-1, 0, 1):
            for dx in (-1, 0, 1):
                eroded &= np.roll(np.roll(exact, dy, axis=0), dx, axis=1)
        out[name] = eroded
    return out


def main():
    args = sys.argv[1:]
    json_out = None
    if "--json" in args:
        i = args.index("--json")
        json_out = args[i + 1]
        del args[i:i + 2]
    if len(args) != 4:
        raise SystemExit(__doc__)
    code, radflux = read_pfm(args[0]), read_pfm(args[1])
    seed1, seed2 = (np.load(p).astype(np.float64) for p in args[2:4])
    if not (code.shape == radflux.shape == seed1.shape == seed2.shape):
        raise SystemExit(f"image sizes differ: {code.shape} {radflux.shape} {seed1.shape} "
                         f"{seed2.shape}")
    cycles = (seed1 + seed2) / 2
    rows, errors, seed_errors = [], [], []
    print(f"{'surface':12s} band  pixels   cycles    radflux   diff%   seeds%")
    for name, m in masks(code).items():
        if m.sum() == 0:
            raise SystemExit(f"{name}: no pixels in the mask (camera or scene changed?)")
        for b, band in enumerate(BANDS):
            ref = cycles[m, b].mean()
            got = radflux[m, b].mean()
            diff = 100 * (got / ref - 1)
            seeds = 100 * (seed1[m, b].mean() / seed2[m, b].mean() - 1)
            print(f"{name:12s} {band}  {int(m.sum()):7d} {ref:9.4f} {got:9.4f} {diff:+7.3f} "
                  f"{seeds:+7.3f}")
            rows.append({"surface": name, "band": band, "pixels": int(m.sum()), "cycles": ref,
                         "radflux": got, "diff_percent": diff, "seed_diff_percent": seeds})
            if name not in EMITTERS:
                errors.append(diff)
                seed_errors.append(seeds)
    errors, seed_errors = np.array(errors), np.array(seed_errors)
    worst = rows[[i for i, r in enumerate(rows) if r["surface"] not in EMITTERS][
        int(np.argmax(np.abs(errors)))]]
    rms = float(np.sqrt(np.mean(errors ** 2)))
    seed_rms = float(np.sqrt(np.mean(seed_errors ** 2)))
    print(f"RMS over {len(errors)} (surface, band), emitter excluded: {rms:.3f}%; worst "
          f"{worst['surface']} {worst['band']} {worst['diff_percent']:+.3f}%; "
          f"Cycles seed 1 vs 2: RMS {seed_rms:.3f}% (the mean of both: half the variance)")
    if json_out:
        with open(json_out, "w") as f:
            json.dump({"rms_percent": rms, "worst": worst, "seed_rms_percent": seed_rms,
                       "rows": rows}, f, indent=1)


if __name__ == "__main__":
    main()

#!/usr/bin/python3
"""Per-surface mean radiance of radflux's Cornell box pictures against Cycles.

Usage: cornell_vs_cycles.py MASK.pfm CYCLES_SEED1.npy CYCLES_SEED2.npy RADFLUX.pfm... [--json OUT]

MASK.pfm is radflux's render of the flat-coded scene (every object emits radiance k, k = 1, 2,
... in the order of CODES, and reflects nothing): a pixel belongs to object k when all three
bands equal k to 1e-4 and so do its 8 neighbours (one pixel of erosion, so that no pixel
straddles an edge in either renderer: Cycles' box filter spans the pixel, radflux takes its
centre). For each surface and band: the mean radiance over its pixels in Cycles (the mean of the
two seeds) and in radflux, and the relative difference; the two seeds' difference measures the
reference's own noise. The RMS and the worst exclude the emitter (its radiance is its Ke in
both, plus a little reflected light).

With one RADFLUX picture: that run's table, RMS and worst. With several (one per radflux
--seed): per (surface, band) the mean difference over the runs (the bias) and their standard
deviation (the run-to-run noise); the RMS and worst of the mean differences; and each run's own
RMS, with their mean, minimum and maximum (what a single run scores).

A RADFLUX picture n times the mask's size in both directions (same camera) is box-averaged down
to it: n x n samples per pixel, as Cycles' box filter (a pixel straddling an edge inside one
object, e.g. a block's front and side faces, is not eroded by the mask and must mean the same).
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


def box_down(image, shape):
    """image averaged over n x n blocks down to shape (h, w, 3); n must be a whole number."""
    n = image.shape[0] // shape[0]
    if n < 1 or image.shape != (shape[0] * n, shape[1] * n, shape[2]):
        raise SystemExit(f"picture {image.shape} is not a whole multiple of the mask {shape}")
    return image.reshape(shape[0], n, shape[1], n, shape[2]).mean(axis=(1, 3))


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


def compare(m, radflux, cycles):
    """Per band: percent difference of radflux's mean over mask m from Cycles'."""
    return [100 * (radflux[m, b].mean() / cycles[m, b].mean() - 1) for b in range(len(BANDS))]


def main():
    args = sys.argv[1:]
    json_out = None
    if "--json" in args:
        i = args.index("--json")
        json_out = args[i + 1]
        del args[i:i + 2]
    if len(args) < 4:
        raise SystemExit(__doc__)
    code = read_pfm(args[0])
    seed1, seed2 = (np.load(p).astype(np.float64) for p in args[1:3])
    runs = [box_down(read_pfm(p), code.shape) for p in args[3:]]
    if any(im.shape != code.shape for im in [seed1, seed2] + runs):
        raise SystemExit(f"image sizes differ: {[im.shape for im in [code, seed1, seed2] + runs]}")
    cycles = (seed1 + seed2) / 2
    rows, kept = [], []
    many = len(runs) > 1
    print(f"{'surface':12s} band  pixels   cycles    radflux   diff%   " +
          ("sd%     " if many else "") + "seeds%")
    for name, m in masks(code).items():
        if m.sum() == 0:
            raise SystemExit(f"{name}: no pixels in the mask (camera or scene changed?)")
        diffs = np.array([compare(m, r, cycles) for r in runs])  # runs x bands
        seeds = compare(m, seed1, seed2)
        for b, band in enumerate(BANDS):
            ref = cycles[m, b].mean()
            got = float(np.mean([r[m, b].mean() for r in runs]))
            diff, sd = float(diffs[:, b].mean()), float(diffs[:, b].std(ddof=1)) if many else 0.0
            print(f"{name:12s} {band}  {int(m.sum()):7d} {ref:9.4f} {got:9.4f} {diff:+7.3f} " +
                  (f"{sd:7.3f} " if many else "") + f"{seeds[b]:+7.3f}")
            rows.append({"surface": name, "band": band, "pixels": int(m.sum()), "cycles": ref,
                         "radflux": got, "diff_percent": diff, "run_sd_percent": sd,
                         "run_diff_percent": diffs[:, b].tolist(),
                         "seed_diff_percent": seeds[b]})
            if name not in EMITTERS:
                kept.append(len(rows) - 1)
    errors = np.array([rows[i]["diff_percent"] for i in kept])
    per_run = np.array([rows[i]["run_diff_percent"] for i in kept])  # (surface, band) x runs
    seed_errors = np.array([rows[i]["seed_diff_percent"] for i in kept])
    worst = rows[kept[int(np.argmax(np.abs(errors)))]]
    rms = float(np.sqrt(np.mean(errors ** 2)))
    run_rms = np.sqrt(np.mean(per_run ** 2, axis=0))
    seed_rms = float(np.sqrt(np.mean(seed_errors ** 2)))
    what = f"the mean over {len(runs)} runs" if many else "one run"
    print(f"RMS over {len(errors)} (surface, band), emitter excluded, {what}: {rms:.3f}%; worst "
          f"{worst['surface']} {worst['band']} {worst['diff_percent']:+.3f}%")
    if many:
        noise = float(np.sqrt(np.mean(per_run.std(axis=1, ddof=1) ** 2)))
        print(f"single runs: RMS mean {run_rms.mean():.3f}% (min {run_rms.min():.3f}, max "
              f"{run_rms.max():.3f}: {' '.join(f'{v:.2f}' for v in run_rms)}); run-to-run sd, "
              f"RMS over (surface, band): {noise:.3f}%")
    print(f"Cycles seed 1 vs 2: RMS {seed_rms:.3f}% (the mean of both: half the variance)")
    if json_out:
        with open(json_out, "w") as f:
            json.dump({"rms_percent": rms, "worst": worst, "runs": len(runs),
                       "run_rms_percent": run_rms.tolist(), "seed_rms_percent": seed_rms,
                       "rows": rows}, f, indent=1)


if __name__ == "__main__":
    main()

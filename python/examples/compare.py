"""Compare four samplers side by side: their points, expected power spectra and radial means.

    python python/examples/compare.py [--samplers random,jittered,pmj02bn,ccvt] [-n 1024]
                                      [--realizations 16] [--resolution 128] [--out FILE]

A tutorial in one file (no notebook): every number comes from ``strata``, the drawing from
matplotlib. Writes ``out/python-compare.png`` (or ``--out``) and prints the point-set measures.

How to read the picture (one column per sampler):

* top: the first realization's points, each in [0, 1)^2;
* middle: the expected periodogram ``E[P(u, v)]`` over the realizations, in dB, DC in the
  centre. White noise (``random``) is flat at 0 dB; a good sampler for rendering is dark
  (little power) in a disc around DC, since the variance of a Monte Carlo estimate is the
  integrand's spectrum weighted by this one;
* bottom: the radial mean of that spectrum against the frequency in units of ``sqrt(N)`` (the
  "Nyquist" of N points), with white noise's level 1 dashed, and the anisotropy in dB (10
  log10 of the ring's variance over its mean squared: ``-10 log10(R)`` for an isotropic
  pattern averaged over R realizations, higher where the pattern prefers directions).
"""

from __future__ import annotations

import argparse
import os
import time

import matplotlib

matplotlib.use("Agg")  # no display needed
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import strata_sampling as ss  # noqa: E402


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--samplers", default="random,jittered,pmj02bn,ccvt",
                    help="comma-separated sampler names (see ss.samplers())")
    ap.add_argument("-n", type=int, default=1024, help="points per set (default 1024)")
    ap.add_argument("--realizations", type=int, default=16,
                    help="sets per expected spectrum (default 16)")
    ap.add_argument("--resolution", type=int, default=128,
                    help="spectrum frequencies |u|, |v| <= K/2 (default K = 128)")
    ap.add_argument("--seed", type=int, default=1, help="seed of the first set (default 1)")
    ap.add_argument("--out", default=os.path.join("out", "python-compare.png"),
                    help="the PNG to write (default out/python-compare.png)")
    args = ap.parse_args()
    names = [s.strip() for s in args.samplers.split(",") if s.strip()]
    k = args.resolution

    info = {s["name"]: s for s in ss.samplers()}
    fig, axes = plt.subplots(3, len(names), figsize=(3.4 * len(names), 10.2),
                             gridspec_kw={"height_ratios": [1, 1, 0.8], "wspace": 0.12},
                             squeeze=False)
    print(f"{'sampler':<16} {'N':>6} {'min dist':>9} {'avg dist':>9} {'nu_eff':>7} {'time':>8}")
    for col, name in enumerate(names):
        n = ss.nearest_count(name, args.n)  # fixed-count samplers take some counts only
        t = time.perf_counter()
        # 1. the points of one set: an (n, 2) float32 array
        pts = ss.points(name, n, seed=args.seed)
        # 2. the expected spectrum over R sets (set r seeded by seed + r, made in parallel)
        spec = ss.sampler_spectrum(name, n, k, realizations=args.realizations,
                                       seed=args.seed)
        # 3. its radial mean and anisotropy, and the PSA point-set measures
        rad = ss.radial(spec)
        psa = ss.psa(pts)
        elapsed = time.perf_counter() - t
        print(f"{name:<16} {n:>6} {psa['global_min_distance']:>9.3f} "
              f"{psa['average_min_distance']:>9.3f} {psa['effective_nyquist'] or 0:>7.3f} "
              f"{elapsed:>7.2f}s")

        ax = axes[0, col]
        ax.scatter(pts[:, 0], pts[:, 1], s=1.5, c="black", linewidths=0)
        ax.set(xlim=(0, 1), ylim=(0, 1), aspect="equal", xticks=[], yticks=[])
        kind = "progressive" if info[name]["progressive"] else "fixed-count"
        ax.set_title(f"{name}\n{n} points, {kind}", fontsize=11)

        ax = axes[1, col]
        db = 10 * np.log10(np.maximum(spec, 1e-3))
        db[k // 2, k // 2] = np.nan  # DC is N: off the scale
        h = k // 2
        im = ax.imshow(db, origin="lower", cmap="magma", vmin=-15, vmax=8,
                       extent=(-h - 0.5, h + 0.5, -h - 0.5, h + 0.5))
        ax.set(xticks=[-h, 0, h], yticks=[-h, 0, h])
        ax.tick_params(labelsize=8)
        if col > 0:
            ax.set_yticklabels([])

        ax = axes[2, col]
        f = rad.frequency / np.sqrt(n)
        ax.plot(f, rad.power, color="C0", lw=1.2, label="radial mean")
        ax.axhline(1, color="gray", ls="--", lw=0.8)
        ax.set(xlim=(0, f.max()), ylim=(0, 2.8))
        ax.set_xlabel("frequency / sqrt(N)", fontsize=9)
        ax.tick_params(labelsize=8)
        ax2 = ax.twinx()
        ax2.plot(f, rad.anisotropy, color="C3", lw=0.8, alpha=0.7, label="anisotropy (right)")
        ax2.set_ylim(-30, 5)
        ax2.tick_params(labelsize=8, colors="C3")
        # one scale per row: labels on the outer panels only
        if col == 0:
            ax.set_ylabel("radial mean power (white noise = 1)", fontsize=9, color="C0")
            ax.legend(handles=ax.get_lines()[:1] + ax2.get_lines(), fontsize=8,
                      loc="upper left", frameon=False)
        else:
            ax.set_yticklabels([])
        if col == len(names) - 1:
            ax2.set_ylabel("anisotropy (dB)", fontsize=9, color="C3")
        else:
            ax2.set_yticklabels([])

    fig.colorbar(im, ax=axes[1, :].tolist(), shrink=0.85, pad=0.01,
                 label="expected power (dB; white noise = 0)")
    fig.suptitle(f"strata: points, expected power spectra over {args.realizations} sets "
                 f"(|u|, |v| <= {k // 2}), radial means", fontsize=13)
    os.makedirs(os.path.dirname(os.path.abspath(args.out)), exist_ok=True)
    fig.savefig(args.out, dpi=110, bbox_inches="tight")
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()

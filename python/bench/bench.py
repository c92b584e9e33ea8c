"""Benchmarks of strata against scipy.stats.qmc and numpy, row by row in one run.

    python python/bench/bench.py [--repeats R] [--markdown]

Each row times the same task both ways, alternating the two within every repeat, and reports
the medians (wall clock, ``time.perf_counter``) and the ratio. Both sides make the same
number of points of the same dimension; strata returns float32, scipy float64 (each library's
native type). A last column checks that the two did the same job (same discrepancy value, same
spectrum, as many Poisson-disk points at the same radius).

numpy's BLAS runs one thread unless ``OPENBLAS_NUM_THREADS`` (or ``OMP_NUM_THREADS``) is set:
on the 2-core machine of the README, numpy's direct DFT is fastest that way (about 125 ms,
against 200 to 380 ms with two threads, whose spinning second thread competes with everything
else). Set the variable to measure numpy's other configurations.
"""

from __future__ import annotations

import argparse
import os

if "OMP_NUM_THREADS" not in os.environ:  # before numpy loads its BLAS
    os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
    os.environ.setdefault("MKL_NUM_THREADS", "1")
import platform
import statistics
import time
from typing import Callable, List, Tuple

import numpy as np
import scipy
from scipy.stats import qmc

import strata_sampling as ss


def numpy_dft(points: np.ndarray, k: int) -> np.ndarray:
    """The periodogram on ``|u|, |v| <= k/2`` by a direct DFT in numpy: separable in ``u`` and
    ``v``, one complex matrix product (the fastest direct form in numpy)."""
    f = np.arange(-k // 2, k // 2 + 1)
    x = points.astype(np.float64)
    ex = np.exp(-2j * np.pi * np.outer(f, x[:, 0]))
    ey = np.exp(-2j * np.pi * np.outer(f, x[:, 1]))
    return np.abs(ey @ ex.T) ** 2 / len(x)


def timed(f: Callable[[], object]) -> Tuple[float, object]:
    t = time.perf_counter()
    out = f()
    return time.perf_counter() - t, out


def row(
    name: str,
    ours: Callable[[int], object],
    theirs: Callable[[int], object],
    repeats: int,
    check: Callable[[object, object], str],
) -> Tuple[str, float, float, str]:
    """Times ``ours(r)`` and ``theirs(r)`` alternately ``repeats`` times (``r`` the repeat,
    used as a seed), after one untimed warm-up of each."""
    a, b = ours(0), theirs(0)
    ta: List[float] = []
    tb: List[float] = []
    for r in range(1, repeats + 1):
        t, a = timed(lambda: ours(r))
        ta.append(t)
        t, b = timed(lambda: theirs(r))
        tb.append(t)
    return name, statistics.median(ta), statistics.median(tb), check(a, b)


def fmt(t: float) -> str:
    return f"{t * 1e3:.1f} ms" if t < 10 else f"{t:.1f} s"


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--repeats", type=int, default=7, help="repeats per row (default 7)")
    ap.add_argument(
        "--poisson-repeats", type=int, default=3,
        help="repeats of the Poisson-disk rows, where scipy takes seconds (default 3)",
    )
    ap.add_argument("--markdown", action="store_true", help="print a Markdown table")
    args = ap.parse_args()
    R, P = args.repeats, args.poisson_repeats

    def shape(a, b):
        return f"{np.shape(a)} vs {np.shape(b)}"

    rows = []
    rows.append(row(
        "Sobol' 2^20 x 8 (scrambled)",
        lambda s: ss.points("sobol", 1 << 20, seed=s, dims=8),
        lambda s: qmc.Sobol(8, seed=s).random_base2(20),
        R, shape,
    ))
    rows.append(row(
        "Halton 2^16 x 8 (scrambled)",
        lambda s: ss.points("halton", 1 << 16, seed=s, dims=8),
        lambda s: qmc.Halton(8, seed=s).random(1 << 16),
        R, shape,
    ))
    rows.append(row(
        "Latin hypercube 2^16 x 8",
        lambda s: ss.points("latin", 1 << 16, seed=s, dims=8),
        lambda s: qmc.LatinHypercube(8, seed=s).random(1 << 16),
        R, shape,
    ))
    for n in (1024, 4096):
        radius = 0.7 * ss.relative_radius_max(n)  # the same absolute radius on both sides
        rows.append(row(
            f"Poisson disk {n} (radius 0.7 r_max)",
            lambda s, n=n: ss.points("poisson", n, seed=s, radius=0.7),
            lambda s, n=n, r=radius: qmc.PoissonDisk(2, radius=r, seed=s).random(n),
            P,
            lambda a, b: f"{len(a)} vs {len(b)} points",
        ))
    x = np.random.default_rng(7).random((4096, 2))
    rows.append(row(
        "centered discrepancy 4096 x 2",
        lambda s: ss.discrepancy(x, "CD"),
        lambda s: qmc.discrepancy(x, method="CD"),
        R,
        lambda a, b: f"relative difference {abs(a - b) / b:.1e}",
    ))
    x32 = x.astype(np.float32)
    rows.append(row(
        "spectrum 4096 points, K = 256",
        lambda s: ss.spectrum(x32, 256),
        lambda s: numpy_dft(x32, 256),
        R,
        lambda a, b: f"max difference {np.max(np.abs(a - b)):.1e} (DC = 4096)",
    ))

    blas = os.environ.get("OPENBLAS_NUM_THREADS") or os.environ.get("OMP_NUM_THREADS")
    print(
        f"strata {ss.__version__}, scipy {scipy.__version__}, numpy {np.__version__}, "
        f"Python {platform.python_version()}, {os.cpu_count()} CPUs ({platform.machine()}), "
        f"BLAS threads {blas}; medians of {R} repeats ({P} for the Poisson disk)"
    )
    head = ("task", "strata", "scipy / numpy", "speed-up", "same job")
    if args.markdown:
        print("| " + " | ".join(head) + " |")
        print("|---|---:|---:|---:|---|")
        for name, a, b, note in rows:
            print(f"| {name} | {fmt(a)} | {fmt(b)} | {b / a:.1f}x | {note} |")
    else:
        w = max(len(r[0]) for r in rows)
        print(f"{head[0]:<{w}}  {head[1]:>10}  {head[2]:>13}  {head[3]:>8}  {head[4]}")
        for name, a, b, note in rows:
            print(f"{name:<{w}}  {fmt(a):>10}  {fmt(b):>13}  {b / a:>7.1f}x  {note}")


if __name__ == "__main__":
    main()

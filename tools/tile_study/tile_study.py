"""Issue 39's a-priori tile, as a feasibility study: can a swap-optimised 64x64 toroidal
assignment of per-pixel samples (pixel p takes the 1-spp sample of pixel pi(p) of
`PixelSampler("sobol", 1, seed=7)`) make the error of PURE-INTERACTION test functions blue
(low-band share <= 0.5x of the unoptimised assignment's) on held-out functions, while the main
effects stay blue? The optimiser minimises the low-pass power (Gaussian sigma 2 px, radius 6) of
K training error images by simulated annealing over pixel swaps (swap_kernel.c, incremental).

Usage: python3 tools/tile_study/tile_study.py --D 8 --K 256 --iters 100000000
           [--train-interaction | --only-interaction] [--out PREFIX] [--markdown FILE]
Needs the Python package (`pip install ./python`), numpy and gcc (it compiles swap_kernel.c next
to itself on first run). `--markdown FILE` writes the table into FILE as the section
`tile-study-D<D>-<training>`."""
import argparse, ctypes, os, subprocess, time, json
import numpy as np
import strata_sampling as ss

import sys as _sys
_sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from markdown_section import write_section  # noqa: E402 (tools/)

HERE = os.path.dirname(os.path.abspath(__file__))
W = 64; N = W * W

def load_kernel():
    so = os.path.join(HERE, "swap_kernel.so"); src = os.path.join(HERE, "swap_kernel.c")
    if not os.path.exists(so) or os.path.getmtime(so) < os.path.getmtime(src):
        subprocess.check_call(["gcc", "-O3", "-march=native", "-shared", "-fPIC", "-o", so, src, "-lm"])
    lib = ctypes.CDLL(so)
    P = np.ctypeslib.ndpointer
    d64 = P(np.float64, flags="C"); i32 = P(np.int32, flags="C"); i64 = P(np.int64, flags="C")
    lib.compute_S.argtypes = [ctypes.c_int, ctypes.c_int, d64, i32, ctypes.c_int, i32, i32, d64, d64]
    lib.energy.argtypes = [ctypes.c_int, ctypes.c_int, d64, i32, d64]; lib.energy.restype = ctypes.c_double
    lib.optimize.argtypes = [ctypes.c_int, ctypes.c_int, d64, i32, d64, ctypes.c_int, i32, i32, d64,
                             ctypes.c_int, d64, ctypes.c_long, ctypes.c_double, ctypes.c_double, ctypes.c_int,
                             ctypes.c_double, ctypes.c_uint64, i64, P(np.float64)]
    return lib

# ---------------- points ----------------
def get_points(dims):
    ps = ss.PixelSampler("sobol", 1, seed=7)
    px = np.stack(np.meshgrid(np.arange(W), np.arange(W)), -1).reshape(-1, 2)  # row i = (x, y), i = y*64 + x
    assert np.all(px[:, 0] + W * px[:, 1] == np.arange(N))
    X = ps.sample(px, np.zeros(N, dtype=np.int64), dims=12).astype(np.float64)
    return X[:, dims]

# ---------------- test functions ----------------
# each function: callable f(X) -> values (N,), plus exact/MC integral
UMC = np.random.default_rng(12345).random((1 << 20, 12))

def hs_draw(rng, idx):
    """random Heaviside / half-space in a draw's own space (1D or 2D). returns (f, mean)"""
    idx = list(idx)
    if len(idx) == 1:
        b = rng.uniform(0.05, 0.95); s = rng.choice([-1, 1]); i = idx[0]
        f = lambda X: (s * (X[:, i] - b) > 0).astype(float)
        return f, (1 - b) if s > 0 else b
    th = rng.uniform(0, 2 * np.pi); a = np.array([np.cos(th), np.sin(th)])
    corners = np.array([[0, 0], [0, 1], [1, 0], [1, 1]]) @ a
    lo, hi = corners.min(), corners.max(); b = rng.uniform(lo + 0.1 * (hi - lo), hi - 0.1 * (hi - lo))
    f = lambda X: (X[:, idx] @ a > b).astype(float)
    return f, float(f(UMC[:, :len(idx)] if False else _mc_cols(idx)).mean())

def _mc_cols(idx):
    M = np.zeros((UMC.shape[0], max(idx) + 1)); M[:, idx] = UMC[:, :len(idx)]; return M

def oblique(rng, D):
    a = rng.normal(size=D); c = rng.random(D); b = a @ c
    return lambda X: (X @ a > b).astype(float)

def gaussian(rng, D):
    k = rng.integers(2, min(4, D) + 1); S = rng.choice(D, k, replace=False)
    c = rng.random(k); s = rng.uniform(0.15, 0.4)
    return lambda X: np.exp(-((X[:, S] - c) ** 2).sum(1) / (2 * s * s))

def product(rng, da, db, pure):
    h1, m1 = hs_draw(rng, da); h2, m2 = hs_draw(rng, db)
    if pure:   # h1 h2 minus main effects = (h1-m1)(h2-m2)
        return lambda X: (h1(X) - m1) * (h2(X) - m2)
    return lambda X: h1(X) * h2(X)

def draws_for(D):
    if D == 8:   # local indices of dims [0,1,2,3,8,9,10,11]
        return {"film": [0, 1], "lens": [2, 3], "lobe": [4], "lchoice": [5], "lpt": [6, 7]}
    if D == 4:   # dims [0,1,10,11]
        return {"film": [0, 1], "lpt": [2, 3]}

def training_set(rng, D, K, train_interaction, only_interaction=False):
    dr = draws_for(D); names = list(dr); fs = []
    if only_interaction:   # every training function is a pure-interaction product of two different draws
        for k in range(K):
            a, b = rng.choice(len(names), 2, replace=False)
            fs.append(product(rng, dr[names[a]], dr[names[b]], pure=True))
        return fs
    for k in range(K):
        r = k % 6
        if r in (0, 1): fs.append(oblique(rng, D))
        elif r in (2, 3):
            a, b = rng.choice(len(names), 2, replace=False)
            fs.append(product(rng, dr[names[a]], dr[names[b]], pure=train_interaction))
        elif r == 4: fs.append(hs_draw(rng, dr[names[rng.integers(len(names))]])[0])
        else: fs.append(gaussian(rng, D))
    return fs

def eval_sets(rng, D, n):
    dr = draws_for(D); sets = {}
    pairs = [("film", "lpt"), ("lens", "lpt"), ("lchoice", "lpt")] if D == 8 else [("film", "lpt")]
    for a, b in pairs:
        sets[f"pureint {a}x{b}"] = [product(rng, dr[a], dr[b], True) for _ in range(n)]
    for a, b in pairs[:1]:
        sets[f"raw product {a}x{b}"] = [product(rng, dr[a], dr[b], False) for _ in range(n)]
    names = list(dr)
    sets["one-draw main effect"] = [hs_draw(rng, dr[names[i % len(names)]])[0] for i in range(n)]
    sets["oblique all-D"] = [oblique(rng, D) for _ in range(n)]
    sets["train-like (new draws)"] = training_set(rng, D, n, False)
    return sets

# ---------------- metric ----------------
fx = np.fft.fftfreq(W); FR = np.sqrt(fx[None, :] ** 2 + fx[:, None] ** 2)
LOW = (FR < 1 / 8) & (FR > 0); NONDC = FR > 0
def lowband_share(img):
    P = np.abs(np.fft.fft2(img - img.mean())) ** 2
    return P[LOW].sum() / P[NONDC].sum()

def evaluate(X, perm, fs):
    Xp = X[perm]  # pixel p (row-major, p = y*64+x) uses sample perm[p]
    sh, rm = [], []
    for f in fs:
        v = f(Xp); e = v - f(X).mean()
        if v.std() < 1e-12: continue
        sh.append(lowband_share(e.reshape(W, W))); rm.append(np.sqrt(np.mean(e ** 2)))
    sh = np.array(sh); return sh.mean(), sh.std(ddof=1) / np.sqrt(len(sh)), float(np.mean(rm)), len(sh)

# ---------------- optimisation ----------------
def window(sigma, R):
    o = [(dx, dy) for dy in range(-R, R + 1) for dx in range(-R, R + 1) if (dx or dy) and dx * dx + dy * dy <= R * R]
    odx = np.array([a for a, _ in o], np.int32); ody = np.array([b for _, b in o], np.int32)
    ow = np.exp(-(odx ** 2 + ody ** 2) / (2 * sigma ** 2)).astype(np.float64)
    wl = np.zeros((2 * R + 1, 2 * R + 1)); wl[ody + R, odx + R] = ow
    return odx, ody, ow, wl.ravel().copy()

def optimise(lib, X, fs, iters, sigma, R, seed, log):
    E = np.stack([f(X) for f in fs], 1); E = E - E.mean(0)
    E = E / np.maximum(E.std(0), 1e-12); E = np.ascontiguousarray(E); K = E.shape[1]
    odx, ody, ow, wl = window(sigma, R)
    rng = np.random.default_rng(seed)
    pi = rng.permutation(N).astype(np.int32)
    S = np.zeros((N, K)); lib.compute_S(W, K, E, pi, len(ow), odx, ody, ow, S)
    E0 = lib.energy(W, K, E, pi, S)
    # temperature scale from random swap deltas
    a = rng.integers(N, size=2000); b = rng.integers(N, size=2000)
    d = E[pi[b]] - E[pi[a]]; dl = 2 * np.abs((d * (S[a] - S[b])).sum(1))
    T0 = 0.02 * np.median(dl); T1 = T0 * 1e-3
    stats = np.zeros(2, np.int64); dE = np.zeros(1)
    chunks = 10; t0 = time.time()
    for c in range(chunks):
        # piecewise schedule: each chunk covers its slice of the geometric schedule
        Ta = T0 * (T1 / T0) ** (c / chunks); Tb = T0 * (T1 / T0) ** ((c + 1) / chunks)
        lib.optimize(W, K, E, pi, S, len(ow), odx, ody, ow, R, wl, iters // chunks, Ta, Tb, 6, 0.5,
                     int(seed * 1000 + c), stats, dE)
        log(f"  chunk {c}: accepted {stats[0]} energy {lib.energy(W, K, E, pi, S):.1f} (start {E0:.1f}) t={time.time()-t0:.1f}s")
    el = time.time() - t0
    S2 = np.zeros((N, K)); lib.compute_S(W, K, E, pi, len(ow), odx, ody, ow, S2)
    log(f"  incremental-vs-recomputed S max err {np.abs(S - S2).max():.2e}")
    return pi.astype(np.int64), el

def write_table(path, name, a, res, elapsed):
    """Writes the table into the Markdown file `path` as the section `name`
    (`tools/markdown_section.py`)."""
    import shlex, sys
    cmd = " ".join(shlex.quote(x) for x in ["python3", "tools/tile_study/tile_study.py"] + sys.argv[1:])
    training = ("pure-interaction products of two draws only" if a.only_interaction else
                "oblique half-spaces, products of two draws' half-spaces"
                + (" (pure-interaction parts)" if a.train_interaction else "")
                + ", one-draw half-spaces and Gaussians")
    body = (f"<!-- written by `{cmd}` -->\n\n"
            f"A 64x64 toroidal tile: pixel p takes the 1-spp sample (dimensions "
            f"{'0-3, 8-11' if a.D == 8 else '0-1, 10-11'}) of pixel pi(p) of `sobol` (seed 7); "
            f"pi optimised by {a.iters} attempted swaps ({elapsed:.0f} s, one core) to minimise the "
            f"low-pass power of {a.K} training errors ({training}). Low-band share (below 1/8 "
            f"cycle per pixel; white: about 0.047) of the error image, mean +- standard error over "
            f"{a.neval} held-out functions per class (the first row: the training set); the RMSE "
            f"is the same for every assignment (the same samples, rearranged).\n\n"
            "| class | identity | random | optimised | optimised / random |\n|---|---|---|---|---|\n")
    for cname, row in res.items():
        cells = [f"{m:.4f} +- {s:.4f}" for m, s, _, _ in row.values()]
        body += f"| {cname} | " + " | ".join(cells) + f" | {row['optimised'][0] / row['random'][0]:.2f} |\n"
    write_section(path, name, body)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--D", type=int, default=8); ap.add_argument("--K", type=int, default=256)
    ap.add_argument("--iters", type=int, default=20_000_000); ap.add_argument("--sigma", type=float, default=2.0)
    ap.add_argument("--R", type=int, default=6); ap.add_argument("--neval", type=int, default=64)
    ap.add_argument("--train-interaction", action="store_true", help="training products are pure-interaction (centred) products")
    ap.add_argument("--only-interaction", action="store_true", help="train ONLY on pure-interaction products")
    ap.add_argument("--out", default=None)
    ap.add_argument("--markdown", default=None, help="write the table into FILE as a section")
    a = ap.parse_args()
    dims = [0, 1, 2, 3, 8, 9, 10, 11] if a.D == 8 else [0, 1, 10, 11]
    X = get_points(dims); lib = load_kernel()
    def log(s): print(s, flush=True)
    fs = training_set(np.random.default_rng(1), a.D, a.K, a.train_interaction, a.only_interaction)
    log(f"D={a.D} K={a.K} iters={a.iters} sigma={a.sigma} R={a.R} train_interaction={a.train_interaction} only_interaction={a.only_interaction}")
    pi_opt, el = optimise(lib, X, fs, a.iters, a.sigma, a.R, 3, log)
    log(f"swap attempts {a.iters} in {el:.1f}s -> {a.iters/el/1e6:.2f} M attempts/s")
    ev = eval_sets(np.random.default_rng(999), a.D, a.neval)
    ev = {"TRAINING set (in-sample)": fs, **ev}
    assigns = {"identity": np.arange(N), "random": np.random.default_rng(5).permutation(N), "optimised": pi_opt}
    res = {}
    log(f"{'class':32s} " + " ".join(f"{k:>22s}" for k in assigns) + "   ratio opt/random")
    for cname, cfs in ev.items():
        row = {k: evaluate(X, p, cfs) for k, p in assigns.items()}; res[cname] = row
        log(f"{cname:32s} " + " ".join(f"{m:.4f}±{s:.4f} rmse{r:.3f}" for m, s, r, n in row.values())
            + f"   {row['optimised'][0]/row['random'][0]:.2f}")
    if a.markdown:
        mode = "pureint-only" if a.only_interaction else ("mixed-pureint" if a.train_interaction else "mixed")
        write_table(a.markdown, f"tile-study-D{a.D}-{mode}", a, res, el)
    if a.out:
        np.save(a.out + "_perm.npy", pi_opt)
        json.dump({c: {k: list(v) for k, v in r.items()} for c, r in res.items()}, open(a.out + ".json", "w"), indent=1)

if __name__ == "__main__":
    main()

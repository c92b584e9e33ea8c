"""Diagnostic: neighbour error correlations of main effects (film, lpt) vs their pure interaction, per tile.
Ensemble kernel K_a(p,q)=E_h[e_h(p)e_h(q)]/var over random half-spaces h in draw a; for independent h1,h2 the
interaction kernel is exactly K_a*K_b pixel-pair-wise."""
import numpy as np, sys
from tile_study import get_points, hs_draw, N, W
X = get_points([0, 1, 10, 11]); rng = np.random.default_rng(77)
def ens(perm, idx, n=400):
    Xp = X[perm]; E = []
    for _ in range(n):
        f, m = hs_draw(rng, idx); e = f(Xp) - m; E.append(e / e.std())
    return np.array(E)  # n x N
offs = [(dx, dy) for dx in range(-2, 3) for dy in range(-2, 3) if 0 < dx*dx+dy*dy <= 4]
pix = np.arange(N); x, y = pix % W, pix // W
for name, perm in [("identity", np.arange(N)), ("random", np.random.default_rng(5).permutation(N))] + \
        [(f, np.load(f + "_perm.npy")) for f in sys.argv[1:]]:
    Ea, Eb = ens(perm, [0, 1]), ens(perm, [2, 3])
    ka, kb = [], []
    for dx, dy in offs:
        q = ((y + dy) % W) * W + (x + dx) % W
        ka.append((Ea * Ea[:, q]).mean(0)); kb.append((Eb * Eb[:, q]).mean(0))
    ka, kb = np.concatenate(ka), np.concatenate(kb)
    print(f"{name:24s} mean K_film {ka.mean():+.3f}  mean K_lpt {kb.mean():+.3f}  mean K_film*K_lpt (interaction) {(ka*kb).mean():+.4f}"
          f"  product of means {ka.mean()*kb.mean():+.4f}  corr(K_film,K_lpt) {np.corrcoef(ka,kb)[0,1]:+.2f}")

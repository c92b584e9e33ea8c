"""The analysis tools on point sets made with numpy (not only ours): spectra against a direct
numpy DFT, radial means against numpy binning, discrepancies against scipy's, distances against
brute force, convergence rows against the points they are computed from."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.stats import qmc

import strata_sampling as ss


def numpy_periodogram(points: np.ndarray, k: int) -> np.ndarray:
    """``P(u, v) = |sum_j exp(-2 pi i (u x_j + v y_j))|^2 / N`` for ``|u|, |v| <= k/2``, row
    ``v``, column ``u``: the direct DFT, separable in u and v (one complex matrix product)."""
    f = np.arange(-k // 2, k // 2 + 1)
    x = points.astype(np.float64)
    ex = np.exp(-2j * np.pi * np.outer(f, x[:, 0]))  # (K+1, N): u, point
    ey = np.exp(-2j * np.pi * np.outer(f, x[:, 1]))  # (K+1, N): v, point
    s = ey @ ex.T  # s[v, u] = sum_j e^{-2 pi i v y_j} e^{-2 pi i u x_j}
    return np.abs(s) ** 2 / len(x)


def numpy_radial(p: np.ndarray):
    """Radial mean and anisotropy by numpy: rings round(|w|) = b, DC left out."""
    k = p.shape[0] - 1
    f = np.arange(-k // 2, k // 2 + 1)
    u, v = np.meshgrid(f, f)
    ring = np.floor(np.hypot(u, v) + 0.5).astype(int)
    ring[k // 2, k // 2] = -1
    power, aniso = [], []
    for b in range(1, k // 2 + 1):
        vals = p[ring == b]
        m = vals.mean()
        power.append(m)
        aniso.append(10 * np.log10(vals.var(ddof=1) / m**2))
    return np.array(power), np.array(aniso)


RNG = np.random.default_rng(2024)


@pytest.mark.parametrize("n,k", [(1, 8), (300, 32), (1000, 64)])
def test_spectrum_of_numpy_points_equals_a_direct_dft(n, k):
    x = RNG.random((n, 2))  # float64, made by numpy
    ours = ss.spectrum(x, k)
    assert ours.shape == (k + 1, k + 1) and ours.dtype == np.float64
    # the float64 points are used as float32 (the crate's point type)
    ref32 = numpy_periodogram(x.astype(np.float32), k)
    np.testing.assert_allclose(ours, ref32, rtol=0, atol=1e-6)
    # and within float32 rounding of the float64 points' own spectrum
    np.testing.assert_allclose(ours, numpy_periodogram(x, k), rtol=1e-4, atol=1e-3)
    direct = ss.spectrum(x, k, method="direct")
    np.testing.assert_allclose(direct, ref32, rtol=1e-9, atol=1e-9)
    assert ours[k // 2, k // 2] == pytest.approx(n)  # DC = N
    np.testing.assert_allclose(ours, ours[::-1, ::-1], atol=1e-6)  # P(w) = P(-w)


def test_spectrum_of_a_grid_and_of_float32_input():
    # an 8 x 8 grid: power only at multiples of 8 in u and v
    g = (np.stack(np.meshgrid(np.arange(8), np.arange(8)), -1).reshape(-1, 2) + 0.5) / 8
    p = ss.spectrum(g.astype(np.float32), 32)
    f = np.arange(-16, 17)
    on_lattice = (f[:, None] % 8 == 0) & (f[None, :] % 8 == 0)
    assert np.all(np.abs(p[on_lattice] - 64) < 1e-6)
    assert np.all(p[~on_lattice] < 1e-6)
    np.testing.assert_allclose(p, numpy_periodogram(g, 32), atol=1e-6)


def test_expected_spectrum_is_the_mean_periodogram():
    sets = [ss.points("jittered", 256, seed=s) for s in range(6)]
    mean = np.mean([numpy_periodogram(s, 32) for s in sets], axis=0)
    for given in (sets, np.stack(sets), tuple(sets)):
        np.testing.assert_allclose(ss.expected_spectrum(given, 32), mean, atol=1e-6)
    # numpy-made sets too, any number of them
    r = RNG.random((3, 100, 2))
    np.testing.assert_allclose(
        ss.expected_spectrum(r, 16),
        np.mean([numpy_periodogram(s.astype(np.float32), 16) for s in r], axis=0),
        atol=1e-6,
    )


def test_sampler_spectrum_is_the_expected_spectrum_of_the_seeds_sets():
    # realization r is points(name, n, seed=seed + r), as in the crate's spectrum program
    ours = ss.sampler_spectrum("poisson", 256, 32, realizations=5, seed=9, radius=0.6)
    sets = [ss.points("poisson", 256, seed=9 + r, radius=0.6) for r in range(5)]
    np.testing.assert_array_equal(ours, ss.expected_spectrum(sets, 32))
    with pytest.raises(ValueError, match="perfect square"):
        ss.sampler_spectrum("jittered", 10, 32)
    with pytest.raises(ValueError, match="realizations = 0 is not allowed"):
        ss.sampler_spectrum("jittered", 16, 32, realizations=0)


def test_radial_mean_and_anisotropy_equal_numpy_binning():
    sets = RNG.random((4, 500, 2))
    p = ss.expected_spectrum(sets, 64)
    r = ss.radial(p)
    assert r.frequency.tolist() == list(range(1, 33))
    power, aniso = numpy_radial(p)
    np.testing.assert_allclose(r.power, power, rtol=1e-12)
    np.testing.assert_allclose(r.anisotropy, aniso, rtol=1e-9, atol=1e-9)
    # white noise: flat at 1; anisotropy near -10 log10(R) = -6 dB for R = 4 sets
    assert abs(r.power[4:].mean() - 1) < 0.1
    assert abs(np.median(r.anisotropy[4:]) + 6.0) < 1.5
    assert r.count.sum() == np.count_nonzero(
        np.floor(np.hypot(*np.meshgrid(np.arange(-32, 33), np.arange(-32, 33))) + 0.5) <= 32
    ) - 1


def test_blue_noise_has_low_power_near_dc_and_jitter_is_between():
    k = 64
    radials = {}
    for name in ("random", "jittered", "ccvt"):
        kw = {"iterations": 20} if name == "ccvt" else {}
        sets = [ss.points(name, 256, seed=s, **kw) for s in range(4)]
        radials[name] = ss.radial(ss.expected_spectrum(sets, k)).power
    low = slice(0, 8)  # |w| < 8 < sqrt(256)
    assert radials["ccvt"][low].mean() < radials["jittered"][low].mean()
    assert radials["jittered"][low].mean() < 0.5 * radials["random"][low].mean()


@pytest.mark.parametrize("method", ["CD", "WD", "MD", "L2-star"])
@pytest.mark.parametrize("d", [1, 2, 3, 5])
def test_discrepancies_equal_scipys(method, d):
    # the closed forms subtract terms of size (19/12)^d: rounding leaves ~1e-15 of them
    tol = dict(rel=1e-9, abs=1e-13 * (19 / 12) ** d)
    for x in (RNG.random((200, d)), qmc.Sobol(d, seed=3).random(128)):
        ref = qmc.discrepancy(x, method=method)
        assert ss.discrepancy(x, method) == pytest.approx(ref, **tol)
        x32 = x.astype(np.float32)  # float32 without a copy: the same value as scipy's
        ref32 = qmc.discrepancy(x32.astype(np.float64), method=method)
        assert ss.discrepancy(x32, method) == pytest.approx(ref32, **tol)
    # points on the closed cube's faces are allowed, as in scipy
    edge = np.array([[0.0] * d, [1.0] * d, [0.5] * d])
    assert ss.discrepancy(edge, method) == pytest.approx(
        qmc.discrepancy(edge, method=method), rel=1e-10
    )


def test_star_discrepancy_and_t_values():
    assert ss.discrepancy(np.array([[0.0, 0.0]]), "star") == pytest.approx(1.0)
    x = RNG.random((40, 2))
    star = ss.discrepancy(x, "star")
    # every anchored box [0, a) x [0, b) on a grid gives a lower bound
    a = np.linspace(0.01, 1, 100)
    counts = ((x[:, None, None, 0] < a[None, :, None]) & (x[:, None, None, 1] < a[None, None, :]))
    local = np.abs(counts.mean(axis=0) - a[:, None] * a[None, :])
    assert local.max() <= star + 1e-12
    assert star < local.max() + 0.05
    assert ss.net_t_value(ss.points("pmj02", 256)) == 0
    assert ss.net_t_value(RNG.random((256, 2))) >= 3
    assert ss.net_t_value(RNG.random((100, 2))) is None
    # issue 38, N22: [0, 1) whatever the count, and said so
    for bad in ([[1.0, 0.5], [0.1, 0.1]], [[1.0, 0.5], [0.1, 0.1], [0.2, 0.2]]):
        with pytest.raises(ValueError, match=r"outside \[0, 1\)"):
            ss.net_t_value(np.array(bad))


def test_psa_of_one_point_has_no_distances():
    """issue 38, N22: a single point has no neighbour; its distances are None, not NaN."""
    m = ss.psa(np.array([[0.5, 0.5]], dtype=np.float32))
    assert m["count"] == 1
    assert m["global_min_distance"] is None and m["average_min_distance"] is None


def test_distances_equal_brute_force():
    x = RNG.random((300, 2))
    x32 = x.astype(np.float32)  # the crate's point type: compare on the rounded points
    y = x32.astype(np.float64)
    diff = np.abs(y[:, None, :] - y[None, :, :])
    diff = np.minimum(diff, 1 - diff)  # on the torus
    dist = np.hypot(diff[..., 0], diff[..., 1])
    np.fill_diagonal(dist, np.inf)
    np.testing.assert_allclose(ss.nearest_distances(x), dist.min(axis=1), rtol=1e-12)
    assert ss.min_distance(x) == pytest.approx(dist.min(), rel=1e-12)
    assert ss.min_distance(x32, relative=True) == pytest.approx(
        dist.min() / np.sqrt(2 / (np.sqrt(3) * 300)), rel=1e-12
    )
    # dart throwing at radius 0.7 keeps every pair at least 0.7 r_max apart
    p = ss.points("poisson", 1024, seed=2, radius=0.7)
    assert ss.min_distance(p, relative=True) >= 0.7 - 1e-6


def test_psa_measures():
    g = (np.stack(np.meshgrid(np.arange(16), np.arange(16)), -1).reshape(-1, 2)) / 16
    m = ss.psa(g)
    expected = (1 / 16) / ss.relative_radius_max(256)
    assert m["count"] == 256
    assert m["global_min_distance"] == pytest.approx(expected, rel=1e-6)
    assert m["average_min_distance"] == pytest.approx(expected, rel=1e-6)
    assert 0.75 < m["effective_nyquist"] <= 1.0
    # random points: global minimum near 0, average near 0.47 (PSA's figures)
    r = ss.psa(RNG.random((8, 1024, 2)))
    assert r["global_min_distance"] < 0.1 and 0.4 < r["average_min_distance"] < 0.55


def test_convergence_rows_are_the_estimates_of_our_points():
    rows = ss.convergence("jittered", "bilinear", [16, 64, 256], seeds=8)
    assert [r["n"] for r in rows] == [16, 64, 256]
    for r in rows:
        est = [ss.points("jittered", r["n"], seed=s).astype(np.float64).prod(axis=1).mean()
               for s in range(8)]
        assert r["mean"] == pytest.approx(np.mean(est), rel=1e-12)
        assert r["variance"] == pytest.approx(np.var(est, ddof=1), rel=1e-9)
        assert r["rmse"] == pytest.approx(np.sqrt(np.mean((np.array(est) - 0.25) ** 2)), rel=1e-9)
        assert r["predicted_variance"] > 0 and r["ns_per_sample"] > 0
    # a Python integrand gives the same estimates
    py = ss.convergence("jittered", lambda x: x[:, 0] * x[:, 1], [16, 64, 256], 8, exact=0.25)
    for a, b in zip(rows, py):
        assert a["mean"] == pytest.approx(b["mean"], rel=1e-12)
        assert a["variance"] == pytest.approx(b["variance"], rel=1e-9)
        assert a["rmse"] == pytest.approx(b["rmse"], rel=1e-9)
    # jittered converges faster than random on a smooth integrand (fixed seeds: deterministic)
    ns = [16, 64, 256, 1024]
    slope = {}
    for name in ("random", "jittered"):
        rs = ss.convergence(name, "gaussian", ns, seeds=16, predict=False)
        slope[name] = ss.fit_slope([r["n"] for r in rs], [r["variance"] for r in rs])
    assert -1.4 < slope["random"] < -0.6
    assert slope["jittered"] < -1.6
    # several integrands at once, 4D ones for samplers with D dimensions
    both = ss.convergence("sobol", ["disk", "gaussian4d"], [64], seeds=4)
    assert [r["integrand"] for r in both] == ["disk", "gaussian4d"]


def test_fit_slope_and_integrands():
    ns = np.array([16.0, 64.0, 256.0, 1024.0])
    assert ss.fit_slope(ns, 3 * ns**-1.5) == pytest.approx(-1.5, abs=1e-12)
    assert ss.fit_slope([4], [1]) is None
    names = [f["name"] for f in ss.integrands()]
    assert names == ["disk", "triangle", "step", "gaussian", "bilinear", "gaussian4d", "ball4d"]
    assert {f["name"]: f["exact"] for f in ss.integrands()}["bilinear"] == 0.25

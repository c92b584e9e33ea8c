"""``ss.Engine`` as a ``scipy.stats.qmc.QMCEngine``: progressive sequences continue across
calls, reset and fast-forward, fixed-count samplers give sets of the counts they accept, and
scipy's own tools (discrepancy, scale, integers, qmc_quad) run on them."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import qmc_quad
from scipy.stats import qmc

import strata_sampling as ss


@pytest.mark.parametrize("name,d", [("sobol", 5), ("halton", 3), ("pmj02", 2), ("random", 4),
                                    ("lattice", 3), ("best-candidate", 2)])
def test_progressive_engines_continue_the_sequence(name, d):
    e = ss.Engine(name, d, seed=11)
    assert isinstance(e, qmc.QMCEngine) and e.progressive and e.d == d
    ref = ss.points(name, 40, seed=11, dims=d).astype(np.float64)
    a = e.random(5)
    b = e.random(11)
    assert a.dtype == np.float64 and a.shape == (5, d)
    np.testing.assert_array_equal(np.vstack([a, b]), ref[:16])
    assert e.num_generated == 16
    # reset starts again; fast_forward skips
    np.testing.assert_array_equal(e.reset().random(16), ref[:16])
    e.reset().fast_forward(7)
    assert e.num_generated == 7
    np.testing.assert_array_equal(e.random(9), ref[7:16])
    # scipy's base fast_forward path (random + discard) agrees with ours
    e.reset()
    qmc.QMCEngine.fast_forward(e, 3)
    np.testing.assert_array_equal(e.random(2), ref[3:5])
    assert e.random(0).shape == (0, d)


def test_fixed_count_engines_give_sets_of_allowed_counts():
    e = ss.Engine("jittered", 2, seed=3)
    assert not e.progressive and e.counts == "perfect squares"
    first = e.random(64)
    np.testing.assert_array_equal(first, ss.points("jittered", 64, seed=3))
    second = e.random(64)
    assert not np.array_equal(first, second)
    for s in (first, second):  # each call is a whole jittered set
        cells = {(int(x * 8), int(y * 8)) for x, y in s}
        assert len(cells) == 64
    with pytest.raises(ValueError, match=r"perfect square \(nearest allowed: 9 or 16\)"):
        e.random(10)
    np.testing.assert_array_equal(e.reset().random(64), first)
    assert e.allowed_counts(10, 40) == [16, 25, 36]
    # D-dimensional fixed-count sets
    oa = ss.Engine("oa-bose", 4, seed=2)
    np.testing.assert_array_equal(oa.random(49), ss.points("oa-bose", 49, seed=2, dims=4))


def test_scipy_discrepancy_scale_and_integers_work_on_our_points():
    e = ss.Engine("sobol", 3, seed=5)
    x = e.random(256)
    assert qmc.discrepancy(x) == pytest.approx(ss.discrepancy(x), rel=1e-10)
    # scrambled Sobol' beats i.i.d. uniform points by a wide margin at 256 points
    r = np.random.default_rng(1).random((256, 3))
    assert qmc.discrepancy(x) < 0.2 * qmc.discrepancy(r)
    scaled = qmc.scale(x, [-1, 0, 10], [1, 2, 20])
    assert scaled.min(axis=0).tolist() >= [-1, 0, 10]
    assert scaled.max(axis=0).tolist() < [1, 2, 20]
    k = ss.Engine("halton", 2, seed=1).integers([0, 10], u_bounds=[4, 13], n=12)
    assert k.shape == (12, 2) and k[:, 0].max() < 4 and k[:, 1].min() >= 10


def test_qmc_quad_makes_independent_copies():
    # int_[0,1]^3 x y z = 1/8; qmc_quad builds one engine per estimate from ours
    f = lambda x: x[0] * x[1] * x[2]  # noqa: E731
    res = qmc_quad(f, [0, 0, 0], [1, 1, 1], n_estimates=8, n_points=1024,
                   qrng=ss.Engine("sobol", 3, seed=7))
    assert res.standard_error > 0  # the copies differ
    assert abs(res.integral - 0.125) < 6 * res.standard_error + 1e-9
    assert res.standard_error < 1e-4  # far below random sampling's ~ 2e-3
    again = qmc_quad(f, [0, 0, 0], [1, 1, 1], n_estimates=8, n_points=1024,
                     qrng=ss.Engine("sobol", 3, seed=7))
    assert again.integral == res.integral  # deterministic for a given seed
    # a fixed-count sampler whose count is qmc_quad's n_points
    jit = qmc_quad(lambda x: x[0] * x[1], [0, 0], [1, 1], n_points=1024,
                   qrng=ss.Engine("jittered", 2, seed=1))
    assert abs(jit.integral - 0.25) < 6 * jit.standard_error + 1e-9


def test_seeds():
    g1, g2 = np.random.default_rng(42), np.random.default_rng(42)
    a, b = ss.Engine("sobol", 2, seed=g1), ss.Engine("sobol", 2, seed=g2)
    assert a.seed == b.seed
    np.testing.assert_array_equal(a.random(8), b.random(8))
    c, d = ss.Engine("sobol", 2), ss.Engine("sobol", 2)  # fresh entropy
    assert isinstance(c.seed, int) and c.seed != d.seed
    np.testing.assert_array_equal(
        c.random(8), ss.points("sobol", 8, seed=c.seed).astype(np.float64)
    )
    assert repr(ss.Engine("poisson", 2, seed=3, radius=0.5)) == (
        "Engine('poisson', d=2, seed=3, radius=0.5)"
    )


def test_engine_errors():
    with pytest.raises(ValueError, match="unknown sampler 'sobel'; known samplers: random"):
        ss.Engine("sobel", 2)
    with pytest.raises(ValueError, match="2-dimensional points only"):
        ss.Engine("jittered", 3)
    with pytest.raises(ValueError, match="dims"):
        ss.Engine("sobol", 2000)
    with pytest.raises(TypeError, match="did you mean 'radius'"):
        ss.Engine("poisson", 2, raduis=0.5)
    with pytest.raises(ValueError, match="takes no radius"):
        ss.Engine("sobol", 2, radius=0.5)
    with pytest.raises(ValueError, match="d = -1 is out of range"):
        ss.Engine("sobol", -1)
    with pytest.raises(ValueError, match="d = 0 is not allowed: pmj02 has 2-dimensional points"):
        ss.Engine("pmj02", 0)
    with pytest.raises(ValueError, match="'toto' is not a valid optimization method"):
        ss.Engine("sobol", 2, optimization="toto")


@pytest.mark.parametrize("name", ["sobol", "halton"])
def test_fast_forward_continues_the_sequence(name):
    # sobol (3 dims) skips in constant time in the crate, halton draws and drops: both must
    # land on the same points as drawing them
    e = ss.Engine(name, 3, seed=4)
    e.fast_forward(1000)
    got = e.random(10)
    want = ss.points(name, 1010, seed=4, dims=3)[1000:]
    assert np.array_equal(got.astype(np.float32), want)
    assert e.num_generated == 1010
    with pytest.raises(ValueError):
        e.fast_forward(-1)
    with pytest.raises(TypeError):
        e.fast_forward(True)


def test_fast_forward_is_constant_time_for_sobol():
    # 2^40 points would take hours to draw; the skip is O(1), then the stream goes on
    e = ss.Engine("sobol", 4, seed=2)
    e.fast_forward(1 << 40)
    assert e.num_generated == 1 << 40
    x = e.random(8)
    assert x.shape == (8, 4) and np.all((x >= 0) & (x < 1))


# issue 38, N14: seeds as scipy and numpy take them

SCIPY_SEED = 170382760648021597650530316304495310428  # QMCEngineTests' default seed


@pytest.mark.parametrize("seed", [0, 1, 2**32, 2**63, 2**64 - 1, np.uint64(2**64 - 1)])
def test_seeds_below_two_to_the_64_are_the_seed_itself(seed):
    e = ss.Engine("sobol", 3, seed=seed)
    assert e.seed == int(seed)
    np.testing.assert_array_equal(e.random(16), ss.points("sobol", 16, seed=int(seed), dims=3))


def test_large_ints_and_seed_sequences_are_hashed_as_documented():
    # an int >= 2^64 stands for SeedSequence(int), whose first two 32-bit words of state are
    # the low and high halves of the 64-bit seed: a fixed value, on every platform
    assert ss.Engine("sobol", 2, seed=SCIPY_SEED).seed == 10103525735708876616
    seq = np.random.SeedSequence(SCIPY_SEED)
    assert ss.Engine("sobol", 2, seed=seq).seed == 10103525735708876616
    assert ss.Engine("sobol", 2, seed=seq).seed == 10103525735708876616  # not consumed
    lo, hi = np.random.SeedSequence(2**64).generate_state(2, np.uint32)
    assert ss.Engine("halton", 2, seed=2**64).seed == int(lo) | int(hi) << 32
    kids = np.random.SeedSequence(5).spawn(3)
    assert len({ss.Engine("sobol", 2, seed=k).seed for k in kids}) == 3
    # the same mapping in every seed-taking function
    np.testing.assert_array_equal(
        ss.points("pmj02", 16, seed=SCIPY_SEED), ss.points("pmj02", 16, seed=10103525735708876616)
    )
    np.testing.assert_array_equal(
        ss.PixelSampler("sobol", 16, seed=seq).sample([1, 2], np.arange(16)),
        ss.PixelSampler("sobol", 16, seed=10103525735708876616).sample([1, 2], np.arange(16)),
    )
    assert ss.PixelSampler("sobol", 16, seed=seq).seed == 10103525735708876616


def test_rng_is_the_spec7_name_of_seed():
    np.testing.assert_array_equal(
        ss.Engine("sobol", 2, rng=7).random(8), ss.Engine("sobol", 2, seed=7).random(8)
    )
    assert ss.Engine("sobol", 2, rng=np.random.SeedSequence(3)).seed == ss.Engine(
        "sobol", 2, seed=np.random.SeedSequence(3)).seed
    # a generator is consumed: engines made one after the other differ (as scipy's)
    g = np.random.default_rng(0xA29CABB11CFDF44FF6CAC8BEC254C2A0)
    a, b = ss.Engine("pmj02", 2, rng=g), ss.Engine("pmj02", 2, rng=g)
    assert a.seed != b.seed
    # a BitGenerator is wrapped in a Generator
    assert ss.Engine("sobol", 2, rng=np.random.PCG64(1)).seed == ss.Engine(
        "sobol", 2, rng=np.random.Generator(np.random.PCG64(1))).seed
    with pytest.raises(TypeError, match="got both seed and rng"):
        ss.Engine("sobol", 2, seed=1, rng=1)
    with pytest.raises(ValueError, match="seed = -1 is out of range; allowed: an int >= 0"):
        ss.Engine("sobol", 2, rng=-1)
    with pytest.raises(TypeError, match="not RandomState"):
        ss.Engine("sobol", 2, seed=np.random.RandomState(1))


def test_zero_dimensions_and_optimization_as_for_scipy_engines():
    for name, n in (("sobol", 4), ("latin", 5)):
        e = ss.Engine(name, 0, seed=1)
        assert e.random(n).shape == (n, 0) and e.num_generated == n
    e = ss.Engine("sobol", 2, seed=1, optimization="random-cd")
    assert repr(e) == "Engine('sobol', d=2, seed=1, optimization='random-cd')"
    x = e.random(32)
    plain = ss.points("sobol", 32, seed=1).astype(np.float64)
    assert qmc.discrepancy(x) <= qmc.discrepancy(plain)
    # qmc_quad's copies keep the optimization
    assert e._init_quad == {"name": "sobol", "d": 2, "optimization": "random-cd"}


# issue 38, N13: deterministic samplers give no independent replicates


def test_qmc_quad_refuses_a_deterministic_sampler():
    # regular's points do not depend on the seed: qmc_quad's copies would all be equal and
    # its standard error 0.0 whatever the true error (4.1e-5 here: 1/6 is exact)
    with pytest.raises(ValueError, match=r"regular is deterministic.*use 'jittered'"):
        qmc_quad(lambda x: x[0] ** 2 * x[1], [0, 0], [1, 1], n_points=1024,
                 qrng=ss.Engine("regular", 2, seed=1))
    # jittered, regular's randomized form, gives an honest error estimate
    res = qmc_quad(lambda x: x[0] ** 2 * x[1], [0, 0], [1, 1], n_points=1024,
                   qrng=ss.Engine("jittered", 2, seed=1))
    assert res.standard_error > 0
    assert abs(res.integral - 1 / 6) < 6 * res.standard_error


@pytest.mark.parametrize("entry", ss.samplers(), ids=lambda e: e["name"])
def test_the_seeded_flag_is_what_the_points_do(entry):
    # every registered sampler, checked empirically: two seeds, same points iff not seeded
    name = entry["name"]
    n = ss.nearest_count(name, 64)
    for d in [2] if entry["dimensions"] == "2" else [2, 3]:
        same = np.array_equal(
            ss.points(name, n, seed=1, dims=d), ss.points(name, n, seed=2, dims=d)
        )
        assert same == (not entry["seeded"]), (name, d)
    if entry["seeded"]:
        ss.Engine(name, 2, seed=1)
    else:
        with pytest.raises(ValueError, match="is deterministic"):
            ss.Engine(name, 2, seed=1)

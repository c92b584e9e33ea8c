"""Pickling and copying (issue 38, N12): ``Engine`` and ``PixelSampler`` survive ``pickle``,
``copy.copy`` and ``copy.deepcopy``, so ``multiprocessing``, ``concurrent.futures`` and joblib
can ship them to other processes; an engine resumes exactly where it stopped."""

from __future__ import annotations

import concurrent.futures
import copy
import multiprocessing
import operator
import pickle

import numpy as np
import pytest
from scipy.integrate import qmc_quad

import strata_sampling as ss
from strata_sampling import _strata

PROGRESSIVE = [e["name"] for e in ss.samplers() if e["progressive"]]


def _copies(obj):
    yield pickle.loads(pickle.dumps(obj))
    yield pickle.loads(pickle.dumps(obj, protocol=2))
    yield copy.deepcopy(obj)
    yield copy.copy(obj)


@pytest.mark.parametrize("name", PROGRESSIVE)
def test_a_progressive_engine_resumes_where_it_stopped(name):
    e = ss.Engine(name, 2, seed=9)
    e.random(5)
    for c in _copies(e):
        assert type(c) is ss.Engine and c.seed == e.seed and c.num_generated == 5
        assert repr(c) == repr(e)
        np.testing.assert_array_equal(c.random(7), ss.points(name, 12, seed=9)[5:])
    np.testing.assert_array_equal(e.random(7), ss.points(name, 12, seed=9)[5:])
    # the copies are independent of the original: drawing from one moves only that one
    c = copy.deepcopy(e)
    c.random(3)
    assert c.num_generated == 15 and e.num_generated == 12


@pytest.mark.parametrize("name,n", [("jittered", 16), ("oa-bose", 25), ("poisson", 20),
                                    ("latin", 7)])
def test_a_fixed_count_engine_resumes_with_its_next_sets(name, n):
    e = ss.Engine(name, 2, seed=4)
    e.random(n), e.random(n), e.random(ss.nearest_count(name, 4 * n))
    restored = pickle.loads(pickle.dumps(e))
    for _ in range(2):
        np.testing.assert_array_equal(restored.random(n), e.random(n))
    m = ss.nearest_count(name, 4 * n)
    np.testing.assert_array_equal(restored.random(m), e.random(m))
    np.testing.assert_array_equal(restored.reset().random(n), ss.points(name, n, seed=4))


def test_state_beyond_the_points_survives():
    # a constant-time skip far ahead, scipy's generator, the optimization, the parameters
    e = ss.Engine("sobol", 3, seed=2, optimization="random-cd")
    e.fast_forward(1 << 40)
    c = pickle.loads(pickle.dumps(e))
    assert c.num_generated == 1 << 40
    np.testing.assert_array_equal(c.random(16), e.random(16))
    p = ss.Engine("pmjbn", 2, seed=3, candidates=10)
    p.random(3)
    c = copy.deepcopy(p)
    assert c._params == {"candidates": 10}
    np.testing.assert_array_equal(c.random(5), p.random(5))
    # qmc_quad spawns its copies' seeds from scipy's generator: the same after a round trip
    f = lambda x: np.exp(x[0] + x[1])  # noqa: E731
    a = ss.Engine("halton", 2, seed=np.random.default_rng(5))
    b = pickle.loads(pickle.dumps(a))
    assert qmc_quad(f, [0, 0], [1, 1], qrng=a) == qmc_quad(f, [0, 0], [1, 1], qrng=b)


def test_the_compiled_sampler_pickles_with_its_position():
    s = _strata.Sampler("halton", 1, 3, 4)
    out = np.empty((10, 4), np.float32)
    s.fill(out)
    assert s.drawn == 10
    c = pickle.loads(pickle.dumps(s))
    assert (c.name, c.count, c.dims, c.drawn, c.progressive) == ("halton", 1, 4, 10, True)
    a, b = np.empty((6, 4), np.float32), np.empty((6, 4), np.float32)
    s.fill(a)
    c.fill(b)
    np.testing.assert_array_equal(a, b)


def test_a_sampler_past_two_to_the_64_points_pickles_with_its_position():
    # issue 43, A5: `drawn` counted in u64 wrapped, and the copy resumed at the wrong place
    s = _strata.Sampler("sobol", 1, 3, 2)
    assert s.skip(2**64 - 1) and s.skip(5)
    assert s.drawn == 2**64 + 4
    c = pickle.loads(pickle.dumps(s))
    assert c.drawn == 2**64 + 4
    a, b = np.empty((6, 2), np.float32), np.empty((6, 2), np.float32)
    s.fill(a)
    c.fill(b)
    np.testing.assert_array_equal(a, b)
    # a sampler skipped by 2^64 + 4 in one go stands at the same place
    t = _strata.restore_sampler("sobol", 1, 3, 2, 2**64 + 4 + 6)
    u = np.empty((6, 2), np.float32)
    t.fill(u)
    s.fill(a)
    np.testing.assert_array_equal(u, a)


@pytest.mark.parametrize("sequence", ["sobol", "zjoint-4", "zsobol"])
def test_pixel_sampler_pickles_and_copies(sequence):
    ps = ss.PixelSampler(sequence, 16, seed=2**70, resolution=(64, 32))
    px = np.stack(np.meshgrid(np.arange(8), np.arange(4)), -1)
    want = ps.sample(px, 5, dims=7)
    for c in _copies(ps):
        assert repr(c) == repr(ps) and c.resolution == (64, 32) and c.seed == ps.seed
        assert c.sequence == ps.sequence
        np.testing.assert_array_equal(c.sample(px, 5, dims=7), want)


def test_engines_and_pixel_samplers_cross_process_boundaries():
    # a fresh interpreter (spawn: no state inherited) gets them by pickle and continues
    e = ss.Engine("sobol", 4, seed=7)
    e.random(100)
    ps = ss.PixelSampler("pmj02", 16, seed=7)
    ctx = multiprocessing.get_context("spawn")
    with concurrent.futures.ProcessPoolExecutor(1, mp_context=ctx) as pool:
        got = pool.submit(operator.methodcaller("random", 28), e).result(timeout=120)
        values = pool.submit(
            operator.methodcaller("sample", [3, 4], np.arange(16), 4), ps
        ).result(timeout=120)
    np.testing.assert_array_equal(got, e.random(28))
    np.testing.assert_array_equal(values, ps.sample([3, 4], np.arange(16), 4))

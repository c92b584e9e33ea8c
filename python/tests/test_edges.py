"""The edges of the counting helpers, the fits and the engine (issue 24, rows 5, 6, 11, 14):
every answer is one the crate accepts, over the whole input range, or a clear error."""

from __future__ import annotations

import numpy as np
import pytest

import strata_sampling as ss

U64_MAX = 2**64 - 1
FIXED = [s["name"] for s in ss.samplers() if not s["progressive"]]


@pytest.mark.parametrize("name", FIXED)
@pytest.mark.parametrize("n", [0, 1, 2**31 - 1, 2**31, 2**32, 2**40, U64_MAX])
def test_nearest_count_is_always_allowed(name, n):
    c = ss.nearest_count(name, n)
    assert c >= 1
    # the count is one the sampler accepts: the crate's own check says so
    assert ss._strata.count_error(name, c) is None, (name, n, c)


@pytest.mark.parametrize("name", FIXED)
def test_allowed_counts_over_the_whole_range(name):
    s = next(e for e in ss.samplers() if e["name"] == name)
    if s["counts"].startswith("any"):
        with pytest.raises(ValueError, match="at most"):
            ss.allowed_counts(name, 0, U64_MAX)
        return
    counts = ss.allowed_counts(name, 0, U64_MAX)
    assert counts == sorted(set(counts)) and counts
    assert all(ss._strata.count_error(name, c) is None for c in counts[-3:])


def test_allowed_counts_of_a_progressive_engine_are_bounded():
    e = ss.Engine("random", 2)
    with pytest.raises(ValueError, match="at most"):
        e.allowed_counts(0, U64_MAX)
    assert e.allowed_counts(0, 3) == [1, 2, 3]


@pytest.mark.parametrize("n", [0, 1, 17, 2**31 - 1, 2**32 - 1])
def test_round_count_is_never_zero(n):
    ps = ss.PixelSampler("jittered", 16)
    c = ps.round_count(n)
    assert c >= 1
    assert int(round(c**0.5)) ** 2 == c
    assert c >= min(n, 65535**2)


def test_fit_slope_and_radius_refuse_what_they_cannot_answer():
    with pytest.raises(ValueError, match="x has 3 values and y 2"):
        ss.fit_slope([1, 2, 4], [1, 2])
    with pytest.raises(ValueError, match="n = 0 is out of range"):
        ss.relative_radius_max(0)
    assert ss.relative_radius_max(1) > ss.relative_radius_max(2)


def test_fast_forward_is_constant_time_for_sobol_in_two_dimensions():
    e = ss.Engine("sobol", 2, seed=3)
    # a sampler that cannot skip refuses more than 2^31 dropped points (next test), so these
    # return only because the skip is constant time (drawing 2^32 points took 35 s)
    e.fast_forward(2**32)
    e.fast_forward(2**40)
    assert e.num_generated == 2**32 + 2**40
    assert e.random(4).shape == (4, 2)
    # the skip lands where drawing would
    a = ss.Engine("sobol", 2, seed=3)
    a.fast_forward(1000)
    want = ss.points("sobol", 1010, seed=3)[1000:]
    assert np.array_equal(a.random(10).astype(np.float32), want)


def test_fast_forward_refuses_an_endless_draw_and_drop():
    e = ss.Engine("halton", 2)
    with pytest.raises(ValueError, match="cannot skip ahead in constant time"):
        e.fast_forward(U64_MAX)
    assert e.num_generated == 0


def test_convergence_with_no_integrand_of_the_sampler_dimension_is_an_error():
    with pytest.raises(ValueError, match="gaussian4d"):
        ss.convergence("pmj02", "gaussian4d", [16], 4)

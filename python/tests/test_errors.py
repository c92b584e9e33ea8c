"""Bad input: every wrong dtype, shape, layout, value, name, count or keyword raises
``ValueError`` or ``TypeError`` with a message that says what was wrong and what is allowed;
nothing crashes the interpreter (the compiled functions called directly included)."""

from __future__ import annotations

import numpy as np
import pytest

import strata_sampling as ss
from strata_sampling import _strata

GOOD = np.random.default_rng(0).random((64, 2))


@pytest.mark.parametrize(
    "call,exc,match",
    [
        (lambda: ss.points("sobel", 4), ValueError, "unknown sampler 'sobel'; known samplers: random, regular"),
        (lambda: ss.points("sobol", -5), ValueError, r"n = -5 is out of range; allowed: 0 to"),
        (lambda: ss.points("sobol", 0), ValueError, "sobol cannot make 0 samples"),
        (lambda: ss.points("sobol", 4.0), TypeError, "n must be a whole number"),
        (lambda: ss.points("sobol", True), TypeError, "not a bool"),
        (lambda: ss.points("jittered", 10), ValueError, r"perfect square \(nearest allowed: 9 or 16\)"),
        (lambda: ss.points("poisson", 16, raduis=0.5), TypeError, "did you mean 'radius'"),
        (lambda: ss.points("jittered", 16, radius=0.5), ValueError, "jittered takes no radius; samplers that do: poisson, bridson"),
        (lambda: ss.points("poisson", 16, radius=1.5), ValueError, "radius = 1.5 is not allowed"),
        (lambda: ss.points("poisson", 16, radius=float("nan")), ValueError, "finite"),
        (lambda: ss.points("poisson", 16, radius="big"), TypeError, "radius must be a number"),
        (lambda: ss.points("ccvt", 16, iterations=-1), ValueError, "iterations = -1 is out of range"),
        (lambda: ss.points("sobol", 4, dims=0), ValueError, "dims = 0 is out of range"),
        (lambda: ss.points("jittered", 16, dims=3), ValueError, "2-dimensional points only; samplers with D dimensions: random, sobol"),
        (lambda: ss.points("sobol", 4, dims=1001), ValueError, "sobol: dims = 1001 is not allowed: 1 to 1000"),
        (lambda: ss.points("sobol", 4, seed=-1), ValueError, "seed = -1 is out of range"),
        (lambda: ss.points("sobol", 4, seed=1.5), TypeError, "seed must be an int >= 0 .*SeedSequence, Generator or BitGenerator; not float"),
        (lambda: ss.points("sobol", 4, seed=True), TypeError, "seed must be .*; not a bool"),
        (lambda: ss.points("sobol", 4, seed=-2**70), ValueError, "as numpy.random.default_rng refuses them"),
        (lambda: ss.points("oa-bose", 49, dims=9), ValueError, "oa-bose"),
        # issue 38's second hostile pass: numpy's "Maximum allowed dimension exceeded" and an
        # 8 TiB MemoryError said nothing about n
        (lambda: ss.points("sobol", 2**64 - 1), ValueError, r"at most 2\^31 values per call"),
        (lambda: ss.points("sobol", 2**40), ValueError, r"n x dims = 1099511627776 x 2"),
        (lambda: ss.allowed_counts("random", 0, 2**64 - 1), ValueError, r"listing 1 to 2147483648 would make 2147483648 numbers"),
    ],
)
def test_points_arguments(call, exc, match):
    with pytest.raises(exc, match=match):
        call()


def _with(value, at=(5, 1)):
    a = GOOD.copy()
    a[at] = value
    return a


@pytest.mark.parametrize("fn", [
    lambda p: ss.spectrum(p, 16),
    lambda p: ss.expected_spectrum([p], 16),
    lambda p: ss.psa(p),
    lambda p: ss.min_distance(p),
    lambda p: ss.nearest_distances(p),
])
@pytest.mark.parametrize(
    "points,exc,match",
    [
        (np.random.default_rng(2).random((64, 3)), ValueError, r"shape \(64, 3\); \(n, 2\)"),
        (GOOD.astype(np.complex128), TypeError, "dtype complex128; real numbers are needed"),
        (np.array([[None, 0.5]] * 4), TypeError, "dtype object; real numbers are needed"),
        ((GOOD * 100).astype(np.int64), ValueError, r"point \d+ is .*in \[0, 1\)"),
        (_with(np.nan), ValueError, r"point 5 is .*nan.*coordinates must be finite and in \[0, 1\)"),
        (_with(1.0), ValueError, r"point 5 is .*1\.0.*in \[0, 1\)"),
        (_with(-1e-50), ValueError, r"point 5 .*in \[0, 1\)"),
        (_with(np.inf).astype(np.float32), ValueError, r"point 5 is \(.*inf\).*in \[0, 1\)"),
        (_with(1.0).astype(np.float32), ValueError, r"point 5 is .*in \[0, 1\)"),
        (GOOD[:0], ValueError, r"shape \(0, 2\)"),
        (GOOD[:, 0].copy(), ValueError, r"shape \(64,\)"),
        ([[0.1, 0.2], [0.3]], (TypeError, ValueError), r"points must be an array|shape \(2,\)"),
        ("points", TypeError, "not a string"),
    ],
)
def test_point_set_inputs(fn, points, exc, match):
    with pytest.raises(exc, match=match):
        fn(points)


@pytest.mark.parametrize("fn", [
    lambda p: ss.spectrum(p, 16),
    lambda p: ss.psa(p),
    lambda p: ss.nearest_distances(p),
    lambda p: ss.discrepancy(p, "CD"),
    lambda p: ss.net_t_value(p),
])
def test_numpy_layouts_are_copied_not_refused(fn):
    """numpy conventions: a strided view, a Fortran-ordered array, byte-swapped float32 and
    float64, an integer-valued array and a float16 array are accepted and give the values of
    the same points as a contiguous native array."""
    base = np.random.default_rng(3).random((64, 4))
    view = base[:, ::2]  # strided, not contiguous
    want = fn(np.ascontiguousarray(view))
    for variant in (
        view,
        np.asfortranarray(view),
        np.ascontiguousarray(view).astype(">f8"),
        list(map(list, np.ascontiguousarray(view))),
    ):
        got = fn(variant)
        _same(got, want)
    want32 = fn(np.ascontiguousarray(view, dtype=np.float32))
    _same(fn(np.ascontiguousarray(view, dtype=np.float32).astype(">f4")), want32)
    _same(fn(np.asfortranarray(view, dtype=np.float32)), want32)
    zeros = np.zeros((8, 2), np.int32)
    _same(fn(zeros), fn(np.zeros((8, 2))))
    half = (0.99 * np.ascontiguousarray(view)).astype(np.float16)  # none rounds up to 1
    _same(fn(half), fn(half.astype(np.float64)))


def _same(a, b):
    if isinstance(a, dict):
        assert a.keys() == b.keys()
        for k in a:
            _same(a[k], b[k])
    elif isinstance(a, np.ndarray):
        np.testing.assert_array_equal(a, b)
    else:
        assert a == b or (a != a and b != b)


def test_lists_and_float64_just_below_one_are_accepted():
    pts = [[0.1, 0.2], [0.3, 0.4], [1 - 1e-12, 0.5]]  # rounds to 1.0 in float32: kept below
    assert ss.spectrum(pts, 8).shape == (9, 9)
    assert ss.min_distance(pts) > 0


@pytest.mark.parametrize(
    "call,exc,match",
    [
        (lambda: ss.spectrum(GOOD, 15), ValueError, "resolution = 15 is not allowed: an even number from 2 to 2048"),
        (lambda: ss.spectrum(GOOD, 4096), ValueError, "an even number from 2 to 2048"),
        (lambda: ss.spectrum(GOOD, -2), ValueError, "resolution = -2 is out of range"),
        (lambda: ss.spectrum(GOOD, 16, method="fft"), ValueError, "unknown method 'fft'; allowed: nufft, direct"),
        (lambda: ss.expected_spectrum([GOOD, GOOD[:10]], 16), ValueError, "realization 1 has 10 points, realization 0 has 64"),
        (lambda: ss.expected_spectrum([], 16), ValueError, "no point set given"),
        (lambda: ss.expected_spectrum(np.zeros((2, 2, 2, 2)), 16), ValueError, r"\(n, 2\) or \(r, n, 2\)"),
        (lambda: ss.psa([GOOD, GOOD[:10]]), ValueError, "all must have the same count"),
        (lambda: ss.min_distance(GOOD[:1]), ValueError, "at least 2 are needed"),
        (lambda: ss.radial(np.zeros((16, 16))), ValueError, r"\(K\+1, K\+1\) array with K even"),
        (lambda: ss.radial(np.zeros((17, 9))), ValueError, r"shape \[17, 9\]"),
        (lambda: ss.radial(np.full((17, 17), np.nan)), ValueError, "values must be finite"),
        (lambda: ss.radial(np.zeros(17)), ValueError, "a \\(K\\+1, K\\+1\\) array is needed"),
        (lambda: ss.radial(np.array([["a"]])), TypeError, "real numbers"),
        (lambda: ss.discrepancy(GOOD, "L2"), ValueError, "unknown method 'L2'; allowed: CD, WD, MD, L2-star, star"),
        (lambda: ss.discrepancy(GOOD + 1, "CD"), ValueError, r"outside \[0, 1\]"),
        (lambda: ss.discrepancy(_with(np.nan), "WD"), ValueError, r"coordinate NaN is outside \[0, 1\]"),
        (lambda: ss.discrepancy(GOOD.astype(np.complex64), "CD"), TypeError, "complex64"),
        (lambda: ss.discrepancy(np.zeros((3, 3)), "star"), ValueError, "2D sets; these points have 3 dimensions"),
        (lambda: ss.net_t_value(np.zeros((4, 3))), ValueError, r"\(n, 2\) is needed"),
        (lambda: ss.convergence("jittered", "disc", [16], 4), ValueError, "unknown integrand 'disc'; known integrands: disk"),
        (lambda: ss.convergence("jittered", "disk", [10], 4), ValueError, r"no allowed count between 10 and 10 \(it takes perfect squares"),
        (lambda: ss.convergence("jittered", "disk", [16], 1), ValueError, "seeds = 1 is out of range; allowed: 2 to"),
        (lambda: ss.convergence("jittered", 3, [16], 4), TypeError, "a name, a list of names or a callable"),
        (lambda: ss.convergence("sobol", lambda x: x[:, 0][:5], [16], 4), ValueError, r"returned shape \(5,\) for 16 points"),
    ],
)
def test_analysis_arguments(call, exc, match):
    with pytest.raises(exc, match=match):
        call()


@pytest.mark.parametrize(
    "call,exc,match",
    [
        (lambda: ss.PixelSampler("pmj", 16), ValueError, "no path-tracer sequence named 'pmj'; the sequences: random, jittered"),
        (lambda: ss.PixelSampler("jittered", 10), ValueError, r"square number of samples per pixel \(nearest allowed: 9 or 16\)"),
        (lambda: ss.PixelSampler("sobol", 0), ValueError, "at least 1 sample per pixel"),
        (lambda: ss.PixelSampler("sobol", 16, -3), ValueError, "seed = -3"),
        (lambda: ss.PixelSampler("zsobol", 16, resolution=(0, 4)), ValueError, "zsobol"),
        (lambda: ss.PixelSampler("zsobol", 16, resolution=5), TypeError, "pair"),
        (lambda: ss.PixelSampler("sobol", 16).sample([1.5, 2], [0]), TypeError, "pixels must be integers, not float64"),
        (lambda: ss.PixelSampler("sobol", 16).sample([-1, 2], [0]), ValueError, "pixels holds -1; allowed: 0 to 4294967295"),
        (lambda: ss.PixelSampler("sobol", 16).sample([2**32, 2], [0]), ValueError, "pixels holds 4294967296"),
        (lambda: ss.PixelSampler("sobol", 16).sample([[1, 2, 3]], [0]), ValueError, r"pixels have shape \(1, 3\); \(\.\.\., 2\)"),
        (lambda: ss.PixelSampler("sobol", 16).sample([1, 2], [-4]), ValueError, "indices holds -4"),
        (lambda: ss.PixelSampler("sobol", 16).sample([1, 2], [0.5]), TypeError, "indices must be integers"),
        (lambda: ss.PixelSampler("sobol", 16).sample([[1, 2]] * 3, [0, 1]), ValueError, "do not broadcast"),
        (lambda: ss.PixelSampler("sobol", 16).sample([1, 2], [0], dims=0), ValueError, "dims = 0"),
    ],
)
def test_pixel_sampler_arguments(call, exc, match):
    with pytest.raises(exc, match=match):
        call()


def test_the_compiled_functions_refuse_bad_arrays_without_crashing():
    s = _strata.Sampler("sobol", 16, 1, 3)
    with pytest.raises(TypeError):
        s.fill(np.zeros((16, 3), np.float64))  # wrong dtype
    with pytest.raises(ValueError, match="3 columns are needed|has 2 columns"):
        s.fill(np.zeros((16, 2), np.float32))
    with pytest.raises(ValueError, match="C-contiguous"):
        s.fill(np.zeros((3, 16), np.float32).T)
    ro = np.zeros((16, 3), np.float32)
    ro.flags.writeable = False
    with pytest.raises(ValueError, match="cannot be written"):
        s.fill(ro)
    with pytest.raises(TypeError):
        _strata.periodogram(GOOD, 16)  # float64 where float32 is taken
    with pytest.raises(ValueError, match="C-contiguous"):
        _strata.periodogram(np.zeros((2, 8), np.float32).T, 16)
    with pytest.raises(ValueError, match=r"\(n, 2\) is needed"):
        _strata.periodogram(np.zeros((8, 3), np.float32), 16)
    with pytest.raises(OverflowError):
        _strata.Sampler("sobol", -1, 1, 2)
    ps = _strata.PixelSampler("sobol", 16, 1)
    with pytest.raises(ValueError, match=r"\(2, 2\) is needed"):
        ps.fill(np.zeros((3, 2), np.uint32), np.zeros(2, np.uint64), np.zeros((2, 2), np.float32))
    with pytest.raises(ValueError, match="output has shape"):
        ps.fill(np.zeros((2, 2), np.uint32), np.zeros(2, np.uint64), np.zeros((3, 2), np.float32))
    # the array is fine after all that
    out = np.zeros((16, 3), np.float32)
    s.fill(out)
    assert (out > 0).any()


def test_a_huge_count_fails_cleanly():
    with pytest.raises((MemoryError, ValueError)):
        ss.points("sobol", 2**62, dims=4)
    with pytest.raises(ValueError, match="cannot make"):
        ss.points("jittered", 2**62)  # refused before anything is allocated


# issue 38, N15: Python ints beyond int64 as sample indices


def test_python_int_indices_up_to_two_to_the_64_are_uint64():
    ps = ss.PixelSampler("sobol", 16, seed=3)
    big = np.array([0, 2**64 - 1, 2**63], dtype=np.uint64)
    want = ps.sample([3, 4], big, dims=3)
    np.testing.assert_array_equal(ps.sample([3, 4], [0, 2**64 - 1, 2**63], dims=3), want)
    np.testing.assert_array_equal(ps.sample([3, 4], (0, 2**64 - 1, 2**63), dims=3), want)
    np.testing.assert_array_equal(ps.sample([3, 4], 2**64 - 1, dims=3), want[1])
    nested = ps.sample([3, 4], [[0, 2**64 - 1], [2**63, 0]], dims=3)
    np.testing.assert_array_equal(nested[0, 1], want[1])
    np.testing.assert_array_equal(nested[1, 0], want[2])
    # exactly: 2^64 - 1 and 2^64 - 2 would be the same float64
    a = ps.sample([3, 4], [2**64 - 2, 2**64 - 1], dims=2)
    b = ps.sample([3, 4], np.array([2**64 - 2, 2**64 - 1], np.uint64), dims=2)
    np.testing.assert_array_equal(a, b)


@pytest.mark.parametrize(
    "indices,exc,match",
    [
        ([-1, 2**64 - 1], ValueError, r"indices holds -1; allowed: 0 to 18446744073709551615"),
        ([0, 2**64], ValueError, r"indices holds 18446744073709551616; allowed: 0 to"),
        (2**64, ValueError, r"indices holds 18446744073709551616"),
        ([0.5, 2**64 - 1], TypeError, "indices must be integers, not float64"),
        ([None, 2**64], TypeError, "indices must be integers, not object"),
    ],
)
def test_python_int_indices_out_of_range_are_refused(indices, exc, match):
    with pytest.raises(exc, match=match):
        ss.PixelSampler("sobol", 16).sample([1, 2], indices)


def test_python_int_pixels_out_of_range_are_refused():
    with pytest.raises(ValueError, match=r"pixels holds 18446744073709551616; allowed: 0 to 4294967295"):
        ss.PixelSampler("sobol", 16).sample([2**64, 1], [0])

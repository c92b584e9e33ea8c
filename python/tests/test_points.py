"""``ss.points`` and ``ss.PixelSampler`` against the crate's ``points`` program: the
same arguments give the same float32 values, bit for bit, for every sampler and sequence."""

from __future__ import annotations

import threading

import numpy as np
import pytest

import strata_sampling as ss

# (sampler, n, seed, dims, parameters): the command line's parameters, D dimensions where a
# sampler has them, extreme seeds
CASES = [
    ("random", 100, 1, 2, {}),
    ("random", 64, 5, 3, {}),
    ("random", 10, 2, 1, {}),
    ("regular", 16, 1, 2, {}),
    ("jittered", 64, 7, 2, {}),
    ("nrooks", 50, 3, 2, {}),
    ("multijittered", 36, 4, 2, {}),
    ("cmj", 100, 9, 2, {}),
    ("pmj", 256, 1, 2, {}),
    ("pmjbn", 64, 2, 2, {"candidates": 4}),
    ("pmj02", 1000, 11, 2, {}),
    ("pmj02bn", 128, 3, 2, {}),
    ("pmj02-stochastic", 512, 8, 2, {}),
    ("poisson", 300, 5, 2, {"radius": 0.75}),
    ("bridson", 300, 6, 2, {}),
    ("bridson", 300, 6, 2, {"attempts": 3}),
    ("pmj02bn", 128, 3, 2, {"sweeps": 1}),
    ("net02bn", 64, 4, 2, {"iterations": 3}),
    ("best-candidate", 200, 7, 2, {"candidates": 2}),
    ("lloyd", 64, 8, 2, {"iterations": 20}),
    ("ccvt", 64, 9, 2, {"iterations": 5, "capacity": 16}),
    ("sobol", 1000, 2**64 - 1, 7, {}),
    ("sobol", 33, 0, 2, {}),
    ("halton", 500, 12, 5, {}),
    ("lattice", 256, 13, 4, {}),
    ("fibonacci", 89, 14, 2, {}),
    ("latin", 100, 15, 6, {}),
    ("uncorrelated", 49, 16, 4, {}),
    ("oa-bose", 49, 17, 5, {}),
    ("oa-bush", 125, 18, 4, {"strength": 3}),
]
# every other registered sampler (added to the crate later) at its count nearest to 64
CASES += [
    (s["name"], ss.nearest_count(s["name"], 64), 3, 2, {})
    for s in ss.samplers()
    if s["name"] not in {c[0] for c in CASES}
]


def cli_args(name, n, seed, dims, params):
    args = ["--sampler", name, "-n", n, "--seed", seed, "--dims", dims]
    for k, v in params.items():
        args += [f"--{k}", v]
    return args


@pytest.mark.parametrize("name,n,seed,dims,params", CASES, ids=lambda v: str(v))
def test_points_equal_the_command_line(points_cli, name, n, seed, dims, params):
    ours = ss.points(name, n, seed=seed, dims=dims, **params)
    theirs = points_cli(*cli_args(name, n, seed, dims, params))
    assert ours.dtype == np.float32 and ours.shape == (n, dims)
    assert ours.flags.c_contiguous
    # bit for bit, not approximately
    np.testing.assert_array_equal(ours.view(np.uint32), theirs.view(np.uint32))


@pytest.mark.parametrize(
    "args",
    [("jittered", 10), ("oa-bose", 50), ("fibonacci", 90), ("unknown-sampler", 4)],
)
def test_errors_carry_the_crates_message(points_cli_error, args):
    name, n = args
    with pytest.raises(ValueError) as e:
        ss.points(name, n)
    cli = points_cli_error("--sampler", name, "-n", n)
    assert str(e.value) in cli  # the program prints "points: error: MESSAGE"
    assert "allowed" in str(e.value) or "known samplers" in str(e.value)


def test_points_are_in_the_unit_square_and_depend_on_the_seed():
    for s in ss.samplers():
        n = ss.nearest_count(s["name"], 64)
        kw = {"iterations": 5} if s["name"] in ("lloyd", "ccvt") else {}
        a = ss.points(s["name"], n, seed=1, **kw)
        b = ss.points(s["name"], n, seed=2, **kw)
        assert ((a >= 0) & (a < 1)).all(), s["name"]
        if s["name"] != "regular":  # cell centres: no randomness
            assert not np.array_equal(a, b), s["name"]
        np.testing.assert_array_equal(a, ss.points(s["name"], n, seed=1, **kw))


def test_progressive_prefixes_and_fixed_count_sets():
    # a progressive sequence's first n points are a prefix of its first 2n
    a = ss.points("pmj02", 64, seed=3)
    np.testing.assert_array_equal(a, ss.points("pmj02", 128, seed=3)[:64])
    # a jittered set has one point in each cell of the s x s grid
    j = ss.points("jittered", 256, seed=4)
    cells = (j * 16).astype(int)
    assert len({(x, y) for x, y in cells}) == 256


def test_sobol_prefixes_are_nets():
    x = ss.points("sobol", 1024, seed=5)
    assert ss.net_t_value(x) == 0
    assert ss.net_t_value(x[:512]) == 0


def test_sampler_table():
    table = {s["name"]: s for s in ss.samplers()}
    assert table["jittered"]["counts"] == "perfect squares"
    assert not table["jittered"]["progressive"]
    assert table["sobol"]["progressive"] and table["sobol"]["dimensions"] == "D"
    assert table["sobol"]["pixel_sampler"] and not table["ccvt"]["pixel_sampler"]
    assert [p["name"] for p in table["poisson"]["parameters"]] == ["radius"]
    assert table["poisson"]["parameters"][0]["default"] == 0.7
    assert table["pmj02"]["rates"]["discontinuous"] == -1.5
    assert ss.allowed_counts("jittered", 10, 50) == [16, 25, 36, 49]
    assert ss.allowed_counts("oa-bose", 1, 30) == [4, 9, 16, 25]
    assert ss.nearest_count("jittered", 1000) == 1024


def test_every_declared_parameter_is_a_keyword_and_an_alias_sets_the_same_value():
    # the keywords come from the samplers' declarations: each sampler's own parameters
    # (the defaults given explicitly change nothing), and pmj02bn's old name for its sweeps
    for s in ss.samplers():
        if s["name"] in {"lloyd", "ccvt", "bnot", "net02bn", "best-candidate"}:
            continue  # slow at their defaults; covered by CASES with small values
        n = ss.nearest_count(s["name"], 64)
        for p in s["parameters"]:
            assert p["kind"] in {"whole number", "number"} and p["help"], p
            default = int(p["default"]) if p["kind"] == "whole number" else p["default"]
            given = ss.points(s["name"], n, seed=5, **{p["name"]: default})
            np.testing.assert_array_equal(given, ss.points(s["name"], n, seed=5))
    np.testing.assert_array_equal(
        ss.points("pmj02bn", 64, iterations=0), ss.points("pmj02bn", 64, sweeps=0)
    )
    assert (ss.points("pmj02bn", 64, sweeps=0) != ss.points("pmj02bn", 64)).any()
    with pytest.raises(ValueError, match="1 to 1000"):
        ss.points("bridson", 64, attempts=0)
    with pytest.raises(ValueError, match="takes no attempts"):
        ss.points("jittered", 64, attempts=3)


# --- the path-tracer adapter ----------------------------------------------------------------

PIXEL_CASES = [
    ("random", 16, 1, (3, 4), 5),
    ("jittered", 16, 2, (0, 0), 4),
    ("pmj02", 64, 3, (10, 20), 7),
    ("sobol", 64, 2**64 - 1, (4294967295, 7), 6),
    ("halton", 24, 5, (1, 1), 3),
    ("lattice", 32, 6, (9, 2), 2),
    ("zsobol", 16, 7, (5, 6), 5),
    ("zpmj02", 16, 8, (300, 6), 4),  # outside the 256 x 256 image: the pixel's own copies
]


@pytest.mark.parametrize("seq,n,seed,pixel,dims", PIXEL_CASES, ids=lambda v: str(v))
def test_pixel_sampler_equals_the_command_line(points_cli, seq, n, seed, pixel, dims):
    ps = ss.PixelSampler(seq, n, seed)
    ours = ps.sample(pixel, np.arange(n), dims)
    theirs = points_cli(
        "--sampler", seq, "-n", n, "--seed", seed, "--pixel", f"{pixel[0]},{pixel[1]}",
        "--dims", dims,
    )
    np.testing.assert_array_equal(ours.view(np.uint32), theirs.view(np.uint32))


@pytest.mark.parametrize("pixel", [(7, 9), (100, 9)])
def test_z_ordered_sequences_take_the_resolution(points_cli, pixel):
    ps = ss.PixelSampler("zsobol", 16, 3, resolution=(64, 32))
    ours = ps.sample(pixel, np.arange(16), 4)
    theirs = points_cli(
        "--sampler", "zsobol", "-n", 16, "--seed", 3, "--pixel", f"{pixel[0]},{pixel[1]}",
        "--dims", 4, "--resolution", "64x32",
    )
    np.testing.assert_array_equal(ours, theirs)
    # (100, 9) lies outside the 64 x 32 image and falls back to its own copies, which are
    # `sobol`'s; (7, 9) is on the curve, whose order depends on the image's size (the pixel
    # order permutes the image's base-4 digits), so it differs from sobol's
    own = ss.PixelSampler("sobol", 16, 3).sample(pixel, np.arange(16), 4)
    assert np.array_equal(ours, own) == (pixel == (100, 9))


def test_pixel_sampler_broadcasts_like_numpy():
    ps = ss.PixelSampler("pmj02", 16, 9)
    pixels = np.array([[0, 0], [1, 0], [5, 7]])
    idx = np.arange(16)
    grid = ps.sample(pixels[:, None, :], idx[None, :], 3)  # every pixel x every index
    assert grid.shape == (3, 16, 3)
    for k, p in enumerate(pixels):
        np.testing.assert_array_equal(grid[k], ps.sample(p, idx, 3))
        # and one (pixel, index) at a time
        for i in (0, 5, 15):
            np.testing.assert_array_equal(grid[k, i], ps.sample(p, i, 3))
    # pixels (m, 2) with indices (m,): one row per pair
    pairs = ps.sample(pixels, np.array([3, 4, 5]), 2)
    assert pairs.shape == (3, 2)
    for k in range(3):
        np.testing.assert_array_equal(pairs[k], grid[k, 3 + k, :2])


def test_pixel_sampler_dimensions_and_first_dim():
    ps = ss.PixelSampler("sobol", 64, 4)
    idx = np.arange(64)
    full = ps.sample((2, 3), idx, 8)
    # dimensions 4..7 on their own are the same values
    np.testing.assert_array_equal(ps.sample((2, 3), idx, 4, first_dim=4), full[:, 4:])
    # a 1D draw at d is the first coordinate of the 2D draw at d
    np.testing.assert_array_equal(ps.sample((2, 3), idx, 1, first_dim=6)[:, 0], full[:, 6])
    # each 2D draw of a pixel is a (0, m, 2)-net at 64 samples
    for d in (0, 2, 4, 6):
        assert ss.net_t_value(np.ascontiguousarray(full[:, d : d + 2])) == 0
    # and different pixels get different values
    assert not np.array_equal(full, ps.sample((3, 2), idx, 8))
    assert ps.round_count(50) == 64 and ps.spp == 64 and ps.sequence == "sobol"
    assert (64, 1) in ps.promised_strata(64)


def test_results_do_not_depend_on_threads_and_the_gil_is_released():
    ps = ss.PixelSampler("sobol", 64, 4)
    pixels = np.stack(np.meshgrid(np.arange(64), np.arange(64)), axis=-1).reshape(-1, 2)
    ref = ps.sample(pixels, np.arange(pixels.shape[0]) % 64, 6)
    counter = [0]
    stop = threading.Event()

    def spin():
        while not stop.is_set():
            counter[0] += 1

    t = threading.Thread(target=spin)
    t.start()
    try:
        c0 = counter[0]
        big = ss.points("sobol", 1 << 20, dims=8)
        c1 = counter[0]
    finally:
        stop.set()
        t.join()
    # the other thread ran while Rust generated 8 million values
    assert c1 - c0 > 100
    assert big.shape == (1 << 20, 8)
    results = [None] * 4

    def work(k):
        results[k] = ps.sample(pixels, np.arange(pixels.shape[0]) % 64, 6)

    threads = [threading.Thread(target=work, args=(k,)) for k in range(4)]
    for th in threads:
        th.start()
    for th in threads:
        th.join()
    for r in results:
        np.testing.assert_array_equal(r, ref)


def test_long_sobol_fills_split_over_threads_equal_one_thread():
    # 2^17 x 8 values is over the parallel threshold (2^18 values a thread): the split fill,
    # each thread skipping to its share, must equal small serial fills, and the stream must
    # continue after it as one sampler's would (the next call starts where this one ended)
    n, d = 1 << 17, 8
    par = ss._strata.Sampler("sobol", n, 5, d)
    a = np.empty((n, d), np.float32)
    par.fill(a)
    a_next = np.empty((1000, d), np.float32)
    par.fill(a_next)
    ser = ss._strata.Sampler("sobol", n, 5, d)
    b = np.empty((n + 1000, d), np.float32)
    for k in range(0, n + 1000, 1 << 12):
        ser.fill(b[k : min(k + (1 << 12), n + 1000)])
    assert np.array_equal(a, b[:n])
    assert np.array_equal(a_next, b[n:])

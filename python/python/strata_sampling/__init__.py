"""strata: sample patterns for Monte Carlo rendering, as numpy arrays.

Every sampler of the Rust crate ``strata`` (PMJ, pmj02bn, Owen-scrambled Sobol', Halton,
orthogonal arrays, Poisson disk, CCVT, Lloyd, ...), its path-tracer pixel sampler, and its
analysis tools (power spectra with radial means and anisotropy, PSA measures, discrepancies,
convergence studies), without a second implementation: the values are the crate's, bit for bit.

>>> import strata_sampling
>>> x = strata_sampling.points("pmj02", 256, seed=7)            # (256, 2) float32
>>> s = strata_sampling.spectrum(x, 64)                          # (65, 65) periodogram, DC in the centre
>>> r = strata_sampling.radial(s)                                # radial mean and anisotropy
>>> d = strata_sampling.discrepancy(x, "CD")                     # as scipy.stats.qmc.discrepancy
>>> e = strata_sampling.Engine("sobol", 5, seed=3)               # a scipy.stats.qmc.QMCEngine

Errors are ``ValueError`` (or ``TypeError`` for the wrong kind of argument) with the crate's
message: what was wrong and what is allowed. The GIL is released while Rust works.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any, Callable, Dict, Iterable, List, NamedTuple, Optional, Union

import numpy as np

from . import _strata
from . import _validate as _v

if TYPE_CHECKING:  # the Engine needs scipy, imported on first use
    from ._engine import Engine

__version__ = "0.1.0"

__all__ = [
    "Engine",
    "PixelSampler",
    "Radial",
    "allowed_counts",
    "convergence",
    "discrepancy",
    "estimate",
    "expected_spectrum",
    "fit_slope",
    "integrands",
    "min_distance",
    "nearest_count",
    "nearest_distances",
    "net_t_value",
    "points",
    "psa",
    "radial",
    "relative_radius_max",
    "sampler_spectrum",
    "samplers",
    "sequences",
    "spectrum",
    "summarize",
]

#: The discrepancy methods: scipy's ``"CD"``, ``"WD"``, ``"MD"`` (squared, as scipy returns
#: them) and ``"L2-star"``, and ``"star"`` (the exact star discrepancy of a 2D set).
DISCREPANCY_METHODS: tuple = tuple(_strata.DISCREPANCY_METHODS)

#: The largest spectrum resolution ``K``.
MAX_RESOLUTION: int = _strata.MAX_RESOLUTION


def __getattr__(name: str) -> Any:
    # `strata_sampling.Engine` imports scipy on first use, so that `import strata` does not need it
    if name == "Engine":
        from ._engine import Engine

        return Engine
    raise AttributeError(f"module 'strata' has no attribute {name!r}")


# ---------------------------------------------------------------------------------------------
# samplers


def samplers() -> List[Dict[str, Any]]:
    """Every registered sampler, simplest first, as dicts with the keys

    ``name``, ``description``, ``paper``, ``progressive`` (endless sequence) or not (fixed-count
    sets), ``counts`` (the count rule in words, e.g. ``"perfect squares"``), ``dimensions``
    (``"2"`` or ``"D"``), ``parameters`` (a list of dicts: ``name``, ``kind``, ``default``,
    ``allowed``, ``help``, from each sampler's declaration),
    ``promise`` (the stratification it promises), ``rates`` (published variance exponents on
    ``discontinuous``/``smooth``/``higher``-dimensional integrands, ``None`` where unpublished),
    ``expensive``, ``pixel_sampler`` (whether ``PixelSampler`` has it as a sequence) and
    ``seeded`` (False for a deterministic sampler such as ``regular``, whose points do not
    depend on the seed: ``Engine`` refuses it, since it cannot give independent replicates).
    """
    adapter = set(_strata.sequence_names())
    out = _strata.registry_entries()
    for e in out:
        e["pixel_sampler"] = e["name"] in adapter
    return out


def sequences() -> List[str]:
    """The sequences of the path-tracer adapter (``PixelSampler``)."""
    return list(_strata.sequence_names())


def allowed_counts(name: str, lo: int, hi: int) -> List[int]:
    """The counts in ``[lo, hi]`` that sampler ``name`` accepts, in increasing order."""
    lo = _v.whole(lo, "lo", 0, _v.U64_MAX)
    hi = _v.whole(hi, "hi", 0, _v.U64_MAX)
    return list(_strata.allowed_counts(name, lo, hi))


def nearest_count(name: str, n: int) -> int:
    """The count nearest to ``n`` that sampler ``name`` accepts (the smaller one on a tie)."""
    return int(_strata.nearest_count(name, _v.whole(n, "n", 0, _v.U64_MAX)))


#: The most values ``points`` makes in one call (2^31 float32: 8 GiB).
MAX_VALUES = 1 << 31


def points(name: str, n: int, *, seed: Any = 1, dims: int = 2, **params: Any) -> np.ndarray:
    """The first ``n`` points of sampler ``name``: an ``(n, dims)`` float32 array in [0, 1).

    Bit-identical to ``cargo run --release --example points -- --sampler NAME -n N --seed S
    --dims D [--radius ...]``: a fixed-count sampler's first set of ``n`` (``n`` must be a
    count it accepts, see ``samplers()``), a progressive sampler's first ``n`` points.

    ``seed``: an int >= 0 (one in ``[0, 2^64)`` is the ``--seed`` of the command line, a larger
    one stands for ``numpy.random.SeedSequence(seed)``), a ``numpy.random.SeedSequence``,
    ``Generator`` or ``BitGenerator`` (the mapping is ``Engine``'s, see its docstring).

    ``params`` are the optional parameters some samplers take, by the names their samplers
    declare (``samplers()`` lists each sampler's, with kind, range, default and help):
    ``radius`` (Poisson disk), ``iterations`` (Lloyd, CCVT, ``net02bn``, ``pmj02bn``),
    ``strength`` (``oa-bush``), ``candidates`` (best candidate, ``pmjbn``), ``capacity`` (CCVT).

    >>> strata_sampling.points("jittered", 16, seed=3).shape
    (16, 2)
    """
    n = _v.whole(n, "n", 0, _v.U64_MAX)
    seed = _v.seed_value(seed)
    dims = _v.whole(dims, "dims", 1, _strata.MAX_DIMENSIONS)
    p = _v.sampler_params(params, "points")
    # a refused count is reported before anything is allocated
    err = _strata.count_error(name, n)
    if err is not None:
        raise ValueError(err)
    if n * dims > MAX_VALUES:
        raise ValueError(
            f"points: n x dims = {n} x {dims} = {n * dims} values ({4 * n * dims / 2**30:.3g} GiB "
            f"of float32); allowed: at most 2^31 values per call (8 GiB): draw a progressive "
            f"sampler in parts with Engine.random, or fewer dimensions"
        )
    out = np.empty((n, dims), dtype=np.float32)
    _strata.Sampler(name, n, seed, dims, **p).fill(out)
    return out


class PixelSampler:
    """The path-tracer adapter: stratified, independent values by (pixel, sample index,
    dimension), as ``strata::PixelSampler`` gives them to a renderer.

    ``sequence`` is one of ``strata_sampling.sequences()`` (the Rust crate's declarations: its
    table is in the crate's docs and in ``docs/cli.md``; ``zjoint`` also as ``zjoint-G`` for
    groups of ``G`` dimensions); ``spp`` the samples per pixel
    (used by ``jittered``, which needs a square, ``halton`` and the Z-ordered sequences);
    ``resolution`` the ``(width, height)`` image of the Z-ordered sequences; ``seed`` is taken
    as by ``points`` (the 64-bit seed used is ``.seed``). It pickles and copies (``pickle``,
    ``copy.deepcopy``, ``multiprocessing``): it has no position, values being by pixel and
    sample index.

    >>> ps = strata_sampling.PixelSampler("sobol", 16, seed=7)
    >>> v = ps.sample([3, 4], np.arange(16), dims=5)    # (16, 5) float32
    """

    def __init__(
        self, sequence: str, spp: int, seed: Any = 1, *, resolution: tuple = (256, 256)
    ) -> None:
        spp = _v.whole(spp, "spp", 0, _v.U32_MAX)
        seed = _v.seed_value(seed)
        try:
            w, h = resolution
        except (TypeError, ValueError):
            raise TypeError(
                f"resolution must be a pair (width, height), not {resolution!r}"
            ) from None
        w = _v.whole(w, "resolution width", 0, _v.U32_MAX)
        h = _v.whole(h, "resolution height", 0, _v.U32_MAX)
        self._inner = _strata.PixelSampler(sequence, spp, seed, (w, h))
        self.seed = seed
        self.resolution = (w, h)

    @property
    def sequence(self) -> str:
        """The sequence's name."""
        return str(self._inner.sequence)

    @property
    def spp(self) -> int:
        """Samples per pixel."""
        return int(self._inner.spp)

    def round_count(self, n: int) -> int:
        """The sample count nearest above ``n`` at which the sequence is best stratified."""
        return int(self._inner.round_count(_v.whole(n, "n", 0, _v.U32_MAX)))

    def promised_strata(self, n: int) -> List[tuple]:
        """The grids ``(columns, rows)`` on which the first ``n`` samples of every draw lie,
        each cell holding the same number of points (empty where none is promised)."""
        return list(self._inner.promised_strata(_v.whole(n, "n", 0, _v.U64_MAX)))

    def sample(self, pixels: Any, indices: Any, dims: int = 2, *, first_dim: int = 0) -> np.ndarray:
        """The values of dimensions ``first_dim`` to ``first_dim + dims - 1`` of pixel
        ``pixels`` at sample ``indices``, vectorized with numpy broadcasting.

        ``pixels`` holds integer ``(x, y)`` pairs in its last axis (shape ``(..., 2)``),
        ``indices`` integer sample indices (shape ``(...)``; 0 to 2^64 - 1, Python ints
        beyond int64 included, read exactly); the result has the broadcast
        shape of the two plus ``(dims,)``, float32. Each row is what a renderer gets from
        ``start_pixel_sample(pixel, index, first_dim)`` then ``get_pixel_2d`` (dimensions 0-1),
        ``get_2d`` pairs and, for an odd count, a last ``get_1d`` (Rust's
        ``PixelSampler::fill_sample``): the values ``points --pixel X,Y --dims D`` prints.
        Rows are computed in parallel, without the GIL.
        """
        dims = _v.whole(dims, "dims", 1, _v.U32_MAX)
        first_dim = _v.whole(first_dim, "first_dim", 0, _v.U32_MAX)
        if first_dim + dims - 1 > _v.U32_MAX:
            raise ValueError(
                f"first_dim + dims = {first_dim + dims} goes past dimension 2^32 - 1"
            )
        px = _integers(pixels, "pixels", _v.U32_MAX)
        idx = _integers(indices, "indices", _v.U64_MAX)
        if px.ndim == 0 or px.shape[-1] != 2:
            raise ValueError(f"pixels have shape {px.shape}; (..., 2) pairs (x, y) are needed")
        try:
            batch = np.broadcast_shapes(px.shape[:-1], idx.shape)
        except ValueError:
            raise ValueError(
                f"pixels of shape {px.shape} (pairs in the last axis) and indices of shape "
                f"{idx.shape} do not broadcast together"
            ) from None
        m = int(np.prod(batch, dtype=np.int64))
        px = np.ascontiguousarray(np.broadcast_to(px, batch + (2,)), dtype=np.uint32)
        idx = np.ascontiguousarray(np.broadcast_to(idx, batch), dtype=np.uint64)
        out = np.empty(batch + (dims,), dtype=np.float32)
        if m:
            self._inner.fill(px.reshape(m, 2), idx.reshape(m), out.reshape(m, dims), first_dim)
        return out

    def __repr__(self) -> str:
        return f"PixelSampler({self.sequence!r}, spp={self.spp}, seed={self.seed})"


def _integers(values: Any, what: str, hi: int) -> np.ndarray:
    """An integer array with values in ``[0, hi]``. Python ints (in lists, tuples or alone)
    that numpy would turn into float64 or objects (beyond int64: up to 2^64 - 1, or mixed
    with negative ones) are read exactly, as uint64 or int64."""
    a = np.asarray(values)
    if a.dtype.kind in "fO" and not isinstance(values, np.ndarray):
        exact = _python_ints(values, what, hi)
        if exact is not None:
            a = exact
    if a.dtype == object or a.dtype.kind not in "iu":
        raise TypeError(f"{what} must be integers, not {a.dtype}")
    if a.size:
        lo_v, hi_v = int(a.min()), int(a.max())
        if lo_v < 0 or hi_v > hi:
            bad = lo_v if lo_v < 0 else hi_v
            raise ValueError(f"{what} holds {bad}; allowed: 0 to {hi}")
    return a


def _python_ints(values: Any, what: str, hi: int) -> Optional[np.ndarray]:
    """``values`` (nested lists or tuples of Python or numpy ints, or one int) as an exact
    uint64 array, after checking that every value is in ``[0, hi]`` (``hi < 2^64``); ``None``
    if some value is not an int (a float, a bool, ``None``, ...) or the nesting is ragged."""
    try:
        obj = np.array(values, dtype=object)
    except ValueError:  # ragged
        return None
    flat = obj.reshape(-1).tolist()
    if not flat or not all(
        isinstance(v, (int, np.integer)) and not isinstance(v, (bool, np.bool_)) for v in flat
    ):
        return None
    ints = [int(v) for v in flat]
    lo_v, hi_v = min(ints), max(ints)
    if lo_v < 0 or hi_v > hi:
        bad = lo_v if lo_v < 0 else hi_v
        raise ValueError(f"{what} holds {bad}; allowed: 0 to {hi}")
    return np.array(ints, dtype=np.uint64).reshape(obj.shape)


# ---------------------------------------------------------------------------------------------
# spectra and point-set measures


class Radial(NamedTuple):
    """The radial mean of a spectrum: per ring ``b = 1..K/2`` of frequencies with
    ``round(|w|) = b``, the mean ``power``, the ``anisotropy`` in dB (``10 log10(var /
    mean^2)``, about 0 for one white-noise periodogram, ``-10 log10(R)`` for an isotropic
    pattern averaged over ``R`` sets) and the number of frequencies (``count``)."""

    frequency: np.ndarray
    power: np.ndarray
    anisotropy: np.ndarray
    count: np.ndarray


def _resolution(resolution: Any) -> int:
    k = _v.whole(resolution, "resolution", 0, _v.U32_MAX)
    return k


def spectrum(points: Any, resolution: int, *, method: str = "nufft") -> np.ndarray:
    """The periodogram ``P(u, v) = |sum_k exp(-2 pi i (u x_k + v y_k))|^2 / N`` of a 2D point
    set on the integer frequencies ``|u|, |v| <= K/2`` (``K = resolution``, even, 2 to 2048):
    a ``(K+1, K+1)`` float64 array, row ``v``, column ``u``, DC (``P = N``) in the centre.

    ``points``: ``(n, 2)`` in [0, 1), float32 (used as is) or float64 (rounded to float32).
    ``method``: ``"nufft"`` (a non-uniform FFT, within 1e-7 of the direct sum) or ``"direct"``
    (every exponential summed, ``O(N K^2)``).
    """
    m = _v.method_name(method, ("nufft", "direct"), "spectrum")
    p = _v.points_2d(points, "spectrum")
    return _strata.periodogram(p, _resolution(resolution), m == "direct")


def expected_spectrum(sets: Any, resolution: int) -> np.ndarray:
    """The expected power spectrum: the mean periodogram (see ``spectrum``) of several
    realizations of a pattern, a ``(r, n, 2)`` array or a sequence of ``(n, 2)`` arrays (all
    with the same ``n``). Sets run in parallel and are summed in a fixed order, so the result
    does not depend on the number of threads."""
    s = _v.point_sets(sets, "expected_spectrum")
    return _strata.expected_spectrum(s, _resolution(resolution))


def sampler_spectrum(
    name: str,
    n: int,
    resolution: int,
    *,
    realizations: int = 16,
    seed: Any = 1,
    **params: Any,
) -> np.ndarray:
    """The expected spectrum of sampler ``name`` at ``n`` points (see ``expected_spectrum``)
    over ``realizations`` sets, set ``r`` being ``points(name, n, seed=seed + r, **params)``
    as in the crate's ``spectrum`` program (``seed`` taken as by ``points``, then ``+ r`` on the
    64-bit seed, wrapping); the sets are generated and transformed in parallel, without the
    GIL."""
    n = _v.whole(n, "n", 0, _v.U64_MAX)
    seed = _v.seed_value(seed)
    realizations = _v.whole(realizations, "realizations", 0, _v.U32_MAX)
    p = _v.sampler_params(params, "sampler_spectrum")
    err = _strata.count_error(name, n)
    if err is not None:
        raise ValueError(err)
    return _strata.sampler_spectrum(name, n, _resolution(resolution), realizations, seed, **p)


def radial(spectrum: Any) -> Radial:
    """The radial mean and anisotropy of a ``(K+1, K+1)`` spectrum (as ``spectrum`` and
    ``expected_spectrum`` return): a ``Radial(frequency, power, anisotropy, count)`` of arrays
    over the rings ``1..K/2``."""
    a = np.asarray(spectrum)
    if a.dtype.kind not in "fiu":
        raise TypeError(f"radial: the spectrum must be real numbers, not {a.dtype}")
    if a.ndim != 2:
        raise ValueError(
            f"radial: the spectrum has shape {a.shape}; a (K+1, K+1) array is needed"
        )
    f, p, an, c = _strata.radial(np.ascontiguousarray(a, dtype=np.float64))
    return Radial(f, p, an, c)


def psa(points: Any) -> Dict[str, Any]:
    """The point-set measures of Schlömer's PSA (Heck, Schlömer, Deussen 2013) of one set
    (``(n, 2)``) or averaged over several (``(r, n, 2)`` or a sequence of ``(n, 2)``): a dict of
    ``count``, ``global_min_distance`` and ``average_min_distance`` (toroidal, relative to
    ``r_max(n)``, the spacing of a hexagonal packing; ``None`` for single points, which have no
    neighbour), ``effective_nyquist`` and ``oscillations`` (``None`` above 2^16 points or below
    2)."""
    return dict(_strata.psa(_v.point_sets(points, "psa")))


def nearest_distances(points: Any) -> np.ndarray:
    """The toroidal distance from each point of a 2D set (``(n, 2)``, ``n >= 2``) to its
    nearest neighbour, float64."""
    return _strata.nearest_distances(_v.points_2d(points, "nearest_distances"))


def min_distance(points: Any, *, relative: bool = False) -> float:
    """The smallest toroidal distance between two points of a 2D set; with ``relative``, in
    units of ``r_max(n)`` (1 for a hexagonal packing, about 0.77 for dart throwing)."""
    p = _v.points_2d(points, "min_distance")
    d = float(_strata.nearest_distances(p).min())
    return d / _strata.relative_radius_max(p.shape[0]) if relative else d


def relative_radius_max(n: int) -> float:
    """``r_max(n) = sqrt(2 / (sqrt(3) n))``: the neighbour distance of ``n`` points in a
    hexagonal packing of the unit torus."""
    return float(_strata.relative_radius_max(_v.whole(n, "n", 1, 2**63 - 1)))


def discrepancy(points: Any, method: str = "CD") -> float:
    """The discrepancy of a ``(n, d)`` point set (float32 or float64, coordinates in
    [0, 1]), by scipy's definitions and names: ``"CD"`` (centered L2, squared), ``"WD"``
    (wrap-around, squared), ``"MD"`` (mixture, squared), ``"L2-star"`` (Warnock's formula, not
    squared); and ``"star"``, the exact star discrepancy of a 2D set of at most 16384
    points. Equal to ``scipy.stats.qmc.discrepancy(points, method=method)`` for scipy's
    methods."""
    m = _v.method_name(method, DISCREPANCY_METHODS, "discrepancy")
    return float(_strata.discrepancy(_v.points_any(points, "discrepancy"), m))


def net_t_value(points: Any) -> Optional[int]:
    """The quality parameter ``t`` of a 2D set of ``2^m`` points as a base-2
    ``(t, m, 2)``-net (0 for pmj02 and Sobol' prefixes), or ``None`` when ``n`` is not a power
    of two. Coordinates in [0, 1)."""
    return _strata.net_t_value(_v.points_any(points, "net_t_value"))


# ---------------------------------------------------------------------------------------------
# convergence


def integrands() -> List[Dict[str, Any]]:
    """The test integrands with exact values (``disk``, ``triangle``, ``step``, ``gaussian``,
    ``bilinear`` in 2D; ``gaussian4d``, ``ball4d``), as dicts of ``name``, ``dimensions``,
    ``smooth``, ``exact`` and ``variance`` (of one uniform sample)."""
    return list(_strata.integrands())


def convergence(
    name: str,
    integrand: Union[str, Iterable[str], Callable[[np.ndarray], np.ndarray]],
    ns: Iterable[int],
    seeds: int = 32,
    *,
    predict: bool = True,
    dims: int = 2,
    exact: Optional[float] = None,
) -> List[Dict[str, Any]]:
    """The convergence of sampler ``name`` on ``integrand`` at the counts ``ns``: for each
    count and integrand, the estimates ``(1/N) sum f(x_k)`` over seeds ``0 .. seeds - 1`` (seed
    ``s`` uses exactly ``points(name, N, seed=s)``), as rows of the ``tradeoff`` program's
    ``tradeoff.csv``: dicts of ``sampler``, ``integrand``, ``n``, ``seeds``, ``mean``,
    ``variance`` (unbiased, over seeds), ``rmse`` (against the exact value), ``ns_per_sample``
    (generation time, not deterministic) and ``predicted_variance`` (from the expected
    spectrum, 2D integrands, with ``predict``).

    ``integrand``: a name of ``integrands()`` or a list of names (the crate evaluates them,
    seeds in parallel), or a Python callable taking an ``(N, dims)`` float64 array and
    returning ``N`` values (then ``exact`` gives the RMSE, ``ns_per_sample`` and
    ``predicted_variance`` are ``None``). ``fit_slope`` fits the rate of the variance.
    """
    seeds = _v.whole(seeds, "seeds", 2, _strata.MAX_SEEDS)
    try:
        counts = [_v.whole(n, "n", 1, _strata.MAX_STUDY_COUNT) for n in ns]
    except TypeError:
        if isinstance(ns, (int, np.integer)):
            counts = [_v.whole(ns, "n", 1, _strata.MAX_STUDY_COUNT)]
        else:
            raise
    if callable(integrand):
        return _convergence_callable(name, integrand, counts, seeds, dims, exact)
    try:
        names = [integrand] if isinstance(integrand, str) else list(integrand)
    except TypeError:
        names = [None]
    if not names or not all(isinstance(f, str) for f in names):
        raise TypeError("integrand must be a name, a list of names or a callable")
    return list(_strata.convergence(name, names, counts, seeds, bool(predict)))


def _convergence_callable(
    name: str,
    f: Callable[[np.ndarray], np.ndarray],
    counts: List[int],
    seeds: int,
    dims: int,
    exact: Optional[float],
) -> List[Dict[str, Any]]:
    label = getattr(f, "__name__", "callable")
    rows = []
    for n in counts:
        est = np.empty(seeds)
        for s in range(seeds):
            x = points(name, n, seed=s, dims=dims).astype(np.float64)
            v = np.asarray(f(x), dtype=np.float64)
            if v.shape != (n,):
                raise ValueError(
                    f"convergence: the integrand returned shape {v.shape} for {n} points; "
                    f"({n},) is needed"
                )
            est[s] = v.sum() / n
        # shifted by the first estimate, as the crate does: identical estimates give 0
        d = est - est[0]
        variance = max((np.sum(d * d) - np.sum(d) ** 2 / seeds) / (seeds - 1), 0.0)
        rmse = float(np.sqrt(np.mean((est - exact) ** 2))) if exact is not None else None
        rows.append(
            {
                "sampler": name,
                "integrand": label,
                "n": n,
                "seeds": seeds,
                "mean": float(est.mean()),
                "variance": float(variance),
                "rmse": rmse,
                "ns_per_sample": None,
                "predicted_variance": None,
            }
        )
    return rows


def estimate(integrand: str, points: np.ndarray) -> float:
    """One seed's estimate ``(1/N) sum f(x_k)`` of the integrand named ``integrand`` (one of
    ``integrands()``) over ``points`` (``(N, d)``, ``d`` at least its dimensions), summed in the
    points' order: what ``convergence`` computes for each seed. With ``summarize``, a study
    split over seeds (on several processes or machines) gives ``convergence``'s rows bit for
    bit: ``estimate(f, points(name, N, seed=s))`` for each seed ``s``."""
    a = np.ascontiguousarray(points, dtype=np.float32)
    if a.ndim != 2:
        raise ValueError(f"estimate: points have shape {a.shape}; (N, d) is needed")
    return _strata.estimate(integrand, a)


def summarize(integrand: str, estimates: Iterable[float]) -> Dict[str, float]:
    """The ``mean``, ``variance`` (unbiased) and ``rmse`` (against the exact value) of the
    estimates of ``integrand`` over seeds, given in the seeds' order, as ``convergence``'s rows
    have them."""
    mean, variance, rmse = _strata.summarize(integrand, [float(e) for e in estimates])
    return {"mean": mean, "variance": variance, "rmse": rmse}


def fit_slope(x: Iterable[float], y: Iterable[float]) -> Optional[float]:
    """The least-squares slope of ``log y`` against ``log x`` over the pairs with ``x, y > 0``
    (``None`` with fewer than two): the convergence rate of a variance against ``N``."""
    x, y = list(x), list(y)
    if len(x) != len(y):
        raise ValueError(
            f"fit_slope: x has {len(x)} values and y {len(y)}; they must pair up one to one"
        )
    pairs = [(float(a), float(b)) for a, b in zip(x, y)]
    return _strata.fit_slope(pairs)

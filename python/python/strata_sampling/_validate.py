"""Argument checks shared by the public functions: each turns a bad argument into a
``TypeError`` (wrong kind of thing) or ``ValueError`` (wrong value) that says what was given
and what is allowed, before anything reaches the compiled module."""

from __future__ import annotations

import difflib
import operator
from typing import Any, Dict

import numpy as np

from . import _strata

#: The optional sampler parameters and their kinds (``"whole"`` or ``"real"``), as the samplers
#: of the crate declare them (one declaration per parameter, next to each sampler; see
#: ``strata_sampling.samplers()`` for which sampler takes which, with ranges and defaults).
PARAMETER_KINDS: Dict[str, str] = dict(_strata.parameter_kinds())
SAMPLER_PARAMETERS = tuple(PARAMETER_KINDS)

#: The registered samplers whose points do not depend on the seed, from the registry's
#: ``seeded`` flag (``tests/test_engine.py`` checks every registered sampler against it, two
#: seeds giving the same points exactly for these).
UNSEEDED = frozenset(e["name"] for e in _strata.registry_entries() if not e["seeded"])

#: A seeded sampler to use instead of each unseeded one, for the error messages.
SEEDED_INSTEAD = {"regular": "jittered"}

U32_MAX = 2**32 - 1
U64_MAX = 2**64 - 1

#: The largest float32 below 1: float64 coordinates in [0, 1) that would round up to 1.0 in
#: float32 are stored as this value.
BELOW_ONE_F32 = np.nextafter(np.float32(1.0), np.float32(0.0))


def whole(value: Any, what: str, lo: int, hi: int) -> int:
    """``value`` as a Python int in ``[lo, hi]`` (bools and floats are refused)."""
    if isinstance(value, (bool, np.bool_)):
        raise TypeError(f"{what} must be a whole number, not a bool")
    try:
        v = operator.index(value)
    except TypeError:
        raise TypeError(
            f"{what} must be a whole number ({lo} to {hi}), not {type(value).__name__} {value!r}"
        ) from None
    if v < lo or v > hi:
        raise ValueError(f"{what} = {v} is out of range; allowed: {lo} to {hi}")
    return v


#: What a seed may be, for the error messages.
SEED_KINDS = (
    "an int >= 0 (0 to 2^64 - 1 is the sampler's seed itself, a larger one is hashed), a "
    "numpy.random.SeedSequence, Generator or BitGenerator"
)


def seed_from_sequence(sequence: np.random.SeedSequence) -> int:
    """The 64-bit seed a ``numpy.random.SeedSequence`` stands for: its first two 32-bit words of
    state, ``generate_state(2, numpy.uint32)``, as the low and high halves (the same on every
    platform and for every numpy with ``SeedSequence``)."""
    lo, hi = (int(w) for w in sequence.generate_state(2, np.uint32))
    return lo | (hi << 32)


def seed_value(seed: Any, what: str = "seed") -> int:
    """The 64-bit sampler seed of ``seed``, taken as scipy and numpy take seeds:

    * an int in ``[0, 2^64)`` (Python or numpy) is the seed itself, so its values never change;
    * a larger int ``s`` stands for ``numpy.random.SeedSequence(s)`` (as
      ``numpy.random.default_rng(s)`` reads it), reduced by ``seed_from_sequence``;
    * a ``numpy.random.SeedSequence`` is reduced by ``seed_from_sequence`` (children of
      ``spawn`` give different seeds);
    * a ``numpy.random.Generator`` (or a ``BitGenerator``, wrapped in one) gives one draw,
      ``integers(0, 2**64, dtype=numpy.uint64)``, which advances it: engines made one after the
      other from one generator differ, as scipy's do.

    Negative ints are refused, as ``numpy.random.default_rng`` refuses them; bools, floats and
    anything else are a ``TypeError``.
    """
    if isinstance(seed, np.random.Generator):
        return int(seed.integers(0, 2**64, dtype=np.uint64))
    if isinstance(seed, np.random.BitGenerator):
        return seed_value(np.random.Generator(seed), what)
    if isinstance(seed, np.random.SeedSequence):
        return seed_from_sequence(seed)
    if isinstance(seed, (bool, np.bool_)):
        raise TypeError(f"{what} must be {SEED_KINDS}; not a bool")
    try:
        v = operator.index(seed)
    except TypeError:
        raise TypeError(
            f"{what} must be {SEED_KINDS}; not {type(seed).__name__} {seed!r}"
        ) from None
    if v < 0:
        raise ValueError(
            f"{what} = {v} is out of range; allowed: {SEED_KINDS} (negative ints are refused, "
            "as numpy.random.default_rng refuses them)"
        )
    if v <= U64_MAX:
        return v
    return seed_from_sequence(np.random.SeedSequence(v))


def sampler_params(params: Dict[str, Any], function: str) -> Dict[str, Any]:
    """Checks the names and types of the optional sampler parameters (which samplers take
    which, and their ranges, the crate checks)."""
    out: Dict[str, Any] = {}
    for key, value in params.items():
        if key not in SAMPLER_PARAMETERS:
            close = difflib.get_close_matches(key, SAMPLER_PARAMETERS, n=1)
            hint = f" (did you mean '{close[0]}'?)" if close else ""
            raise TypeError(
                f"{function}() got an unexpected keyword argument '{key}'{hint}; sampler "
                f"parameters: {', '.join(SAMPLER_PARAMETERS)}"
            )
        if value is None:
            continue
        if PARAMETER_KINDS[key] == "real":
            if isinstance(value, (bool, np.bool_)) or not isinstance(
                value, (int, float, np.integer, np.floating)
            ):
                raise TypeError(f"{key} must be a number, not {type(value).__name__}")
            r = float(value)
            if not np.isfinite(r):
                raise ValueError(
                    f"{key} = {r} is not allowed: a finite number (each sampler's range: "
                    "strata_sampling.samplers())"
                )
            out[key] = r
        else:
            out[key] = whole(value, key, 0, U32_MAX)
    return out


def float_array(points: Any, what: str) -> np.ndarray:
    """``points`` as a C-contiguous, native-order float32 or float64 ndarray, following numpy's
    conventions: any array-like (lists, tuples, views, Fortran-ordered or byte-swapped arrays,
    integer arrays) is accepted; float32 and float64 keep their type, other real numbers become
    float64; a copy is made only when the input is not already in that form."""
    if isinstance(points, (str, bytes)):
        raise TypeError(f"{what}: points must be an array of shape (n, d), not a string")
    try:
        a = np.asarray(points)
    except (TypeError, ValueError) as e:
        raise TypeError(
            f"{what}: points must be an array of shape (n, d) of real numbers ({e})"
        ) from None
    if a.dtype.kind == "f" and a.dtype.itemsize in (4, 8):
        native = a.dtype.newbyteorder("=")
    elif a.dtype.kind in "iuf" and a.dtype != object:
        native = np.dtype(np.float64)
    else:
        raise TypeError(
            f"{what}: points have dtype {a.dtype}; real numbers are needed (float32 or "
            f"float64 are used as they are, integers and other floats become float64)"
        )
    return np.ascontiguousarray(a, dtype=native)


def points_any(points: Any, what: str) -> np.ndarray:
    """A ``(n, d)`` float32 or float64 C-contiguous array, not empty."""
    a = float_array(points, what)
    if a.ndim != 2 or a.shape[0] == 0 or a.shape[1] == 0:
        raise ValueError(
            f"{what}: points have shape {a.shape}; (n, d) with n >= 1 and d >= 1 is needed"
        )
    return a


def points_2d(points: Any, what: str) -> np.ndarray:
    """A ``(n, 2)`` float32 C-contiguous array with coordinates in [0, 1) (float64 input is
    checked, then rounded to float32, values just below 1 to the largest float32 below 1)."""
    a = float_array(points, what)
    if a.ndim != 2 or a.shape[1] != 2 or a.shape[0] == 0:
        raise ValueError(f"{what}: points have shape {a.shape}; (n, 2) with n >= 1 is needed")
    if a.dtype == np.float32:
        return a  # the crate checks the range
    bad = ~((a >= 0.0) & (a < 1.0))
    if bad.any():
        i = int(np.argmax(bad.any(axis=1)))
        raise ValueError(
            f"{what}: point {i} is ({a[i, 0]!r}, {a[i, 1]!r}); coordinates must be finite "
            f"and in [0, 1)"
        )
    f = a.astype(np.float32)
    np.minimum(f, BELOW_ONE_F32, out=f)
    return f


def point_sets(sets: Any, what: str) -> list:
    """One or more ``(n, 2)`` sets: a ``(n, 2)`` array is one set, a ``(r, n, 2)`` array or a
    sequence of ``(n, 2)`` arrays is ``r`` sets."""
    if isinstance(sets, (str, bytes)):
        raise TypeError(f"{what}: a point set or a sequence of point sets is needed, not a string")
    if isinstance(sets, (list, tuple)) and sets and not any(
        isinstance(s, np.ndarray) for s in sets
    ):
        try:  # nested lists of numbers: one set (n, 2) or several (r, n, 2)
            sets = np.asarray(sets, dtype=np.float64)
        except (TypeError, ValueError):
            pass  # sets of different sizes: a sequence of sets
    if isinstance(sets, np.ndarray):
        if sets.ndim == 2:
            return [points_2d(sets, what)]
        if sets.ndim == 3:
            return [points_2d(s, f"{what}: set {k}") for k, s in enumerate(sets)]
        raise ValueError(
            f"{what}: an array of shape {sets.shape}; (n, 2) or (r, n, 2) is needed"
        )
    try:
        items = list(sets)
    except TypeError:
        raise TypeError(f"{what}: a point set or a sequence of point sets is needed") from None
    if not items:
        raise ValueError(f"{what}: no point set given; at least one is needed")
    return [points_2d(s, f"{what}: set {k}") for k, s in enumerate(items)]


def method_name(method: Any, allowed: tuple, what: str) -> str:
    """``method`` if it is one of ``allowed``."""
    if not isinstance(method, str) or method not in allowed:
        raise ValueError(f"{what}: unknown method {method!r}; allowed: {', '.join(allowed)}")
    return method


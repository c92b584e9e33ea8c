"""``strata_sampling.Engine``: every sampler as a ``scipy.stats.qmc.QMCEngine``."""

from __future__ import annotations

import copy
from typing import Any, Dict, Optional, Union

import numpy as np
from scipy.stats import qmc

from . import _strata
from . import _validate as _v

#: The most points ``fast_forward`` draws and drops for a sampler that cannot skip.
_MAX_DROPPED = 1 << 31

#: Points drawn at once when fast-forwarding (bounds the memory of a long skip).
_SKIP_CHUNK = 1 << 16


class Engine(qmc.QMCEngine):
    """Sampler ``name`` in ``d`` dimensions as a ``scipy.stats.qmc.QMCEngine``: ``random``,
    ``integers``, ``reset`` and ``fast_forward`` work as for scipy's engines, and so do
    ``qmc.discrepancy``, ``qmc.scale`` and ``scipy.integrate.qmc_quad(..., qrng=engine)``.

    * A **progressive** sampler (``sobol``, ``halton``, ``pmj02``, ``random``, ...) is one
      endless sequence: ``random(n)`` returns its next ``n`` points, so ``random(5)`` then
      ``random(11)`` give the same 16 points as ``strata_sampling.points(name, 16, seed=seed,
      dims=d)``; ``reset`` starts again; ``fast_forward(n)`` skips ``n`` points.
    * A deterministic sampler (``regular``: ``strata_sampling.samplers()`` says ``seeded:
      False``) is refused: its "independent" sets would all be the same, and so would the
      copies ``qmc_quad`` makes to estimate its error. ``jittered`` is its randomized form.
    * A **fixed-count** sampler (``jittered``, ``poisson``, ``oa-bose``, ``ccvt``, ...) makes
      sets of a count it accepts (``Engine.counts`` says which; a refused count raises
      ``ValueError`` naming the nearest allowed ones): each ``random(n)`` returns the next
      independent set of ``n`` points, the first one equal to ``strata_sampling.points(name, n,
      seed=seed, dims=d)``; ``fast_forward(n)`` skips one set of ``n``.

    ``seed``: an int >= 0 (any size, as scipy takes them: one in ``[0, 2^64)`` is the
    sampler's seed itself, the seed of ``strata_sampling.points``; a larger one ``s`` stands for
    ``numpy.random.SeedSequence(s)``), a ``numpy.random.SeedSequence`` (reduced to 64 bits:
    the first two 32-bit words of ``generate_state(2, numpy.uint32)``, low then high), a
    ``numpy.random.Generator`` or ``BitGenerator`` (one 64-bit seed is drawn from it, as
    ``qmc_quad`` does to make independent copies; engines made one after another from one
    generator differ) or ``None`` (fresh entropy). The 64-bit seed used is ``engine.seed``.
    ``rng`` is the same argument under its SPEC 7 name (scipy >= 1.15 calls it so); give one
    of ``seed`` and ``rng``, not both. An int means the same with either name, as it does for
    scipy's engines.

    ``optimization``: scipy's post-processing of each ``random`` call, ``None``,
    ``"random-cd"`` or ``"lloyd"`` (it reorders or moves the sampler's points, so their
    structure is no longer the sampler's). ``params``: the sampler's optional parameters
    (``radius``, ``iterations``, ``strength``, ``candidates``, ``capacity``, ...).

    ``d`` may be 0 for a sampler with D dimensions: ``random(n)`` then has shape ``(n, 0)``,
    as for scipy's engines.

    Points are returned as float64 (scipy's type) holding the sampler's float32 values
    exactly.

    An engine pickles and copies (``pickle``, ``copy.copy``, ``copy.deepcopy``; so
    ``multiprocessing`` and joblib can ship it): the copy is independent and continues exactly
    where the engine stood. Restoring a sampler that cannot skip ahead in constant time
    redraws the points it had given, which costs what drawing them did.
    """

    def __init__(
        self,
        name: str,
        d: int,
        *,
        seed: Union[int, np.random.SeedSequence, np.random.Generator, None] = None,
        rng: Union[int, np.random.SeedSequence, np.random.Generator, None] = None,
        optimization: Optional[str] = None,
        **params: Any,
    ) -> None:
        entry = next((e for e in _strata.registry_entries() if e["name"] == name), None)
        if entry is None:
            _strata.nearest_count(name, 1)  # raises the crate's "unknown sampler" error
        assert entry is not None
        if entry["name"] in _v.UNSEEDED:
            instead = _v.SEEDED_INSTEAD.get(entry["name"], "a seeded sampler")
            raise ValueError(
                f"{name} is deterministic: its points do not depend on the seed, so an Engine "
                f"could not give independent sets, and the copies that "
                f"scipy.integrate.qmc_quad makes would all be equal (a standard error of 0 "
                f"whatever the true error); use '{instead}' (randomized; every sampler but "
                f"{', '.join(sorted(_v.UNSEEDED))} is), or strata_sampling.points({name!r}, n) "
                f"for the points themselves"
            )
        d = _v.whole(d, "d", 0, _strata.MAX_DIMENSIONS)
        self._params: Dict[str, Any] = _v.sampler_params(params, "Engine")
        if seed is not None and rng is not None:
            raise TypeError(
                "Engine() got both seed and rng: they are one argument (rng is its SPEC 7 "
                "name); give one of them"
            )
        if seed is None:
            seed = rng if rng is not None else np.random.default_rng()
        if isinstance(seed, np.random.BitGenerator):
            seed = np.random.Generator(seed)
        self.seed: int = _v.seed_value(seed)
        # scipy's own generator (qmc_quad spawns the copies' seeds from it, "random-cd" draws
        # from it): a child of the generator given, else one seeded by the 64-bit seed
        base_rng = seed if isinstance(seed, np.random.Generator) else None
        if base_rng is None:
            base_rng = np.random.default_rng(self.seed)
        extra = {} if optimization is None else {"optimization": optimization}
        try:
            super().__init__(d=d, rng=base_rng, **extra)
        except TypeError:  # scipy < 1.15 calls it `seed`
            super().__init__(d=d, seed=base_rng, **extra)
        self.name: str = entry["name"]
        self.progressive: bool = bool(entry["progressive"])
        #: The counts a fixed-count sampler accepts, in words ("perfect squares", ...).
        self.counts: str = "any N >= 1" if self.progressive else entry["counts"]
        # what qmc_quad passes to type(engine)(seed=..., **engine._init_quad)
        self._init_quad = {"name": name, "d": d, **extra, **self._params}
        self._sets: Dict[int, Any] = {}
        self._sequence: Optional[Any] = None
        if entry["dimensions"] == "2" and d != 2:
            if d == 0:
                takers = [e["name"] for e in _strata.registry_entries() if e["dimensions"] == "D"]
                raise ValueError(
                    f"{name}: d = 0 is not allowed: {name} has 2-dimensional points only; "
                    f"samplers with D dimensions (0 included, for an empty engine): "
                    f"{', '.join(takers)}"
                )
            self._build(_strata.nearest_count(name, 1))  # raises the crate's error
        if self.progressive:
            self._sequence = self._build(1)

    def _build(self, count: int) -> Any:
        """The sampler for sets of ``count`` (any count for a progressive sequence); ``None``
        for an engine of 0 dimensions, which has no coordinates to draw."""
        if self.d == 0:
            return None
        return _strata.Sampler(self.name, count, self.seed, self.d, **self._params)

    def allowed_counts(self, lo: int, hi: int) -> list:
        """The counts in ``[lo, hi]`` that ``random`` accepts (the crate's list, which refuses
        to list a range of more than 2^24 counts of a sampler that takes any count)."""
        lo = _v.whole(lo, "lo", 0, _v.U64_MAX)
        hi = _v.whole(hi, "hi", 0, _v.U64_MAX)
        return list(_strata.allowed_counts(self.name, lo, hi))

    def _random(self, n: int = 1, *, workers: int = 1) -> np.ndarray:
        n = _v.whole(n, "n", 0, _v.U64_MAX)
        out = np.empty((n, self.d), dtype=np.float32)
        if n == 0:
            return out.astype(np.float64)
        if self.progressive:
            if self._sequence is not None:  # None: 0 dimensions, nothing to draw
                self._sequence.fill(out)
        else:
            err = _strata.count_error(self.name, n)
            if err is not None:
                raise ValueError(
                    f"{err}; a fixed-count engine returns sets of a count it accepts "
                    f"({self.counts}), one independent set per call"
                )
            s = self._sets.get(n)
            if s is None:
                s = self._sets[n] = self._build(n)
            if s is not None:
                s.fill(out)
        return out.astype(np.float64)

    def reset(self) -> "Engine":
        """Starts the sequence (or the sets) again from the beginning."""
        super().reset()
        self._sets.clear()
        if self.progressive:
            self._sequence = self._build(1)
        return self

    def fast_forward(self, n: int) -> "Engine":
        """Skips ``n`` points of a progressive sequence (one set of ``n`` of a fixed-count
        sampler)."""
        n = _v.whole(n, "fast_forward: n", 0, _v.U64_MAX)
        if not self.progressive:
            return super().fast_forward(n)
        if self._sequence is None:  # 0 dimensions: nothing to draw
            self.num_generated += n
            return self
        if self._sequence.skip(n):  # constant time where the crate can (Sobol', the lattice)
            self.num_generated += n
            return self
        if n > _MAX_DROPPED:
            raise ValueError(
                f"fast_forward: {self.name} cannot skip ahead in constant time, so the points "
                f"would be drawn and dropped; allowed: at most {_MAX_DROPPED} ({n} asked)"
            )
        scratch = np.empty((min(n, _SKIP_CHUNK), self.d), dtype=np.float32)
        left = n
        while left > 0:
            k = min(left, _SKIP_CHUNK)
            self._sequence.fill(scratch[:k])
            left -= k
        self.num_generated += n
        return self

    def __copy__(self) -> "Engine":
        """An independent copy, as ``copy.deepcopy`` makes: a shallow copy would share the
        sampler, and two engines would take turns drawing from one stream."""
        return copy.deepcopy(self)

    def __repr__(self) -> str:
        extra = "".join(f", {k}={v!r}" for k, v in self._params.items())
        optimization = getattr(self, "_optimization", None)
        if optimization is not None:
            extra = f", optimization={optimization!r}{extra}"
        return f"Engine({self.name!r}, d={self.d}, seed={self.seed}{extra})"

"""Type stub of the compiled module ``strata_sampling._strata`` (see ``python/src/*.rs``). The public
API is ``strata``; these are its building blocks, with no argument checks beyond the types."""

from typing import Any, Dict, List, Optional, Tuple

import numpy as np
import numpy.typing as npt

MAX_RESOLUTION: int
MAX_DIMENSIONS: int
MAX_FIXED_COUNT: int
MAX_STUDY_COUNT: int
MAX_SEEDS: int
DISCREPANCY_METHODS: List[str]

class Sampler:
    """A registered sampler built as the ``points`` program builds it."""

    def __init__(
        self,
        name: str,
        count: int,
        seed: int,
        dims: int,
        **parameters: Optional[float],
    ) -> None: ...
    def fill(self, out: npt.NDArray[np.float32]) -> None:
        """Writes the next ``out.shape[0]`` points into the C-contiguous ``(n, dims)`` array."""
    def skip(self, n: int) -> bool:
        """Moves ``n`` points on in constant time where the sampler can (Sobol'); False and
        nothing changed otherwise."""
    def __reduce__(self) -> Tuple[Any, Tuple[Any, ...]]:
        """Pickles as ``restore_sampler(name, count, seed, dims, drawn, parameters)``."""
    @property
    def drawn(self) -> int:
        """The points given so far."""
    @property
    def name(self) -> str: ...
    @property
    def dims(self) -> int: ...
    @property
    def count(self) -> int: ...
    @property
    def progressive(self) -> bool: ...

class PixelSampler:
    """The path-tracer adapter."""

    def __init__(
        self, sequence: str, spp: int, seed: int, resolution: Tuple[int, int] = (256, 256)
    ) -> None: ...
    def fill(
        self,
        pixels: npt.NDArray[np.uint32],
        indices: npt.NDArray[np.uint64],
        out: npt.NDArray[np.float32],
        first: int = 0,
    ) -> None:
        """Row ``k`` of ``out`` gets the values of ``pixels[k]`` at sample ``indices[k]``."""
    @property
    def spp(self) -> int: ...
    @property
    def sequence(self) -> str: ...
    def round_count(self, n: int) -> int: ...
    def promised_strata(self, n: int) -> List[Tuple[int, int]]: ...
    def __reduce__(self) -> Tuple[Any, Tuple[Any, ...]]: ...

def restore_sampler(
    name: str,
    count: int,
    seed: int,
    dims: int,
    drawn: int,
    parameters: Optional[Dict[str, float]] = None,
) -> Sampler:
    """Sampler ``name`` moved on by ``drawn`` points (skipped, or drawn and dropped)."""

def registry_entries() -> List[Dict[str, Any]]: ...
def allows_count(name: str, n: int) -> bool: ...
def nearest_count(name: str, n: int) -> int: ...
def allowed_counts(name: str, lo: int, hi: int) -> List[int]: ...
def count_error(name: str, n: int) -> Optional[str]: ...
def sequence_names() -> List[str]: ...
def periodogram(
    points: npt.NDArray[np.float32], resolution: int, direct: bool = False
) -> npt.NDArray[np.float64]: ...
def expected_spectrum(
    sets: List[npt.NDArray[np.float32]], resolution: int
) -> npt.NDArray[np.float64]: ...
def sampler_spectrum(
    name: str,
    count: int,
    resolution: int,
    realizations: int,
    seed: int,
    **parameters: Optional[float],
) -> npt.NDArray[np.float64]: ...
def radial(
    values: npt.NDArray[np.float64],
) -> Tuple[
    npt.NDArray[np.uint32], npt.NDArray[np.float64], npt.NDArray[np.float64], npt.NDArray[np.uint64]
]: ...
def psa(sets: List[npt.NDArray[np.float32]]) -> Dict[str, Any]: ...
def nearest_distances(points: npt.NDArray[np.float32]) -> npt.NDArray[np.float64]: ...
def relative_radius_max(n: int) -> float: ...
def parameter_kinds() -> List[Tuple[str, str]]: ...
def discrepancy(points: npt.NDArray[np.floating[Any]], method: str) -> float: ...
def net_t_value(points: npt.NDArray[np.floating[Any]]) -> Optional[int]: ...
def integrands() -> List[Dict[str, Any]]: ...
def convergence(
    name: str, integrands: List[str], ns: List[int], seeds: int, predict: bool = True
) -> List[Dict[str, Any]]: ...
def estimate(integrand: str, points: np.ndarray) -> float: ...
def summarize(integrand: str, estimates: List[float]) -> Tuple[float, float, float]: ...
def fit_slope(pairs: List[Tuple[float, float]]) -> Optional[float]: ...
def published_rate(name: str, integrand: str) -> Optional[float]: ...

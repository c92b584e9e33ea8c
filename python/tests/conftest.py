"""Shared fixtures: the crate's ``points`` program (built once with cargo, or named by the
``STRATA_POINTS`` environment variable), to compare the package with the command line."""

from __future__ import annotations

import json
import os
import shutil
import struct
import subprocess
from pathlib import Path
from typing import Callable

import numpy as np
import pytest

REPO = Path(__file__).resolve().parents[2]

UTK_MAGIC = 0x214B5455
UTK_F32 = 4


def _build_points() -> str:
    """Builds ``examples/points.rs`` (dev profile, whatever ``CARGO_TARGET_DIR`` says) and
    returns the executable's path."""
    cargo = shutil.which("cargo")
    if cargo is None:
        pytest.skip("cargo is not on PATH; set STRATA_POINTS to the points program")
    r = subprocess.run(
        [cargo, "build", "--example", "points", "--message-format=json-render-diagnostics"],
        cwd=REPO,
        capture_output=True,
        text=True,
    )
    if r.returncode != 0:
        pytest.fail(f"cargo build --example points failed:\n{r.stderr[-4000:]}")
    for line in r.stdout.splitlines():
        msg = json.loads(line)
        if (
            msg.get("reason") == "compiler-artifact"
            and msg["target"]["name"] == "points"
            and msg.get("executable")
        ):
            return msg["executable"]
    pytest.fail("cargo built no points executable")
    raise AssertionError  # unreachable


def parse_utk_bin(data: bytes) -> np.ndarray:
    """One set of a UTK binary file (as ``points --format bin`` writes it) as ``(n, d)``
    float32."""
    magic, kind, sets, n, d = struct.unpack_from("<IB3xIII", data)
    assert magic == UTK_MAGIC and kind == UTK_F32 and sets == 1
    values = np.frombuffer(data, dtype="<f4", offset=20)
    assert values.size == n * d
    return values.reshape(n, d).astype(np.float32)


@pytest.fixture(scope="session")
def points_cli() -> Callable[..., np.ndarray]:
    """``points_cli("--sampler", "sobol", "-n", "16")``: the values the ``points`` program
    prints for these arguments, exactly (read from its UTK binary output)."""
    exe = os.environ.get("STRATA_POINTS") or _build_points()

    def run(*args: str) -> np.ndarray:
        r = subprocess.run(
            [exe, *map(str, args), "--format", "bin"], capture_output=True, check=False
        )
        if r.returncode != 0:
            raise RuntimeError(f"points {' '.join(map(str, args))}: {r.stderr.decode()}")
        return parse_utk_bin(r.stdout)

    return run


@pytest.fixture(scope="session")
def points_cli_error(points_cli: Callable[..., np.ndarray]) -> Callable[..., str]:
    """``points_cli_error(*args)``: the one-line error of the ``points`` program for ``args``."""

    def run(*args: str) -> str:
        try:
            points_cli(*args)
        except RuntimeError as e:
            return str(e)
        raise AssertionError(f"points {args} succeeded")

    return run


def pytest_configure(config: pytest.Config) -> None:
    # scipy's QMCEngineTests (tests/test_scipy_engine.py) carry the marks of scipy's own runs
    config.addinivalue_line(
        "markers", "thread_unsafe: scipy's mark of tests that pytest-run-parallel runs alone"
    )

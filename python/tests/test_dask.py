"""``examples/dask_sweep.py``: its rows are ``ss.convergence``'s and its spectra
``ss.sampler_spectrum``'s bit for bit, in one process and on a ``LocalCluster`` of two worker
processes; a failing seed is reported and resumed, a dying worker loses nothing, and it runs
without Dask. The cluster tests are skipped when ``dask.distributed`` is not installed."""

from __future__ import annotations

import importlib.util
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import strata_sampling as ss

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "dask_sweep.py"
if "dask_sweep" not in sys.modules:  # imported by its name, as a user's `import dask_sweep`
    _spec = importlib.util.spec_from_file_location("dask_sweep", EXAMPLE)
    sys.modules["dask_sweep"] = importlib.util.module_from_spec(_spec)
    _spec.loader.exec_module(sys.modules["dask_sweep"])
ds = sys.modules["dask_sweep"]

# gaussian4d: 4D points for random and sobol (and so their 2D integrands too), none for jittered
SMALL = dict(samplers=("random", "jittered", "sobol"),
             integrands=("disk", "step", "gaussian", "gaussian4d"), ns=(16, 64, 256), seeds=10,
             spectrum_n=256, resolution=32, chunk=3)  # uneven chunks: 3 + 3 + 3 + 1 seeds


def assert_same(a, b) -> None:
    assert a.config == b.config and a.rows == b.rows and a.slopes == b.slopes  # == on floats
    assert a.missing == b.missing
    assert {k: sorted(v) for k, v in a.values.items()} == {
        k: sorted(v) for k, v in b.values.items()}
    for k, d in a.values.items():
        for s, v in d.items():
            assert np.array_equal(v, b.values[k][s]) if k[0] == "spectrum" else v == b.values[k][s]
    assert a.spectra.keys() == b.spectra.keys()
    assert all(np.array_equal(a.spectra[k], b.spectra[k]) for k in a.spectra)


def faulty(*faults):
    """``ds.run_chunk``, failing as ``faults`` say: ``(group, seed, action, times, marker)``,
    action ``"raise"`` or ``"exit"`` (the worker process dies); the first ``times`` attempts
    at that seed fail, counted by the files of the directory ``marker`` (across processes)."""
    inner = ds.run_chunk

    def task(chunk):
        for group, seed, action, times, marker in faults:
            if group == chunk["group"] and seed in chunk["seeds"]:
                os.makedirs(marker, exist_ok=True)
                if (k := len(os.listdir(marker))) < times:
                    open(os.path.join(marker, str(k)), "w").close()
                    if action == "exit":
                        os._exit(70)
                    raise RuntimeError(f"injected fault at seed {seed}")
        return inner(chunk)

    return task


@pytest.fixture(scope="module")
def reference():
    return ds.run(None, **SMALL)


@pytest.fixture(scope="module")
def client():
    distributed = pytest.importorskip("distributed")
    with distributed.Client(n_workers=2, threads_per_worker=1, processes=True,
                            dashboard_address=":0") as c:
        yield c


def test_in_process_equals_the_crates_one_call_studies(reference):
    cfg = reference.config
    rows = [r for name in cfg["samplers"]
            for r in ss.convergence(name, cfg["integrands"], cfg["ns"], cfg["seeds"],
                                    predict=False)]
    keys = ("sampler", "integrand", "n", "seeds", "mean", "variance", "rmse")
    assert reference.rows == [{k: r[k] for k in keys} for r in rows]
    assert {r["sampler"] for r in rows if r["integrand"] == "gaussian4d"} == {"random", "sobol"}
    assert set(reference.slopes) == {(r["sampler"], r["integrand"]) for r in rows}
    for (name, f), slope in reference.slopes.items():
        mine = [r for r in rows if (r["sampler"], r["integrand"]) == (name, f)]
        assert slope == ss.fit_slope(cfg["ns"], [r["variance"] for r in mine])
    for name in cfg["samplers"]:
        e = ss.sampler_spectrum(name, cfg["spectrum_n"], cfg["resolution"],
                                realizations=cfg["seeds"], seed=0)
        assert np.array_equal(reference.spectra[name], e), name


def test_neither_arrival_order_nor_chunk_size_matters(reference):
    arrived = {k: dict(reversed(v.items())) for k, v in reversed(reference.values.items())}
    assert_same(reference, ds.reduce_sweep(ds.Sweep(reference.config, arrived)))
    assert_same(reference, ds.run(None, **{**SMALL, "chunk": 4}))


def test_works_without_dask(monkeypatch):
    # dask made unimportable: the in-process sweep runs, the CLI says what to install
    code = (
        "import sys; sys.modules['dask'] = sys.modules['distributed'] = None; "
        f"sys.path.insert(0, {str(EXAMPLE.parent)!r}); import dask_sweep as d; "
        "s = d.run(None, samplers=('jittered',), ns=(16,), seeds=2, spectrum_n=16, "
        "resolution=8); assert not s.missing and len(s.rows) == 2; print('ok'); "
        "sys.exit(d.main(['--seeds', '2']))"
    )
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60)
    assert r.stdout.startswith("ok"), r.stderr
    assert r.returncode == 2 and 'pip install "dask[distributed]"' in r.stderr
    monkeypatch.setitem(sys.modules, "distributed", None)
    with pytest.raises(ImportError, match="dask"):  # a client given, no Dask: the same message
        ds.run(object(), **SMALL)


def test_distributed_equals_one_process_bit_for_bit(client, reference):
    from distributed import get_task_stream

    with get_task_stream(client) as ts:
        s = ds.run(client, **SMALL)
    assert len({t["worker"] for t in ts.data}) == 2  # both workers ran tasks
    assert_same(reference, s)


def test_a_failing_seed_is_reported_kept_apart_and_resumed(client, reference, tmp_path, capsys):
    jit, sob = ("convergence", "jittered", 64), ("spectrum", "sobol", 256)
    s = ds.run(client, **SMALL, task=faulty(
        (jit, 4, "raise", 99, str(tmp_path / "a")),  # always
        (sob, 9, "raise", 99, str(tmp_path / "b")),
        (("convergence", "sobol", 16), 7, "raise", 2, str(tmp_path / "c")),  # retried away
    ))
    assert sorted((m["study"], m["sampler"], m["n"], m["seeds"]) for m in s.missing) == [
        (*jit, [3, 4, 5]), (*sob, [9])]
    assert all("RuntimeError: injected fault" in m["error"] for m in s.missing)
    assert [len(os.listdir(tmp_path / d)) for d in "abc"] == [3, 3, 2]  # 1 + retries=2
    err = capsys.readouterr().err
    assert "missing: convergence jittered n=64 seeds [3, 4, 5]: RuntimeError" in err
    assert "missing: spectrum sobol n=256 seeds [9]: RuntimeError" in err
    lost = {jit: {3, 4, 5}, sob: {9}}
    for k, d in reference.values.items():  # every other seed kept
        assert set(s.values.get(k, {})) == set(d) - lost.get(k, set()), k
        for seed, v in s.values.get(k, {}).items():
            assert np.array_equal(v, d[seed]) if k[0] == "spectrum" else v == d[seed]
    assert s.rows == [r for r in reference.rows if (r["sampler"], r["n"]) != ("jittered", 64)]
    assert set(s.slopes) == {k for k in reference.slopes if k[0] != "jittered"}
    assert set(s.spectra) == {"random", "jittered"}
    s.save(tmp_path / "sweep.pkl")
    ran = []

    def counting(chunk):
        ran.append((chunk["group"], chunk["seeds"]))
        return ds.run_chunk(chunk)

    done = ds.run(None, **SMALL, previous=ds.Sweep.load(tmp_path / "sweep.pkl"), task=counting)
    assert sorted(ran) == [(jit, [3, 4, 5]), (sob, [9])]  # only what was missing
    assert_same(reference, done)


def test_a_worker_dying_mid_sweep_loses_nothing(client, reference, tmp_path):
    # a worker process exits in the middle of a task: the nanny restarts it, the scheduler
    # reruns what it held, and the sweep is complete and unchanged
    deaths = tmp_path / "deaths"
    s = ds.run(client, **SMALL, task=faulty((("spectrum", "jittered", 256), 5, "exit", 1,
                                             str(deaths))))
    assert len(os.listdir(deaths)) == 1
    assert_same(reference, s)

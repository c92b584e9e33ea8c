"""A convergence study and expected spectra over seeds on Dask: a template for splitting a study.

    python dask_sweep.py                               # a LocalCluster, one worker per core
    python dask_sweep.py --workers 4 --save sweep.pkl  # 4 workers; the results kept in a file
    python dask_sweep.py --scheduler tcp://HOST:8786   # a running cluster
    python dask_sweep.py --resume sweep.pkl --save sweep.pkl   # only the seeds it misses
    python dask_sweep.py --in-process                  # no Dask

A task, a chunk of seeds of one sampler at one count, calls the package only: ``ss.points``
then ``ss.estimate`` or ``ss.spectrum`` per seed. Here the per-seed results are taken in seed
order, whatever order they arrived in, into ``ss.summarize`` and ``ss.fit_slope``, and the
periodograms summed in seed order over their number as ``ss.sampler_spectrum`` does (merging
chunks' own ``sampler_spectrum`` would regroup that sum and change the last bits). So the rows
are ``ss.convergence(sampler, integrands, ns, seeds, predict=False)``'s and the spectra
``ss.sampler_spectrum(sampler, n, K, realizations=seeds, seed=0)``, bit for bit, on any
cluster. As in ``convergence``, with a 4D integrand a sampler with 4 dimensions draws 4D points
for every integrand, and one without skips the 4D ones. Tasks retry; a worker that dies loses
nothing fetched; a chunk that still fails is printed and listed in ``Sweep.missing``, the rest
kept, and ``run(..., previous=sweep)`` (``--resume``) computes only what is missing.
"""

from __future__ import annotations

import argparse
import os
import pickle
import sys
import time
import uuid
from dataclasses import dataclass, field
from typing import Any, Callable, Dict, List, Optional, Sequence

import numpy as np

import strata_sampling as ss

DASK_MISSING = ('the distributed sweep needs Dask: pip install "dask[distributed]" '
                "(or run in this process: run(client=None), --in-process)")
DIMS = {f["name"]: f["dimensions"] for f in ss.integrands()}


def run_chunk(chunk: Dict[str, Any]) -> List[Any]:
    """One task (plain data in and out): per seed of ``chunk["seeds"]``, the estimates
    ``{integrand: value}`` or the periodogram."""
    name, n, seeds = chunk["sampler"], chunk["n"], chunk["seeds"]
    if chunk["study"] == "spectrum":
        return [ss.spectrum(ss.points(name, n, seed=s), chunk["resolution"]) for s in seeds]
    xs = (ss.points(name, n, seed=s, dims=chunk["dims"]) for s in seeds)
    return [{f: ss.estimate(f, x) for f in chunk["integrands"]} for x in xs]


@dataclass
class Sweep:
    """``values[(study, sampler, n)][seed]``: the per-seed results, kept when other seeds fail;
    ``missing``: the failed chunks (``study``, ``sampler``, ``n``, ``seeds``, ``error``);
    ``rows``, ``slopes`` and ``spectra``: reduced from the complete groups only."""

    config: Dict[str, Any]
    values: Dict[tuple, Dict[int, Any]] = field(default_factory=dict)
    missing: List[Dict[str, Any]] = field(default_factory=list)
    rows: List[Dict[str, Any]] = field(default_factory=list)
    slopes: Dict[tuple, Optional[float]] = field(default_factory=dict)
    spectra: Dict[str, np.ndarray] = field(default_factory=dict)

    def save(self, path: str) -> None:
        with open(f"{path}.tmp", "wb") as fh:  # plain data: loads without this module
            pickle.dump((self.config, self.values, self.missing), fh)
        os.replace(f"{path}.tmp", path)

    @classmethod
    def load(cls, path: str) -> Sweep:
        with open(path, "rb") as fh:
            return reduce_sweep(cls(*pickle.load(fh)))


def chunks(cfg: Dict[str, Any], size: int) -> List[Dict[str, Any]]:
    """The tasks' arguments: ``size`` seeds of one group each."""
    out: List[Dict[str, Any]] = []

    def add(study: str, name: str, n: int, **kw: Any) -> None:
        for a in range(0, cfg["seeds"], size):
            out.append(dict(study=study, sampler=name, n=n, group=(study, name, n),
                            seeds=list(range(a, min(a + size, cfg["seeds"]))), **kw))

    for name in cfg["samplers"]:
        for n in cfg["ns"]:
            dims = max(DIMS[f] for f in cfg["integrands"])
            try:  # the dimensions ss.convergence draws: the integrands', if the sampler has them
                ss.points(name, n, dims=dims)
            except ValueError:
                dims = 2
            if fs := [f for f in cfg["integrands"] if DIMS[f] <= dims]:
                add("convergence", name, n, integrands=fs, dims=dims)
        add("spectrum", name, cfg["spectrum_n"], resolution=cfg["resolution"])
    return out


def reduce_sweep(sweep: Sweep) -> Sweep:
    """Rows, slopes and spectra from the per-seed values, taken in seed order."""
    cfg, seeds = sweep.config, list(range(sweep.config["seeds"]))
    sweep.rows, sweep.slopes, sweep.spectra = [], {}, {}
    for name in cfg["samplers"]:
        done = 0
        for n in cfg["ns"]:
            got = sweep.values.get(("convergence", name, n), {})
            if sorted(got) == seeds:
                done += 1
                for f in got[0]:
                    e = [got[s][f] for s in seeds]
                    sweep.rows.append({"sampler": name, "integrand": f, "n": n,
                                       "seeds": len(e), **ss.summarize(f, e)})
        for f in cfg["integrands"] if done == len(cfg["ns"]) else ():
            rs = [r for r in sweep.rows if (r["sampler"], r["integrand"]) == (name, f)]
            if rs:
                sweep.slopes[(name, f)] = ss.fit_slope([r["n"] for r in rs],
                                                       [r["variance"] for r in rs])
        got = sweep.values.get(("spectrum", name, cfg["spectrum_n"]), {})
        if sorted(got) == seeds:
            acc = np.zeros_like(got[0])
            for s in seeds:
                acc += got[s]
            sweep.spectra[name] = acc / len(seeds)
    return sweep


def run(client: Any = None, *,
        samplers: Sequence[str] = ("random", "jittered", "pmj02bn", "sobol"),
        integrands: Sequence[str] = ("disk", "gaussian", "gaussian4d"),
        ns: Sequence[int] = (16, 64, 256, 1024), seeds: int = 64, spectrum_n: int = 1024,
        resolution: int = 128, chunk: int = 8, retries: int = 2,
        previous: Optional[Sweep] = None, task: Callable = run_chunk) -> Sweep:
    """The sweep on ``client`` (a ``distributed.Client``) or, with ``None``, in this process,
    with the same bits. ``chunk`` seeds per task, each retried ``retries`` times. With
    ``previous`` (a ``Sweep`` of the same arguments) only its missing seeds are computed.
    ``task``: the function of a chunk (tests wrap it to inject faults)."""
    cfg = dict(samplers=list(samplers), integrands=list(integrands), ns=[int(n) for n in ns],
               seeds=int(seeds), spectrum_n=int(spectrum_n), resolution=int(resolution))
    if seeds < 2 or chunk < 1 or not set(integrands) <= set(DIMS):
        raise ValueError(f"seeds >= 2, chunk >= 1 and integrands of {', '.join(DIMS)} needed")
    for name, n in [(name, n) for name in samplers for n in [*cfg["ns"], cfg["spectrum_n"]]]:
        if ss.nearest_count(name, n) != n:
            raise ValueError(f"{name} does not take n = {n}; see ss.allowed_counts")
    sweep = Sweep(cfg)
    if previous is not None:
        if previous.config != cfg:
            raise ValueError("previous: a sweep of other arguments")
        sweep.values = {k: dict(v) for k, v in previous.values.items()}
    todo = [c for c in chunks(cfg, chunk)
            if not set(c["seeds"]) <= set(sweep.values.get(c["group"], ()))]
    if client is None:
        for c in todo:
            for attempt in range(retries + 1):
                try:
                    _store(sweep, c, task(c))
                    break
                except Exception as e:  # noqa: BLE001 - reported, not fatal
                    if attempt == retries:
                        _fail(sweep, c, e)
    else:
        _run_on(client, todo, task, retries, sweep)
    for m in sweep.missing:
        print(f"missing: {m['study']} {m['sampler']} n={m['n']} seeds {m['seeds']}: {m['error']}",
              file=sys.stderr)
    return reduce_sweep(sweep)


def _store(sweep: Sweep, c: Dict[str, Any], values: List[Any]) -> None:
    sweep.values.setdefault(c["group"], {}).update(zip(c["seeds"], values))


def _fail(sweep: Sweep, c: Dict[str, Any], e: BaseException) -> None:
    sweep.missing.append({"study": c["study"], "sampler": c["sampler"], "n": c["n"],
                          "seeds": c["seeds"], "error": f"{type(e).__name__}: {e}"})


def _run_on(client: Any, todo: List[Dict[str, Any]], task: Callable, retries: int,
            sweep: Sweep) -> None:
    try:
        from distributed import as_completed
    except ImportError as e:
        raise ImportError(DASK_MISSING) from e
    if __name__ != "__main__":  # imported, not run: the scheduler and workers import it too
        client.upload_file(__file__)  # (a script's functions travel by value)
    run_id = uuid.uuid4().hex[:8]  # fresh keys: nothing reused from an earlier run
    keys = [f"{c['study']}-{c['sampler']}-{c['n']}-seeds{c['seeds'][0]}-{run_id}" for c in todo]
    chunk_of, pending = dict(zip(keys, todo)), set(keys)
    futures = client.map(task, todo, key=keys, retries=retries)
    try:
        for fut in as_completed(futures):  # one result at a time, kept here, then released
            try:
                _store(sweep, chunk_of[fut.key], fut.result())
            except (KeyboardInterrupt, SystemExit):
                raise
            except BaseException as e:  # noqa: BLE001 - its error after retries, KilledWorker
                _fail(sweep, chunk_of[fut.key], e)
            pending.discard(fut.key)
            fut.release()
    except Exception as e:  # noqa: BLE001 - e.g. the scheduler is gone: keep what came back
        for k in sorted(pending):
            _fail(sweep, chunk_of[k], e)


def report(sweep: Sweep, seconds: float) -> None:
    cfg = sweep.config
    print(f"variance slope over n = {cfg['ns']} ({cfg['seeds']} seeds), then RMSE by n")
    for (name, f), slope in sweep.slopes.items():
        rmse = [r["rmse"] for r in sweep.rows if (r["sampler"], r["integrand"]) == (name, f)]
        slope = "-" if slope is None else f"{slope:.2f}"
        print(f"  {name:<10} {f:<11} {slope:>6} ", *(f"{x:.2e}" for x in rmse))
    print(f"expected spectra, n = {cfg['spectrum_n']}: radial power at f = sqrt(n) / 2, sqrt(n)")
    for name, e in sweep.spectra.items():
        r, k = ss.radial(e), cfg["spectrum_n"] ** 0.5
        print(f"  {name:<10}", *(f"{p:8.4f}" for p in np.interp([k / 2, k], *r[:2])))
    lost = sum(len(m["seeds"]) for m in sweep.missing)
    print(f"{seconds:.1f} s; " + (f"MISSING {lost} seeds (see above)" if lost else "complete"))


def main(argv: Optional[Sequence[str]] = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--scheduler", metavar="ADDR", help="tcp://HOST:8786 (default: a LocalCluster)")
    ap.add_argument("--workers", type=int, help="LocalCluster workers (default: one per core)")
    ap.add_argument("--in-process", action="store_true", help="no Dask")
    ap.add_argument("--seeds", type=int, default=64, help="seeds per count (default 64)")
    ap.add_argument("--chunk", type=int, default=8, help="seeds per task (default 8)")
    ap.add_argument("--save", metavar="FILE", help="write the results to FILE")
    ap.add_argument("--resume", metavar="FILE", help="compute only what FILE misses")
    args = ap.parse_args(argv)
    kw = dict(seeds=args.seeds, chunk=args.chunk,
              previous=Sweep.load(args.resume) if args.resume else None)
    t = time.perf_counter()
    if args.in_process:
        sweep = run(None, **kw)
    else:
        try:
            from distributed import Client
        except ImportError:
            print(f"error: {DASK_MISSING}", file=sys.stderr)
            return 2
        where = (dict(address=args.scheduler) if args.scheduler  # else a LocalCluster
                 else dict(n_workers=args.workers, threads_per_worker=1))
        with Client(**where) as client:
            sweep = run(client, **kw)
    report(sweep, time.perf_counter() - t)
    if args.save:
        sweep.save(args.save)
    return 1 if sweep.missing else 0


if __name__ == "__main__":
    sys.exit(main())

"""Where a study's sweeps run: in this process (numba threads), a local process pool, or Dask.

IDA, multiple stripes and the collapse-acceleration curves search collapse boundaries in rounds
(a scan, then bisection steps); every round is one list of items (arch, motion, scale) for
:func:`archrock.dynamics.sweep.sweep`.  A :class:`SweepRunner` holds the packed arches and motions and runs
round after round on one executor, as ``ensemble`` does:

* in-process (default): the numba ``prange`` loop over the items, all numba threads;
* ``workers`` N > 1: a local process pool of N workers (one core each, serial compiled loop); the
  arches and motions are sent to each worker once, when it starts;
* ``scheduler``: an existing Dask cluster (an address or a ``distributed.Client``); the arches
  and motions are scattered to every worker once.

The items of a round are cut into chunks so that progress can be shown; results never depend on
the executor or the chunks (each item is independent).

With ``pulses=(kind, sign, durations)`` (the collapse-acceleration curves) an item carries its own
motion: item (arch, j, a) is arch under ``pulse(kind, sign * a, durations[j])``, scale 1, the very
motion ``respond`` gets in :func:`archrock.studies.curves.collapse_amplitude`.  The pulses are built where
the item runs (a worker gets four numbers per item, not the samples), at most :data:`PULSE_CHUNK`
items per sweep call to bound their memory.
"""

from __future__ import annotations

import os

import numpy as np

from ..errors import ArchInputError
from ..dynamics.sweep import SweepArches, SweepMotions, sweep

__all__ = ["SweepRunner", "ResultStore", "check_workers"]

_STATE: dict = {}


def check_workers(workers) -> int | None:
    """``workers`` as None (in-process) or an integer >= 1 (1 is in-process too)."""
    if workers is None:
        return None
    if isinstance(workers, bool) or not isinstance(workers, (int, np.integer)) or workers < 1:
        raise ArchInputError(f"workers: {workers!r}; allowed an integer >= 1")
    return int(workers)


def _init_worker(parent, arches, motions):
    from .ensemble.executors import _worker_init

    _worker_init(parent)
    _STATE["arches"] = SweepArches.from_arrays(arches)
    _STATE["motions"] = SweepMotions(**motions)


#: items per sweep call when each item carries its own pulse (``pulses``, module doc)
PULSE_CHUNK = 4096
#: least items per in-process chunk (one parallel call each)
IN_PROCESS_CHUNK = 2048


def _sweep_items(arches, motions, a, m, s, pulses, **kw):
    """:func:`~archrock.dynamics.sweep.sweep` of the items; with ``pulses`` (module doc) motion m is the
    index of a duration and s the pulse's |amplitude| [g], each item's pulse built here."""
    if pulses is None:
        return sweep(arches, motions, a, m, s, **kw)
    from ..groundmotion import pulse

    kind, sign, durations = pulses
    n = len(a)
    own = SweepMotions.of([pulse(kind, sign * float(x), float(durations[j]))
                           for j, x in zip(m, s)])
    return sweep(arches, own, a, np.arange(n), np.ones(n), **kw)


def _pool_chunk(a, m, s, max_events, early_stop, pulses=None):
    return _sweep_items(_STATE["arches"], _STATE["motions"], a, m, s, pulses, parallel=False,
                        max_events=max_events, early_stop=early_stop)


def _dask_chunk(arches, motions, a, m, s, max_events, early_stop, pulses=None):
    return _sweep_items(SweepArches.from_arrays(arches), SweepMotions(**motions), a, m, s,
                        pulses, parallel=False, max_events=max_events, early_stop=early_stop)


#: columns of a stored chunk of items (:class:`ResultStore`)
_STORED = ("status", "peak", "t_collapse", "t_unstable", "t_limit", "n_events")
STORE_FORMAT = "archrock-sweep/1"


def _digest(arches: SweepArches, motions: SweepMotions, extra: dict) -> str:
    """sha256 of everything an item's result depends on: the packed arches and motions (their
    bytes), the run settings and the package's sources."""
    import hashlib
    import json

    from .._jit import _package_digest

    h = hashlib.sha256()
    for name, arr in sorted(arches.arrays().items()) + [
            (k, v) for k, v in sorted(motions.arrays().items()) if k != "names"]:
        a = np.ascontiguousarray(arr)
        h.update(f"{name}\0{a.dtype.str}\0{a.shape}\0".encode())
        h.update(a.tobytes())
    h.update(json.dumps(extra, sort_keys=True).encode())
    h.update(_package_digest().encode())
    return h.hexdigest()


class ResultStore:
    """Finished items of a study's sweeps kept in a folder (``--out DIR``), so that a killed
    study started again recomputes nothing it had finished: ``manifest.json`` (format, the
    digest of the inputs, what the study is) and ``items/chunk-NNNNN.parquet`` (arch, motion,
    scale and the results of each item), each written atomically.  A folder holding another
    study's items (another digest) is refused.  Needs pyarrow (the 'ensemble' extra)."""

    def __init__(self, folder, arches, motions, *, about: dict | None = None,
                 settings: dict | None = None):
        from pathlib import Path

        try:
            import pyarrow.parquet as pq  # noqa: F401
        except ImportError:
            raise ImportError("--out needs pyarrow: pip install 'archrock[ensemble]'") from None
        self.folder = Path(folder)
        self.digest = _digest(arches, motions, settings or {})
        man = self.folder / "manifest.json"
        import json

        if man.exists():
            try:
                old = json.loads(man.read_text(encoding="utf-8"))
            except (OSError, ValueError) as exc:
                raise ArchInputError(f"out: {str(man)!r} cannot be read ({exc}); allowed a "
                                     f"folder written by this study, or a new one") from None
            if old.get("format") != STORE_FORMAT or old.get("digest") != self.digest:
                raise ArchInputError(f"out: {str(self.folder)!r} holds another study (other "
                                     f"arches, records, settings or archrock version); allowed "
                                     f"the folder of this very study, or a new one")
        else:
            self.folder.mkdir(parents=True, exist_ok=True)
            tmp = man.with_name(f"manifest.json.tmp-{os.getpid()}")
            tmp.write_text(json.dumps({"format": STORE_FORMAT, "digest": self.digest,
                                       "study": about or {}}, indent=2), encoding="utf-8")
            os.replace(tmp, man)
        (self.folder / "items").mkdir(exist_ok=True)
        for stale in (self.folder / "items").glob("*.tmp-*"):
            stale.unlink()
        self.done: dict = {}
        self.next = 0  # number of the next chunk file: after every existing one, never reused
        for f in sorted((self.folder / "items").glob("chunk-*.parquet")):
            try:
                self._load(f)
            except Exception:  # noqa: BLE001 - an unreadable chunk is recomputed, not fatal
                continue
            finally:
                num = f.stem.split("-")[-1]
                if num.isdigit():
                    self.next = max(self.next, int(num) + 1)
        self.loaded = len(self.done)

    @staticmethod
    def _key(a, m, s):
        return (int(a), int(m), float(s))

    def _load(self, path):
        import pyarrow.parquet as pq

        tab = pq.read_table(path).to_pydict()
        for i, (a, m, s) in enumerate(zip(tab["arch"], tab["motion"], tab["scale"])):
            self.done[self._key(a, m, s)] = tuple(tab[c][i] for c in _STORED)

    def lookup(self, a, m, s):
        """(indices of items found, their rows), the rest missing."""
        return [self.done.get(self._key(*x)) for x in zip(a, m, s)]

    def write(self, a, m, s, res):
        import pyarrow as pa
        import pyarrow.parquet as pq

        cols = {"arch": np.asarray(a, np.int64), "motion": np.asarray(m, np.int64),
                "scale": np.asarray(s, float), **{c: np.asarray(res[c]) for c in _STORED}}
        path = self.folder / "items" / f"chunk-{self.next:05d}.parquet"
        tmp = path.with_name(f"{path.name}.tmp-{os.getpid()}")
        pq.write_table(pa.table(cols), tmp)
        os.replace(tmp, path)
        self.next += 1
        for i, key in enumerate(zip(a, m, s)):
            self.done[self._key(*key)] = tuple(cols[c][i].item() for c in _STORED)


class SweepRunner:
    """Runs item lists on one executor (module doc); use as a context manager.  pulses:
    (kind, sign, durations) when each item carries its own pulse (module doc); ``motions`` are
    then the unit pulses of the durations (what a :class:`ResultStore`'s digest reads)."""

    def __init__(self, arches: SweepArches, motions: SweepMotions, *, workers=None,
                 scheduler=None, max_events: int | None = None, early_stop: bool = False,
                 bar=None, store: ResultStore | None = None, pulses=None):
        self.arches, self.motions = arches, motions
        self.pulses = None if pulses is None else (
            str(pulses[0]), int(pulses[1]), tuple(float(x) for x in pulses[2]))
        self.workers = check_workers(workers)
        self.scheduler = scheduler
        self.max_events = max_events
        self.early_stop = bool(early_stop)
        self.bar = bar
        self.store = store
        self.pool = self.client = None
        self.responses = 0
        self.executor = "in-process"

    def __enter__(self):
        if self.scheduler is not None:
            self._start_dask()
        elif self.workers is not None and self.workers > 1:
            self._start_pool()
        return self

    def _start_pool(self):
        import multiprocessing as mp
        from concurrent.futures import ProcessPoolExecutor

        n = min(self.workers, os.cpu_count() or 1) if self.workers else 1
        self.pool = ProcessPoolExecutor(
            max_workers=n, mp_context=mp.get_context("spawn"), initializer=_init_worker,
            initargs=(os.getpid(), self.arches.arrays(), self.motions.arrays()))
        self.n_parts = n
        self.executor = f"process pool ({n})"

    def _start_dask(self):
        try:
            from distributed import Client
        except ImportError:
            raise ImportError("running on a Dask cluster needs the 'dask' extra: "
                              "pip install 'archrock[dask]'") from None
        from .ensemble.executors import SCHEDULER_TIMEOUT_S

        self.own = not isinstance(self.scheduler, Client)
        if self.own:
            try:
                self.client = Client(self.scheduler, timeout=SCHEDULER_TIMEOUT_S)
            except (OSError, ValueError, TypeError) as exc:
                reason = " ".join(str(exc).split()) or type(exc).__name__
                raise ArchInputError(f"scheduler: cannot connect to {self.scheduler!r} "
                                     f"({reason})") from None
        else:
            self.client = self.scheduler
        self.remote = (self.client.scatter(self.arches.arrays(), broadcast=True),
                       self.client.scatter(self.motions.arrays(), broadcast=True))
        self.n_parts = max(1, sum(self.client.nthreads().values()))
        self.executor = "dask"

    def __exit__(self, exc_type, exc, tb):
        if self.pool is not None:
            if exc_type is not None:
                procs = list((getattr(self.pool, "_processes", None) or {}).values())
                self.pool.shutdown(wait=False, cancel_futures=True)
                for p in procs:
                    if p.is_alive():
                        p.terminate()
            else:
                self.pool.shutdown(wait=True)
        if self.client is not None and self.own:
            self.client.close()
        return False

    def __call__(self, arch_index, motion_index, scales) -> dict:
        """Results of :func:`~archrock.dynamics.sweep.sweep` for the items, in their order (items kept in
        the :class:`ResultStore` are read, not run again)."""
        a = np.asarray(arch_index, dtype=np.int64).ravel()
        m = np.asarray(motion_index, dtype=np.int64).ravel()
        s = np.asarray(scales, dtype=float).ravel()
        if self.store is None:
            return self._run(a, m, s)
        rows = self.store.lookup(a, m, s)
        todo = np.array([i for i, r in enumerate(rows) if r is None], dtype=np.int64)
        if a.size - todo.size and self.bar is not None:
            self.bar.update(a.size - todo.size)
        new = self._run(a[todo], m[todo], s[todo])
        out = {c: np.zeros(a.size, dtype=new[c].dtype) for c in _STORED}
        for c_i, c in enumerate(_STORED):
            for i, r in enumerate(rows):
                if r is not None:
                    out[c][i] = r[c_i]
            out[c][todo] = new[c]
        return out

    def _run(self, a, m, s) -> dict:
        N = a.size
        if N == 0:
            return {"status": np.zeros(0, dtype=np.int64), "peak": np.zeros(0),
                    "t_collapse": np.zeros(0), "t_unstable": np.zeros(0),
                    "t_limit": np.zeros(0), "n_events": np.zeros(0, dtype=np.int64)}
        parts = getattr(self, "n_parts", 1)
        # a few chunks per worker (load balance), at most ~20 per round (progress), >= 64 items
        n_chunks = max(1, min(max(4 * parts, 20 if self.bar is not None else 1), N // 64))
        if self.pool is None and self.client is None:
            # in-process, every chunk is one parallel call that waits for its slowest item:
            # small chunks leave threads idle (items differ in cost by orders of magnitude)
            n_chunks = max(1, min(n_chunks, N // IN_PROCESS_CHUNK))
        if self.pulses is not None:  # each item's pulse in memory: bounded chunks
            n_chunks = max(n_chunks, -(-N // PULSE_CHUNK))
        edges = np.linspace(0, N, n_chunks + 1).astype(int)
        chunks = [(edges[i], edges[i + 1]) for i in range(n_chunks) if edges[i + 1] > edges[i]]
        out = [None] * len(chunks)
        if self.pool is not None or self.client is not None:
            if self.pool is not None:
                futs = {self.pool.submit(_pool_chunk, a[i:j], m[i:j], s[i:j], self.max_events,
                                         self.early_stop, self.pulses): c
                        for c, (i, j) in enumerate(chunks)}
                from concurrent.futures import as_completed
            else:
                from distributed import as_completed

                futs = {self.client.submit(_dask_chunk, *self.remote, a[i:j], m[i:j], s[i:j],
                                           self.max_events, self.early_stop, self.pulses,
                                           pure=False): c
                        for c, (i, j) in enumerate(chunks)}
            for fut in as_completed(list(futs)):
                c = futs[fut]
                out[c] = fut.result()
                self._keep(a, m, s, chunks[c], out[c])
                self._done(chunks[c][1] - chunks[c][0])
        else:
            for c, (i, j) in enumerate(chunks):
                out[c] = _sweep_items(self.arches, self.motions, a[i:j], m[i:j], s[i:j],
                                      self.pulses, max_events=self.max_events,
                                      early_stop=self.early_stop)
                self._keep(a, m, s, (i, j), out[c])
                self._done(j - i)
        res = {k: np.concatenate([o[k] for o in out]) for k in out[0] if k != "seconds"}
        return res

    def _keep(self, a, m, s, chunk, res):
        if self.store is not None:
            i, j = chunk
            self.store.write(a[i:j], m[i:j], s[i:j], res)

    def _done(self, n):
        self.responses += n
        if self.bar is not None:
            self.bar.update(n)

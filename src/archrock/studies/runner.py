"""How a study runs: one frozen :class:`RunSettings` (workers, scheduler, output folder,
progress) taken by every study as ``settings=``, as scikit-learn's estimators take ``n_jobs``;
and the :class:`SweepRunner` of the studies that search collapse boundaries.

Every study (:func:`~archrock.studies.ensemble.run_ensemble`, the collapse curves, IDA and
multiple stripes, Sobol indices, defect maps, verification ensembles, the paper's study, the
assessment) runs on the executors of :mod:`archrock.studies.executors` (in-process, process
pool, Dask), keeps its finished work in the store of :mod:`archrock.studies.store` (atomic
Parquet files, a manifest, provenance, resume by verification) and reports through the one
progress protocol of :mod:`archrock._progress` (the CLI renders it).  The 0.6 keyword
arguments (``workers=``, ``scheduler=``, ``out=``, ``out_dir=``, ``progress=``) are gone in 0.7:
``settings=`` alone says how a study runs.

IDA, multiple stripes and the collapse-acceleration curves search collapse boundaries in rounds
(a scan, then bisection steps); every round is one list of items (arch, motion, scale) for
:func:`archrock.dynamics.sweep.sweep`.  A :class:`SweepRunner` holds the packed arches and
motions and runs round after round on one executor (in-process: the numba ``prange`` loop over
the items, or with the settings' device 'gpu' one item per GPU thread; a pool or Dask: the
arches and motions sent to each worker once).  The arches are packed (and their tables
built) on the CPU whatever the device: that is done once per study, the rounds many times.
The items of a round are cut into chunks so that progress can be shown; results never depend
on the executor or the chunks (each item is independent).

With ``pulses=(kind, sign, durations)`` (the collapse-acceleration curves) an item carries its own
motion: item (arch, j, a) is arch under ``pulse(kind, sign * a, durations[j])``, scale 1, the very
motion ``respond`` gets in :func:`archrock.studies.curves.collapse_amplitude`.  The pulses are built where
the item runs (a worker gets four numbers per item, not the samples), at most :data:`PULSE_CHUNK`
items per sweep call to bound their memory.
"""

from __future__ import annotations

import os
from dataclasses import dataclass, fields, replace
from pathlib import Path

import numpy as np

from .._device import check_device, resolve_device
from .._progress import check_progress
from ..errors import ArchInputError
from ..dynamics.sweep import SweepArches, SweepMotions, sweep
from .executors import Executor
from .store import ResultStore  # noqa: F401 - its 0.6 home

__all__ = ["RunSettings", "SweepRunner", "ResultStore",
           "check_workers"]


def check_workers(workers) -> int | None:
    """``workers`` as None (in-process) or an integer >= 1 (1 is in-process too)."""
    if workers is None:
        return None
    if isinstance(workers, bool) or not isinstance(workers, (int, np.integer)) or workers < 1:
        raise ArchInputError(f"workers: {workers!r}; allowed an integer >= 1")
    return int(workers)


def _is_client(scheduler) -> bool:
    """A ``distributed.Client`` (without importing Dask: a Client exists only once it is)."""
    import sys

    mod = sys.modules.get("distributed")
    return mod is not None and isinstance(scheduler, mod.Client)


@dataclass(frozen=True)
class RunSettings:
    """How a study runs (never what it computes: results are bit for bit the same whatever
    these are).

    workers: None or 1, in this process (numba threads); N > 1, a local process pool of
    min(N, cores) workers.  scheduler: None, or an existing Dask cluster (its address, or a
    ``distributed.Client``), which takes precedence over ``workers``.  out: None, or the folder
    that keeps the finished work (a rerun with the same folder recomputes nothing it had
    finished).  progress: None (silent), True (lines to the ``archrock.progress`` logger) or a
    callable given one line of text (:mod:`archrock._progress`; the CLI renders on stderr).
    device: where the compiled batch kernels run, 'cpu' (default), 'gpu' or 'auto' (the GPU
    where one is present and the work is large enough, :func:`archrock._device.resolve_device`);
    'gpu' runs in this process only (a GPU serves one process, not a pool's workers), and
    'auto' with a pool or Dask is the CPU.  Studies whose kernels have no GPU build (the
    contact engine, the arch-by-arch 'respond' engine) refuse 'gpu' (:meth:`on_cpu`)."""

    workers: int | None = None
    scheduler: object = None
    out: Path | None = None
    progress: object = None
    device: str = "cpu"

    def __post_init__(self):
        object.__setattr__(self, "workers", check_workers(self.workers))
        object.__setattr__(self, "device", check_device(self.device))
        sch = self.scheduler
        if sch is not None and not (isinstance(sch, str) and sch.strip()) and not _is_client(sch):
            raise ArchInputError(f"scheduler: {sch!r}; allowed None, a Dask scheduler's "
                                 f"address (e.g. 'tcp://host:8786') or a distributed.Client")
        if self.out is not None:
            if not isinstance(self.out, (str, os.PathLike)) or not str(self.out).strip():
                raise ArchInputError(f"out: {self.out!r}; allowed None or a folder path")
            object.__setattr__(self, "out", Path(self.out))
        if self.progress is False:
            object.__setattr__(self, "progress", None)
        check_progress(self.progress)
        if self.device == "gpu" and self.executor != "in-process":
            raise ArchInputError(
                f"device: 'gpu' runs in this process (a GPU serves one process, not a "
                f"{self.executor}'s workers); allowed device 'gpu' with workers 1 and no "
                f"scheduler (in-process), or device 'cpu' or 'auto' ('auto' on a "
                f"{self.executor} is the CPU)")

    @property
    def executor(self) -> str:
        """"dask", "process pool" or "in-process" (what these settings run on)."""
        if self.scheduler is not None:
            return "dask"
        return "process pool" if self.workers is not None and self.workers > 1 else "in-process"

    @property
    def sink(self):
        """The progress callable (None: silent)."""
        return check_progress(self.progress)

    @property
    def run_device(self) -> str:
        """The device a run on these settings asks its batch kernels for: ``device``, except
        'auto' on a process pool or Dask, which is the CPU (one GPU, many workers)."""
        return "cpu" if self.executor != "in-process" else self.device

    def only(self, study: str, *used: str) -> "RunSettings":
        """These settings, refused by field when ``study`` does not use it (``used``: the
        fields of workers, scheduler, out and device it does use; progress every study
        uses; device 'auto' is the CPU where it is not used)."""
        for name in ("workers", "scheduler", "out"):
            if name not in used and getattr(self, name) is not None:
                raise ArchInputError(f"{name}: {getattr(self, name)!r}; {study} runs in this "
                                     f"process and keeps no folder of finished work; allowed "
                                     f"None")
        return self if "device" in used else self.on_cpu(study)

    def on_cpu(self, study: str) -> "RunSettings":
        """These settings for ``study``, whose kernels run on the CPU only: device 'gpu' is
        refused by name ('auto' is then the CPU)."""
        if self.device == "gpu":
            raise ArchInputError(f"device: 'gpu'; {study} runs on the CPU only (the GPU builds "
                                 f"are the batch kernels and the sweep, docs/gpu.md); allowed "
                                 f"'cpu' or 'auto'")
        return self

    def replace(self, **changes) -> "RunSettings":
        return replace(self, **changes)

    def to_dict(self) -> dict:
        """The settings as JSON values; a Client or a progress callable cannot be written and
        is refused by name."""
        if self.scheduler is not None and not isinstance(self.scheduler, str):
            raise ArchInputError("scheduler: a distributed.Client cannot be written to JSON; "
                                 "allowed its address")
        if self.progress not in (None, True):
            raise ArchInputError("progress: a callable cannot be written to JSON; allowed "
                                 "None or true")
        return {"workers": self.workers, "scheduler": self.scheduler,
                "out": None if self.out is None else str(self.out), "progress": self.progress,
                "device": self.device}

    @classmethod
    def from_dict(cls, data) -> "RunSettings":
        if isinstance(data, RunSettings):
            return data
        if data is None:
            return cls()
        if not isinstance(data, dict):
            raise ArchInputError(f"settings: {data!r}; allowed a RunSettings or a dict")
        known = {f.name for f in fields(cls)}
        extra = sorted(set(data) - known)
        if extra:
            raise ArchInputError(f"settings: unknown field {extra[0]!r}; allowed "
                                 f"{', '.join(sorted(known))}")
        return cls(**data)


def _sweep_state(shared):
    """A pool or Dask worker's arches and motions, rebuilt from their arrays."""
    arches, motions = shared
    return SweepArches.from_arrays(arches), SweepMotions(**motions)


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


def _chunk(state, a, m, s, max_events, early_stop, pulses, kw):
    """A task of a sweep's round on any executor: ``state`` is (arches, motions)."""
    return _sweep_items(state[0], state[1], a, m, s, pulses, max_events=max_events,
                        early_stop=early_stop, **kw)


class SweepRunner:
    """Runs item lists on the executor of ``settings`` (module doc); use as a context manager.
    pulses: (kind, sign, durations) when each item carries its own pulse (module doc);
    ``motions`` are then the unit pulses of the durations (what a :class:`ResultStore`'s
    digest reads).  ``bar``: a :class:`archrock._progress.Progress`; ``store``: the
    :class:`ResultStore` of ``settings.out``, if any."""

    def __init__(self, arches: SweepArches, motions: SweepMotions, settings=None, *,
                 max_events: int | None = None, early_stop: bool = False, bar=None,
                 store=None, pulses=None):
        self.arches, self.motions = arches, motions
        self.pulses = None if pulses is None else (
            str(pulses[0]), int(pulses[1]), tuple(float(x) for x in pulses[2]))
        self.settings = RunSettings.from_dict(settings)
        if self.settings.run_device == "gpu":
            # no GPU here: say so before the first round, not after the arches' preparation
            resolve_device("gpu")
        self.max_events = max_events
        self.early_stop = bool(early_stop)
        self.bar = bar
        self.store = store
        self.responses = 0
        self.ex = Executor(self.settings, shared=(arches.arrays(), motions.arrays()),
                           setup=_sweep_state, local=(arches, motions))

    @property
    def executor(self) -> str:
        return self.ex.name

    def __enter__(self):
        self.ex.__enter__()
        return self

    def __exit__(self, exc_type, exc, tb):
        return self.ex.__exit__(exc_type, exc, tb)

    def __call__(self, arch_index, motion_index, scales) -> dict:
        """Results of :func:`~archrock.dynamics.sweep.sweep` for the items, in their order
        (items kept in the :class:`ResultStore` are read, not run again)."""
        from .store import _STORED

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
        # a few chunks per worker (load balance), at most ~20 per round (progress), >= 64 items
        n_chunks = max(1, min(max(4 * self.ex.parts, 20 if self.bar is not None else 1), N // 64))
        if self.ex.in_process:
            # in-process, every chunk is one parallel call that waits for its slowest item:
            # small chunks leave threads idle (items differ in cost by orders of magnitude)
            n_chunks = max(1, min(n_chunks, N // IN_PROCESS_CHUNK))
            if self.settings.run_device == "gpu":
                # a GPU wants every item of the round in one launch (and one copy of the arches)
                n_chunks = 1
        if self.pulses is not None:  # each item's pulse in memory: bounded chunks
            n_chunks = max(n_chunks, -(-N // PULSE_CHUNK))
        edges = np.linspace(0, N, n_chunks + 1).astype(int)
        chunks = [(edges[i], edges[i + 1]) for i in range(n_chunks) if edges[i + 1] > edges[i]]
        # a worker's loop is serial (one worker, one core); in-process sweep's own default, on
        # the settings' device (a pool or Dask runs on the CPU: the settings refuse 'gpu' there)
        kw = {"device": self.settings.run_device} if self.ex.in_process else {"parallel": False}
        tasks = [(a[i:j], m[i:j], s[i:j], self.max_events, self.early_stop, self.pulses, kw)
                 for i, j in chunks]
        out = [None] * len(chunks)
        for c, res in self.ex.map_unordered(_chunk, tasks):
            out[c] = res
            i, j = chunks[c]
            if self.store is not None:
                self.store.write(a[i:j], m[i:j], s[i:j], res)
            self.responses += j - i
            if self.bar is not None:
                self.bar.update(j - i)
        # the per-item arrays; a call's seconds, device and GPU timing stay with the call
        return {k: np.concatenate([o[k] for o in out]) for k in out[0]
                if isinstance(out[0][k], np.ndarray)}

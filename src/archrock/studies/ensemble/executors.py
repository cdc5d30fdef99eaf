"""Where an ensemble's batches are computed: in this process, a local process pool, or Dask.

Every executor hands each finished batch to ``finished(b, df, timings)`` in the calling process,
in the order the batches complete; the results do not depend on that order (each batch has its
own random stream).
"""

from __future__ import annotations

import contextlib
import os
import signal
import threading
import time

from ...errors import ArchInputError
from .compute import run_batch, run_batches
from .config import EnsembleConfig

__all__ = ["SCHEDULER_TIMEOUT_S", "execute", "worker_pool"]

#: How often [s] a pool worker checks that its parent is alive (it exits when the parent dies).
PARENT_CHECK_S = 0.5

#: seconds to wait for a Dask scheduler given by address before giving up with an ArchInputError.
SCHEDULER_TIMEOUT_S = 10.0

#: in-process, consecutive batches are computed together up to this many arches: the Python
#: around the compiled loops (about 3 ms a call) is then paid per group, not per batch, and
#: each parallel loop has more arches to share out; finished batches are still handed over
#: (and stored) one by one, at the end of their group
GROUP_ARCHES = 4000


def execute(config: EnsembleConfig, todo: list[int], finished, workers: int = 1,
            scheduler=None) -> str:
    """Compute the batches ``todo`` and return the executor's name: on the Dask ``scheduler``
    (an address or a ``distributed.Client``) if given, else a process pool of ``workers`` > 1,
    else in-process (the numba parallel loop over the arches of each batch)."""
    if todo and scheduler is not None:
        _run_dask(scheduler, config.to_dict(), todo, finished)
        return "dask"
    if todo and workers > 1:
        _run_process_pool(config.to_dict(), todo, workers, finished)
        return f"process pool ({workers})"
    for group in _groups(config, todo):
        for b, df, timings in run_batches(config, group, parallel=True):
            finished(b, df, timings)
    return "in-process"


def _groups(config: EnsembleConfig, todo: list[int]) -> list[list[int]]:
    """``todo`` cut into runs of consecutive batches of at most :data:`GROUP_ARCHES` arches
    (at least one batch each), computed in one call in-process."""
    groups, size = [], 0
    for b in todo:
        n = config.batch_range(b)[1]
        if groups and groups[-1][-1] == b - 1 and size + n <= GROUP_ARCHES:
            groups[-1].append(b)
            size += n
        else:
            groups.append([b])
            size = n
    return groups


def _run_batch_task(config_dict: dict, b: int):
    """Process-pool / Dask entry point (serial numba loop: one worker = one core)."""
    return b, *run_batch(config_dict, b, parallel=False)


def _watch_parent(parent: int) -> None:
    while True:
        time.sleep(PARENT_CHECK_S)
        if os.getppid() != parent:  # re-parented: the parent died (kill -9, OOM killer)
            os._exit(1)


def _worker_init(parent: int) -> None:
    """Pool worker set-up: Ctrl-C is the parent's to handle (it stops the pool; workers would
    only print tracebacks), and a watchdog thread ends the worker if the parent dies, which a
    process pool does not do by itself."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    threading.Thread(target=_watch_parent, args=(parent,), daemon=True).start()


@contextlib.contextmanager
def worker_pool(workers: int, spawn: bool = False):
    """A ProcessPoolExecutor of ``workers`` whose workers die with this process; on an error or
    Ctrl-C in the caller the pending tasks are cancelled and the workers stopped at once."""
    import multiprocessing as mp
    from concurrent.futures import ProcessPoolExecutor

    ctx = mp.get_context("spawn") if spawn else None
    pool = ProcessPoolExecutor(max_workers=workers, mp_context=ctx, initializer=_worker_init,
                               initargs=(os.getpid(),))
    try:
        yield pool
    except BaseException:
        procs = list((getattr(pool, "_processes", None) or {}).values())
        pool.shutdown(wait=False, cancel_futures=True)
        for p in procs:  # a running task is not cancelled by shutdown: stop its worker
            if p.is_alive():
                p.terminate()
        raise
    else:
        pool.shutdown(wait=True)


def _run_process_pool(cfg_dict, todo, workers, finished):
    from concurrent.futures import as_completed

    with worker_pool(workers, spawn=True) as pool:
        futs = [pool.submit(_run_batch_task, cfg_dict, b) for b in todo]
        for fut in as_completed(futs):
            finished(*fut.result())


def _run_dask(scheduler, cfg_dict, todo, finished):
    try:
        from distributed import Client, as_completed
    except ImportError:
        raise ImportError("running on a Dask cluster needs the 'dask' extra: "
                          "pip install 'archrock[dask]'") from None
    own = not isinstance(scheduler, Client)
    if own:
        try:
            client = Client(scheduler, timeout=SCHEDULER_TIMEOUT_S)
        except (OSError, ValueError, TypeError) as exc:
            reason = " ".join(str(exc).split()) or type(exc).__name__
            raise ArchInputError(f"scheduler: cannot connect to {scheduler!r} ({reason})") from None
    else:
        client = scheduler
    try:
        futs = [client.submit(_run_batch_task, cfg_dict, b, pure=False) for b in todo]
        for fut in as_completed(futs):
            finished(*fut.result())
    finally:
        if own:
            client.close()

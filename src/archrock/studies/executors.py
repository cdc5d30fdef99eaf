"""Where a study's work runs: in this process, a local process pool, or Dask; one family for
ensembles (:mod:`archrock.studies.ensemble.run`) and sweeps (:class:`archrock.studies.runner.
SweepRunner`).

An :class:`Executor`, opened from a :class:`~archrock.studies.runner.RunSettings`, runs tasks
``fn(shared, *args)`` and yields ``(task number, result)`` as the tasks finish:

* in-process (``workers`` None or 1, no ``scheduler``): one after the other, in order; ``fn``
  gets the caller's own ``local`` object (the parallel numba loops use every thread);
* process pool (``workers`` N > 1): min(N, cores) spawned workers, one core each; ``shared`` is
  sent to each worker once, when it starts (``setup(shared)`` there, if given, builds what the
  tasks get); workers die with this process, and on an error or Ctrl-C the pending tasks are
  cancelled and the workers stopped at once;
* Dask (``scheduler``: an address or a ``distributed.Client``): ``shared`` is scattered to
  every worker once and each task gets it (through ``setup`` when given).

Results never depend on the executor: every task is independent and carries its own inputs.
"""

from __future__ import annotations

import contextlib
import os
import signal
import threading
import time

from ..errors import ArchInputError

__all__ = ["Executor", "worker_pool", "connect", "SCHEDULER_TIMEOUT_S", "PARENT_CHECK_S"]

#: How often [s] a pool worker checks that its parent is alive (it exits when the parent dies).
PARENT_CHECK_S = 0.5

#: seconds to wait for a Dask scheduler given by address before giving up with an ArchInputError.
SCHEDULER_TIMEOUT_S = 10.0

_STATE: dict = {}


def _watch_parent(parent: int) -> None:
    while True:
        time.sleep(PARENT_CHECK_S)
        if os.getppid() != parent:  # re-parented: the parent died (kill -9, OOM killer)
            os._exit(1)


def _worker_init(parent: int, setup=None, shared=None) -> None:
    """Pool worker set-up: Ctrl-C is the parent's to handle (it stops the pool; workers would
    only print tracebacks), a watchdog thread ends the worker if the parent dies, which a
    process pool does not do by itself; and the tasks' shared state is built once."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    threading.Thread(target=_watch_parent, args=(parent,), daemon=True).start()
    _STATE["shared"] = shared if setup is None else setup(shared)


@contextlib.contextmanager
def worker_pool(workers: int, spawn: bool = False, setup=None, shared=None):
    """A ProcessPoolExecutor of ``workers`` whose workers die with this process; on an error or
    Ctrl-C in the caller the pending tasks are cancelled and the workers stopped at once."""
    import multiprocessing as mp
    from concurrent.futures import ProcessPoolExecutor

    ctx = mp.get_context("spawn") if spawn else None
    pool = ProcessPoolExecutor(max_workers=workers, mp_context=ctx, initializer=_worker_init,
                               initargs=(os.getpid(), setup, shared))
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


def connect(scheduler):
    """(client, own): a ``distributed.Client`` for ``scheduler`` (an address, connected within
    :data:`SCHEDULER_TIMEOUT_S`, or a Client, used as it is); own: this call opened it."""
    try:
        from distributed import Client
    except ImportError:
        raise ImportError("running on a Dask cluster needs the 'dask' extra: "
                          "pip install 'archrock[dask]'") from None
    if isinstance(scheduler, Client):
        return scheduler, False
    try:
        return Client(scheduler, timeout=SCHEDULER_TIMEOUT_S), True
    except (OSError, ValueError, TypeError) as exc:
        reason = " ".join(str(exc).split()) or type(exc).__name__
        raise ArchInputError(f"scheduler: cannot connect to {scheduler!r} ({reason})") from None


def _pool_task(fn, args):
    return fn(_STATE["shared"], *args)


def _dask_task(fn, setup, shared, args):
    return fn(shared if setup is None else setup(shared), *args)


class Executor:
    """One executor of the family (module doc), a context manager.  ``local``: what in-process
    tasks get (default ``shared``); ``name``: "in-process", "process pool (N)" or "dask";
    ``parts``: tasks that run at once."""

    def __init__(self, settings, *, shared=None, setup=None, local=None):
        self.scheduler = settings.scheduler
        self.workers = settings.workers
        self.shared, self.setup = shared, setup
        self.local = shared if local is None else local
        self.pool = self.client = None
        self._stack = contextlib.ExitStack()
        self.name, self.parts = "in-process", 1

    @property
    def in_process(self) -> bool:
        return self.pool is None and self.client is None

    def __enter__(self):
        try:
            if self.scheduler is not None:
                self.client, own = connect(self.scheduler)
                if own:
                    self._stack.callback(self.client.close)
                # one future for the whole shared state (a dict or tuple would be scattered
                # item by item); Dask hands each task its value
                self.remote = (None if self.shared is None else
                               self.client.scatter([self.shared], broadcast=True)[0])
                self.parts = max(1, sum(self.client.nthreads().values()))
                self.name = "dask"
            elif self.workers is not None and self.workers > 1:
                n = min(self.workers, os.cpu_count() or 1)
                self.pool = self._stack.enter_context(
                    worker_pool(n, spawn=True, setup=self.setup, shared=self.shared))
                self.parts, self.name = n, f"process pool ({n})"
        except BaseException:
            self._stack.close()
            raise
        return self

    def __exit__(self, *exc):
        return self._stack.__exit__(*exc)

    def map_unordered(self, fn, tasks):
        """``(i, fn(shared, *tasks[i]))`` for every task, as they finish (in order in-process)."""
        tasks = list(tasks)
        if self.in_process:
            for i, args in enumerate(tasks):
                yield i, fn(self.local, *args)
            return
        if self.pool is not None:
            from concurrent.futures import as_completed

            futs = {self.pool.submit(_pool_task, fn, args): i for i, args in enumerate(tasks)}
        else:
            from distributed import as_completed

            futs = {self.client.submit(_dask_task, fn, self.setup, self.remote, args,
                                       pure=False): i for i, args in enumerate(tasks)}
        for fut in as_completed(list(futs)):
            yield futs[fut], fut.result()

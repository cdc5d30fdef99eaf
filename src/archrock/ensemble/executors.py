"""Where an ensemble's batches are computed: in this process, a local process pool, or Dask.

Every executor hands each finished batch to ``finished(b, df, timings)`` in the calling process,
in the order the batches complete; the results do not depend on that order (each batch has its
own random stream).
"""

from __future__ import annotations

from ..errors import ArchInputError
from .compute import run_batch
from .config import EnsembleConfig

__all__ = ["SCHEDULER_TIMEOUT_S", "execute"]

#: seconds to wait for a Dask scheduler given by address before giving up with an ArchInputError.
SCHEDULER_TIMEOUT_S = 10.0


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
    for b in todo:
        df, timings = run_batch(config, b, parallel=True)
        finished(b, df, timings)
    return "in-process"


def _run_batch_task(config_dict: dict, b: int):
    """Process-pool / Dask entry point (serial numba loop: one worker = one core)."""
    return b, *run_batch(config_dict, b, parallel=False)


def _run_process_pool(cfg_dict, todo, workers, finished):
    import multiprocessing as mp
    from concurrent.futures import ProcessPoolExecutor, as_completed

    with ProcessPoolExecutor(max_workers=workers, mp_context=mp.get_context("spawn")) as pool:
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

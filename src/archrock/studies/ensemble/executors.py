"""Where an ensemble's batches are computed: on an :class:`archrock.studies.executors.Executor`
(in-process, a local process pool, or Dask), the one executor family of the studies.

Every executor hands each finished batch to ``finished(b, df, timings)`` in the calling process,
in the order the batches complete; the results do not depend on that order (each batch has its
own random stream).  The run settings' ``device`` says where the compiled kernels run: the GPU
only in-process (:class:`~archrock.studies.runner.RunSettings` refuses it with a pool or Dask,
where 'auto' is the CPU).
"""

from __future__ import annotations

from ..._device import resolve_device
from ..executors import SCHEDULER_TIMEOUT_S, Executor, worker_pool  # noqa: F401 - 0.6 names
from .compute import run_batches
from .config import EnsembleConfig

__all__ = ["SCHEDULER_TIMEOUT_S", "execute", "run_device", "worker_pool"]

#: in-process, consecutive batches are computed together up to this many arches: the Python
#: around the compiled loops (about 3 ms a call) is then paid per group, not per batch, and
#: each parallel loop has more arches to share out; finished batches are still handed over
#: (and stored) one by one, at the end of their group
GROUP_ARCHES = 4000
#: on the GPU, groups of up to this many arches: a launch then has threads enough to fill a
#: large GPU, and the compilation (once per process) and the transfers are paid per group; at
#: least :data:`archrock._device.AUTO_MIN_ARCHES`, below which 'auto' keeps the CPU
GPU_GROUP_ARCHES = 100_000


def run_device(config: EnsembleConfig, todo: list[int], settings) -> str:
    """'cpu' or 'gpu': where the batches ``todo`` run on ``settings`` (its ``device``; 'auto'
    decided once for the run, on the arches left to compute, so that every batch of a run
    names the same device; a pool or Dask runs on the CPU)."""
    n = int(sum(config.batch_range(b)[1] for b in todo))
    return resolve_device(settings.run_device, n)


def execute(config: EnsembleConfig, todo: list[int], finished, settings,
            device: str | None = None) -> tuple[str, str]:
    """Compute the batches ``todo`` on the executor of ``settings`` (a
    :class:`~archrock.studies.runner.RunSettings`) and return (the executor's name, the device
    that ran: 'cpu' or 'gpu').  In-process the batches go in groups (:func:`_groups`) through
    the numba parallel loop or the GPU; in a pool or on Dask one batch a task, each worker's
    loop serial (one worker = one core).  ``device``: as :func:`run_device` decides (default)."""
    device = run_device(config, todo, settings) if device is None else device
    if not todo:
        return "in-process", device
    # a worker reads the configuration once, when it starts (Dask: once a task); in-process
    # the object itself, never its dict
    shared = None if settings.executor == "in-process" else config.to_dict()
    with Executor(settings, shared=shared, setup=EnsembleConfig.from_dict, local=config) as ex:
        limit = GPU_GROUP_ARCHES if device == "gpu" else None
        groups = _groups(config, todo, limit) if ex.in_process else [[b] for b in todo]
        for _, done in ex.map_unordered(_batches_task,
                                        [(g, ex.in_process, device) for g in groups]):
            for b, df, timings in done:
                finished(b, df, timings)
        return ex.name, device


def _groups(config: EnsembleConfig, todo: list[int], limit: int | None = None) -> list[list[int]]:
    """``todo`` cut into runs of consecutive batches of at most ``limit`` arches (default
    :data:`GROUP_ARCHES`; at least one batch each), computed in one call in-process."""
    limit = GROUP_ARCHES if limit is None else limit
    groups, size = [], 0
    for b in todo:
        n = config.batch_range(b)[1]
        if groups and groups[-1][-1] == b - 1 and size + n <= limit:
            groups[-1].append(b)
            size += n
        else:
            groups.append([b])
            size = n
    return groups


def _batches_task(config: EnsembleConfig, group: list[int], parallel: bool,
                  device: str = "cpu"):
    """The batches of ``group`` on ``device``: [(b, df, timings)]."""
    return run_batches(config, group, parallel, device)

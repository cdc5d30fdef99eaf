"""Where an ensemble's batches are computed: on an :class:`archrock.studies.executors.Executor`
(in-process, a local process pool, or Dask), the one executor family of the studies.

Every executor hands each finished batch to ``finished(b, df, timings)`` in the calling process,
in the order the batches complete; the results do not depend on that order (each batch has its
own random stream).
"""

from __future__ import annotations

from ..executors import SCHEDULER_TIMEOUT_S, Executor, worker_pool  # noqa: F401 - 0.6 names
from .compute import run_batches
from .config import EnsembleConfig

__all__ = ["SCHEDULER_TIMEOUT_S", "execute", "worker_pool"]

#: in-process, consecutive batches are computed together up to this many arches: the Python
#: around the compiled loops (about 3 ms a call) is then paid per group, not per batch, and
#: each parallel loop has more arches to share out; finished batches are still handed over
#: (and stored) one by one, at the end of their group
GROUP_ARCHES = 4000


def execute(config: EnsembleConfig, todo: list[int], finished, settings) -> str:
    """Compute the batches ``todo`` on the executor of ``settings`` (a
    :class:`~archrock.studies.runner.RunSettings`) and return the executor's name.  In-process
    the batches go in groups (:func:`_groups`) through the numba parallel loop; in a pool or on
    Dask one batch a task, each worker's loop serial (one worker = one core)."""
    if not todo:
        return "in-process"
    # a worker reads the configuration once, when it starts (Dask: once a task); in-process
    # the object itself, never its dict
    shared = None if settings.executor == "in-process" else config.to_dict()
    with Executor(settings, shared=shared, setup=EnsembleConfig.from_dict, local=config) as ex:
        groups = _groups(config, todo) if ex.in_process else [[b] for b in todo]
        for _, done in ex.map_unordered(_batches_task, [(g, ex.in_process) for g in groups]):
            for b, df, timings in done:
                finished(b, df, timings)
        return ex.name


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


def _batches_task(config: EnsembleConfig, group: list[int], parallel: bool):
    """The batches of ``group``: [(b, df, timings)]."""
    return run_batches(config, group, parallel)

"""Monte Carlo over random arches drawn around one nominal arch.

Each sample is an irregular arch whose collapse multipliers k_l, k_r and mechanisms are found by
limit analysis and, under a ground motion, whose response is integrated to rest or collapse.

Reproducibility: sample i is arch i of :class:`~archrock.geometry.sampling.ArchSampler` (nominal,
spreads, seed): it depends on neither the batch size, nor the number of workers, nor the order in
which batches finish, and it is sample i of ``curves`` and ``fragility`` too.

Execution (``settings=RunSettings(...)``): in-process by default (numba ``prange`` over the
arches of a batch), ``workers > 1`` for a local process pool over batches, ``scheduler=ADDRESS``
for an existing Dask cluster.  With ``out`` every finished batch is written as a Parquet file next to ``manifest.json``;
running again with the same ``out`` and configuration computes only the missing batches.

Modules: :mod:`.config` (:class:`EnsembleConfig`), :mod:`.compute` (one batch: :func:`run_batch`, :func:`sample_arch`), :mod:`.store`
(batch files with provenance, manifest), :mod:`.progress`, :mod:`.summary`
(:class:`EnsembleResult` and its statistics), :mod:`.executors` (in-process, process pool, Dask)
and :mod:`.run` (:func:`run_ensemble`: configure, decide the dynamics, prepare the nominal,
then the batches of :mod:`.resume`).
"""

from .compute import COLUMNS, run_batch, sample_arch
from .config import EnsembleConfig
from .run import run_ensemble
from .store import EnsembleConfigMismatch
from .summary import PAPER_RANDOM_ARCHES, EnsembleResult

__all__ = ["EnsembleConfig", "EnsembleResult", "EnsembleConfigMismatch", "run_ensemble", "run_batch",
           "sample_arch", "COLUMNS", "PAPER_RANDOM_ARCHES"]

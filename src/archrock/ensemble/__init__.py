"""Monte Carlo over random arches drawn around one nominal arch.

Each sample is an irregular arch whose collapse multipliers k_l, k_r and mechanisms are found by
limit analysis and, under a ground motion, whose response is integrated to rest or collapse.

Reproducibility: the samples are cut into batches of ``batch_size``; batch b draws its arches
from its own random stream ``SeedSequence(seed, spawn_key=(b,))``, so every sample depends only
on (seed, batch_size, its index), never on the number of workers or on the order in which
batches finish.

Execution: in-process by default (numba ``prange`` over the arches of a batch), ``workers > 1``
for a local process pool over batches, ``scheduler=ADDRESS`` for an existing Dask cluster.
With ``out_dir`` every finished batch is written as a Parquet file next to ``manifest.json``;
running again with the same ``out_dir`` and configuration computes only the missing batches.

Modules: :mod:`.config` (:class:`EnsembleConfig`), :mod:`.impact` (the impact law of the
samples), :mod:`.compute` (one batch: :func:`run_batch`, :func:`sample_arch`), :mod:`.store`
(batch files with provenance, manifest), :mod:`.progress`, :mod:`.summary`
(:class:`EnsembleResult` and its statistics), :mod:`.executors` (in-process, process pool, Dask)
and :mod:`.run` (:func:`run_ensemble`).
"""

from .compute import COLUMNS, run_batch, sample_arch
from .config import EnsembleConfig
from .impact import IMPACT_CHOICES, resolve_impact
from .run import run_ensemble
from .store import EnsembleConfigMismatch
from .summary import PAPER_RANDOM_ARCHES, EnsembleResult

__all__ = ["EnsembleConfig", "EnsembleResult", "EnsembleConfigMismatch", "run_ensemble", "run_batch",
           "resolve_impact", "sample_arch", "COLUMNS", "PAPER_RANDOM_ARCHES", "IMPACT_CHOICES"]

"""One batch of an ensemble: draw its random arches, analyse them and tabulate the results.

Each sample is an irregular arch (docs/method.md, Geometry: span_i = (alpha/n)(1 + s_a U),
t_i = t (1 + s_t U), R_i = R + s_R t U, spans rescaled to the embrace) whose collapse multipliers
k_l, k_r and mechanisms are found by limit analysis and, under a ground motion, whose response is
integrated to rest or collapse (:mod:`archrock.dynamics.batch`).

Reproducibility: sample i is arch i of the configuration's :class:`~archrock.geometry.sampling.ArchSampler`
(nominal, spreads, seed), so it depends on neither the batch size, nor the number of workers, nor
the order in which batches finish, and it is the same arch as sample i of ``curves`` and
``fragility``.
"""

from __future__ import annotations

import os
import time

import numpy as np

from ..._device import resolve_device
from ...dynamics.batch import MAX_EVENTS, ST_NOT_RUN, STATUS_NAMES, prepare_batch, simulate_batch
from ...errors import ArchInputError
from ..store import COLUMNS
from .config import EnsembleConfig

__all__ = ["COLUMNS", "run_batch", "run_batches", "sample_arch"]


def _on_moved_supports(arch, movement):
    """A sample on moved supports (re-closed, docs/supports.md), or why it is left out: an
    arch that cannot stand there is "cannot stand" (its collapse under its own weight)."""
    from ...errors import ArchrockError, InvalidSampleError
    from ...statics.supports import on_moved_supports

    if isinstance(arch, Exception):
        return arch
    try:
        return on_moved_supports(arch, movement)
    except ArchrockError as exc:
        return InvalidSampleError(f"cannot stand on its moved supports ({movement.describe()}): "
                                  f"{' '.join(str(exc).split())}")


def sample_arch(config: EnsembleConfig, index: int):
    """The random arch of sample ``index`` (0-based) of the ensemble, rebuilt from the seed (on
    its moved supports when the configuration has a support movement; InvalidSampleError when it
    cannot stand there)."""
    if isinstance(index, bool) or int(index) != index or not 0 <= index < config.samples:
        raise ArchInputError(f"index: {index!r}; allowed 0..{config.samples - 1}")
    arch = config.sampler.arch(int(index))
    if config.support is None:
        return arch
    moved = _on_moved_supports(arch, config.movements(int(index), 1)[0])
    if isinstance(moved, Exception):
        raise moved
    return moved


def run_batch(config: EnsembleConfig | dict, b: int, parallel: bool = True,
              device: str = "cpu"):
    """Compute batch ``b`` of an ensemble (self-contained: only the config and b are needed).

    Returns (DataFrame with the columns of :data:`COLUMNS`, timings dict).  ``parallel`` uses
    the numba parallel loop; process-pool and Dask workers run it serially.  ``device``:
    'cpu', 'gpu' or 'auto', where the preparation and the responses run
    (:func:`archrock._device.resolve_device`; a run setting, never part of the results' key).
    """
    cfg = config if isinstance(config, EnsembleConfig) else EnsembleConfig.from_dict(config)
    if not 0 <= b < cfg.n_batches:
        raise ArchInputError(f"batch: {b}; allowed 0..{cfg.n_batches - 1}")
    return run_batches(cfg, [b], parallel, device)[0][1:]


def run_batches(cfg: EnsembleConfig, batches, parallel: bool = True,
                device: str = "cpu") -> list:
    """:func:`run_batch` of consecutive batches (b, b + 1, ...) computed together: one
    preparation and one response call for all their arches, then one table per batch.  The
    rows are those of :func:`run_batch` batch by batch (every arch is computed on its own);
    only the Python around the compiled loops is paid once.  Timings are shared out in
    proportion to the batches' sizes; they name the ``device`` that ran ('cpu' or 'gpu',
    ``device`` resolved once for the group).  Returns [(b, DataFrame, timings), ...]."""
    t0 = time.perf_counter()
    bs = _consecutive(cfg, batches)
    start = cfg.batch_range(bs[0])[0]
    last, n_last = cfg.batch_range(bs[-1])
    nb = last + n_last - start
    # one device for the whole group: 'auto' decides on the group's size, once, so that the
    # preparation and the responses of an arch run on the same device
    device = resolve_device(device, nb)
    pb = _prepare_group(cfg, start, nb, parallel, device)
    error = pb.error.copy()  # as prepared, before the responses
    res, status, sim_seconds = _responses(cfg, pb, error, nb, parallel, device)
    table = _group_table(cfg, bs, start, pb, res, status, error)
    prepare_s = float(sum(pb.seconds.values()))
    total_s = time.perf_counter() - t0
    out = []
    # the group's table cut into the batches' tables (copy-on-write slices: building a table
    # per batch converted every string column again)
    for b in bs:
        lo, count = cfg.batch_range(b)
        lo -= start
        df = table.iloc[lo:lo + count].reset_index(drop=True)
        share = count / nb
        out.append((b, df, {"prepare_s": prepare_s * share, "response_s": float(sim_seconds) * share,
                            "total_s": total_s * share, "device": device,
                            "pid": os.getpid()}))
    return out


def _consecutive(cfg: EnsembleConfig, batches) -> list[int]:
    """``batches`` as a list of consecutive batch numbers of the ensemble, or refused."""
    bs = [int(b) for b in batches]
    if not bs or any(not 0 <= b < cfg.n_batches for b in bs):
        raise ArchInputError(f"batches: {bs}; allowed consecutive batches in 0..{cfg.n_batches - 1}")
    if bs != list(range(bs[0], bs[0] + len(bs))):
        raise ArchInputError(f"batches: {bs}; allowed consecutive batches")
    return bs


def _prepare_group(cfg: EnsembleConfig, start: int, nb: int, parallel: bool,
                   device: str = "cpu"):
    """The prepared batch (:func:`~archrock.dynamics.batch.prepare_batch`) of samples start ..
    start + nb - 1, on ``device``."""
    sampler = cfg.sampler
    if cfg.support is not None:  # each arch on its moved supports, as an object
        return prepare_batch([_on_moved_supports(a, mv) for a, mv in
                              zip(sampler.arches(start, nb), cfg.movements(start, nb))],
                             impact=cfg.impact.resolved(cfg.analysed_nominal), parallel=parallel,
                             device=device)
    if sampler.finite:  # finite strength: the arches as objects, each with its f_c
        return prepare_batch(sampler.arches(start, nb),
                             impact=cfg.impact.resolved(sampler.nominal), parallel=parallel,
                             device=device)
    if sampler.circular:
        spans, thick, radii = sampler.draw(start, nb)
        return prepare_batch(spans, radii, thick, sampler.nominal.density,
                             impact=cfg.impact.resolved(sampler.nominal), parallel=parallel,
                             device=device)
    # any other family: drawn as arrays, row for row the arches' (invalid draws carry their
    # reason)
    from .familybatch import prepare_family_batch

    return prepare_family_batch(sampler, start, nb, impact=cfg.impact.resolved(sampler.nominal),
                                parallel=parallel, device=device)


def _responses(cfg: EnsembleConfig, pb, error, nb: int, parallel: bool,
               device: str = "cpu") -> tuple:
    """(response columns, status names, seconds of the responses) of the prepared arches; on
    rigid ground without a motion: NaN and zero columns, status "limit-only" or "failed"."""
    if cfg.motion is None:
        res = {"peak": np.full(nb, np.nan), "t_collapse": np.full(nb, np.nan),
               "t_limit": np.full(nb, np.nan), "t_unstable": np.full(nb, np.nan),
               "n_impacts": np.zeros(nb, dtype=np.int64),
               "n_activations": np.zeros(nb, dtype=np.int64),
               "events_truncated": np.zeros(nb, dtype=bool),
               "early_stopped": np.zeros(nb, dtype=bool)}
        return res, np.where(error == "", "limit-only", "failed").astype(object), 0.0
    res = simulate_batch(pb, cfg.motion.build(), dt=cfg.dt, t_free=cfg.t_free, parallel=parallel,
                         tabulate=cfg.tabulate, max_events=MAX_EVENTS, early_stop=cfg.early_stop,
                         device=device)
    # status names by table look-up (codes -1 .. 3), not arch by arch
    names = np.array(["failed"] + [STATUS_NAMES.get(c, "failed") for c in range(4)],
                     dtype=object)
    return res, names[np.clip(res["status"], ST_NOT_RUN, 3) + 1], res["seconds"]


def _group_table(cfg: EnsembleConfig, bs, start: int, pb, res: dict, status, error):
    """One table (columns :data:`COLUMNS`) of the samples of batches ``bs``."""
    import pandas as pd

    nb = len(status)
    batch_of = np.concatenate([np.full(cfg.batch_range(b)[1], b, dtype=np.int64) for b in bs])
    return pd.DataFrame({
        "batch": batch_of,
        "index": np.arange(start, start + nb, dtype=np.int64),
        "k_l": pb.k_l, "k_r": pb.k_r,
        # object arrays of str: pandas makes them its string columns without a numpy copy
        "mech_l": pb.mech_l, "mech_r": pb.mech_r,
        "c_l_to_r": pb.c_l_to_r, "c_r_to_l": pb.c_r_to_l,
        "collapsed": status == "collapsed",
        "status": status,
        "peak": res["peak"], "t_collapse": res["t_collapse"], "t_limit": res["t_limit"],
        "t_unstable": res["t_unstable"],
        "n_impacts": res["n_impacts"].astype(np.int64),
        "n_activations": res["n_activations"].astype(np.int64),
        "events_truncated": res["events_truncated"].astype(bool),
        "early_stopped": res["early_stopped"].astype(bool),
        "error": error,
    }, columns=COLUMNS)

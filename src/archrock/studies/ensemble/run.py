"""Run (or resume) an ensemble: the batches missing from the output folder are computed, the
others loaded, and the per-sample tables joined into an :class:`EnsembleResult`."""

from __future__ import annotations

import time

from ...errors import ArchInputError
from ...geometry import Arch
from ..work import RECORD_RESPONSE_S_PER_S, SAMPLE_LIMIT_S, SAMPLE_RESPONSE_S, check_work
from .config import EnsembleConfig
from .executors import execute
from ..._progress import Progress
from ..enginestudy import UNSET_FRICTION
from ..runner import RunSettings
from .compute import run_batches
from ..store import (OTHER_CODE, Manifest, batch_path, code_digest, is_damage, read_batch,
                    same_bits, say_damage, write_batch, written_by)
from .summary import EnsembleResult

__all__ = ["run_ensemble"]


def _nominal_info(config: EnsembleConfig) -> dict:
    """k_l, k_r and mechanisms of the nominal arch as analysed; on an arch with piers also
    whether the four-link model can follow it (``single_dof``, docs/piers-dynamics.md)."""
    info = _nominal_multipliers(config)
    from ...dynamics.piers import pier_blocks

    arch = config.analysed_nominal
    if pier_blocks(arch)[0]:
        from ...dynamics.piers import single_dof_check
        from ...dynamics.response import prepare
        from ...errors import ArchrockError

        try:  # the verdict needs the four-link models (c_v does not enter it)
            info["single_dof"] = single_dof_check(prepare(arch, 0.8)).to_dict()
        except ArchrockError:  # no four-link model on the nominal: nothing to warn about
            pass
    return info


def _nominal_multipliers(config: EnsembleConfig) -> dict:
    from ...dynamics.batch import mechanism_label
    from ...statics.kinematic import kinematic_mechanisms, kinematic_multipliers_batch
    from ...statics.liftoff import certify_candidates
    from ...statics.sums import arch_sums

    arch = config.analysed_nominal  # on its moved supports, if any
    if not isinstance(arch, Arch):
        m_l, m_r = kinematic_mechanisms(arch)
        return {"k_l": float(m_l.multiplier), "k_r": float(m_r.multiplier), "mech_l": m_l.label,
                "mech_r": m_r.label}
    k_l, k_r, i_l, i_r = kinematic_multipliers_batch(arch.spans[None], arch.radii[None],
                                                     arch.thicknesses[None])
    gov_l, gov_r = certify_candidates(arch_sums(arch), arch.n, i_l, i_r)
    if not (gov_l[0] and gov_r[0]):
        # a joint of the nominal arch lifts off: its Heyman multipliers and mechanisms, as for
        # every other shape (the batch's numbers, above, are those of the samples otherwise)
        m_l, m_r = kinematic_mechanisms(arch)
        return {"k_l": float(m_l.multiplier), "k_r": float(m_r.multiplier), "mech_l": m_l.label,
                "mech_r": m_r.label}
    return {"k_l": float(k_l[0]), "k_r": float(k_r[0]), "mech_l": mechanism_label(arch.n, int(i_l[0])),
            "mech_r": mechanism_label(arch.n, int(i_r[0]))}


def _impact_info(config: EnsembleConfig) -> dict:
    """The impact spec as given, as applied to the samples, and in words (manifest, summary)."""
    applied = config.impact.resolved(config.analysed_nominal)
    return {**config.impact.to_dict(), "applied": applied.to_dict(),
            "description": config.impact.describe()
            + (f": c_v = {applied.cv:.6g}" if applied is not config.impact else "")}


def _check_ensemble_work(config: EnsembleConfig, workers: int) -> float:
    """Estimated seconds of the whole ensemble (before resuming: a bound on what is left)."""
    each = SAMPLE_LIMIT_S
    if config.motion is not None:
        each = SAMPLE_RESPONSE_S + (RECORD_RESPONSE_S_PER_S * config.motion.build().duration
                                    if config.motion.to_dict()["type"] == "record" else 0.0)
    import os

    cores = workers if workers > 1 else (os.cpu_count() or 1)  # in-process: numba threads
    return check_work("ensemble", config.samples, "arches", each,
                      "reduce --samples (10,000 give P(collapse) to about 1%), or run on a Dask "
                      "cluster (--scheduler)", cores)


def run_ensemble(config: EnsembleConfig, *, keep_frame: bool = True, settings=None,
                 dynamics: str = "auto", engine=None,
                 friction=UNSET_FRICTION) -> EnsembleResult:
    """Run (or resume) an ensemble.

    settings: how it runs (:class:`~archrock.studies.runner.RunSettings`, default in-process,
    nothing written, silent): ``out`` the folder of the batches and manifest, resumed if it
    exists; ``workers`` > 1 a local process pool over batches (None or 1: in-process, the numba
    parallel loop); ``scheduler`` a Dask cluster, which takes precedence over ``workers``;
    ``progress`` the progress protocol of :mod:`archrock._progress` (0.7 removed the 0.6
    keywords ``out``, ``out_dir``, ``workers``, ``scheduler``, ``progress``).  keep_frame: False keeps no per-sample table in
    memory (needs ``out``): each batch is written and dropped, the result's ``frame`` is None
    and its summary is computed from the stored batches
    (:mod:`archrock.studies.ensemble.streaming`), so memory stays that of one batch however
    many samples (10^7 and more).
    dynamics: "auto" (default), "fourlink" or "engine" (:func:`archrock.studies.enginestudy.
    choose_dynamics`): under a motion, where one degree of freedom cannot follow the nominal
    arch (its piers rock with it) or where asked, the arches are run in the contact engine
    and an :class:`~archrock.studies.enginestudy.EngineEnsembleResult` is returned (nothing
    stored; ``engine``: its :class:`~archrock.studies.enginestudy.EngineRun`); on rigid ground
    "auto" is the four-link ensemble, unchanged.  The choice is in the summary's nominal
    ("dynamics") where the arch has piers or another dynamics was asked for.  friction: the
    Coulomb coefficient the routing checks the joints against (default the package's; None:
    sliding excluded), the command's one friction, which ``engine`` should use too.
    """
    import pandas as pd

    if not isinstance(config, EnsembleConfig):
        raise ArchInputError(f"config: expected an EnsembleConfig, got {type(config).__name__}")
    settings = RunSettings.from_dict(settings)
    workers = settings.workers or 1
    scheduler, out = settings.scheduler, settings.out
    if not isinstance(keep_frame, bool):
        raise ArchInputError(f"keep_frame: {keep_frame!r}; allowed true or false")
    if not keep_frame and out is None:
        raise ArchInputError("keep_frame: False needs out (the summary is then read from "
                             "the stored batches)")
    from ..enginestudy import choose_dynamics

    choice = choose_dynamics(config.analysed_nominal, dynamics,
                             friction=friction)  # checks the values first
    if choice.engine and config.motion is not None:  # docs/piers-dynamics.md
        from ..enginestudy import engine_ensemble

        bar = Progress(config.samples, settings.progress, desc="engine ensemble")
        try:
            return engine_ensemble(config, engine, dynamics=choice,
                                   progress=lambda line: bar.update(1))
        finally:
            bar.close()
    _check_ensemble_work(config, workers if scheduler is None else 1)
    t_start = time.perf_counter()
    impact = _impact_info(config)
    nominal = _nominal_info(config)
    if choice.single_dof is not None or choice.requested != "auto":
        nominal["dynamics"] = choice.to_dict()  # rigid ground under "auto": as before
    manifest = Manifest(out, config, impact, nominal) if out is not None else None
    frames: dict[int, object] = {}
    done: set[int] = set()
    batch_timings: dict[int, dict] = {}
    todo = []
    recomputed: dict[int, str] = {}
    foreign: dict[str, list[int]] = {}  # batches written by other sources, by their digest
    bar = Progress(config.samples, settings.progress)

    def loaded(b, df):
        done.add(b)
        if keep_frame:
            frames[b] = df
        manifest.batch_done(b, len(df), {}, computed=False)
        bar.update(len(df))

    def recompute(b, why):
        todo.append(b)
        recomputed[b] = why
        manifest.run["recomputed"][str(b)] = why
        line = f"ensemble: recomputing batch {b}: {batch_path(out, b).name} {why}"
        if is_damage(why):  # never silent, even without progress output
            say_damage(line, bar.note if bar.enabled else None)
        else:
            bar.note(line)

    def finished(b, df, timings):
        done.add(b)
        if keep_frame:
            frames[b] = df
        batch_timings[b] = timings
        if out is not None:
            write_batch(out, b, df, config)
            manifest.batch_done(b, len(df), timings, computed=True)
            manifest.save()
        bar.update(len(df))

    try:
        mine = code_digest() if out is not None else None
        for b in range(config.n_batches):
            df, why = read_batch(out, b, config, any_code=True) if out is not None else (None, None)
            writer = written_by(out, b) if df is not None else mine
            if writer != mine:
                foreign.setdefault(writer, []).append(b)
            elif df is not None:
                loaded(b, df)
            elif why is not None:
                recompute(b, why)
            else:
                todo.append(b)
            del df
        for digest, bs in foreign.items():
            # resume by verification: the first batch of these sources is recomputed here; the
            # others are kept (and re-stamped with this code's digest) only if it comes out bit
            # for bit the same, so an older release's folder resumes without recomputing
            old, _ = read_batch(out, bs[0], config, any_code=True)
            recomputed[bs[0]] = manifest.run["recomputed"][str(bs[0])] = (
                f"{OTHER_CODE} ({str(digest)[:12]}): recomputed to verify its other batches")
            (_, new, timings), = run_batches(config, [bs[0]],
                                                 settings.executor == "in-process")
            finished(bs[0], new, timings)
            differs = same_bits(old, read_batch(out, bs[0], config)[0])
            del old, new
            if differs is None:
                bar.note(f"ensemble: batch {bs[0]}, {OTHER_CODE} ({str(digest)[:12]}), "
                         f"recomputed bit for bit the same: its {len(bs) - 1} other batch(es) "
                         f"kept")
                manifest.run.setdefault("verified", {})[str(digest)] = {
                    "recomputed_batch": bs[0], "kept": bs[1:]}
                for b in bs[1:]:
                    df, _ = read_batch(out, b, config, any_code=True)
                    write_batch(out, b, df, config)
                    loaded(b, df)
                    del df
            else:
                for b in bs[1:]:
                    recompute(b, f"{OTHER_CODE}, whose batch {bs[0]} this code recomputes "
                                 f"differently ({differs})")
        todo.sort()
        if manifest is not None:
            manifest.save()

        executor = execute(config, todo, finished, settings)
    finally:
        bar.close()
        if manifest is not None:
            manifest.finish(complete=len(done) == config.n_batches)
    frame = pd.concat([frames[b] for b in sorted(frames)], ignore_index=True) if keep_frame else None
    wall = time.perf_counter() - t_start
    computed = sorted(batch_timings)
    n_computed = int(sum(config.batch_range(b)[1] for b in computed))
    timing = {"wall_s": wall, "executor": executor, "workers": workers,
              "computed_batches": computed, "loaded_batches": sorted(done - set(computed)),
              "recomputed_batches": {str(b): why for b, why in sorted(recomputed.items())},
              "computed_samples": n_computed,
              "samples_per_s": n_computed / wall if n_computed and wall > 0 else None,
              "prepare_s": float(sum(t["prepare_s"] for t in batch_timings.values())),
              "response_s": float(sum(t["response_s"] for t in batch_timings.values()))}
    return EnsembleResult(config, frame, nominal, impact, timing,
                          str(out) if out is not None else None)

"""Run (or resume) an ensemble, in four steps: check the configuration and run settings,
decide the dynamics (four-link model or contact engine), prepare the nominal arch (its
multipliers, mechanisms and impact law, for the manifest and the summary), then the batches
(:mod:`.resume`: those missing from the output folder are computed, the others loaded) joined
into an :class:`EnsembleResult`."""

from __future__ import annotations

import time

from ..._device import resolve_device
from ...errors import ArchInputError
from ...geometry import Arch
from ..work import (RECORD_RESPONSE_S_PER_S, SAMPLE_FINITE_S, SAMPLE_LIMIT_S, SAMPLE_RESPONSE_S,
                    check_work)
from .config import EnsembleConfig
from ..._progress import Progress
from ..enginestudy import UNSET_FRICTION
from ..runner import RunSettings
from .resume import EnsembleBatches
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
    if getattr(arch, "fc", None) is not None:  # finite strength: the statics that honour it
        from ...statics.limit import limit_analysis

        lim = limit_analysis(arch, verify=False)
        return {"k_l": float(lim.k_l), "k_r": float(lim.k_r), "mech_l": lim.mechanism_l.label,
                "mech_r": lim.mechanism_r.label, "fc": float(arch.fc)}
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
    if config.sampler.finite:  # each arch through the crushing statics, one at a time
        each += SAMPLE_FINITE_S
    import os

    # in-process: numba threads (the finite-strength arches run one at a time)
    cores = workers if workers > 1 else 1 if config.sampler.finite else (os.cpu_count() or 1)
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
    ``device`` where the batch kernels run ('cpu', 'gpu' in-process only, 'auto'; the
    summary's timing names the one that ran; a folder resumes on either);
    ``progress`` the progress protocol of :mod:`archrock._progress` (0.7 removed the 0.6
    keywords ``out``, ``out_dir``, ``workers``, ``scheduler``, ``progress``).
    keep_frame: False keeps no per-sample table in memory (needs ``out``): each batch is written and dropped, the result's ``frame`` is None
    and its summary is computed from the stored batches
    (:mod:`archrock.studies.ensemble.streaming`), so memory stays that of one batch however
    many samples (10^7 and more).
    dynamics: "auto" (default), "fourlink" or "engine" (:func:`archrock.studies.enginestudy.
    choose_dynamics`): under a motion, where one degree of freedom cannot follow the nominal
    arch (its piers rock with it) or where asked, the arches are run in the contact engine
    and an :class:`~archrock.studies.ensemble.engine.EngineEnsembleResult` is returned (nothing
    stored; ``engine``: its :class:`~archrock.studies.enginestudy.EngineRun`); on rigid ground
    "auto" is the four-link ensemble, unchanged.  The choice is in the summary's nominal
    ("dynamics") where the arch has piers or another dynamics was asked for.  friction: the
    Coulomb coefficient the routing checks the joints against (default the package's; None:
    sliding excluded), the command's one friction, which ``engine`` should use too.
    """
    settings = configure(config, keep_frame, settings)
    choice = decide_dynamics(config, dynamics, friction)
    if choice.engine and config.motion is not None:  # docs/piers-dynamics.md
        return _engine_ensemble(config, engine, choice, settings)
    _check_ensemble_work(config, (settings.workers or 1) if settings.scheduler is None else 1)
    t_start = time.perf_counter()
    impact, nominal = prepare_nominal(config, choice)
    batches = EnsembleBatches(config, settings, keep_frame, impact, nominal, t_start)
    batches.run()
    return EnsembleResult(config, batches.frame(), nominal, impact,
                          batches.timing(settings.workers or 1),
                          str(settings.out) if settings.out is not None else None)


def configure(config: EnsembleConfig, keep_frame, settings) -> RunSettings:
    """The run settings, once the configuration and ``keep_frame`` are checked."""
    if not isinstance(config, EnsembleConfig):
        raise ArchInputError(f"config: expected an EnsembleConfig, got {type(config).__name__}")
    settings = RunSettings.from_dict(settings)
    if settings.device == "gpu":  # before any work: a GPU asked for and none usable here
        resolve_device("gpu")
    if not isinstance(keep_frame, bool):
        raise ArchInputError(f"keep_frame: {keep_frame!r}; allowed true or false")
    if not keep_frame and settings.out is None:
        raise ArchInputError("keep_frame: False needs out (the summary is then read from "
                             "the stored batches)")
    return settings


def decide_dynamics(config: EnsembleConfig, dynamics: str, friction):
    """The dynamics of the ensemble (:func:`archrock.studies.enginestudy.choose_dynamics` on
    the nominal arch as analysed); it checks ``dynamics`` and ``friction`` first."""
    from ..enginestudy import choose_dynamics

    return choose_dynamics(config.analysed_nominal, dynamics, friction=friction)


def _engine_ensemble(config: EnsembleConfig, engine, choice, settings):
    """The ensemble run in the contact engine (nothing stored), arch by arch on the bar."""
    from .engine import engine_ensemble

    settings.on_cpu("the contact engine's ensemble")
    bar = Progress(config.samples, settings.progress, desc="engine ensemble")
    try:
        return engine_ensemble(config, engine, dynamics=choice,
                               progress=lambda line: bar.update(1))
    finally:
        bar.close()


def prepare_nominal(config: EnsembleConfig, choice) -> tuple[dict, dict]:
    """(impact, nominal) of the manifest and summary: the impact law as applied, and the
    nominal arch's multipliers and mechanisms (with the dynamics chosen where the arch has
    piers or another dynamics was asked for; on rigid ground under "auto": as before)."""
    impact = _impact_info(config)
    nominal = _nominal_info(config)
    if choice.single_dof is not None or choice.requested != "auto":
        nominal["dynamics"] = choice.to_dict()
    return impact, nominal

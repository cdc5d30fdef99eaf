"""An ensemble's random arches run in the contact engine, where one degree of freedom cannot
follow the arch (:func:`archrock.studies.enginestudy.choose_dynamics`): sample i is sample i of
the :class:`~archrock.studies.ensemble.EnsembleConfig`'s sampler, as in the four-link ensemble,
each run in the engine under the configuration's motion; P(collapse) with its Wilson interval.
:func:`~archrock.studies.ensemble.run.run_ensemble` sends an ensemble here when the engine
governs."""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np

from ...errors import ArchInputError, ArchrockError
from ..enginestudy import DynamicsChoice, EngineRun, engine_run_cost_s
from ..work import check_work
from .compute import sample_arch
from .config import EnsembleConfig
from .statistics import _wilson

__all__ = ["EngineEnsembleResult", "engine_ensemble", "ENGINE_COLUMNS"]


def _stats(x) -> dict:
    x = np.asarray(x, float)
    x = x[np.isfinite(x)]
    if not x.size:
        return {"count": 0, "mean": None, "min": None, "median": None, "max": None}
    return {"count": int(x.size), "mean": float(x.mean()), "min": float(x.min()),
            "median": float(np.median(x)), "max": float(x.max())}


#: Columns of an engine ensemble's rows.
ENGINE_COLUMNS = ("index", "k_l", "k_r", "collapsed", "status", "peak", "t_collapse",
                  "t_final", "seconds", "error")


@dataclass(frozen=True)
class EngineEnsembleResult:
    """Result of :func:`engine_ensemble`: one row per sample (:data:`ENGINE_COLUMNS`: status
    'rest', 'collapsed' or 'moving' (still moving when t_free ran out: counted as not
    collapsed) or 'failed' with ``error``), the ensemble's configuration, the engine run, the
    dynamics choice that sent it here and the timing (wall_s, estimate_s)."""

    config: object
    rows: tuple = field(repr=False)
    run: EngineRun = field(default_factory=EngineRun)
    dynamics: DynamicsChoice | None = None
    nominal: dict = field(default_factory=dict)
    timing: dict = field(default_factory=dict)

    @property
    def frame(self):
        import pandas as pd

        return pd.DataFrame(list(self.rows), columns=list(ENGINE_COLUMNS))

    def summary(self, confidence: float = 0.95) -> dict:
        """JSON-ready: counts (every sample one outcome), P(collapse | integrated) with its
        Wilson interval (None and a note with no integrated sample), peaks of the survivors,
        how it was computed."""
        rows = self.rows
        n = len(rows)
        ran = [r for r in rows if r["status"] != "failed"]
        k = sum(1 for r in ran if r["collapsed"])
        reasons: dict[str, int] = {}
        for r in rows:
            if r["status"] == "failed":
                key = r["error"].split(":")[0]
                reasons[key] = reasons.get(key, 0) + 1
        status = {s: sum(1 for r in ran if r["status"] == s) for s in ("rest", "collapsed",
                                                                        "moving")}
        pc = _wilson(k, len(ran), confidence, "conditional: collapsed / integrated samples "
                     "(engine runs that ended); failed samples left out", collapses=k)
        m = self.config.motion
        return {
            "samples": n, "seed": self.config.seed,
            "spreads": self.config.spreads.to_dict(),
            "how": "contact engine",
            "dynamics": None if self.dynamics is None else self.dynamics.to_dict(),
            "engine": self.run.to_dict(),
            "motion": None if m is None else m.to_dict(),
            "nominal": self.nominal,
            "outcomes": {"samples": n, "integrated": len(ran), "failed": n - len(ran),
                         "status": status, "failed_reasons": reasons},
            "p_collapse": pc,
            "peak_rad": _stats([r["peak"] for r in ran if not r["collapsed"]]),
            "t_collapse_s": _stats([r["t_collapse"] for r in ran if r["collapsed"]]),
            "timing": dict(self.timing),
        }

    def to_dict(self) -> dict:
        return {"summary": self.summary(), "rows": [dict(r) for r in self.rows]}


def engine_ensemble(config, engine: EngineRun | None = None, *,
                    dynamics: DynamicsChoice | None = None, progress=None) -> EngineEnsembleResult:
    """The ensemble of ``config`` (an :class:`~archrock.studies.ensemble.EnsembleConfig` with
    a motion) run in the contact engine: sample i is ``sample_arch(config, i)``, the arch of the
    four-link ensemble (on its moved supports where the configuration has them).  engine: how
    each response is run (:class:`EngineRun`, default settings); dynamics: the choice that sent it here (kept in the
    result); progress: a callable given one line per arch (never printed here).  The work is
    estimated from the nominal arch first (:func:`engine_run_cost_s`) and refused beyond the
    bound of :mod:`archrock.studies.work`."""
    run, motion = _engine_ensemble_inputs(config, engine, progress)
    nominal = config.analysed_nominal
    each = engine_run_cost_s(nominal, float(motion.times[-1]), run)
    est = check_work("engine ensemble", config.samples, "arches", each,
                     "reduce --samples (the engine takes seconds an arch), or use the four-link "
                     "model (--dynamics fourlink) where it is valid", 1, kernel=False)
    t0 = time.perf_counter()
    rows = []
    for i in range(config.samples):
        rows.append(_engine_sample(lambda: sample_arch(config, i), i, motion, run))
        if progress is not None:
            progress(f"engine ensemble: arch {i + 1}/{config.samples} {rows[-1]['status']} "
                     f"({rows[-1]['seconds']:.1f} s)")
    wall = time.perf_counter() - t0
    return EngineEnsembleResult(config, tuple(rows), run, dynamics, _nominal_limits(nominal),
                                {"wall_s": wall, "estimate_s": est,
                                 "seconds_per_arch": wall / config.samples})


def _engine_ensemble_inputs(config, engine, progress):
    """The engine run and the ground motion of :func:`engine_ensemble`, checked."""
    if not isinstance(config, EnsembleConfig):
        raise ArchInputError(f"config: expected an EnsembleConfig, got {type(config).__name__}")
    if config.motion is None:
        raise ArchInputError("motion: None; the engine ensemble needs a ground motion (a "
                             "PulseSpec or RecordSpec)")
    run = EngineRun() if engine is None else engine
    if not isinstance(run, EngineRun):
        raise ArchInputError(f"engine: {run!r}; allowed None or an EngineRun")
    if progress is not None and not callable(progress):
        raise ArchInputError(f"progress: {progress!r}; allowed None or a callable")
    return run, config.motion.build()


def _engine_sample(make_arch, i: int, motion, run: EngineRun) -> dict:
    """The row (:data:`ENGINE_COLUMNS`) of sample ``i`` (its arch from ``make_arch()``) under
    ``motion``; status "failed" with the reason where the arch or the run has no answer."""
    from ...dynamics.response import prepare

    t1 = time.perf_counter()
    row = dict.fromkeys(ENGINE_COLUMNS)
    row.update(index=i, k_l=math.nan, k_r=math.nan, collapsed=False, status="failed",
               peak=math.nan, t_collapse=math.nan, t_final=math.nan, error="")
    try:
        arch = make_arch()
        model = prepare(arch, "momentum")  # the limit mechanisms, for k and phi
        row["k_l"], row["k_r"] = float(model.k_l), float(model.k_r)
        res = run.respond(arch, motion, model)
    except ArchrockError as exc:
        row["error"] = " ".join(str(exc).split())
    else:
        row.update(collapsed=res.collapsed, status=res.status, peak=float(res.peak),
                   t_collapse=math.nan if res.t_collapse is None else float(res.t_collapse),
                   t_final=float(res.t_final))
    row["seconds"] = time.perf_counter() - t1
    return row


def _nominal_limits(nominal) -> dict:
    """The nominal arch's k_l, k_r [g] and mechanisms (None where it has none)."""
    from ...dynamics.response import prepare

    try:
        nm = prepare(nominal, "momentum")
        return {"k_l": float(nm.k_l), "k_r": float(nm.k_r),
                "mech_l": nm.mechanism("l").mechanism.label,
                "mech_r": nm.mechanism("r").mechanism.label}
    except (ArchrockError, AttributeError):
        return {"k_l": None, "k_r": None}

"""IDA fragility by the contact engine, for arches one degree of freedom cannot follow (issue 31).

Where :func:`~archrock.studies.enginestudy.choose_dynamics` sends an arch to the contact engine
(piers that rock with it, joints that slide), the four-link IDA of :mod:`archrock.studies.ida`
would be unconservative (heavy piers: 3.02 g by the four-link model, 0.71 g by the engine).
:func:`engine_ida` runs every (record, scale) of a grid in the engine instead:

* each cell is one :meth:`~archrock.studies.enginestudy.EngineRun.respond` of the arch to the
  record scaled by the grid's factor; the IM convention is the IDA's (IM = scale x the record's
  IM per unit scale, :mod:`archrock.groundmotion.intensity`);
* the IDA capacity of a record is the smallest collapsing scale of the grid (no bisection: an
  engine run takes seconds, and the grid is what was asked for);
* the lognormal fit is the IDA's own (:func:`~archrock.studies.fragility.fit_ida_moments`:
  moments, or censored MLE with its plateau test where some records never collapse);
* records run in parallel on the studies' executors (:mod:`archrock.studies.executors`) with
  the settings' ``workers`` > 1 (or a Dask ``scheduler``); every cell is independent, so the
  matrix does not depend on them.

The work is estimated first (:func:`~archrock.studies.enginestudy.engine_run_cost_s`, refused
beyond :data:`archrock.studies.work.MAX_WORK_S`); progress is one line per finished record,
given to a callback, never printed.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np

from .._records import readonly_arrays
from ..errors import ArchInputError, ArchrockError
from ..groundmotion import check_pga
from ..groundmotion.intensity import im_at
from .enginestudy import DynamicsChoice, EngineRun, engine_run_cost_s
from .fragility import first_collapse, fit_ida_moments
from .ida import _fit, _grid, _im, _im_factor, _records, _units_text
from .work import check_work

__all__ = ["EngineIDAResult", "engine_ida"]


@dataclass(frozen=True)
class EngineIDAResult:
    """Result of :func:`engine_ida`.

    records: the records' names; scales: the grid (scale factors); collapsed[i, j]: record i at
    scales[j] collapsed the arch; status[i][j]: 'rest', 'collapsed', 'moving' (still moving when
    the free motion ran out: not a collapse) or 'failed' (errors[i][j] says why: not a
    collapse); factors[i]: record i's IM per unit scale; pga_g[i]: its PGA [g] at scale 1;
    first_scales[i]: its IDA capacity, the
    smallest collapsing scale of the grid (None: none collapsed); im: the IM ('pga' [g], ...);
    fit: the lognormal fragility on the first-collapse IMs (None where it cannot be identified,
    fit_error says why); run: the :class:`EngineRun`; dynamics: the DynamicsChoice's dict that
    sent the arch here (None if not given); timing: wall_s, estimate_s, runs, workers."""

    records: tuple
    scales: np.ndarray
    collapsed: np.ndarray
    status: tuple
    errors: tuple
    factors: np.ndarray
    pga_g: np.ndarray
    first_scales: tuple
    im: str
    fit: object
    fit_error: str | None
    run: EngineRun
    dynamics: dict | None = None
    timing: dict = field(default_factory=dict)

    def __post_init__(self):
        readonly_arrays(self)

    @property
    def first_ims(self) -> np.ndarray:
        """Each record's IDA capacity in IM units (inf where it never collapsed)."""
        return np.array([np.inf if s is None else im_at(f, self.im, s)
                         for s, f in zip(self.first_scales, self.factors)])

    @property
    def max_ims(self) -> np.ndarray:
        """Each record's IM at the top of the grid (what a never-collapsing record survived)."""
        return np.array([im_at(f, self.im, float(self.scales[-1])) for f in self.factors])

    @property
    def n_censored(self) -> int:
        return sum(s is None for s in self.first_scales)

    def as_ida(self):
        """The same data as an :class:`~archrock.studies.ida.IDAResult` (one curve per record,
        arch 0; bracket: the grid's last survival below the first collapse, None where the
        lowest scale already collapsed), for the IDA's report lines and figure."""
        from .ida import IDACurve, IDAResult

        curves = []
        fi, mi = self.first_ims, self.max_ims
        for i, name in enumerate(self.records):
            fc = first_collapse(self.scales, self.collapsed[i])
            first = self.first_scales[i]
            j = None if first is None else int(np.flatnonzero(self.collapsed[i])[0])
            bracket = (None if not j else (float(self.scales[j - 1]), float(first)))
            curves.append(IDACurve(name, 0, float(self.pga_g[i]), self.scales,
                                   self.collapsed[i], first, bracket,
                                   None if first is None else float(fi[i]),
                                   tuple(fc["survivals_above"]), fc["resurrections"],
                                   float(mi[i]), below_grid=j == 0))
        return IDAResult(tuple(curves), self.im, self.fit, self.fit_error)

    def to_dict(self) -> dict:
        """JSON-ready: the grid, the matrix, each record's capacity, the fit and how."""
        fi = self.first_ims
        recs = []
        for i, name in enumerate(self.records):
            fc = first_collapse(self.scales, self.collapsed[i])
            recs.append({"name": name, "pga_g": float(self.pga_g[i]),
                         "im_per_unit_scale": float(self.factors[i]),
                         "first_scale": self.first_scales[i],
                         "first_im": None if math.isinf(fi[i]) else float(fi[i]),
                         "max_im": float(self.max_ims[i]),
                         "survivals_above": fc["survivals_above"],
                         "resurrections": fc["resurrections"],
                         "status": list(self.status[i]),
                         "errors": [e for e in self.errors[i] if e]})
        return {"method": "ida", "how": "contact engine", "im": self.im,
                "im_units": _units_text(self.im),
                "capacity": "smallest collapsing scale of the grid (not bisected)",
                "scales": [float(s) for s in self.scales],
                "collapsed": self.collapsed.astype(int).tolist(),
                "n_records": len(self.records), "n_censored": self.n_censored,
                "fit": None if self.fit is None else self.fit.to_dict(),
                "fit_error": self.fit_error, "records": recs,
                "engine": self.run.to_dict(), "dynamics": self.dynamics,
                "timing": dict(self.timing)}


def _record_row(shared, i: int):
    """Task: record ``i`` of ``shared`` = (arch, records, scales, run) at every scale of the grid;
    (statuses, errors, seconds).  A cell the engine cannot run is 'failed', not a collapse."""
    arch, recs, scales, run = shared
    from ..dynamics.response import prepare

    t0 = time.perf_counter()
    model = prepare(arch, "momentum")  # the limit mechanisms, for the engine's peak rotation
    status, errors = [], []
    for s in scales:
        try:
            res = run.respond(arch, recs[i].scaled(float(s)), model)
        except ArchrockError as exc:
            status.append("failed")
            errors.append(" ".join(str(exc).split()))
        else:
            status.append("collapsed" if res.collapsed else res.status)
            errors.append("")
    return tuple(status), tuple(errors), time.perf_counter() - t0


def _check_inputs(records, scales, im, run, n_boot, dynamics, settings):
    """The records, grid, IM, engine run and run settings of :func:`engine_ida`, checked."""
    from .runner import RunSettings

    settings = RunSettings.from_dict(settings).only("engine_ida", "workers", "scheduler")
    recs = _records(records)
    s = _grid("scales", scales)
    im = _im(im)
    run = EngineRun() if run is None else run
    if not isinstance(run, EngineRun):
        raise ArchInputError(f"run: {run!r}; allowed None or an EngineRun")
    if isinstance(n_boot, bool) or not isinstance(n_boot, (int, np.integer)) or n_boot < 0 \
            or n_boot == 1:
        raise ArchInputError(f"n_boot: {n_boot!r}; allowed 0 (no band) or an integer >= 2")
    if dynamics is not None and not isinstance(dynamics, (DynamicsChoice, dict)):
        raise ArchInputError(f"dynamics: {dynamics!r}; allowed None, a DynamicsChoice or its "
                             f"dict")
    return recs, s, im, run, settings


def _check_engine_work(arch, recs, s, run, workers) -> float:
    """Estimated seconds of the grid's engine runs, refused beyond the work bound (and a
    scaled PGA beyond MAX_PGA_G)."""
    top = max(recs, key=lambda r: r.pga)
    check_pga(float(s[-1]) * top.pga_g, f"scales: {s[-1]:g} x record {top.name!r}",
              "reduce the largest scale factor", warn=False)
    longest = max(float(r.times[-1]) for r in recs)
    return check_work("engine ida", len(recs) * s.size, "engine runs",
                      engine_run_cost_s(arch, longest, run),
                      "reduce the scale factors or the records (the engine takes seconds a "
                      "run), or use the four-link model (--dynamics fourlink) where it is valid",
                      workers, kernel=False)


def _run_records(arch, recs, s, run, settings):
    """Every record's row of :func:`_record_row`, in the records' order, on the executor of
    ``settings`` (one task a record); and the executor's name."""
    from .executors import Executor

    progress = settings.sink
    rows: list = [None] * len(recs)
    shared = (arch, tuple(recs), tuple(float(x) for x in s), run)
    with Executor(settings, shared=shared) as ex:
        for done, (i, row) in enumerate(ex.map_unordered(_record_row,
                                                         [(i,) for i in range(len(recs))]), 1):
            rows[i] = row
            if progress is not None:
                k = sum(st == "collapsed" for st in row[0])
                progress(f"engine ida: record {done}/{len(recs)} {recs[i].name!r}: "
                         f"{k}/{s.size} scales collapsed ({row[2]:.1f} s)")
    return rows, ex.name


def _engine_fit(firsts, factors, im, s, n_boot, seed, confidence):
    """The IDA's lognormal fit of the first-collapse IMs (censored at the grid's top where a
    record never collapsed); (fit, error), and the IMs."""
    x = np.array([np.inf if f is None else im_at(g, im, f) for f, g in zip(firsts, factors)])
    kw = dict(n_boot=int(n_boot), seed=seed, confidence=confidence, n_records=len(firsts))
    if np.any(np.isinf(x)):  # records that never collapsed: right-censored at the grid's top
        return _fit(fit_ida_moments, x, censored="mle", plateau="auto",
                    max_intensity=np.array([im_at(g, im, float(s[-1])) for g in factors]), **kw)
    return _fit(fit_ida_moments, x, **kw)


def engine_ida(arch, records, scales, *, im: str = "pga", run: EngineRun | None = None,
               n_boot: int = 0, seed=0, confidence: float = 0.9, dynamics=None,
               settings=None) -> EngineIDAResult:
    """IDA of ``arch`` by the contact engine: every record of ``records`` (GroundMotions) scaled
    by every factor of ``scales`` (strictly increasing, > 0), one engine run each (``run``: an
    :class:`EngineRun`, default settings).  im: the IM of the capacities and the fit (as
    :func:`archrock.studies.ida.ida`); n_boot, seed, confidence: the fit's bootstrap band (0:
    none); dynamics: the DynamicsChoice (or its dict) that sent the arch here, kept in the
    result.  settings (:class:`~archrock.studies.runner.RunSettings` or its dict): ``workers``
    N > 1 a process pool over the records, ``scheduler`` a Dask cluster instead, ``progress``
    one line per finished record; no ``out`` (nothing is kept).  Refused beyond the work bound
    (estimated from :func:`engine_run_cost_s` of the longest record)."""
    recs, s, im, run, settings = _check_inputs(records, scales, im, run, n_boot, dynamics,
                                               settings)
    est = _check_engine_work(arch, recs, s, run, settings.workers or 1)
    factors = np.array([_im_factor(r, im) for r in recs])
    t0 = time.perf_counter()
    rows, where = _run_records(arch, recs, s, run, settings)
    wall = time.perf_counter() - t0
    collapsed = np.array([[st == "collapsed" for st in r[0]] for r in rows], dtype=bool)
    firsts = tuple(first_collapse(s, c)["first_collapse"] for c in collapsed)
    fit, err = _engine_fit(firsts, factors, im, s, n_boot, seed, confidence)
    dyn = dynamics.to_dict() if isinstance(dynamics, DynamicsChoice) else dynamics
    n_runs = len(recs) * s.size
    return EngineIDAResult(tuple(r.name for r in recs), s, collapsed,
                           tuple(r[0] for r in rows), tuple(r[1] for r in rows), factors,
                           np.array([r.pga_g for r in recs]), firsts, im, fit, err, run, dyn,
                           {"wall_s": wall, "estimate_s": est, "runs": n_runs,
                            "workers": where, "runs_per_s": n_runs / wall if wall > 0
                            else None})

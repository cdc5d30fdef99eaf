"""Collapse-acceleration curves: the smallest pulse amplitude that collapses an arch, against t_p.

The headline results of De Lorenzis, DeJong and Ochsendorf (2007, EESD 36): for a pulse of kind
``kind`` (Oppenheim's by default), duration ``t_p`` and amplitude ``a`` in g with the sign
``sign`` = the sign of ``a``, i.e. of the pulse's main lobe (-1: xg'' = a < 0 there, which opens
M_l at |a| > k_l; +1: it opens M_r at |a| > k_r), find the first collapse amplitude.  For the
Oppenheim, rectangular, half-sine and one-sine pulses the main lobe is the first push; the Ricker
pulse's first lobe has the opposite sign (-0.446 a) and precedes its main lobe a.

Collapse is **not** monotonic in the amplitude (a stronger pulse can be survived, docs/curves.md),
so :func:`collapse_amplitude` does not bisect blindly:

1. scan |a| on a geometric grid of ``n_scan`` points from just above the activation threshold
   (k of the loaded mechanism) to ``a_max``;
2. bisect between the last survival below the first collapse on the grid and that collapse, to
   ``tol`` [g]: the result is a true boundary (|a| - tol or less survives, |a| collapses);
3. report the survival windows above the first collapse, each edge refined by bisection too.

A window (of collapse below the first grid collapse, or of survival above it) narrower than the
grid's step can be missed: every result states the step it was searched at
(:attr:`CollapseAmplitude.resolution`: the relative step of the geometric grid and its size in g;
Oppenheim's arch at t_p = 1 s survives between 0.46439 and 0.46508 g, a window 0.15% wide that
the default grid, stepping 2.2%, steps over).  The edges of the windows found are bisected to
``min(tol, WINDOW_RTOL |a|)``, so a window narrower than ``tol`` still gets edges of its own.

Impact: by default the paper's practice (:data:`archrock.dynamics.impact.PAPER_PRACTICE`): the "paper"
model on the nominal arch, and its c_v (0.8754 for Oppenheim's arch) as a fixed coefficient on
every random arch of an ensemble.
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass, field

import numpy as np

from .._records import readonly_arrays
from ..errors import ArchInputError, LimitExceededError
from ..geometry import Arch, VoussoirArch
from ..groundmotion import pulse, pulse_kind
from ..dynamics.impact import ImpactSpec
from ..dynamics.population import left_out_summary, prepare_sample
from ..dynamics.response import prepare
from ..geometry.sampling import Spreads
# the search of one amplitude lives in .amplitude; its names stay importable from here, where
# the CLI, the app and the other studies have always found them
from .amplitude import (MAX_BISECTIONS, TOL_MAX_G, TOL_MIN_G, WINDOW_RTOL,  # noqa: F401
                        CollapseAmplitude, _check_int, _check_real, _check_sign, _model,
                        _respond_scan, _RESPOND, _wider, bisect_boundary, check_a_max,
                        check_tol, collapse_amplitude, collapse_mode, parse_range,
                        survival_runs, window_tol)
from .runner import RunSettings
from .work import PROGRESS_S, check_work, response_cost_s

__all__ = [
    "CollapseAmplitude",
    "CollapseCurve",
    "EnsembleCurve",
    "collapse_amplitude",
    "collapse_curve",
    "ensemble_curve",
    "collapse_mode",
    "parse_range",
    "ENGINES",
]

# ---------------------------------------------------------------------------- batch engine
#: items per sweep call of the curves' batch engine (each item carries its own pulse)
_CHUNK = 4096
ENGINES = ("batch", "respond")


def _engine(engine: str) -> str:
    if engine not in ENGINES:
        raise ArchInputError(f"engine: {engine!r}; allowed one of {', '.join(ENGINES)}")
    return engine


class _PulseRunner:
    """Collapse tests of (model, pulse duration, |a|) items, each item with its own
    ``pulse(kind, sign * a, t_p)`` (the very motion ``respond`` gets in
    :func:`collapse_amplitude`), on the executor of a :class:`archrock.studies.runner.SweepRunner`
    (threads, a process pool or Dask; finished items kept in ``out``), remembered per
    (model, duration, |a|)."""

    def __init__(self, models, d, kind, sign, dt, bar=None, *, settings=None):
        from .runner import RunSettings, SweepRunner
        from .store import ResultStore
        from ..dynamics.sweep import SweepArches, SweepMotions

        arches = SweepArches.from_models(models, dt)
        # the unit pulses of the durations: what defines the items besides the arches (and
        # what the digest of a kept folder reads); item (m, j, a) is pulse j scaled to |a|
        units = SweepMotions.of([pulse(kind, float(sign), float(tp)) for tp in d])
        self.index = {float(tp): j for j, tp in enumerate(d)}
        settings = RunSettings.from_dict(settings)
        store = None
        if settings.out is not None:
            store = ResultStore(settings.out, arches, units,
                                about={"study": "collapse-acceleration curves", "pulse": kind,
                                       "sign": sign, "durations": [float(x) for x in d],
                                       "arches": len(models)},
                                # max_events stays in the kept folder's settings so that
                                # 0.6's folders resume; the sweep no longer stops at it (an
                                # item's outcome does not depend on its event table)
                                settings={"study": "curves", "kind": kind, "sign": sign,
                                          "max_events": _RESPOND["max_events"]},
                                note=bar.note if getattr(bar, "enabled", False) else None)
        self.runner = SweepRunner(arches, units, settings,
                                  max_events=None, bar=bar, store=store,
                                  pulses=(kind, sign, d))
        self.cache: dict = {}

    def __enter__(self):
        self.runner.__enter__()
        return self

    def __exit__(self, *exc):
        return self.runner.__exit__(*exc)

    def __call__(self, keys):
        """Outcomes (collapsed) of the (model, duration, |a|) keys, running those not yet run."""
        todo = list(dict.fromkeys(k for k in keys if k not in self.cache))
        if todo:
            res = self.runner([m for m, _, _ in todo], [self.index[tp] for _, tp, _ in todo],
                              [a for _, _, a in todo])
            for k, st, tc in zip(todo, res["status"], res["t_collapse"]):
                self.cache[k] = (bool(st == 1), None if np.isnan(tc) else float(tc))
        return [self.cache[k][0] for k in keys]


def _amplitudes_batch(models, d, kind, sign, *, a_max, n_scan, tol, dt, bar=None,
                      settings=None) -> list:
    """:func:`collapse_amplitude` of every (model, duration), arch-major: the grids of all in
    one sweep, then the bisections of every first collapse and survival-window edge together,
    one step per sweep (the same midpoints as :func:`bisect_boundary`); on the executor of
    ``settings`` (a :class:`~archrock.studies.runner.RunSettings`), the finished responses
    kept in its ``out`` (:class:`_PulseRunner`)."""
    kind = pulse_kind(kind)
    sign = _check_sign(sign)
    tol = check_tol(tol)
    n_scan = _check_int("n_scan", n_scan, 2)
    thrs = [float(m.k_l if sign < 0 else m.k_r) for m in models]
    for thr in thrs:
        check_a_max(a_max, thr)
    with _PulseRunner(models, d, kind, sign, dt, bar, settings=settings) as run:
        return _search(run, models, d, kind, sign, thrs, a_max=a_max, n_scan=n_scan, tol=tol,
                       dt=dt)


def _search(run, models, d, kind, sign, thrs, *, a_max, n_scan, tol, dt) -> list:
    """The grids of every (model, duration) in one call of ``run``, then their bisections
    together, one step per call; the :class:`CollapseAmplitude` of each, arch-major."""
    searches = [(m, float(tp)) for m in range(len(models)) for tp in d]
    grids = {s: np.geomspace(thrs[s[0]] * (1 + 1e-6), a_max, n_scan) for s in searches}
    keys = [(m, tp, float(a)) for (m, tp) in searches for a in grids[(m, tp)]]
    flags = dict(zip(searches, np.array(run(keys)).reshape(len(searches), n_scan)))
    tasks, first, windows = _bisections(searches, grids, flags, thrs, tol)
    _bisect_together(run, tasks, tol)
    for s, lo, hi, _, role, _ in tasks:
        if role == "first":
            first[s] = (lo, hi)
        elif role[0] == "wlo":
            windows[s][role[1]][0] = hi
        else:
            windows[s][role[1]][1] = lo
    counts: dict = {}
    for (m, tp, _) in run.cache:
        counts[(m, tp)] = counts.get((m, tp), 0) + 1
    points = []
    for s in searches:
        m, tp = s
        grid, fl = grids[s], flags[s]
        if s not in first:
            points.append(CollapseAmplitude(tp, kind, sign, None, None, None, None, (), thrs[m],
                                            a_max, tol, grid, fl, counts[s]))
            continue
        lo, hi = first[s]
        # the collapse mode needs the impacts of the response at the boundary: that one response
        # again through respond (the outcome and t_collapse are the sweep's, identical)
        r = _respond_scan(models[m], pulse(kind, sign * hi, tp), dt)
        points.append(CollapseAmplitude(tp, kind, sign, hi, (lo, hi), collapse_mode(r),
                                        r.t_collapse, tuple(tuple(w) for w in windows[s]),
                                        thrs[m], a_max, tol, grid, fl, counts[s]))
    return points


def _bisections(searches, grids, flags, thrs, tol) -> tuple:
    """(tasks, first, windows) of the scans: bisection tasks [search, lo, hi, lo_val, role,
    tol], role 'first', ('wlo', w) or ('whi', w), a window's edges to window_tol (the same
    midpoints as collapse_amplitude); first: the searches whose first collapse is at the
    threshold; windows: each search's windows [lo, hi], their ends filled in by the tasks."""
    tasks, first, windows = [], {}, {}
    for s in searches:
        grid, fl = grids[s], flags[s]
        hits = np.flatnonzero(fl)
        if hits.size == 0:
            continue
        i0 = int(hits[0])
        if i0 == 0:
            first[s] = (thrs[s[0]], float(grid[0]))
        else:
            tasks.append([s, float(grid[i0 - 1]), float(grid[i0]), False, "first", tol])
        ws = []
        for j, k in survival_runs(fl, i0):
            w = len(ws)
            ws.append([None, float(grid[k])])
            tasks.append([s, float(grid[j - 1]), float(grid[j]), True, ("wlo", w),
                          window_tol(tol, float(grid[j - 1]))])
            if k + 1 < grid.size:
                tasks.append([s, float(grid[k]), float(grid[k + 1]), False, ("whi", w),
                              window_tol(tol, float(grid[k]))])
        windows[s] = ws
    return tasks, first, windows


def _bisect_together(run, tasks: list, tol: float) -> None:
    """Every task's bracket narrowed in place, one midpoint of each per call of ``run``: the
    rounds of bisect_boundary, bounded the same way."""
    for _ in range(MAX_BISECTIONS + 1):
        act = [t for t in tasks if _wider(t[1], t[2], t[5])]
        if not act:
            return
        mids = [0.5 * (t[1] + t[2]) for t in act]
        out = run([(t[0][0], t[0][1], x) for t, x in zip(act, mids)])
        for t, x, c in zip(act, mids, out):
            if c == t[3]:
                t[1] = x
            else:
                t[2] = x
    raise LimitExceededError(f"curves: {len(act)} bisections still wider than the tolerance "
                             f"{tol:g} g after {MAX_BISECTIONS} steps")


def _curves_batch(models, d, kind, sign, *, a_max, n_scan, tol, dt, bar=None,
                  settings=None) -> list:
    pts = _amplitudes_batch(models, d, kind, sign, a_max=a_max, n_scan=n_scan, tol=tol, dt=dt,
                            bar=bar, settings=settings)
    out = []
    for i, model in enumerate(models):
        mine = tuple(pts[i * d.size:(i + 1) * d.size])
        amps = np.array([np.nan if p.amplitude is None else p.amplitude for p in mine])
        out.append(CollapseCurve(d, amps, tuple(p.mode for p in mine),
                                 tuple(p.windows for p in mine), mine, float(model.k_l),
                                 float(model.k_r),
                                 (float(model.impact.l_to_r), float(model.impact.r_to_l))))
    return out


# ---------------------------------------------------------------------------- a curve
@dataclass(frozen=True)
class CollapseCurve:
    """First collapse amplitude against pulse duration for one arch.

    durations [s]; amplitudes [g] (NaN where no collapse up to a_max); modes; windows (survival
    windows above the first collapse, per duration); points: the full :class:`CollapseAmplitude`s.
    """

    durations: np.ndarray
    amplitudes: np.ndarray
    modes: tuple
    windows: tuple
    points: tuple = field(repr=False)
    k_l: float = float("nan")
    k_r: float = float("nan")
    cv: tuple[float, float] | None = None

    def __post_init__(self):
        readonly_arrays(self)

    def to_dict(self, scan: bool = False) -> dict:
        pts = []
        for p in self.points:
            d = p.to_dict()
            if not scan:
                d.pop("scan_amplitudes_g")
                d.pop("scan_collapsed")
            pts.append(d)
        return {
            "durations": self.durations.tolist(),
            "amplitudes_g": [None if not math.isfinite(a) else float(a) for a in self.amplitudes],
            "modes": list(self.modes),
            "survival_windows_g": [[list(w) for w in ws] for ws in self.windows],
            # where each list of windows was searched: the grid step under which one is missed
            "windows_resolution": [p.resolution for p in self.points],
            "k_l": self.k_l, "k_r": self.k_r,
            "restitution": None if self.cv is None else {"l_to_r": self.cv[0], "r_to_l": self.cv[1]},
            "points": pts,
        }


def _durations(durations) -> np.ndarray:
    try:
        d = np.atleast_1d(np.asarray(durations, dtype=float))
    except (TypeError, ValueError):
        raise ArchInputError(f"durations: {durations!r}; allowed a list of numbers > 0 s") from None
    if d.ndim != 1 or d.size == 0 or not np.all(np.isfinite(d)) or np.any(d <= 0):
        raise ArchInputError(f"durations: {durations!r}; allowed a non-empty list of numbers > 0 s")
    return d


def _check_curve_work(arches: int, durations: int, n_scan, a_max, tol, workers: int = 1) -> float:
    """Estimated seconds of the curves of ``arches`` x ``durations`` (work bound, module
    :mod:`archrock.studies.work`): a scan of n_scan responses plus its bisections per duration."""
    n_scan = _check_int("n_scan", n_scan, 2)
    a_max = _check_real("a_max", a_max, 0.0, "a finite number > 0 g")
    tol = check_tol(tol)
    per_curve = n_scan + 3 * max(1, math.ceil(math.log2(max(a_max / tol, 2.0))))
    return check_work("curves", arches * durations * per_curve, "responses", response_cost_s(),
                      "reduce --n-scan (150 resolves the windows), the durations or --samples",
                      workers)


def collapse_curve(model, durations, kind: str = "oppenheim", sign: int = -1, *, a_max: float = 10.0,
                   n_scan: int = 150, tol: float = 1e-3, impact=None, cv: float | None = None,
                   literal_cv: bool = False, dt: float | None = None,
                   engine: str = "batch", settings=None) -> CollapseCurve:
    """:func:`collapse_amplitude` for each of ``durations`` [s]; refused beyond the work bound
    of :mod:`archrock.studies.work`.  engine: "batch" (default) runs the scans of every duration in one
    parallel sweep, then every bisection step of all of them in one more
    (:mod:`archrock.dynamics.sweep`); "respond" runs response after response (0.1.0's path).  Both give
    the same curve, bit for bit.  settings (:class:`~archrock.studies.runner.RunSettings`),
    batch engine only: ``workers`` N > 1 a local process pool, ``scheduler`` a Dask cluster (address or
    Client), ``out`` a folder keeping every finished response so that the same call again
    recomputes nothing it had finished."""
    settings = RunSettings.from_dict(settings)
    model = _model(model, impact, cv, literal_cv)
    d = _durations(durations)
    engine = _engine(engine)
    _check_batch_run(engine, settings)
    _check_curve_work(1, d.size, n_scan, a_max, tol, settings.workers or 1)
    if engine == "batch":
        _check_real("a_max", a_max, None, "a finite number > the activation threshold")
        return _curves_batch([model], d, kind, sign, a_max=float(a_max), n_scan=n_scan,
                             tol=tol, dt=dt, settings=settings)[0]
    return _curve(model, d, kind, sign, a_max=a_max, n_scan=n_scan, tol=tol, dt=dt)


def _check_batch_run(engine, settings) -> None:
    """``scheduler`` and ``out`` of the run settings only with the batch engine; device 'gpu'
    only with it too (its sweep has a GPU build; 'respond' runs on the CPU only)."""
    if engine != "batch":
        settings.on_cpu(f"curves by engine {engine!r}")
        for name, v in (("scheduler", settings.scheduler), ("out", settings.out)):
            if v is not None:
                raise ArchInputError(f"{name}: run by the batch engine; allowed with "
                                     f"engine='batch'")


def _curve(model, d, kind, sign, *, a_max, n_scan, tol, dt) -> CollapseCurve:
    pts = tuple(collapse_amplitude(model, float(tp), kind, sign, a_max=a_max, n_scan=n_scan, tol=tol,
                                   dt=dt) for tp in d)
    amps = np.array([np.nan if p.amplitude is None else p.amplitude for p in pts])
    return CollapseCurve(d, amps, tuple(p.mode for p in pts), tuple(p.windows for p in pts), pts,
                         float(model.k_l), float(model.k_r),
                         (float(model.impact.l_to_r), float(model.impact.r_to_l)))


# ---------------------------------------------------------------------------- ensembles
@dataclass(frozen=True)
class EnsembleCurve:
    """Quantile bands of the first collapse amplitude over random arches.

    durations [s]; quantiles (levels); bands[q_index, d_index] [g] (inf where the quantile lies
    among arches that did not collapse up to a_max; NaN: not estimated, see band_note); amplitudes[row, d_index] [g] (inf: no
    collapse), one row per usable arch, row i being sample ``samples[i]``; nominal: the nominal
    arch's curve; seed, spreads (:class:`~archrock.geometry.sampling.Spreads`), impact (the
    :class:`~archrock.dynamics.impact.ImpactSpec` as given) and cv (the fixed c_v applied to the random
    arches, None for a per-arch law) as used.  n_samples: usable arches (the quantiles are over
    them); n_requested: arches drawn; failed: (sample index, reason) of each drawn arch that could
    not be analysed (e.g. it cannot stand), left out of the quantiles.  band_note: why the
    bands are not estimated (one usable arch: bands all NaN), None otherwise.
    """

    durations: np.ndarray
    quantiles: tuple[float, ...]
    bands: np.ndarray
    amplitudes: np.ndarray
    nominal: CollapseCurve
    seed: int
    spreads: Spreads
    impact: ImpactSpec
    cv: float | None
    n_samples: int
    failed: tuple = ()
    samples: tuple = ()
    n_requested: int = 0
    band_note: str | None = None
    #: the support movement of every arch (its dict; docs/supports.md), None on fixed supports
    support: dict | None = None

    def __post_init__(self):
        readonly_arrays(self)

    def to_dict(self) -> dict:
        def f(v):
            return None if not math.isfinite(v) else float(v)
        return {
            "durations": self.durations.tolist(),
            "quantiles": list(self.quantiles),
            # null inside: no collapse up to a_max; null as a whole: not estimated (band_note)
            "bands_g": None if self.band_note else [[f(v) for v in row] for row in self.bands],
            "band_note": self.band_note,
            "left_out": left_out_summary(self.failed, self.n_samples, "the quantiles are"),
            "amplitudes_g": [[f(v) for v in row] for row in self.amplitudes],
            "n_samples": self.n_samples, "n_requested": self.n_requested,
            "samples": list(self.samples), "n_failed": len(self.failed),
            "seed": self.seed, "spreads": self.spreads.to_dict(),
            "impact": self.impact.to_dict(), "cv": self.cv, "failed": [list(x) for x in self.failed],
            "nominal": self.nominal.to_dict(),
            **({} if self.support is None else {"support": self.support}),
        }


def _one_sample(job):
    """(row of first collapse amplitudes, None), or (None, reason) for an unusable arch."""
    sampler, index, impact, durations, kwargs = job
    model, why = prepare_sample(sampler, index, impact)
    if model is None:
        return None, why
    curve = _curve(model, durations, **kwargs)
    return np.where(np.isfinite(curve.amplitudes), curve.amplitudes, np.inf), None


def _batch_rows(nominal, sampler, samples, impact, d, kwargs, bar, run) -> tuple:
    """(the nominal model's curve, the rows of :func:`_one_sample` for samples 0 .. samples - 1),
    the nominal and every usable random arch in one batch (``run``: the run settings)."""
    prepared = [prepare_sample(sampler, i, impact) for i in range(samples)]
    usable = [m for m, _ in prepared if m is not None]
    kw = {k: v for k, v in kwargs.items() if k != "a_max"}
    curves = iter(_curves_batch([nominal] + usable, d, a_max=float(kwargs["a_max"]), bar=bar,
                                **kw, **run))
    nominal_curve = next(curves)
    rows = []
    for model, why in prepared:
        if model is None:
            rows.append((None, why))
        else:
            amps = next(curves).amplitudes
            rows.append((np.where(np.isfinite(amps), amps, np.inf), None))
    return nominal_curve, rows


def ensemble_curve(nominal: Arch, samples: int, seed: int = 0, spreads: Spreads | dict | None = None,
                   durations=(0.2,), quantiles=(0.05, 0.5, 0.95), *, impact=None,
                   literal_cv: bool = False, kind: str = "oppenheim", sign: int = -1, a_max: float = 10.0, n_scan: int = 150,
                   tol: float = 1e-3, dt: float | None = None, engine: str = "batch",
                   settings=None) -> EnsembleCurve:
    """Collapse-acceleration curves of ``samples`` random arches around ``nominal``, as quantiles.

    Arch i is sample i of :class:`~archrock.geometry.sampling.ArchSampler` (nominal, spreads, seed): the
    same arch as sample i of ``ensemble`` and ``fragility``; results do not depend on ``workers``.
    spreads: a :class:`~archrock.geometry.sampling.Spreads` or a dict with keys spread_span,
    spread_thickness, spread_radius (default the default spreads).  impact: an ImpactSpec or what
    ``ImpactSpec.parse`` reads; None = the paper's practice (the "paper" model on the nominal
    arch, its c_v fixed on every random arch).  An arch with no answer under the model
    (:data:`archrock.errors.UNUSABLE_ARCH`: it cannot stand, voussoirs do not overlap, ...) is left
    out and listed in ``failed``; ArchInputError only when no arch is usable.  literal_cv: apply a
    fixed c_v to the rates literally instead of energy-consistently (docs/method.md, Impact).
    engine "batch" (default): the nominal and every random arch and duration of a search step in
    one sweep (:func:`collapse_curve`), on the executor of ``settings``
    (:class:`~archrock.studies.runner.RunSettings`): in-process numba threads, ``workers`` > 1
    a local process pool, ``scheduler`` a Dask cluster; ``out`` a folder keeping every finished
    response (a rerun recomputes nothing it had finished).  "respond": arch after arch,
    ``workers`` > 1 of them at once in a process pool (workers die with this process; no
    ``scheduler`` nor ``out``).  Both give the same curves, bit for bit.  The work is
    estimated first and refused beyond the bound of :mod:`archrock.studies.work`; the settings'
    ``progress`` reports the responses (or arches) done when the estimate exceeds a few
    seconds (:mod:`archrock._progress`).
    """
    settings = RunSettings.from_dict(settings)
    band = _configure_band(nominal, samples, seed, spreads, durations, quantiles, impact,
                           literal_cv, n_scan=n_scan, a_max=a_max, tol=tol,
                           workers=settings.workers or 1)
    kwargs = dict(kind=kind, sign=sign, a_max=a_max, n_scan=n_scan, tol=tol, dt=dt)
    engine = _decide_engine(engine, settings)
    nominal_prepared = _prepare_band_nominal(band, engine, kwargs)
    if engine == "batch":
        nominal_curve, rows = _band_rows_batch(band, nominal_prepared, kwargs, settings)
    else:
        nominal_curve, rows = nominal_prepared, _band_rows_respond(band, kwargs, settings)
    return _band_curve(band, nominal_curve, rows)


@dataclass(frozen=True)
class _Band:
    """What an ensemble curve is computed for, checked (:func:`_configure_band`)."""

    nominal: Arch
    samples: int
    sampler: object
    q: np.ndarray
    d: np.ndarray
    est: float
    spec: ImpactSpec
    resolved: ImpactSpec
    workers: int


def _configure_band(nominal, samples, seed, spreads, durations, quantiles, impact, literal_cv,
                    *, n_scan, a_max, tol, workers) -> _Band:
    """The checked inputs of :func:`ensemble_curve`, its sampler, the estimated seconds
    (refused beyond the work bound) and the impact law as given and as resolved."""
    if not isinstance(nominal, VoussoirArch):
        raise ArchInputError(f"nominal: expected an arch, got {type(nominal).__name__}")
    samples = _check_int("samples", samples, 1)
    from ..statics.supports import study_sampler

    # on moved supports (a nominal of statics.supports.on_moved_supports) every random arch
    # takes the movement too (docs/supports.md); on fixed supports the ArchSampler as before
    sampler = study_sampler(nominal, Spreads.from_dict(spreads), seed)
    q = np.asarray(quantiles, dtype=float)
    if q.ndim != 1 or q.size == 0 or np.any(~np.isfinite(q)) or np.any((q < 0) | (q > 1)):
        raise ArchInputError(f"quantiles: {quantiles!r}; allowed numbers between 0 and 1")
    d = _durations(durations)
    est = _check_curve_work(samples + 1, d.size, n_scan, a_max, tol, workers)
    spec = ImpactSpec.parse(impact, literal=literal_cv)
    return _Band(nominal, samples, sampler, q, d, est, spec, spec.resolved(nominal), workers)


def _decide_engine(engine, settings) -> str:
    """The engine of the curves ("batch" or "respond"), checked against the run settings."""
    engine = _engine(engine)
    _check_batch_run(engine, settings)
    return engine


def _prepare_band_nominal(band: _Band, engine: str, kwargs: dict):
    """The batch engine: the nominal arch's model (checked as :func:`collapse_curve` checks,
    before the arches are drawn); "respond": its curve, computed here."""
    if engine == "batch":
        _check_real("a_max", kwargs["a_max"], None, "a finite number > the activation threshold")
        return prepare(band.nominal, band.spec)
    return collapse_curve(prepare(band.nominal, band.spec), band.d, engine=engine, **kwargs)


def _band_rows_batch(band: _Band, nominal_model, kwargs: dict, settings) -> tuple:
    """(the nominal curve, the rows of every random arch) by the batch engine, the responses
    on the progress bar: the scan and (about) three bisections per arch and duration."""
    from .._progress import Progress

    n_scan, a_max, tol = kwargs["n_scan"], kwargs["a_max"], kwargs["tol"]
    per_curve = _check_int("n_scan", n_scan, 2) + 3 * max(1, math.ceil(math.log2(
        max(float(a_max) / float(tol), 2.0))))
    bar = Progress((band.samples + 1) * band.d.size * per_curve,
                   settings.progress if band.est > PROGRESS_S else None,
                   desc="curves", unit="response")
    try:
        out = _batch_rows(nominal_model, band.sampler, band.samples, band.resolved, band.d,
                          kwargs, bar, dict(settings=settings))
        bar.finish()  # the total counted ~3 bisections a curve: an estimate from above
    finally:
        bar.close()
    return out


def _band_rows_respond(band: _Band, kwargs: dict, settings) -> list:
    """The rows of every random arch, arch after arch (``workers`` > 1 of them at once in a
    process pool)."""
    from .._progress import Progress

    jobs = [(band.sampler, i, band.resolved, band.d, kwargs) for i in range(band.samples)]
    bar = Progress(band.samples, settings.progress if band.est > PROGRESS_S else None,
                   desc="curves", unit="arch")
    rows = []
    try:
        if band.workers == 1:
            for j in jobs:
                rows.append(_one_sample(j))
                bar.update(1)
        else:
            from .executors import worker_pool

            with worker_pool(min(band.workers, os.cpu_count() or 1)) as ex:
                for row in ex.map(_one_sample, jobs):
                    rows.append(row)
                    bar.update(1)
        bar.finish()
    finally:
        bar.close()
    return rows


def _band_curve(band: _Band, nominal_curve, rows) -> EnsembleCurve:
    """The :class:`EnsembleCurve` of the rows: the usable arches' quantiles, the others listed
    in ``failed``; ArchInputError when none is usable."""
    failed = tuple((i, why) for i, (_, why) in enumerate(rows) if why is not None)
    kept = tuple(i for i, (row, _) in enumerate(rows) if row is not None)
    if not kept:
        i, why = failed[0]
        raise ArchInputError(f"samples: none of the {band.samples} random arches is usable "
                             f"(sample {i}: {why}); allowed spreads that give arches able to "
                             f"stand")
    amps = np.array([rows[i][0] for i in kept])
    bands = _quantile_bands(amps, band.q)
    note = None
    if len(kept) == 1:  # every quantile of one arch is its value: a band of zero width
        bands, note = np.full_like(bands, np.nan), "not estimated: one usable arch"
    sampler = band.sampler
    return EnsembleCurve(band.d, tuple(float(x) for x in band.q), bands, amps, nominal_curve,
                         sampler.seed, sampler.spreads, band.spec, band.resolved.cv, len(kept),
                         failed, kept, band.samples, note,
                         None if getattr(sampler, "movement", None) is None
                         else sampler.movement.to_dict())


def _quantile_bands(amps: np.ndarray, q: np.ndarray) -> np.ndarray:
    """bands[q_index, d_index] of the rows ``amps`` (non-collapsing arches as +inf): order
    statistics, linear interpolation; inf where the quantile lies among the +inf."""
    samples = len(amps)
    srt = np.sort(amps, axis=0)
    pos = q[:, None] * (samples - 1)
    lo_i = np.floor(pos).astype(int)
    hi_i = np.minimum(lo_i + 1, samples - 1)
    frac = pos - lo_i
    cols = np.arange(amps.shape[1])[None, :]
    a_lo, a_hi = srt[lo_i, cols], srt[hi_i, cols]
    with np.errstate(invalid="ignore"):
        return np.where(np.isinf(a_hi) & (frac > 0) | np.isinf(a_lo), np.inf,
                        a_lo + frac * (np.where(np.isinf(a_hi), a_lo, a_hi) - a_lo))

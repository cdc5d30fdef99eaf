"""Incremental dynamic analysis (IDA) and multiple-stripe analysis (MSA) of rocking arches.

Intensity measure (IM): ``im="pga"`` (default) is the peak ground acceleration of the *scaled*
record in g, IM = scale * PGA_record / g; ``"pgv"`` [m/s], ``"sa:T"`` (Sa(T, 5%) [g]) and
``"arias"`` [m/s] are those of :mod:`archrock.groundmotion.intensity` (Arias grows as the scale
squared); ``im="scale"`` is the scale factor itself (only meaningful for a single record, or
records normalised beforehand).

* :func:`ida` -- for every record (and every arch), scan the scale factors of a grid, find the
  first collapse (refined by bisection between the last survival below it and it; when the lowest
  grid scale already collapses, between :func:`safe_scale`, where the record cannot activate the
  arch, and it) and report the survivals above it (:func:`archrock.studies.fragility.first_collapse`): rocking collapse is chaotic in the
  scale factor (docs/method.md, Ensembles).  Fragility: :func:`~archrock.studies.fragility.fit_ida_moments` on the
  first-collapse intensities; when some (record, arch) pairs never collapse up to the top of the
  grid, they enter as right-censored at their highest analysed IM (``censored="mle"``).
* :func:`msa` -- at each IM level, run every record (scaled to that level) on every arch, count
  collapses and fit :func:`~archrock.studies.fragility.fit_stripes_mle` (Baker 2015 eq. 11).

Both add percentile bootstrap intervals with ``n_boot > 0`` (:func:`~archrock.studies.fragility.bootstrap_fit`).
Arches: one :class:`~archrock.dynamics.response.DynamicModel` or a list of them (:func:`random_models`
prepares irregular arches from :class:`~archrock.geometry.sampling.ArchSampler`, by default under the
paper's practice: the paper model's c_v of the nominal arch fixed on every arch).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np

from .._records import readonly_arrays
from ..errors import ArchInputError, FitError, LimitExceededError
from .fragility import (FragilityFit, bootstrap_fit, fit_ida_moments, fit_stripes_mle,
                        first_collapse)
from .curves import MAX_BISECTIONS, _wider, bisect_boundary
from ..geometry import Arch
from ..groundmotion import G, GroundMotion, check_pga
from ..groundmotion.intensity import IM_NAMES, im_at, im_units, intensity, parse_im, scale_for
from ..dynamics.impact import ImpactSpec
from ..dynamics.population import PreparedArches, left_out_summary, prepare_many
from ..dynamics.response import DynamicModel, prepare, respond
from ..geometry.sampling import Spreads
from .runner import RunSettings
from .work import (FIT_MLE_S, FIT_MOMENTS_S, PROGRESS_S, check_work,
                   response_cost_s)

__all__ = ["IDACurve", "IDAResult", "StripeResult", "ida", "ida_curve", "msa",
           "random_models", "safe_scale", "IM_KINDS", "ENGINES"]

IM_KINDS = IM_NAMES


# ---------------------------------------------------------------------------- inputs
def _records(records) -> list[GroundMotion]:
    if isinstance(records, GroundMotion):
        records = [records]
    try:
        recs = list(records)
    except TypeError:
        raise ArchInputError(f"records: {records!r}; allowed a list of GroundMotion") from None
    if not recs or not all(isinstance(r, GroundMotion) for r in recs):
        raise ArchInputError("records: allowed a non-empty list of GroundMotion")
    for r in recs:
        if r.pga <= 0:
            raise ArchInputError(f"records: {r.name!r} has PGA 0; allowed records with a nonzero PGA")
    return recs


def _models(models) -> list[DynamicModel]:
    if isinstance(models, (DynamicModel, Arch)):
        models = [models]
    try:
        ms = list(models)
    except TypeError:
        raise ArchInputError(f"models: {models!r}; allowed a DynamicModel or a list of them") from None
    out = []
    for m in ms:
        if isinstance(m, Arch):
            m = prepare(m)  # an arch alone: the paper's model on it (ImpactSpec docs)
        if not isinstance(m, DynamicModel):
            raise ArchInputError(f"models: {type(m).__name__}; allowed DynamicModel or Arch objects")
        out.append(m)
    if not out:
        raise ArchInputError("models: empty; allowed at least one arch")
    return out


def _ids_failed(models, ms) -> tuple[list[int], tuple]:
    """Sample indices of the models and the failed samples (from :class:`PreparedArches`)."""
    ids = getattr(models, "indices", None)
    ids = list(ids) if ids is not None and len(ids) == len(ms) else list(range(len(ms)))
    return ids, tuple(getattr(models, "failed", ()))


def _grid(name: str, values) -> np.ndarray:
    try:
        s = np.atleast_1d(np.asarray(values, dtype=float))
    except (TypeError, ValueError):
        raise ArchInputError(f"{name}: {values!r}; allowed increasing numbers > 0") from None
    if s.ndim != 1 or s.size < 1 or not np.all(np.isfinite(s)) or np.any(s <= 0) or np.any(np.diff(s) <= 0):
        raise ArchInputError(f"{name}: allowed a strictly increasing list of numbers > 0")
    return s


#: Allowed range of the IDA's ``tol``, relative to the scale factor of the first collapse:
#: below 1e-9 finer than the integrator resolves a boundary (and a bisection to 1e-300 would
#: stall at one ulp); above 0.5 the bracket [hi / 2, hi] says nothing a grid does not.
TOL_MIN, TOL_MAX = 1e-9, 0.5


def _check_tol(tol) -> float:
    if (isinstance(tol, bool) or not isinstance(tol, (int, float, np.integer, np.floating))
            or not math.isfinite(tol) or not TOL_MIN <= tol <= TOL_MAX):
        raise ArchInputError(f"tol: {tol!r}; allowed a tolerance relative to the scale factor, "
                             f"{TOL_MIN:g} <= tol <= {TOL_MAX:g}")
    return float(tol)


def _im(im: str) -> str:
    return parse_im(im)


def _units_text(im: str) -> str:
    """The IM's units in the results' JSON ('g (PGA of the scaled record)', ...)."""
    if im == "scale":
        return "scale factor"
    name = "Sa(%s s, 5%%)" % im.split(":")[1] if im.startswith("sa:") else im.upper()
    if im == "arias":
        name = "Arias intensity"
    return f"{im_units(im)} ({name} of the scaled record)"


def _im_factor(record: GroundMotion, im: str) -> float:
    """IM per unit scale factor."""
    # PGA as 0.1.0 computed it (the same float); the others from groundmotion.intensity
    return record.pga / G if im == "pga" else intensity(record, im)


def random_models(nominal: Arch, samples: int, seed: int = 0, spreads: Spreads | dict | None = None,
                  impact=None, literal_cv: bool = False) -> PreparedArches:
    """Samples 0 .. samples - 1 of ``ArchSampler(nominal, spreads, seed)`` (the same arches as
    ``ensemble`` and ``curves`` draw), prepared with :func:`archrock.dynamics.population.prepare_many`.

    impact: an ImpactSpec or what ``ImpactSpec.parse`` reads; None = the paper's practice (the
    "paper" model's c_v of the nominal arch, fixed on every arch); literal_cv: apply a fixed c_v
    to the rates literally (docs/method.md, Impact).  Arches with no answer under the model (it cannot
    stand, the draw is not an arch, ...) are left out and listed in ``failed`` of the result;
    ArchInputError only when no arch is usable.
    """
    if isinstance(samples, bool) or not isinstance(samples, (int, np.integer)) or samples < 1:
        raise ArchInputError(f"samples: {samples!r}; allowed an integer >= 1")
    from ..statics.supports import MovedSampler, study_sampler

    sampler = study_sampler(nominal, Spreads.from_dict(spreads), seed)
    spec = ImpactSpec.parse(impact, literal=literal_cv)
    if isinstance(sampler, MovedSampler):  # the c_v of the nominal as analysed (moved), as the
        spec = spec.resolved(nominal)      # ensemble on moved supports takes it
    return prepare_many(sampler, int(samples), spec)


def _check_analyses(what, recs, n_models, per_pair, n_boot, fit_s) -> float:
    """Estimated seconds of ``per_pair`` responses for each (record, arch) and the bootstrap
    (work bound of :mod:`archrock.studies.work`)."""
    runs = n_models * len(recs) * per_pair
    each = response_cost_s(float(np.mean([r.duration for r in recs])))
    est = check_work(what, runs, "responses", each,
                     "reduce the scale factors or levels, the records or --samples")
    if n_boot:  # the responses' estimate alone decides the progress bar
        check_work(f"{what} bootstrap", n_boot, "fits", fit_s,
                          "reduce --bootstrap (200 give the 90% band to a few %)", kernel=False)
    return est


def _progress(what, total, est, progress, unit="analysis"):
    from .._progress import Progress

    return Progress(total, progress if est > PROGRESS_S else None, desc=what, unit=unit)


def _inputs(records, models, im, settings):
    """The records, models, sample indices, arches left out, IM and run settings of
    :func:`ida` and :func:`msa`, checked."""
    recs, ms = _records(records), _models(models)
    ids, failed = _ids_failed(models, ms)
    return recs, ms, ids, failed, _im(im), RunSettings.from_dict(settings)


ENGINES = ("batch", "respond")


def _engine(engine: str, settings=None) -> str:
    """``engine`` checked; with ``settings``, device 'gpu' refused (before any response) unless
    the engine is the batch one, whose sweep has a GPU build."""
    if engine not in ENGINES:
        raise ArchInputError(f"engine: {engine!r}; allowed one of {', '.join(ENGINES)}")
    if settings is not None and engine != "batch":
        settings.on_cpu(f"IDA and multiple stripes by engine {engine!r}")
    return engine


#: the max_events of the responses of a collapse test (:func:`_collapsed`)
_TEST_EVENTS = 50_000


def _runner(recs, ms, dt, t_free, settings, bar, early_stop=False):
    from .runner import SweepRunner
    from .store import ResultStore
    from ..dynamics.sweep import SweepArches, SweepMotions

    arches, motions = SweepArches.from_models(ms, dt, t_free), SweepMotions.of(recs)
    store = None
    if settings.out is not None:
        store = ResultStore(settings.out, arches, motions,
                            about={"study": "fragility (IDA and stripes)",
                                   "records": [r.name for r in recs], "arches": len(ms)},
                            settings={"max_events": _TEST_EVENTS, "early_stop": bool(early_stop)},
                            note=bar.note if getattr(bar, "enabled", False) else None)
    return SweepRunner(arches, motions, settings,
                       max_events=_TEST_EVENTS, early_stop=early_stop, bar=bar, store=store)


@dataclass
class _Pairs:
    """The search state of every (arch, record) pair of :func:`_ida_batch`: pair p is arch
    ``pa[p]`` under record ``pr[p]``; lo / hi the bracket of its first collapse (NaN: none
    yet), first the grid index of its first collapse, below / safe whether the lowest grid scale
    collapsed and the no-activation scale below it, checks the pairs whose safe scale is tried."""

    pa: np.ndarray
    pr: np.ndarray
    flags: np.ndarray
    lo: np.ndarray
    hi: np.ndarray
    below: np.ndarray
    safe: list
    first: list
    checks: list


def _grid_brackets(flags, s, ms, recs, pa, pr) -> _Pairs:
    """The brackets of the grid scan: between the last survival and the first collapse, or,
    where the lowest grid scale collapsed, from the no-activation scale (to be checked)."""
    P = flags.shape[0]
    b = _Pairs(pa, pr, flags, np.full(P, np.nan), np.full(P, np.nan), np.zeros(P, dtype=bool),
               [None] * P, [None] * P, [])
    for p in range(P):
        hits = np.flatnonzero(flags[p])
        if hits.size == 0:
            continue
        i0 = int(hits[0])
        b.first[p] = i0
        if i0 == 0:
            b.below[p] = True
            x = safe_scale(ms[pa[p]], recs[pr[p]])
            if x < float(s[0]):
                b.safe[p] = x
                b.checks.append(p)
            else:  # not reachable for a consistent model: keep the grid point
                b.hi[p] = float(s[0])
        else:
            b.lo[p], b.hi[p] = float(s[i0 - 1]), float(s[i0])
    return b


def _check_safe(run, b: _Pairs, s) -> None:
    """One round: the no-activation scales of the pairs whose lowest grid scale collapsed; a
    survival there brackets the first collapse, a collapse leaves the grid point alone."""
    if not b.checks:
        return
    c = np.array(b.checks)
    st = run(b.pa[c], b.pr[c], np.array([b.safe[p] for p in b.checks]))["status"]
    for p, collapsed in zip(b.checks, st == 1):
        if collapsed:  # unbracketed: the grid point alone
            b.safe[p], b.hi[p] = None, float(s[0])
        else:
            b.lo[p], b.hi[p] = b.safe[p], float(s[0])


def _bisect_pairs(run, b: _Pairs, tol) -> None:
    """bisect_boundary(test, lo, hi, False, tol, relative=True) of every bracketed pair at
    once, one round a step (the same midpoints, in the same order)."""
    lo, hi = b.lo, b.hi
    for _ in range(MAX_BISECTIONS + 1):  # bounded as bisect_boundary
        act = np.flatnonzero(~np.isnan(lo) & _wider(lo, hi, tol, relative=True))
        if act.size == 0:
            return
        mid = 0.5 * (lo[act] + hi[act])
        col = run(b.pa[act], b.pr[act], mid)["status"] == 1
        lo[act] = np.where(col, lo[act], mid)
        hi[act] = np.where(col, mid, hi[act])
    raise LimitExceededError(f"ida: {act.size} bisections still wider than the "
                             f"tolerance {tol:g} (relative) after {MAX_BISECTIONS} steps")


def _pair_curves(b: _Pairs, recs, ids, s, im, factors) -> list:
    """The :class:`IDACurve` of every pair from its grid and bracket."""
    curves = []
    for p in range(len(b.pa)):
        r, j = recs[b.pr[p]], ids[b.pa[p]]
        f = factors[b.pr[p]]
        fl = b.flags[p]
        if b.first[p] is None:
            curves.append(IDACurve(r.name, j, r.pga_g, s, fl, None, None, None, (), 0,
                                   float(im_at(f, im, s[-1]))))
            continue
        fc = first_collapse(s, fl)
        h = float(b.hi[p])
        br = None if np.isnan(b.lo[p]) else (float(b.lo[p]), h)
        curves.append(IDACurve(r.name, j, r.pga_g, s, fl, h, br, im_at(f, im, h),
                               tuple(fc["survivals_above"]), fc["resurrections"],
                               float(im_at(f, im, s[-1])), bool(b.below[p]), b.safe[p]))
    return curves


def _ida_batch(recs, ms, ids, s, im, tol, dt, t_free, settings, bar,
               early_stop=False, factors=None) -> list:
    """The curves of :func:`ida_curve` for every (arch, record), arch-major, each round of the
    search in one sweep: the grid of every pair, then the no-activation checks of the pairs
    whose lowest grid scale collapsed, then the bisection steps of all pairs together (the same
    midpoints, in the same order, as :func:`~archrock.studies.curves.bisect_boundary`)."""
    A, Rn, n = len(ms), len(recs), s.size
    P = A * Rn
    pa = np.repeat(np.arange(A), Rn)  # pair p = (arch p // Rn, record p % Rn)
    pr = np.tile(np.arange(Rn), A)
    with _runner(recs, ms, dt, t_free, settings, bar, early_stop) as run:
        st = run(np.repeat(pa, n), np.repeat(pr, n), np.tile(s, P))["status"]
        b = _grid_brackets((st == 1).reshape(P, n), s, ms, recs, pa, pr)
        _check_safe(run, b, s)
        _bisect_pairs(run, b, tol)
    factors = [_im_factor(r, im) for r in recs] if factors is None else factors
    return _pair_curves(b, recs, ids, s, im, factors)


def _collapsed(model, record, scale, dt, t_free) -> bool:
    return respond(model, record.scaled(scale), t_end=0.5, dt_out=0.5, dt=dt, t_free=t_free,
                   max_events=_TEST_EVENTS).collapsed


# ---------------------------------------------------------------------------- IDA
@dataclass(frozen=True)
class IDACurve:
    """One IDA curve: a record on an arch.

    scales / collapsed: the grid and the outcomes; first_scale: first collapse scale factor after
    bisection (None if none up to the top of the grid); bracket: (last survival, first collapse)
    scales; first_im: first collapse IM; survivals_above: grid scales above the first collapse that
    survived; resurrections: collapse -> survival switches along the grid; max_im: IM at the top of
    the grid.  below_grid: the lowest scale of the grid already collapsed; the first collapse was
    then bisected between ``safe_scale`` (:func:`safe_scale`, where the record cannot activate the
    arch: a guaranteed survival) and the lowest grid scale.  That range is bisected, not scanned:
    a collapse window inside it, below the boundary found, would be missed.
    """

    record: str
    arch: int
    pga_g: float
    scales: np.ndarray = field(repr=False)
    collapsed: np.ndarray = field(repr=False)
    first_scale: float | None
    bracket: tuple[float, float] | None
    first_im: float | None
    survivals_above: tuple[float, ...]
    resurrections: int
    max_im: float
    below_grid: bool = False
    safe_scale: float | None = None

    def __post_init__(self):
        readonly_arrays(self)

    @property
    def note(self) -> str | None:
        if not self.below_grid:
            return None
        if self.safe_scale is None:
            return "lowest grid scale collapsed; not bracketed"
        return (f"lowest grid scale collapsed: first collapse bisected between the no-activation "
                f"scale {self.safe_scale:.4g} and the lowest grid scale {self.scales[0]:.4g}")

    def to_dict(self) -> dict:
        return {"record": self.record, "arch": self.arch, "pga_g": self.pga_g,
                "scales": self.scales.tolist(), "collapsed": [bool(c) for c in self.collapsed],
                "first_scale": self.first_scale,
                "bracket": None if self.bracket is None else list(self.bracket),
                "first_im": self.first_im, "survivals_above": list(self.survivals_above),
                "resurrections": self.resurrections, "max_im": self.max_im,
                "below_grid": self.below_grid, "safe_scale": self.safe_scale, "note": self.note}


@dataclass(frozen=True)
class IDAResult:
    """IDA over records x arches, with the fragility fitted on first-collapse intensities.

    im: 'pga' (g) or 'scale'; fit: FragilityFit (method 'moments', or 'censored_mle' when some
    curves never collapsed), None when it cannot be identified (fit_error says why; fit_error
    also notes a point fit whose bootstrap band could not be computed).  failed: (sample index,
    reason) of the random arches that could not be analysed and were left out
    (:func:`random_models`); IDACurve.arch is the sample index of each analysed arch.
    """

    curves: tuple[IDACurve, ...]
    im: str
    fit: FragilityFit | None
    fit_error: str | None = None
    failed: tuple = ()

    @property
    def first_ims(self) -> np.ndarray:
        return np.array([np.inf if c.first_im is None else c.first_im for c in self.curves])

    @property
    def n_censored(self) -> int:
        return sum(c.first_im is None for c in self.curves)

    def range_tried(self) -> dict:
        """The top of the range analysed (max_im, the IM's units), the curves that never
        collapsed up to it, and, where none collapsed, the one-sided 95% upper bound on
        P(collapse) there (Clopper-Pearson: 1 - 0.05^(1/n)): all the data can say."""
        from .fragility import collapse_probability

        n, never = len(self.curves), self.n_censored
        top = max(c.max_im for c in self.curves)
        upper = collapse_probability(0, n, 0.9, "clopper-pearson")[2] if never == n else None
        return {"max_im": float(top), "n_never": never, "n_curves": n, "p_upper_95": upper}

    def to_dict(self) -> dict:
        return {"method": "ida", "im": self.im,
                "im_units": _units_text(self.im),
                "fit": None if self.fit is None else self.fit.to_dict(), "fit_error": self.fit_error,
                "n_curves": len(self.curves), "n_censored": self.n_censored,
                "range_tried": self.range_tried(),
                "n_arches": len({c.arch for c in self.curves}),
                "n_records": len({c.record for c in self.curves}),
                "failed": [list(x) for x in self.failed],
                "left_out": left_out_summary(self.failed, len({c.arch for c in self.curves}),
                                             "the fit and its interval are"),
                "curves": [c.to_dict() for c in self.curves]}


def _fit(func, *data, n_boot, seed, confidence, n_records, **kw):
    note = None
    if n_boot and n_boot > 0:
        try:
            fit = bootstrap_fit(func, *data, n_boot=n_boot, confidence=confidence, seed=seed, **kw)
        except FitError as exc:  # the point fit may still exist; say why there is no band
            note = f"no bootstrap band: {exc}"
        else:
            if n_records == 1 and fit.theta_ci is not None:
                # the resampled unit is the (record, arch) pair: with one record the band
                # says nothing about other records
                fit = replace(fit, ci_note="one record: the interval covers the scatter between "
                                          "arches under this record only")
            return fit, None
    try:
        fit = func(*data, **kw)
    except FitError as exc:
        return None, str(exc)
    if note is not None:
        fit = replace(fit, confidence=confidence, n_boot=n_boot,
                      ci_note="not estimated: " + note[len("no bootstrap band: "):])
    return fit, note


def safe_scale(model: DynamicModel, record: GroundMotion) -> float:
    """Largest scale factor at which ``record`` cannot activate ``model`` (paper eq. 1: M_l opens
    only for xg'' < -k_l g, M_r only for xg'' > k_r g): min over the two directions of
    k g / (peak acceleration that way), at least min(k_l, k_r) g / PGA.  A guaranteed survival."""
    a = np.asarray(record.accel, dtype=float)
    neg, pos = float(max(-a.min(), 0.0)), float(max(a.max(), 0.0))
    cands = [model.k_l * G / neg] if neg > 0 else []
    cands += [model.k_r * G / pos] if pos > 0 else []
    return float(min(cands)) * (1.0 - 1e-9)  # a hair below: activation is strict at the threshold


def ida_curve(model: DynamicModel, record: GroundMotion, scales, *, im: str = "pga", tol: float = 1e-3,
              arch_index: int = 0, dt: float | None = None,
              t_free: float | None = None, factor: float | None = None) -> IDACurve:
    """One IDA curve (see :class:`IDACurve`); tol: relative bisection tolerance on the scale."""
    s = _grid("scales", scales)
    im = _im(im)
    tol = _check_tol(tol)
    flags = np.array([_collapsed(model, record, float(x), dt, t_free) for x in s])
    fc = first_collapse(s, flags)
    f = _im_factor(record, im) if factor is None else factor
    if fc["first_collapse"] is None:
        return IDACurve(record.name, arch_index, record.pga_g, s, flags, None, None, None, (), 0,
                        float(im_at(f, im, s[-1])))
    i0 = int(np.flatnonzero(flags)[0])

    def test(x):
        return _collapsed(model, record, x, dt, t_free)

    safe = None
    if i0 == 0:
        # the lowest grid scale collapsed: bisect down from a scale where nothing can activate
        below = True
        safe = safe_scale(model, record)
        if safe < float(s[0]) and not test(safe):
            lo, hi = bisect_boundary(test, safe, float(s[0]), False, tol, relative=True)
        else:  # not reachable for a consistent model; keep the grid point, unbracketed
            lo, hi, safe = None, float(s[0]), None
    else:
        below = False
        lo, hi = bisect_boundary(test, float(s[i0 - 1]), float(s[i0]), False, tol, relative=True)
    return IDACurve(record.name, arch_index, record.pga_g, s, flags, hi,
                    None if lo is None else (lo, hi), im_at(f, im, hi),
                    tuple(fc["survivals_above"]), fc["resurrections"],
                    float(im_at(f, im, s[-1])), below, safe)


def _ida_curves(engine, recs, ms, ids, s, im, tol, dt, t_free, settings, bar, early_stop,
                factors) -> list:
    """The curves of :func:`ida` by ``engine``: the batch rounds (:func:`_ida_batch`) or
    :func:`ida_curve` curve after curve (one progress count each)."""
    if engine == "batch":
        return _ida_batch(recs, ms, ids, s, im, tol, dt, t_free, settings, bar, early_stop,
                          factors)
    curves = []
    for j, m in zip(ids, ms):
        for r, f in zip(recs, factors):
            curves.append(ida_curve(m, r, s, im=im, tol=tol, arch_index=j, dt=dt,
                                    t_free=t_free, factor=f))
            bar.update(1)
    return curves


def _ida_fit(curves, n_boot, seed, confidence, n_records):
    """(fit, error) of the first-collapse IMs: moments, or the censored MLE with its plateau
    test where some curves never collapsed (right-censored at their top IM)."""
    x = np.array([np.inf if c.first_im is None else c.first_im for c in curves])
    kw = dict(n_boot=n_boot, seed=seed, confidence=confidence, n_records=n_records)
    if np.any(np.isinf(x)):
        return _fit(fit_ida_moments, x, censored="mle", plateau="auto",
                    max_intensity=np.array([c.max_im for c in curves]), **kw)
    return _fit(fit_ida_moments, x, **kw)


def ida(records, models, scales, *, im: str = "pga", tol: float = 1e-3, n_boot: int = 0,
        seed=0, confidence: float = 0.9, dt: float | None = None, t_free: float | None = None,
        engine: str = "batch", early_stop: bool = False, settings=None) -> IDAResult:
    """IDA of every record on every arch (models: DynamicModel(s) or Arch(es)); scale grid
    ``scales``. Refused when the largest scaled PGA exceeds MAX_PGA_G or the work its bound
    (:mod:`archrock.studies.work`).  settings: how it runs
    (:class:`~archrock.studies.runner.RunSettings`, its dict or None); its ``progress`` gets
    the responses (or curves) done, for a long run (:mod:`archrock._progress`).

    engine: "batch" (default) runs every (arch, record, scale) of a round (the grid scan, then
    each bisection step) in one parallel call (:mod:`archrock.studies.runner`: in-process numba
    threads, the settings' ``workers`` > 1 processes or a Dask ``scheduler``); "respond" runs curve after curve
    with :func:`ida_curve` (archrock 0.1.0's path).  Both give the same curves, bit for bit
    (:mod:`archrock.dynamics.sweep`).  early_stop (batch engine): end a response once it can no longer
    collapse (:data:`archrock.dynamics.sweep.HAVE_EARLY_STOP`; the outcome is that of the full run unless
    the energy lies within the kernel's 1% margin of a barrier).  The settings' out (batch
    engine): a folder that keeps every finished response (:class:`archrock.studies.store.
    ResultStore`), so that the same call after an interruption recomputes nothing it had
    finished."""
    recs, ms, ids, failed, im, settings = _inputs(records, models, im, settings)
    s = _grid("scales", scales)
    engine = _engine(engine, settings)
    top = max(recs, key=lambda r: r.pga)
    check_pga(float(s[-1]) * top.pga_g, f"scales: {s[-1]:g} x record {top.name!r}",
              "reduce the largest scale factor", warn=False)
    tol = _check_tol(tol)
    bisect_steps = 2 + math.ceil(math.log2(1.0 / tol))
    est = _check_analyses("ida", recs, len(ms), s.size + bisect_steps, n_boot, FIT_MOMENTS_S)
    factors = [_im_factor(r, im) for r in recs]
    total = len(ms) * len(recs) * ((s.size + bisect_steps) if engine == "batch" else 1)
    bar = _progress("ida", total, est, settings.progress,
                    unit="response" if engine == "batch" else "analysis")
    try:
        curves = tuple(_ida_curves(engine, recs, ms, ids, s, im, float(tol), dt, t_free,
                                   settings, bar, early_stop, factors))
        bar.finish()  # batch: the total counted every bisection step; most curves need fewer
    finally:
        bar.close()
    fit, err = _ida_fit(curves, n_boot, seed, confidence, len(recs))
    return IDAResult(curves, im, fit, err, failed)


# ---------------------------------------------------------------------------- MSA
@dataclass(frozen=True)
class StripeResult:
    """Multiple stripes: at each IM level, trials (records x arches) and collapses.

    outcomes[level, arch, record]: collapse flags; fit: binomial MLE (None if not identifiable,
    fit_error says why); arches: sample index of each arch; failed: (sample index, reason) of the
    random arches left out (:func:`random_models`).
    """

    levels: np.ndarray
    trials: np.ndarray
    collapses: np.ndarray
    outcomes: np.ndarray = field(repr=False)
    im: str = "pga"
    fit: FragilityFit | None = None
    fit_error: str | None = None
    records: tuple[str, ...] = ()
    arches: tuple[int, ...] = ()
    failed: tuple = ()

    def __post_init__(self):
        readonly_arrays(self)

    @property
    def fractions(self) -> np.ndarray:
        return self.collapses / self.trials

    def to_dict(self) -> dict:
        return {"method": "msa", "im": self.im,
                "im_units": _units_text(self.im),
                "levels": self.levels.tolist(), "trials": self.trials.tolist(),
                "collapses": self.collapses.tolist(), "records": list(self.records),
                "arches": list(self.arches), "failed": [list(x) for x in self.failed],
                "left_out": left_out_summary(self.failed, len(self.arches),
                                             "the stripes, the fit and its interval are"),
                "fit": None if self.fit is None else self.fit.to_dict(), "fit_error": self.fit_error}


def msa(records, models, levels, *, im: str = "pga", n_boot: int = 0, seed=0,
        confidence: float = 0.9, dt: float | None = None, t_free: float | None = None,
        engine: str = "batch", early_stop: bool = False, settings=None) -> StripeResult:
    """Multiple-stripe analysis at IM ``levels`` (PGA in g for im='pga': each record is scaled by
    level / its PGA in g); stripes fitted by maximum likelihood. Refused above MAX_PGA_G or
    beyond the work bound (:mod:`archrock.studies.work`); ``engine``, ``early_stop`` and
    ``settings`` as :func:`ida` (every level x arch x record in one
    sweep)."""
    recs, ms, ids, failed, im, settings = _inputs(records, models, im, settings)
    lv = _grid("levels", levels)
    engine = _engine(engine, settings)
    factors = [_im_factor(r, im) for r in recs]
    for r, f in zip(recs, factors):
        if not f > 0:
            raise ArchInputError(f"records: {r.name!r} has {im} = 0; allowed records with a "
                                 f"nonzero intensity")
    top = max(float(scale_for(f, im, lv[-1])) * r.pga_g for r, f in zip(recs, factors))
    check_pga(top, f"levels: {lv[-1]:g}", "reduce the top level", warn=False)
    est = _check_analyses("msa", recs, len(ms), lv.size, n_boot, FIT_MLE_S)
    bar = _progress("msa", lv.size * len(ms) * len(recs), est, settings.progress)
    outcomes = np.zeros((lv.size, len(ms), len(recs)), dtype=bool)
    # scale of record k at level i: the same float as the arch-by-arch loop computes
    scale = np.array([[float(scale_for(f, im, x)) for f in factors] for x in lv])
    try:
        if engine == "batch":
            L, A, Rn = lv.size, len(ms), len(recs)
            li, ai, ri = np.meshgrid(np.arange(L), np.arange(A), np.arange(Rn), indexing="ij")
            with _runner(recs, ms, dt, t_free, settings, bar, early_stop) as run:
                st = run(ai.ravel(), ri.ravel(), scale[li.ravel(), ri.ravel()])["status"]
            outcomes[:] = (st == 1).reshape(L, A, Rn)
        else:
            for i, x in enumerate(lv):
                for j, m in enumerate(ms):
                    for k, r in enumerate(recs):
                        outcomes[i, j, k] = _collapsed(m, r, float(scale[i, k]), dt, t_free)
                        bar.update(1)
        bar.finish()
    finally:
        bar.close()
    trials = np.full(lv.size, len(ms) * len(recs))
    coll = outcomes.reshape(lv.size, -1).sum(axis=1)
    fit, err = _fit(fit_stripes_mle, lv, trials, coll, n_boot=n_boot, seed=seed,
                    confidence=confidence, n_records=len(recs), plateau="auto")
    return StripeResult(lv, trials, coll, outcomes, im, fit, err, tuple(r.name for r in recs),
                        tuple(ids), failed)


def default_stripe_levels(ida_result: IDAResult, scales, records, n: int = 8) -> np.ndarray:
    """Default IM levels (the IDA's IM: PGA [g] by default) of the multiple stripes after an IDA:
    ``n`` geometric levels from 0.6 x the smallest to 1.4 x the largest first-collapse IM, so the
    stripes bracket the collapses; if nothing collapsed, from the lowest to the highest IM of the
    records scaled by the lowest and highest scale factors."""
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 1:
        raise ArchInputError(f"n: {n!r}; allowed an integer >= 1")
    f = ida_result.first_ims
    f = f[np.isfinite(f)]
    im = ida_result.im
    unit = [r.pga_g if im == "pga" else _im_factor(r, im) for r in records]
    lo = 0.6 * f.min() if f.size else float(min(im_at(u, im, scales[0]) for u in unit))
    hi = 1.4 * f.max() if f.size else float(max(im_at(u, im, scales[-1]) for u in unit))
    if n > 1 and not hi > lo * (1 + 1e-9):
        # nothing collapsed and the scales give one IM: no range to put stripes in
        s = np.atleast_1d(np.asarray(scales, float))
        grid = ", ".join(f"{x:g}" for x in s[:5]) + (", ..." if s.size > 5 else "")
        raise ArchInputError(
            f"scales: {grid}: no record collapsed and the records scaled by these factors have "
            f"one IM ({lo:g}), so there is no range for the default stripe levels; allowed a "
            f"range of scale factors reaching a collapse (LO:HI:N, e.g. 0.1:3:30), or explicit "
            f"--levels")
    return np.geomspace(lo, hi, n)


__all__ += ["default_stripe_levels"]

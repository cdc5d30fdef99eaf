"""The verification study: the contact engine against the four-link model on a grid of pulses.

For one arch and a grid of pulse amplitudes (in g, signed) and durations (s), run the contact
engine (:func:`archrock.contact.engine_respond`) and the four-link model (:func:`respond`) with
the paper's impact law and with the momentum one (:class:`~archrock.dynamics.impact.ImpactSpec`), record
each model's collapse decision, their agreement, and each model's first-collapse amplitude at
each duration (the smallest |amplitude| of the grid that collapses the arch).

:func:`verify_ensemble` checks the four-link model's mechanisms on many arches: for each arch of
an ensemble (irregular arches of an :class:`~archrock.geometry.sampling.ArchSampler`, or a list)
it runs the engine's ramp (:func:`archrock.contact.ramp`) beside the limit analysis that fixes
the four-link model's mechanism, and records in each direction the two multipliers and hinges,
whether they agree (the same hinges, multipliers within ``k_tol``) and, where not, what differs:
a hinge the engine does not open, a joint it opens besides, sliding, or the multiplier.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np

from .._records import readonly_arrays
from ..contact import EngineSettings, engine_respond
from ..errors import ArchInputError, LimitExceededError
from .runner import RunSettings
from ..geometry import VoussoirArch
from ..groundmotion import PulseSpec
from ..dynamics.impact import ImpactSpec
from ..dynamics.response import prepare, respond

__all__ = ["VerifyResult", "verify", "MODELS", "ArchCheck", "DirectionCheck",
           "EnsembleVerifyResult", "verify_ensemble", "ENGINE_RAMP_S", "DEFAULT_K_TOL"]

#: the compared models, in table order
MODELS = ("engine", "paper", "momentum")


@dataclass(frozen=True, eq=False)
class VerifyResult:
    """Collapse decisions ``collapsed[model]`` (len(durations), len(amplitudes)) bool of each of
    :data:`MODELS`; ``peak[model]`` [rad] the peak (equivalent) rotation; ``cv`` the four-link
    laws' restitution (l_to_r); ``first[model][i]`` the first-collapse |amplitude| [g] at
    duration i (NaN when none of the grid collapses)."""

    arch_name: str
    pulse: str
    amplitudes: np.ndarray
    durations: np.ndarray
    collapsed: dict = field(repr=False)
    peak: dict = field(repr=False)
    cv: dict
    settings: EngineSettings

    def __post_init__(self):
        readonly_arrays(self)

    @property
    def first(self) -> dict:
        out = {}
        order = np.argsort(np.abs(self.amplitudes))
        for m in MODELS:
            row = []
            for i in range(len(self.durations)):
                hit = [abs(self.amplitudes[j]) for j in order if self.collapsed[m][i, j]]
                row.append(hit[0] if hit else float("nan"))
            out[m] = np.array(row)
        return out

    def agreement(self, other: str) -> float:
        """Fraction of the grid where the engine and the four-link ``other`` model agree."""
        return float((self.collapsed["engine"] == self.collapsed[other]).mean())

    def to_dict(self) -> dict:
        first = self.first
        return {"arch": self.arch_name, "pulse": self.pulse,
                "amplitudes": self.amplitudes.tolist(), "durations": self.durations.tolist(),
                "collapsed": {m: self.collapsed[m].tolist() for m in MODELS},
                "peak": {m: self.peak[m].tolist() for m in MODELS},
                "first_collapse": {m: [None if np.isnan(v) else float(v) for v in first[m]]
                                   for m in MODELS},
                "agreement": {m: self.agreement(m) for m in MODELS[1:]},
                "cv": dict(self.cv), "engine": self.settings.to_dict()}


def verify(arch: VoussoirArch, amplitudes, durations, *, pulse: str = "oppenheim",
           settings: EngineSettings | None = None, t_free: float = 20.0,
           run_settings=None) -> VerifyResult:
    """Run the engine and the two four-link models on every (duration, amplitude) of the grid.
    settings: the contact engine's; run_settings: how it runs (a
    :class:`~archrock.studies.runner.RunSettings`, named so beside the engine's settings),
    whose ``progress`` gets a line per grid point."""
    progress = RunSettings.from_dict(run_settings).only("verify").sink
    amps = np.asarray(amplitudes, float).ravel()
    durs = np.asarray(durations, float).ravel()
    if amps.size == 0 or durs.size == 0 or not np.all(np.isfinite(amps)) or np.any(amps == 0):
        raise ArchInputError("amplitudes: expected a list of finite nonzero numbers [g]")
    if not np.all(np.isfinite(durs)) or np.any(durs <= 0):
        raise ArchInputError("durations: expected a list of finite numbers > 0 [s]")
    settings = settings or EngineSettings()
    models = {"paper": prepare(arch, ImpactSpec("paper")),
              "momentum": prepare(arch, ImpactSpec("momentum"))}
    col = {m: np.zeros((durs.size, amps.size), bool) for m in MODELS}
    peak = {m: np.zeros((durs.size, amps.size)) for m in MODELS}
    total = durs.size * amps.size
    for i, d in enumerate(durs):
        for j, a in enumerate(amps):
            motion = PulseSpec(pulse, float(a), float(d)).build()
            t_end = float(motion.times[-1]) + 0.1
            for m, model in models.items():
                r = respond(model, motion, t_end=t_end, dt_out=min(0.01, t_end))
                col[m][i, j], peak[m][i, j] = r.collapsed, r.peak
            e = engine_respond(arch, motion, settings, model=models["paper"], t_end=t_end,
                               dt_out=min(0.01, t_end), t_free=t_free)
            col["engine"][i, j], peak["engine"][i, j] = e.collapsed, e.peak
            if progress:
                progress(f"{i * amps.size + j + 1}/{total}: t_p = {d:g} s, a = {a:g} g: engine "
                         f"{'collapse' if e.collapsed else e.status}, paper "
                         f"{'collapse' if col['paper'][i, j] else 'stands'}, momentum "
                         f"{'collapse' if col['momentum'][i, j] else 'stands'}")
    cv = {m: float(models[m].impact.l_to_r) for m in models}
    return VerifyResult(arch.name, pulse, amps, durs, col, peak, cv, settings)


# ---------------------------------------------------------------------------- over an ensemble
#: Seconds of the engine's ramp in both directions on one arch of about 10 voussoirs at the
#: default settings, for the work estimate (2 to 2.5 s on the 2-core development machine for the
#: arches of docs/verification.md, 4 s leaves room for a loaded machine).
ENGINE_RAMP_S = 4.0
#: Relative difference of the engine's activation multiplier from the limit analysis's beyond
#: which an arch counts as a disagreement (the engine's compliance alone gives up to 3%).
DEFAULT_K_TOL = 0.05


@dataclass(frozen=True)
class DirectionCheck:
    """One direction ('l' or 'r') of one arch: ``k_four_link`` and ``hinges_four_link`` (the limit
    analysis's mechanism, the four-link model's), ``k_engine``, ``hinges_engine`` and ``mode``
    ('rocking', 'sliding', or 'rests': no motion within the ramp's range, k_engine NaN) of the
    engine; ``missing``: four-link hinges the engine does not open, ``extra``: joints it opens
    besides; ``k_error``: k_engine / k_four_link - 1; ``agree``: same hinges, rocking, |k_error|
    <= k_tol."""

    direction: str
    k_four_link: float
    hinges_four_link: tuple[int, ...]
    k_engine: float
    hinges_engine: tuple[int, ...]
    mode: str
    missing: tuple[int, ...]
    extra: tuple[int, ...]
    k_error: float
    agree: bool

    @property
    def differences(self) -> tuple[str, ...]:
        """What differs, in words (empty where the two agree)."""
        out = []
        if self.mode != "rocking":
            out.append(self.mode)
        if self.missing:
            out.append("hinge not opened at joint " + ",".join(map(str, self.missing)))
        if self.extra:
            out.append("extra hinge at joint " + ",".join(map(str, self.extra)))
        if not self.agree and not out:
            out.append(f"k differs by {100 * self.k_error:+.1f}%")
        return tuple(out)

    def to_dict(self) -> dict:
        return {"direction": self.direction, "k_four_link": self.k_four_link,
                "hinges_four_link": list(self.hinges_four_link),
                "k_engine": None if math.isnan(self.k_engine) else self.k_engine,
                "hinges_engine": list(self.hinges_engine), "mode": self.mode,
                "missing": list(self.missing), "extra": list(self.extra),
                "k_error": None if math.isnan(self.k_error) else self.k_error,
                "agree": self.agree, "differences": list(self.differences)}


@dataclass(frozen=True)
class ArchCheck:
    """One arch of :func:`verify_ensemble`: its index in the ensemble, name, number of voussoirs,
    both directions (:class:`DirectionCheck`) and the seconds its ramp took."""

    index: int
    name: str
    n: int
    l: DirectionCheck
    r: DirectionCheck
    seconds: float

    @property
    def agree(self) -> bool:
        return self.l.agree and self.r.agree

    def to_dict(self) -> dict:
        return {"index": self.index, "name": self.name, "n": self.n, "agree": self.agree,
                "l": self.l.to_dict(), "r": self.r.to_dict(), "seconds": self.seconds}


@dataclass(frozen=True)
class EnsembleVerifyResult:
    """Result of :func:`verify_ensemble`: ``arches`` (:class:`ArchCheck`, in ensemble order), the
    engine settings, ``k_tol``, the ramp's options and ``sampler`` (its dict, or None for a given
    list of arches)."""

    arches: tuple
    settings: EngineSettings
    k_tol: float
    ramp: dict
    sampler: dict | None = None

    @property
    def n(self) -> int:
        return len(self.arches)

    @property
    def disagreements(self) -> tuple:
        """(arch index, direction, differences) of every direction where the two disagree."""
        return tuple((a.index, d.direction, d.differences) for a in self.arches
                     for d in (a.l, a.r) if not d.agree)

    @property
    def disagreement_rate(self) -> float:
        """Fraction of the arches where the engine and the four-link model disagree in either
        direction."""
        return sum(not a.agree for a in self.arches) / self.n if self.n else 0.0

    @property
    def where(self) -> dict:
        """Where disagreements occur: counts of {'l'|'r': {'missing': {joint: count}, 'extra':
        {joint: count}, 'sliding': count, 'rests': count, 'k': count}}."""
        out = {}
        for a in self.arches:
            for d in (a.l, a.r):
                if d.agree:
                    continue
                w = out.setdefault(d.direction, {"missing": {}, "extra": {}, "sliding": 0,
                                                 "rests": 0, "k": 0})
                for key in ("missing", "extra"):
                    for j in getattr(d, key):
                        w[key][int(j)] = w[key].get(int(j), 0) + 1
                if d.mode in ("sliding", "rests"):
                    w[d.mode] += 1
                if not math.isnan(d.k_error) and abs(d.k_error) > self.k_tol:
                    w["k"] += 1
        return out

    def k_errors(self, direction: str) -> np.ndarray:
        """k_engine / k_four_link - 1 of every arch in ``direction`` (NaN where it rests)."""
        return np.array([getattr(a, direction).k_error for a in self.arches])

    def to_dict(self) -> dict:
        return {"n": self.n, "disagreement_rate": self.disagreement_rate,
                "disagreements": [{"arch": i, "direction": d, "differences": list(w)}
                                  for i, d, w in self.disagreements],
                "where": {d: {k: (dict((str(j), c) for j, c in sorted(v.items()))
                                  if isinstance(v, dict) else v) for k, v in w.items()}
                          for d, w in self.where.items()},
                "k_tol": self.k_tol, "engine": self.settings.to_dict(), "ramp": dict(self.ramp),
                "sampler": self.sampler, "arches": [a.to_dict() for a in self.arches]}


def _hinge_joints(mech) -> tuple[int, ...]:
    return tuple(sorted(int(h.joint) for h in mech.hinges))


def _check_direction(d: str, lim, res, k_tol: float) -> DirectionCheck:
    k4 = float(getattr(lim, f"k_{d}"))
    h4 = _hinge_joints(lim.mechanism(d))
    if res is None:
        return DirectionCheck(d, k4, h4, float("nan"), (), "rests", h4, (), float("nan"), False)
    he = tuple(sorted(int(j) for j in res.hinges))
    missing = tuple(j for j in h4 if j not in he)
    extra = tuple(j for j in he if j not in h4)
    err = res.multiplier / k4 - 1.0 if k4 > 0 and math.isfinite(k4) else float("nan")
    agree = (res.mode == "rocking" and not missing and not extra
             and math.isfinite(err) and abs(err) <= k_tol)
    return DirectionCheck(d, k4, h4, float(res.multiplier), he, res.mode, missing, extra,
                          float(err), bool(agree))


def _check_arch(index: int, arch: VoussoirArch, settings: EngineSettings, k_tol: float,
                ramp_options: dict) -> ArchCheck:
    from ..contact import ramp_direction, ramp_range
    from ..statics.limit import limit_analysis

    t0 = time.perf_counter()
    lim = limit_analysis(arch, verify=False)
    checks = []
    for d in ("l", "r"):
        start, top = ramp_range(getattr(lim, f"k_{d}"))
        try:
            res = ramp_direction(arch, d, settings, lambda_start=start, lambda_max=top,
                                 **ramp_options)
        except LimitExceededError:
            res = None
        checks.append(_check_direction(d, lim, res, k_tol))
    return ArchCheck(int(index), str(arch.name), int(arch.n), checks[0], checks[1],
                     time.perf_counter() - t0)


def _pool_check(index, source, settings_dict, k_tol, ramp_options):
    """One arch in a pool worker: ``source`` the sampler (arch ``index`` drawn there) or the
    arch itself."""
    from ..geometry.sampling import ArchSampler

    arch = source.arch(index) if isinstance(source, ArchSampler) else source
    return _check_arch(index, arch, EngineSettings.from_dict(settings_dict), k_tol, ramp_options)


#: the ramp's options :func:`verify_ensemble` accepts (those of ``ramp_direction``)
RAMP_OPTIONS = ("rate", "hold", "tol", "threshold", "slide_threshold")


def _ramp_defaults() -> dict:
    """``ramp_direction``'s own defaults of :data:`RAMP_OPTIONS` (read from its signature, so
    that they are written once)."""
    import inspect

    from ..contact import ramp_direction

    params = inspect.signature(ramp_direction).parameters
    return {k: params[k].default for k in RAMP_OPTIONS}


def ramp_cost_s(settings: EngineSettings, ramp_options: dict | None = None) -> float:
    """Estimated seconds of one arch's ramp in both directions: :data:`ENGINE_RAMP_S` scaled by
    the steps (steps_per_T / 400), the solver's iterations (about half the cost at 40) and the
    ramp's duration (its rate and holds against 0.05 per T and 4 T, the defaults)."""
    o = {**_ramp_defaults(), **(ramp_options or {})}
    steps = settings.steps_per_T / 400.0
    iters = 0.5 + 0.5 * settings.iterations / 40.0
    length = 0.5 * 0.05 / float(o["rate"]) + 0.5 * float(o["hold"]) / 4.0
    return ENGINE_RAMP_S * steps * iters * length


def verify_ensemble(arches, n: int | None = None, *, settings: EngineSettings | None = None,
                    k_tol: float = DEFAULT_K_TOL, ramp_options=None,
                    run_settings=None) -> EnsembleVerifyResult:
    """The contact engine against the four-link model's mechanisms, arch by arch, over an
    ensemble (module docstring).

    arches: an :class:`~archrock.geometry.sampling.ArchSampler` (then ``n`` its first n arches,
    n >= 1) or a sequence of arches (``n`` None: all of them); settings: the engine's
    (default :class:`EngineSettings`); k_tol: relative difference of the multipliers beyond which
    a direction disagrees (0 < k_tol < 1); ramp_options: rate, hold, tol, threshold,
    slide_threshold of :func:`~archrock.contact.ramp_direction`; run_settings: how it runs (a
    :class:`~archrock.studies.runner.RunSettings`, named so beside the engine's settings):
    ``workers`` > 1 a process pool of that many, one arch per task (results never depend on
    it), ``progress`` a line per arch.  Bounded by :func:`~archrock.studies.work.check_work`
    (:data:`ENGINE_RAMP_S` an arch)."""
    from .work import check_work

    run = RunSettings.from_dict(run_settings).only("verify_ensemble", "workers")
    sampler, arch_list, items = _ensemble_arches(arches, n)
    if isinstance(k_tol, bool) or not isinstance(k_tol, (int, float)) or not 0 < k_tol < 1:
        raise ArchInputError(f"k_tol: {k_tol!r}; allowed 0 < k_tol < 1")
    workers = run.workers or 1
    opts = dict(ramp_options or {})
    bad = sorted(set(opts) - set(RAMP_OPTIONS))
    if bad:
        raise ArchInputError(f"ramp_options: unknown {bad}; allowed {list(RAMP_OPTIONS)}")
    settings = settings or EngineSettings()
    check_work("verify over an ensemble", len(items), "arches (engine ramps)",
               ramp_cost_s(settings, opts), "give fewer arches (--samples) or more --workers",
               workers=workers, kernel=False)
    results: dict = {}
    progress = run.sink

    def done(chk: ArchCheck):
        results[chk.index] = chk
        if progress:
            progress(_check_line(chk, len(results), len(items)))

    if workers > 1 and len(items) > 1:
        _checks_in_pool(items, sampler, arch_list, settings, float(k_tol), opts, workers, done)
    else:
        for i in items:
            arch = sampler.arch(i) if sampler is not None else arch_list[i]
            done(_check_arch(i, arch, settings, float(k_tol), opts))
    return EnsembleVerifyResult(tuple(results[i] for i in items), settings, float(k_tol),
                                {**_ramp_defaults(), **opts},
                                None if sampler is None else sampler.to_dict())


def _ensemble_arches(arches, n) -> tuple:
    """(sampler or None, list of arches or None, the indices to check) of
    :func:`verify_ensemble`'s ``arches`` and ``n``, refused by name."""
    from ..geometry.sampling import ArchSampler

    if isinstance(arches, ArchSampler):
        if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 1:
            raise ArchInputError(f"n: {n!r}; allowed an integer >= 1 (arches of the sampler)")
        return arches, None, list(range(int(n)))
    try:
        arch_list = list(arches)
    except TypeError:
        raise ArchInputError(f"arches: expected an ArchSampler or a sequence of arches, got "
                             f"{type(arches).__name__}") from None
    if not arch_list or not all(isinstance(a, VoussoirArch) for a in arch_list):
        raise ArchInputError("arches: expected an ArchSampler or a non-empty sequence of "
                             "VoussoirArch")
    if n is not None:
        if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or \
                not 1 <= n <= len(arch_list):
            raise ArchInputError(f"n: {n!r}; allowed 1 <= n <= {len(arch_list)} (the "
                                 f"arches given) or None")
        arch_list = arch_list[:int(n)]
    return None, arch_list, list(range(len(arch_list)))


def _check_line(chk: ArchCheck, done: int, total: int) -> str:
    """The progress line of one arch checked."""
    what = "agree" if chk.agree else "; ".join(
        f"{d.direction}: {', '.join(d.differences)}" for d in (chk.l, chk.r) if not d.agree)
    return (f"{done}/{total}: arch {chk.index}: k_l {chk.l.k_engine:.4f} "
            f"(four-link {chk.l.k_four_link:.4f}), k_r {chk.r.k_engine:.4f} "
            f"({chk.r.k_four_link:.4f}): {what}")


def _checks_in_pool(items, sampler, arch_list, settings, k_tol, opts, workers, done) -> None:
    """:func:`_check_arch` of the items in a process pool, one arch per task, each result
    given to ``done`` as it finishes."""
    from concurrent.futures import as_completed

    from .ensemble.executors import worker_pool

    sd = settings.to_dict()
    with worker_pool(min(workers, len(items)), spawn=True) as pool:
        futs = [pool.submit(_pool_check, i, sampler if sampler is not None else arch_list[i],
                            sd, k_tol, opts) for i in items]
        for fut in as_completed(futs):
            done(fut.result())

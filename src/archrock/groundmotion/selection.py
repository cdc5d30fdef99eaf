"""Records chosen and scaled for a target spectrum, as the codes ask for time-history analysis.

NTC 2018 par. 3.2.3.6 and EN 1998-1 par. 3.2.3.1.2 accept recorded accelerograms scaled to the
site's elastic spectrum when a set of them meets these rules, which :func:`select_records`
checks and states:

* at least 7 records (then the mean of the responses is the design value; with fewer, the
  largest, and the mean rule below does not apply);
* the mean of their 5%-damped spectra nowhere below ``lower`` (90%) of the target in the period
  range of the structure (NTC: 0.15-2.0 s; EC8: 0.2 T1-2 T1);
* the mean PGA of the scaled set not below the site's, a_g S (EC8 3.2.3.1.2 (4)a);
* scale factors within stated bounds (a record is not stretched into another earthquake).

How the records are chosen (pure and deterministic):

1. each record's spectrum on a log-period grid over the range (and the target's own periods
   there, when they are few: its corners are checked), and its own factor f_i: the geometric mean of
   target / Sa_i over the range, clipped to the bounds;
2. its misfit: the rms of log(f_i Sa_i / target) over the range (spectral shape);
3. at most one component per station when the names are FEMA P695 references ``SUITE/NNc``
   (the better fitting of ``1a``/``1b``), so that 7 records are 7 stations; the event is P695's
   record number, a station of an earthquake (the far-field set has 22 stations of 14
   earthquakes: two stations of one earthquake may both be chosen);
4. the ``count`` records of least misfit, then one common adjustment c, the smallest that
   meets the 90% rule and the PGA rule with every c f_i within the bounds;
5. if c would leave the bounds, a bounded search swaps one record at a time for the swap that
   brings the set closest to the rules, until they hold or no swap helps; then
   :class:`~archrock.errors.NoSelectionError` says by how much the best set fails.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass

import numpy as np

from ..errors import ArchInputError, NoSelectionError
from .motion import GroundMotion
from .spectra import response_spectrum

__all__ = ["RecordSelection", "select_records", "check_settings", "station_key", "CODE_MIN_RECORDS",
           "GRID_POINTS", "MAX_SWAPS"]

#: the codes' least number of records whose mean response is the design value
CODE_MIN_RECORDS = 7
#: log-spaced periods over the range where the rules are checked (plus the target's own)
GRID_POINTS = 60
#: most swaps of the bounded search (each tries every member against every other record)
MAX_SWAPS = 50
_P695 = re.compile(r"^(?P<suite>p695-[a-z-]+?)(?:-normalized)?/(?P<record>\d+)[ab]$")


def station_key(name: str) -> str:
    """The station a record stands for: ``SUITE/N`` for a FEMA P695 component ``SUITE/Nc``
    (both components of record N are one station), else the name itself."""
    m = _P695.match(name) if isinstance(name, str) else None
    return f"{m.group('suite')}/{m.group('record')}" if m else str(name)


@dataclass(frozen=True, eq=False)
class RecordSelection:
    """Records chosen and scaled for a target spectrum (module doc).

    ``indices``/``names``/``events``: the chosen records (positions in the motions given);
    ``factors``: each one's scale factor; ``periods`` [s]: the grid over the period range;
    ``spectra`` [g]: each scaled record's Sa (rows), ``mean`` their mean, ``target`` the
    target's; ``ratio_min`` the least mean/target over the range, at ``ratio_period`` [s];
    ``pga_g``: each scaled record's PGA, ``pga_mean_g`` their mean, ``pga_min_g`` the site's
    (None: not checked); ``rules``: (rule, holds, what was found) each; ``rules_hold``: all
    hold.  Arrays are read-only.
    """

    indices: tuple
    names: tuple
    events: tuple
    factors: np.ndarray
    periods: np.ndarray
    spectra: np.ndarray
    mean: np.ndarray
    target: np.ndarray
    ratio_min: float
    ratio_period: float
    pga_g: np.ndarray
    pga_mean_g: float
    pga_min_g: float | None
    count: int
    period_range: tuple
    lower: float
    scale_bounds: tuple
    one_per_station: bool
    damping: float
    rules: tuple
    adjustment: float
    candidates: int
    description: str = ""

    def __post_init__(self):
        for f in ("factors", "periods", "spectra", "mean", "target", "pga_g"):
            a = np.array(getattr(self, f), float)
            a.setflags(write=False)
            object.__setattr__(self, f, a)

    @property
    def rules_hold(self) -> bool:
        """Whether every rule holds (a count below 7 is a rule that does not)."""
        return all(ok for _, ok, _ in self.rules)

    @property
    def code_mean_rule(self) -> bool:
        """Whether the codes' mean rule applies (7 or more records)."""
        return self.count >= CODE_MIN_RECORDS

    def to_dict(self) -> dict:
        return {
            "description": self.description, "count": self.count,
            "period_range": list(self.period_range), "lower": self.lower,
            "scale_bounds": list(self.scale_bounds), "one_per_station": self.one_per_station,
            "damping": self.damping, "candidates": self.candidates,
            "records": [{"index": int(i), "name": n, "event": e, "factor": float(f),
                         "pga_g": float(p)}
                        for i, n, e, f, p in zip(self.indices, self.names, self.events,
                                                  self.factors, self.pga_g)],
            "adjustment": self.adjustment, "ratio_min": self.ratio_min,
            "ratio_period": self.ratio_period, "pga_mean_g": self.pga_mean_g,
            "pga_min_g": self.pga_min_g, "code_mean_rule": self.code_mean_rule,
            "rules_hold": self.rules_hold,
            "rules": [{"rule": r, "holds": ok, "found": found} for r, ok, found in self.rules],
            "periods": self.periods.tolist(), "target": self.target.tolist(),
            "mean": self.mean.tolist(), "spectra": self.spectra.tolist(),
        }


# ---------------------------------------------------------------------------- input
def _pair(field: str, value, what: str) -> tuple[float, float]:
    try:
        lo, hi = (float(x) for x in value)
    except (TypeError, ValueError):
        raise ArchInputError(f"{field}: {value!r}; allowed two numbers {what}") from None
    if not (math.isfinite(lo) and math.isfinite(hi) and 0.0 < lo <= hi):
        raise ArchInputError(f"{field}: ({lo:g}, {hi:g}); allowed two numbers {what}")
    return lo, hi


def _target(periods, sa) -> tuple[np.ndarray, np.ndarray]:
    try:
        t = np.array(periods, float).reshape(-1)
        s = np.array(sa, float).reshape(-1)
    except (TypeError, ValueError):
        raise ArchInputError("target: periods and Sa must be numbers") from None
    if t.size < 2 or t.size != s.size:
        raise ArchInputError(f"target_periods: {t.size} periods for {s.size} values of Sa; "
                             f"allowed at least 2 periods, one Sa each")
    if not (np.all(np.isfinite(t)) and np.all(np.isfinite(s))):
        raise ArchInputError("target_sa_g: allowed finite numbers")
    if np.any(np.diff(t) <= 0) or t[0] < 0:
        raise ArchInputError("target_periods: allowed increasing periods >= 0 s")
    if np.any(s < 0):
        raise ArchInputError("target_sa_g: allowed Sa >= 0 g")
    return t, s


def _grid(tp: np.ndarray, lo: float, hi: float) -> np.ndarray:
    """Log-spaced periods over [lo, hi], with the target's own periods inside when they are
    few (a code spectrum's corners, a table's rows); a densely sampled target is read between
    its periods on the log grid alone."""
    inner = tp[(tp > lo) & (tp < hi)]
    if inner.size > GRID_POINTS:
        inner = inner[:0]
    return np.unique(np.concatenate([np.geomspace(lo, hi, GRID_POINTS), inner]))


def check_settings(count, period_range, lower, scale_bounds) -> tuple:
    """(count, period_range, lower, scale_bounds) checked and as int, floats; ArchInputError
    naming the field otherwise (the range against a target: :func:`select_records`)."""
    if isinstance(count, (bool, np.bool_)) or not isinstance(count, (int, np.integer)) \
            or count < 1:
        raise ArchInputError(f"count: {count!r}; allowed an integer >= 1 (the codes: >= "
                             f"{CODE_MIN_RECORDS})")
    lo, hi = _pair("period_range", period_range, "0 < lo < hi in s")
    if lo == hi:
        raise ArchInputError(f"period_range: ({lo:g}, {hi:g}) s; allowed 0 < lo < hi in s")
    try:
        low = float(lower)
    except (TypeError, ValueError):
        low = math.nan
    if not 0.0 < low <= 1.0:
        raise ArchInputError(f"lower: {lower!r}; allowed a fraction 0 < lower <= 1 (the "
                             f"codes: 0.9)")
    return int(count), (lo, hi), low, _pair("scale_bounds", scale_bounds, "0 < lo <= hi")


def _check(motions, count, period_range, lower, scale_bounds, pga_min_g, names, tp):
    count, (lo, hi), low, bounds = check_settings(count, period_range, lower, scale_bounds)
    if lo < tp[0] or hi > tp[-1]:
        raise ArchInputError(f"period_range: ({lo:g}, {hi:g}) s; allowed lo < hi within the "
                             f"target's periods {tp[0]:g}-{tp[-1]:g} s")
    if pga_min_g is not None and not (math.isfinite(float(pga_min_g)) and pga_min_g >= 0):
        raise ArchInputError(f"pga_min_g: {pga_min_g!r}; allowed None or a number >= 0 g")
    motions = list(motions)
    if not all(isinstance(m, GroundMotion) for m in motions):
        raise ArchInputError("motions: allowed GroundMotions")
    if len(motions) < count:
        raise ArchInputError(f"count: {count}; allowed at most the {len(motions)} records "
                             f"given")
    if names is None:
        names = [m.name for m in motions]
    names = [str(n) for n in names]
    if len(names) != len(motions):
        raise ArchInputError(f"names: {len(names)} for {len(motions)} records; allowed one "
                             f"name per record")
    return motions, names, count, (lo, hi), low, bounds


# ---------------------------------------------------------------------------- search
def _own_factors(sa: np.ndarray, target: np.ndarray, bounds) -> tuple[np.ndarray, np.ndarray]:
    """Each record's factor to the target (geometric mean, clipped) and its misfit (rms log)."""
    with np.errstate(divide="ignore"):
        logs = np.log(target)[None, :] - np.log(np.maximum(sa, 1e-300))
    f = np.clip(np.exp(logs.mean(axis=1)), *bounds)
    misfit = np.sqrt(np.mean((logs - np.log(f)[:, None]) ** 2, axis=1))
    return f, misfit


def _eligible(names, misfit, one_per_station) -> list:
    """Record indices in misfit order, only the best component of each station if asked."""
    order = sorted(range(len(names)), key=lambda i: (misfit[i], i))
    if not one_per_station:
        return order
    seen, out = set(), []
    for i in order:
        key = station_key(names[i])
        if key not in seen:
            seen.add(key)
            out.append(i)
    return out


def _needs(chosen, f, sa, pgas, target, lower, pga_min, bounds):
    """The adjustment the rules need (c_need) and allow (c_max) for the set ``chosen``."""
    fc = f[chosen]
    ratio = (fc[:, None] * sa[chosen]).mean(axis=0) / target
    c_need = lower / float(ratio.min())
    if pga_min:
        c_need = max(c_need, pga_min / float(np.mean(fc * pgas[chosen])))
    c_max = bounds[1] / float(fc.max())
    c_min = bounds[0] / float(fc.min())
    return c_need, c_min, c_max


def _search(pool, count, f, sa, pgas, target, lower, pga_min, bounds) -> tuple[list, float]:
    """The best-fitting ``count`` of ``pool`` (misfit order), then one-record swaps towards the
    rules (bounded, :data:`MAX_SWAPS`); the set and its margin c_max / c_need (>= 1: holds)."""
    chosen = list(pool[:count])
    rest = list(pool[count:])

    def margin(ids):
        need, _, cmax = _needs(ids, f, sa, pgas, target, lower, pga_min, bounds)
        return cmax / need

    best = margin(chosen)
    for _ in range(MAX_SWAPS):
        if best >= 1.0:
            break
        swap = None
        for k in range(count):
            for j, r in enumerate(rest):
                trial = chosen[:k] + [r] + chosen[k + 1:]
                m = margin(trial)
                if m > best * (1 + 1e-12):
                    best, swap = m, (k, j)
        if swap is None:
            break
        k, j = swap
        chosen[k], rest[j] = rest[j], chosen[k]
    return chosen, best


def _failure(chosen, f, sa, pgas, target, lower, pga_min, bounds, count, rng) -> str:
    """What the best set reaches at the largest adjustment the bounds allow."""
    _, _, cmax = _needs(chosen, f, sa, pgas, target, lower, pga_min, bounds)
    fc = f[chosen] * cmax
    ratio = float(((fc[:, None] * sa[chosen]).mean(axis=0) / target).min())
    pga = float(np.mean(fc * pgas[chosen]))
    parts = [f"mean/target {ratio:.3f} (needs >= {lower:g})"]
    if pga_min:
        parts.append(f"mean PGA {pga:.3g} g (needs >= {pga_min:.3g} g)")
    return (f"records: no {count} of them meet the rules within scale factors "
            f"{bounds[0]:g}-{bounds[1]:g} over {rng[0]:g}-{rng[1]:g} s; the best set reaches "
            f"{', '.join(parts)} at the largest factors; widen the scale bounds, give more "
            f"records or choose fewer")


def select_records(motions, target_periods, target_sa_g, *, count: int = CODE_MIN_RECORDS,
                   period_range=(0.15, 2.0), lower: float = 0.90, scale_bounds=(0.5, 4.0),
                   pga_min_g: float | None = None, one_per_station: bool = True, names=None,
                   damping: float = 0.05, description: str = "") -> RecordSelection:
    """``count`` of ``motions`` scaled so that their mean ``damping`` spectrum is nowhere below
    ``lower`` x the target (``target_sa_g`` [g] at ``target_periods`` [s], linear between) over
    ``period_range`` [s], every factor within ``scale_bounds`` and the mean PGA of the scaled set
    at least ``pga_min_g`` [g] (module doc).  ``names`` (default: the motions' names) name the
    records and, as FEMA P695 references, their events (``one_per_station``)."""
    tp, ts = _target(target_periods, target_sa_g)
    motions, names, count, rng, lower, bounds = _check(motions, count, period_range, lower,
                                                scale_bounds, pga_min_g, names, tp)
    events = len({station_key(n) for n in names}) if one_per_station else len(names)
    if events < count:
        raise ArchInputError(f"count: {count}; allowed at most the {events} records of "
                             f"distinct stations given (one_per_station)")
    grid = _grid(tp, *rng)
    target = np.interp(grid, tp, ts)
    if np.any(target <= 0):
        raise ArchInputError(f"target_sa_g: 0 g at {grid[np.argmin(target)]:.3g} s; allowed "
                             f"Sa > 0 g over the period range")
    sa = np.array([response_spectrum(m, grid, damping) for m in motions])
    pgas = np.array([m.pga_g for m in motions])
    f, misfit = _own_factors(sa, target, bounds)
    pool = _eligible(names, misfit, bool(one_per_station))
    pga_min = float(pga_min_g) if pga_min_g else 0.0
    chosen, margin = _search(pool, count, f, sa, pgas, target, lower, pga_min, bounds)
    if margin < 1.0:
        raise NoSelectionError(_failure(chosen, f, sa, pgas, target, lower, pga_min, bounds,
                                        count, rng))
    need, cmin, cmax = _needs(chosen, f, sa, pgas, target, lower, pga_min, bounds)
    # a hair above the least adjustment, so that the rules hold in floating point too
    c = max(min(need * (1.0 + 1e-9), cmax), cmin)
    factors = f[chosen] * c
    scaled = factors[:, None] * sa[chosen]
    mean = scaled.mean(axis=0)
    ratio = mean / target
    k = int(np.argmin(ratio))
    pga_scaled = factors * pgas[chosen]
    rules = _rules(count, lower, rng, float(ratio[k]), float(grid[k]), bounds, factors,
                   pga_min_g, float(pga_scaled.mean()), bool(one_per_station))
    return RecordSelection(
        indices=tuple(int(i) for i in chosen), names=tuple(names[i] for i in chosen),
        events=tuple(station_key(names[i]) for i in chosen), factors=factors, periods=grid,
        spectra=scaled, mean=mean, target=target, ratio_min=float(ratio[k]),
        ratio_period=float(grid[k]), pga_g=pga_scaled, pga_mean_g=float(pga_scaled.mean()),
        pga_min_g=None if pga_min_g is None else float(pga_min_g), count=int(count),
        period_range=rng, lower=lower, scale_bounds=bounds, one_per_station=bool(one_per_station),
        damping=float(damping), rules=rules, adjustment=float(c), candidates=len(pool),
        description=str(description))


def _rules(count, lower, rng, ratio, at, bounds, factors, pga_min_g, pga_mean, one) -> tuple:
    """(rule, holds, what was found) of each rule the codes set (module doc)."""
    n_ok = count >= CODE_MIN_RECORDS
    rules = [
        (f"at least {CODE_MIN_RECORDS} records", n_ok,
         f"{count} records" + ("" if n_ok else "; the codes' mean rule does not apply: "
                                               "the largest response governs")),
        (f"mean spectrum >= {lower:g} x target over {rng[0]:g}-{rng[1]:g} s", ratio >= lower
         - 1e-12, f"least mean/target {ratio:.3f} at {at:.3g} s"),
        (f"scale factors within {bounds[0]:g}-{bounds[1]:g}",
         bool(np.all((factors >= bounds[0] * (1 - 1e-12)) & (factors <= bounds[1] * (1 + 1e-12)))),
         f"factors {factors.min():.3g}-{factors.max():.3g}"),
    ]
    if pga_min_g is not None:
        rules.append((f"mean PGA of the scaled set >= the site's {pga_min_g:.3g} g (a_g S)",
                      pga_mean >= pga_min_g * (1 - 1e-12), f"mean PGA {pga_mean:.3g} g"))
    rules.append(("one component per station (a P695 record number: one station of an "
                  "earthquake)" if one else "components chosen freely (both of one station "
                  "allowed)", True, ""))
    return tuple(rules)

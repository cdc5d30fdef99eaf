"""The first collapse amplitude of one arch under one pulse duration (:func:`collapse_amplitude`):
a scan on a geometric grid, then bisection of the first collapse and of the survival windows'
edges (the method, and why collapse is not monotonic in the amplitude: the docstring of
:mod:`archrock.studies.curves`, which builds its curves on these).  Also the checks and the
number-list grammar the curves and other studies share.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from .._records import readonly_arrays
from ..errors import ArchInputError, LimitExceededError
from ..geometry import Arch
from ..groundmotion import MAX_PGA_G, pulse, pulse_kind
from ..dynamics.impact import ImpactSpec
from ..dynamics.response import DynamicModel, prepare, respond

__all__ = ["CollapseAmplitude", "collapse_amplitude", "collapse_mode", "parse_range",
           "bisect_boundary", "survival_runs", "check_tol", "check_a_max", "window_tol"]

#: Allowed range of ``tol``, the bisection's tolerance on the amplitude [g]: below 1e-9 g the
#: boundary is finer than the integrator resolves it (and a bisection to 1e-300 would stall at one
#: ulp); above 0.1 g the "boundary" is coarser than the activation thresholds of slender arches
#: (0.05-0.4 g) and than the default grid's spacing, i.e. no bisection at all.
TOL_MIN_G, TOL_MAX_G = 1e-9, 0.1
#: Bound on the steps of one bisection (:func:`bisect_boundary`, the batch engine's rounds).
#: From a bracket of at most MAX_PGA_G = 20 g to TOL_MIN_G takes 35 halvings (a relative
#: tolerance of 1e-9 on a bracket [lo, hi] with lo >= 0: 30), so the bound only turns a
#: pathological ``test`` into an error instead of an endless loop.
MAX_BISECTIONS = 64

#: Relative tolerance of the survival windows' edges: they are bisected to min(tol, this x the
#: lower end of their bracket) [g], so a window narrower than ``tol`` (0.0007 g wide at 0.46 g on
#: Oppenheim's arch) has edges that describe it.  A few more halvings per edge, bounded as any.
WINDOW_RTOL = 1e-4


def window_tol(tol: float, lo: float) -> float:
    """Bisection tolerance [g] of a survival window's edge bracketed from ``lo`` [g]."""
    return min(tol, WINDOW_RTOL * lo)


#: Response settings used by every collapse test (outcome only: coarse output sampling).
_RESPOND = {"t_end": 0.5, "dt_out": 0.5, "max_events": 20_000}
#: the most impacts one response of a scan may keep: an arch whose impacts lose almost nothing
#: (three voussoirs keep 99.998% of the energy) rocks on for the whole free-motion time near
#: its threshold, with tens of thousands of impacts; past this the search stops with a message
MAX_RESPONSE_EVENTS = 2_000_000


def _respond_scan(model, motion, dt):
    """``respond`` of one scan point, its event table grown (x10, up to
    :data:`MAX_RESPONSE_EVENTS`) where the arch keeps rocking: the outcome never depends on the
    table's size, only whether it is kept."""
    n = _RESPOND["max_events"]
    while True:
        try:
            return respond(model, motion, dt=dt, **{**_RESPOND, "max_events": n})
        except LimitExceededError:
            if n >= MAX_RESPONSE_EVENTS:
                raise LimitExceededError(
                    f"curves: a response of the scan has more than {MAX_RESPONSE_EVENTS} impacts "
                    f"(the arch keeps rocking with almost no loss at its impacts); lower --a-max "
                    f"or use another impact law (--impact)") from None
            n = min(10 * n, MAX_RESPONSE_EVENTS)


# ---------------------------------------------------------------------------- helpers
def _check_real(name: str, value, lo: float | None = None, allowed: str = "") -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)):
        raise ArchInputError(f"{name}: {value!r}; allowed {allowed or 'a finite number'}")
    v = float(value)
    if not math.isfinite(v) or (lo is not None and v <= lo):
        raise ArchInputError(f"{name}: {value!r}; allowed {allowed or 'a finite number'}")
    return v


def check_tol(value, name: str = "tol") -> float:
    """The amplitude tolerance [g] as a float, or ArchInputError naming ``name`` and the
    allowed range TOL_MIN_G <= tol <= TOL_MAX_G."""
    allowed = (f"a tolerance on the collapse amplitude, {TOL_MIN_G:g} g <= {name} <= "
               f"{TOL_MAX_G:g} g")
    v = _check_real(name, value, 0.0, allowed)
    if not TOL_MIN_G <= v <= TOL_MAX_G:
        raise ArchInputError(f"{name}: {value!r}; allowed {allowed}")
    return v


def _check_int(name: str, value, lo: int) -> int:
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < lo:
        raise ArchInputError(f"{name}: {value!r}; allowed an integer >= {lo}")
    return int(value)


def _check_sign(sign) -> int:
    if isinstance(sign, bool) or sign not in (-1, 1):
        raise ArchInputError(f"sign: {sign!r}; allowed -1 (main lobe xg'' = a < 0, opens M_l) "
                             f"or +1 (opens M_r)")
    return int(sign)


def parse_range(text: str, name: str = "durations", signed: bool = False) -> np.ndarray:
    """``"lo:hi:n"`` (n >= 2 evenly spaced values, both ends included) or ``"a,b,c"`` -> array of
    floats > 0 (``signed``: nonzero, e.g. pulse amplitudes whose sign is the direction): the one
    grammar of the command line's number lists."""
    what = "nonzero numbers" if signed else "numbers > 0"
    if not isinstance(text, str) or not text.strip():
        raise ArchInputError(f"{name}: {text!r}; allowed 'lo:hi:n' or a comma list of {what}")
    try:
        if ":" in text:
            parts = text.split(":")
            if len(parts) != 3:
                raise ValueError
            lo, hi, n = float(parts[0]), float(parts[1]), int(parts[2])
            if n < 2 or not (math.isfinite(lo) and math.isfinite(hi)) or hi <= lo:
                raise ValueError
            vals = np.linspace(lo, hi, n)
        else:
            vals = np.array([float(p) for p in text.split(",")])
    except ValueError:
        raise ArchInputError(f"{name}: {text!r}; allowed 'lo:hi:n' (lo < hi, n >= 2: both ends "
                             f"included; one value: write it alone) or a comma list "
                             f"of {what}") from None
    if vals.size == 0 or not np.all(np.isfinite(vals)) or np.any(vals == 0 if signed
                                                                   else vals <= 0):
        raise ArchInputError(f"{name}: {text!r}; allowed {what}")
    return vals


def collapse_mode(response) -> str | None:
    """'before first impact', 'after N impacts' for a collapsed response, None otherwise."""
    if not response.collapsed:
        return None
    n = len(response.impacts)
    return "before first impact" if n == 0 else f"after {n} impact{'s' if n > 1 else ''}"


def _model(arch_or_model, impact, cv, literal_cv=False):
    if isinstance(arch_or_model, DynamicModel):
        given = [n for n, v in (("impact", impact), ("cv", cv), ("literal_cv", literal_cv))
                 if v is not None and v is not False]
        if given:
            raise ArchInputError(f"{given[0]}: the model is already prepared with its impact law "
                                 f"({arch_or_model.impact.model}); allowed only with an Arch (or "
                                 f"prepare the model with the impact law wanted)")
        return arch_or_model
    if not isinstance(arch_or_model, Arch):
        raise ArchInputError(f"model: expected an Arch or a DynamicModel, got {type(arch_or_model).__name__}")
    # one arch analysed alone is its own nominal arch: the model on it (ImpactSpec docs)
    return prepare(arch_or_model, ImpactSpec.parse(impact, cv=cv, literal=literal_cv))


# ---------------------------------------------------------------------------- one duration
@dataclass(frozen=True)
class CollapseAmplitude:
    """First collapse amplitude of one pulse duration.

    amplitude: first collapse |a| [g] (None if no collapse up to ``a_max``); the signed amplitude
    is ``sign * amplitude``.  bracket: (last survival, first collapse) after bisection, |a| [g],
    hi - lo <= tol.  mode: 'before first impact' or 'after N impacts' at the first collapse;
    t_collapse [s] there: the last upward passage of the unstable position before the rotation
    limit (:attr:`archrock.dynamics.response.Response.t_collapse`; the limit, a numerical stop, does not
    move it).  windows: survival windows above the first collapse, (lo, hi) in |a| [g]:
    lo is the smallest and hi the largest surviving amplitude found (edges bisected to ``tol``;
    hi = a_max when the arch still survives at a_max).  threshold: activation threshold |a| [g]
    (k_l for sign -1, k_r for sign +1).  scan_amplitudes / scan_collapsed: the grid and outcomes.
    :attr:`resolution`: the step of that grid, under which a window may be missed.
    """

    duration: float
    kind: str
    sign: int
    amplitude: float | None
    bracket: tuple[float, float] | None
    mode: str | None
    t_collapse: float | None
    windows: tuple[tuple[float, float], ...]
    threshold: float
    a_max: float
    tol: float
    scan_amplitudes: np.ndarray = field(repr=False)
    scan_collapsed: np.ndarray = field(repr=False)
    n_responses: int = 0

    def __post_init__(self):
        readonly_arrays(self)

    @property
    def resolution(self) -> dict:
        """The resolution the windows were searched at: the geometric grid's relative step, its
        step in g at the first collapse (at the threshold where none) and at a_max, and the
        sentence 'windows narrower than X g may be missed'."""
        g = np.asarray(self.scan_amplitudes, dtype=float)
        rel = float(g[1] / g[0] - 1.0)
        at = self.amplitude if self.amplitude is not None else float(g[0])
        i = min(max(int(np.searchsorted(g, at)), 1), g.size - 1)
        here, top = float(g[i] - g[i - 1]), float(g[-1] - g[-2])
        where = "the first collapse" if self.amplitude is not None else "the threshold"
        return {"grid": "geometric", "n_scan": int(g.size), "step_relative": rel,
                "step_g": here, "step_g_at_a_max": top,
                "edge_tol_g": f"min({self.tol:g}, {WINDOW_RTOL:g} |a|)",
                "note": (f"searched on a grid stepping {100 * rel:.2g}% of |a|: windows narrower "
                         f"than {here:.4f} g near {where} ({at:.4f} g; {top:.3g} g at a_max "
                         f"{self.a_max:g} g) may be missed")}

    def to_dict(self) -> dict:
        return {
            "duration": self.duration, "kind": self.kind, "sign": self.sign,
            "amplitude_g": self.amplitude,
            "bracket_g": None if self.bracket is None else list(self.bracket),
            "mode": self.mode, "t_collapse": self.t_collapse,
            "survival_windows_g": [list(w) for w in self.windows],
            "windows_resolution": self.resolution,
            "threshold_g": self.threshold, "a_max_g": self.a_max, "tol_g": self.tol,
            "scan_amplitudes_g": self.scan_amplitudes.tolist(),
            "scan_collapsed": [bool(c) for c in self.scan_collapsed],
            "n_responses": self.n_responses,
        }


def survival_runs(flags, i0: int):
    """(j, k) of each run of survivals flags[j..k] (False) after the first collapse at i0:
    collapse at j - 1, and at k + 1 unless k is the last grid point."""
    n = len(flags)
    j = i0
    while j < n:
        if flags[j]:
            j += 1
            continue
        k = j
        while k + 1 < n and not flags[k + 1]:
            k += 1
        yield j, k
        j = k + 1


def bisect_boundary(test, lo, hi, lo_val, tol, relative=False):
    """Boundary between lo (outcome ``test(lo) == lo_val``) and hi (the other outcome), narrowed
    until hi - lo <= tol (or tol * hi with ``relative``); returns the final (lo, hi).

    The one bisection of the package: collapse amplitudes here, IDA scale factors in
    :mod:`archrock.studies.ida`.  Collapse is not monotonic, so the result is *a* boundary between the
    given ends, not necessarily the lowest one.  Bounded: it also stops where the bracket is
    one or two ulps wide (a tolerance below the floats' resolution), and raises
    LimitExceededError after MAX_BISECTIONS steps (never reached with the tolerances the
    callers allow: 35 steps at most)."""
    for _ in range(MAX_BISECTIONS):
        if not _wider(lo, hi, tol, relative):
            return lo, hi
        mid = 0.5 * (lo + hi)
        if test(mid) == lo_val:
            lo = mid
        else:
            hi = mid
    if _wider(lo, hi, tol, relative):
        raise LimitExceededError(f"bisection: [{lo:.17g}, {hi:.17g}] still wider than the "
                                 f"tolerance {tol:g}{' relative' if relative else ''} after "
                                 f"{MAX_BISECTIONS} steps")
    return lo, hi


def _wider(lo, hi, tol, relative=False):
    """hi - lo above the tolerance (``tol`` or ``tol * hi``) and above the floats' resolution
    at hi (4 ulps: the midpoint of a narrower bracket is one of its ends).  Arrays too."""
    width = np.abs(hi) * tol if relative else tol
    return (hi - lo > width) & (hi - lo > 4 * np.finfo(float).eps * np.abs(hi))


def collapse_amplitude(model, duration: float, kind: str = "oppenheim", sign: int = -1, *,
                       a_max: float = 10.0, n_scan: int = 150, tol: float = 1e-3,
                       impact=None, cv: float | None = None, literal_cv: bool = False,
                       dt: float | None = None) -> CollapseAmplitude:
    """First collapse amplitude [g] of a ``kind`` pulse of duration ``duration`` [s] (module doc).

    model: a prepared :class:`DynamicModel` (or an Arch, prepared with ``impact``/``cv``/
    ``literal_cv`` as :func:`~archrock.dynamics.response.prepare` reads them; default the paper's model
    on that arch; ``literal_cv=True`` applies a fixed c_v to the rates, docs/method.md, Impact); a prepared
    model carries its own impact law, so ``impact``/``cv``/``literal_cv`` are refused with it.
    sign: -1 or +1, the sign of the amplitude a (of the main lobe; for the Ricker pulse not the
    first push, module doc).
    a_max [g]: top of the scan; n_scan: grid points (geometric spacing); tol [g]: bisection
    tolerance; dt [s]: RK4 step of the fast integrator (default: from the arch's size,
    :func:`archrock.dynamics.response.default_steps`).
    """
    model = _model(model, impact, cv, literal_cv)
    kind = pulse_kind(kind)
    sign = _check_sign(sign)
    tp = _check_real("duration", duration, 0.0, "a finite number > 0 s")
    tol = check_tol(tol)
    n_scan = _check_int("n_scan", n_scan, 2)
    thr = float(model.k_l if sign < 0 else model.k_r)
    a_max = check_a_max(_check_real("a_max", a_max, None, f"a finite number > the activation "
                                                          f"threshold {thr:.4f} g"), thr)
    count = [0]
    cache: dict[float, object] = {}

    def run(a):
        if a not in cache:
            count[0] += 1
            cache[a] = _respond_scan(model, pulse(kind, sign * a, tp), dt)
        return cache[a]

    def test(a):
        return run(a).collapsed

    grid = np.geomspace(thr * (1 + 1e-6), a_max, n_scan)
    flags = np.array([test(float(a)) for a in grid])
    hits = np.flatnonzero(flags)
    if hits.size == 0:
        return CollapseAmplitude(tp, kind, sign, None, None, None, None, (), thr, a_max, tol, grid,
                                 flags, count[0])
    i0 = int(hits[0])
    if i0 == 0:
        lo, hi = thr, float(grid[0])  # collapse right at activation: the threshold is the boundary
    else:
        lo, hi = bisect_boundary(test, float(grid[i0 - 1]), float(grid[i0]), False, tol)
    r = run(hi)
    windows = _windows(test, grid, flags, i0, tol)
    return CollapseAmplitude(tp, kind, sign, hi, (lo, hi), collapse_mode(r), r.t_collapse,
                             windows, thr, a_max, tol, grid, flags, count[0])


def check_a_max(a_max: float, thr: float) -> float:
    """``a_max`` [g] above the activation threshold ``thr`` [g] and within MAX_PGA_G."""
    if a_max <= thr * (1 + 1e-6) or a_max > MAX_PGA_G:
        raise ArchInputError(f"a_max: {a_max!r}; allowed a finite number > the activation "
                             f"threshold {thr:.4f} g and <= {MAX_PGA_G:g} g")
    return a_max


def _windows(test, grid, flags, i0: int, tol: float) -> tuple:
    """The survival windows above the first collapse at grid[i0], each edge bisected to
    :func:`window_tol` (the top edge is the grid's end where the arch survives there)."""
    windows = []
    n = grid.size
    for j, k in survival_runs(flags, i0):
        _, w_lo = bisect_boundary(test, float(grid[j - 1]), float(grid[j]), True,
                                  window_tol(tol, float(grid[j - 1])))
        if k + 1 < n:
            w_hi, _ = bisect_boundary(test, float(grid[k]), float(grid[k + 1]), False,
                                      window_tol(tol, float(grid[k])))
        else:
            w_hi = float(grid[k])
        windows.append((w_lo, w_hi))
    return tuple(windows)

"""Studies by the contact engine where one degree of freedom cannot follow the arch (issue 19).

On an arch whose limit mechanism moves a pier (:func:`archrock.dynamics.piers.single_dof_check`
not valid), the four-link model's first collapse is 2-4x the contact engine's
(docs/piers-dynamics.md: heavy piers 3.02 g against 0.71 g).  This module runs the studies on
such arches with the engine instead:

* :func:`choose_dynamics` -- the routing: ``dynamics`` "auto" (the four-link model where the
  check says it is valid, the engine otherwise), "fourlink" or "engine", with the reason;
* :func:`~archrock.studies.ensemble.engine.engine_ensemble` (in the ensemble's folder, which
  builds on this module) -- the ensemble's random arches in the engine;
* :func:`engine_first_collapse` / :func:`engine_collapse_curve` -- the first-collapse amplitude
  of a pulse by the engine: a short geometric scan from the activation threshold, then a
  bounded bisection to a relative tolerance.

Every run estimates its work first (refused beyond :data:`archrock.studies.work.MAX_WORK_S`),
reports progress through a callback and never prints.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np

from ..errors import ArchInputError, ArchrockError
from .work import check_work

__all__ = ["DYNAMICS", "check_dynamics", "DynamicsChoice", "choose_dynamics", "EngineRun",
           "engine_run_cost_s",
           "EngineFirstCollapse", "engine_first_collapse", "engine_collapse_curve",
           "ENGINE_STEP_S", "ARCHROCK_STEP_S", "engine_curves_section", "activation"]

#: The dynamics a study may use: "auto" (the four-link model where one degree of freedom is
#: valid, the contact engine otherwise), "fourlink", "engine".
DYNAMICS = ("auto", "fourlink", "engine")

#: Seconds of one engine step per contact piece, measured on the development machine (heavy
#: piers, 14 blocks, 400 steps/T: about 1.5e-5 s per step and piece).  The work estimate is
#: rough: runs to the end of t_free at this rate; collapse or rest usually ends a run sooner
#: (heavy piers at 0.7 g: 4.4 s an arch against 8 s estimated), a loaded machine runs slower
#: (0.5 g: 10 s an arch at a load of 6-8 on 2 cores).
ENGINE_STEP_S = 1.5e-5

#: archrock's engine: seconds of one step, a + b m^2 with m = 4 (joints) the rows of its contact
#: problem (two bearing corners per joint, two rows each), measured on the development machine
#: under load (Housner's block 4.5 us, Oppenheim's arch at rest 25 us a step; the dense
#: factorisation grows as m^3 but the rows' matrix dominates up to a few dozen joints).
ARCHROCK_STEP_S = (3e-6, 2.5e-8)

#: choose_dynamics's friction when none is passed: the package's default coefficient (None is a
#: value: sliding excluded by the user).
UNSET_FRICTION = object()


def check_dynamics(value) -> str:
    """``value`` if it is one of :data:`DYNAMICS`, else ArchInputError naming the field."""
    if not isinstance(value, str) or value not in DYNAMICS:
        raise ArchInputError(f"dynamics: {value!r}; allowed one of {', '.join(DYNAMICS)}")
    return value


@dataclass(frozen=True)
class DynamicsChoice:
    """Which dynamics a study uses on an arch, and why.

    requested: the ``dynamics`` asked for; used: "fourlink" or "engine"; reason: in words;
    single_dof: :meth:`archrock.dynamics.piers.SingleDofCheck.to_dict` of the nominal arch, or
    None where it was not needed (no piers) or could not be made."""

    requested: str
    used: str
    reason: str
    single_dof: dict | None = None
    friction: float | None = None
    friction_needed: dict | None = None

    @property
    def engine(self) -> bool:
        return self.used == "engine"

    def to_dict(self) -> dict:
        return {"requested": self.requested, "used": self.used, "reason": self.reason,
                "single_dof": self.single_dof, "friction": self.friction,
                "friction_needed": self.friction_needed}


def _sliding(arch, friction) -> tuple[dict | None, str]:
    """({"l": mu or None, "r": ...}, '') the friction the four-link collapse needs in each
    direction, and why one degree of freedom cannot follow at ``friction`` ('' where it can,
    or where ``friction`` is None: sliding excluded by the user, Heyman's hypothesis)."""
    if friction is None:
        return None, ""
    from ..statics.friction import friction_needed, thrust_friction

    try:
        if getattr(arch, "fc", None) is not None:  # on the finite-strength collapse's thrust
            from ..statics.limit import limit_analysis

            lim = limit_analysis(arch)
            need = thrust_friction(arch, {"l": lim.thrust_l, "r": lim.thrust_r})
        else:
            need = friction_needed(arch)
    except ArchrockError as exc:
        return None, f"the friction the rocking needs could not be found ({' '.join(str(exc).split())})"
    need = {d: need[d] for d in ("l", "r")}
    short = [d for d in ("l", "r") if need[d] is None or need[d] > friction]
    if not short:
        return need, ""
    said = ", ".join(f"M_{d} {'no finite friction' if need[d] is None else f'{need[d]:.3f}'}"
                     for d in short)
    return need, (f"the joints need friction ({said}) to rock without sliding, more than mu = "
                  f"{friction:g}: they slide, and the four-link model assumes they do not")


def choose_dynamics(arch, dynamics: str = "auto", friction=UNSET_FRICTION) -> DynamicsChoice:
    """The dynamics for ``arch`` (:class:`DynamicsChoice`), the one routing every command,
    study, report and the app use.  "auto": the four-link model where one degree of freedom
    follows the arch -- no piers, or piers that stay still in both limit mechanisms
    (:func:`~archrock.dynamics.piers.single_dof_check`), and joints whose Coulomb ``friction``
    (default :data:`~archrock.statics.friction.DEFAULT_FRICTION`; None: sliding excluded by the
    user) carries the four-link collapse without sliding; the contact engine otherwise.
    "fourlink" / "engine": as asked, the checks' verdicts still stated."""
    from ..statics.friction import DEFAULT_FRICTION

    dynamics = check_dynamics(dynamics)
    if friction is UNSET_FRICTION:
        friction = DEFAULT_FRICTION
    elif friction is not None and (isinstance(friction, bool)
                                   or not isinstance(friction, (int, float))
                                   or not math.isfinite(friction) or friction <= 0):
        raise ArchInputError(f"friction: {friction!r}; allowed a finite number > 0, or None "
                             f"(sliding excluded)")
    need, slides = _sliding(arch, friction)
    mu = None if friction is None else float(friction)
    choice = _choose(arch, dynamics, slides)
    reason = choice.reason
    if choice.used == "engine" and getattr(arch, "fc", None) is not None:
        reason += (f"; the engine's rigid blocks do not crush: f_c = {arch.fc:g} MPa is not in "
                   f"its answer (docs/crushing-dynamics.md)")
    return DynamicsChoice(choice.requested, choice.used, reason, choice.single_dof, mu, need)


def _choose(arch, dynamics: str, slides: str) -> DynamicsChoice:
    from ..dynamics.piers import pier_blocks

    check = None
    if pier_blocks(arch)[0]:
        from ..dynamics.piers import single_dof_check
        from ..dynamics.response import prepare

        try:  # the verdict reads the limit mechanisms only (c_v does not enter it)
            check = single_dof_check(prepare(arch, 0.8)).to_dict()
        except ArchrockError as exc:
            check = {"valid": None, "reason": f"no four-link model: {' '.join(str(exc).split())}"}
    if dynamics == "auto":
        if slides:
            return DynamicsChoice("auto", "engine", "one degree of freedom cannot follow the "
                                  "arch: " + slides, check)
        if check is None:
            return DynamicsChoice("auto", "fourlink", "no piers: one degree of freedom (the "
                                  "four-link model) follows the arch")
        if check["valid"] is False:
            return DynamicsChoice("auto", "engine", "single degree of freedom not valid: "
                                  + check["reason"], check)
        if check["valid"] is None:
            return DynamicsChoice("auto", "engine", "the one-degree-of-freedom check could not "
                                  "be made on an arch with piers (" + check["reason"] + ")",
                                  check)
        return DynamicsChoice("auto", "fourlink", "the piers stay still in both limit "
                              "mechanisms: one degree of freedom (the four-link model) follows "
                              "the arch", check)
    said = f"asked for (dynamics={dynamics!r})"
    if dynamics == "fourlink" and check is not None and check["valid"] is False:
        said += "; WARNING single degree of freedom not valid: " + check["reason"]
    if dynamics == "fourlink" and slides:
        said += "; WARNING not valid here: " + slides
    return DynamicsChoice(dynamics, dynamics, said, check)


@dataclass(frozen=True)
class EngineRun:
    """How each engine response of a study is run.

    settings: :class:`~archrock.contact.EngineSettings` (or its dict); t_free [T]: free motion
    after the ground motion at most, in units of T = sqrt(size/g) (30: the heavy-pier arch
    rocks for tens of seconds before it falls or rests); collapse_drop: the drop of a mass
    centre, as a fraction of the size, that counts as collapse
    (:func:`archrock.contact.engine_respond`)."""

    settings: object = None
    t_free: float = 30.0
    collapse_drop: float = 0.2

    def __post_init__(self):
        from ..contact.settings import EngineSettings

        s = self.settings
        if s is None:
            s = EngineSettings()
        elif isinstance(s, dict):
            s = EngineSettings.from_dict(s)
        elif not isinstance(s, EngineSettings):
            raise ArchInputError(f"settings: {s!r}; allowed None, an EngineSettings or its dict")
        object.__setattr__(self, "settings", s)
        for name, lo, hi in (("t_free", 0.0, 1e4), ("collapse_drop", 1e-4, 10.0)):
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, (int, float)) or not lo <= v <= hi:
                raise ArchInputError(f"{name}: {v!r}; allowed {lo:g} <= {name} <= {hi:g}")
            object.__setattr__(self, name, float(v))

    def to_dict(self) -> dict:
        return {"settings": self.settings.to_dict(), "t_free": self.t_free,
                "collapse_drop": self.collapse_drop}

    @classmethod
    def from_dict(cls, data) -> "EngineRun":
        if not isinstance(data, dict) or set(data) - {"settings", "t_free", "collapse_drop"}:
            raise ArchInputError(f"engine run: {data!r}; allowed fields settings, t_free, "
                                 f"collapse_drop")
        return cls(**data)

    def respond(self, arch, motion, model=None):
        """The engine's response of ``arch`` to ``motion``: its outcome, and its peak |phi|
        [rad] sampled every 0.01 s during the motion and at the end of the run."""
        from ..contact.motion import engine_respond

        t_end = float(motion.times[-1])
        return engine_respond(arch, motion, self.settings, model=model, t_end=t_end,
                              dt_out=min(0.01, t_end), t_free=self.t_free,
                              collapse_drop=self.collapse_drop)


def engine_run_cost_s(arch, duration: float, run: EngineRun) -> float:
    """Upper estimate [s] of one engine response of ``arch`` to a motion of ``duration`` [s]:
    the steps to the end of the free motion times the cost of a step: archrock's engine
    :data:`ARCHROCK_STEP_S` (a + b m^2, m = 4 (n + 1) rows), pymunk's :data:`ENGINE_STEP_S` per
    contact piece (about 3 per voussoir at the default outline tolerance)."""
    from ..contact.settings import engine_scales

    sc = engine_scales(arch, run.settings)
    steps = (float(duration) + run.t_free * sc.time_scale) / sc.dt
    if run.settings.engine == "archrock":
        m = 4 * (int(arch.n) + 1)
        return steps * (ARCHROCK_STEP_S[0] + ARCHROCK_STEP_S[1] * m * m)
    pieces = 3 * int(arch.n) + 2
    return steps * pieces * ENGINE_STEP_S * run.settings.iterations / 40.0


# ---------------------------------------------------------------------------- first collapse
@dataclass(frozen=True)
class EngineFirstCollapse:
    """First-collapse amplitude of a pulse by the contact engine.

    duration [s], kind, sign (of the amplitude: -1 pushes toward -x first); amplitude [g]
    (|a|, the smallest collapsing amplitude found: the bracket's top; None where nothing
    collapsed up to a_max); bracket (last survival, first collapse) [g], hi - lo <= rtol * hi;
    threshold: the activation multiplier at the run's friction (:func:`activation`), where
    the scan starts [g];
    scan_amplitudes / scan_collapsed: the scan; n_responses: engine runs made; seconds;
    run: the :class:`EngineRun`; how: "contact engine".  Collapse is not monotonic in the
    amplitude: this is the first boundary above the threshold on the scan's grid."""

    duration: float
    kind: str
    sign: int
    amplitude: float | None
    bracket: tuple | None
    threshold: float
    a_max: float
    rtol: float
    scan_amplitudes: tuple
    scan_collapsed: tuple
    n_responses: int
    seconds: float
    run: EngineRun = field(default_factory=EngineRun)
    how: str = "contact engine"

    # read by the collapse-curve figure and table, as a four-link point
    mode = None
    windows = ()
    t_collapse = None

    @property
    def resolution(self) -> dict:
        """What was searched, in the shape of a four-link point's: no survival windows (the
        engine finds the first boundary only, to rtol), said as such."""
        return {"grid": None, "n_scan": len(self.scan_amplitudes), "step_relative": None,
                "step_g": None, "edge_tol_g": f"{self.rtol:g} |a|",
                "note": (f"the contact engine's first collapse only, bisected to "
                         f"{100 * self.rtol:g}% of |a|: survival windows above it were not "
                         f"searched")}

    def to_dict(self) -> dict:
        return {"duration_s": self.duration, "kind": self.kind, "sign": self.sign,
                "amplitude_g": self.amplitude,
                "bracket_g": None if self.bracket is None else list(self.bracket),
                "threshold_g": self.threshold, "a_max_g": self.a_max, "rtol": self.rtol,
                "scan_amplitudes_g": list(self.scan_amplitudes),
                "scan_collapsed": list(self.scan_collapsed), "n_responses": self.n_responses,
                "seconds": self.seconds, "engine": self.run.to_dict(), "how": self.how}


def activation(arch, model, friction: float) -> dict:
    """{"l": k_l, "r": k_r} [g]: where the engine's joints (Coulomb ``friction``) start to move,
    the scan's threshold: the four-link model's multipliers where the joints carry them without
    sliding, the friction analysis's where they slide first (Oppenheim's arch at mu = 0.4:
    0.2638, not 0.3700); the four-link ones where the friction analysis has no answer."""
    from ..statics.friction import friction_analysis

    k = {"l": float(model.k_l), "r": float(model.k_r)}
    try:
        fa = friction_analysis(arch, friction)
    except ArchrockError:
        return k
    for d in k:
        fd = fa.direction(d)
        if fd.sliding_governs:
            k[d] = min(k[d], float(fd.multiplier))
    return k


def engine_first_collapse(arch, duration: float, kind: str = "oppenheim", sign: int = -1, *,
                          a_max: float = 3.0, n_scan: int = 8, rtol: float = 0.01,
                          run: EngineRun | None = None, model=None,
                          progress=None) -> EngineFirstCollapse:
    """The smallest amplitude |a| [g] of a ``kind`` pulse of ``duration`` [s] (amplitude sign
    ``sign``) that collapses ``arch`` in the contact engine: a geometric scan of ``n_scan``
    amplitudes from the activation multiplier at the run's friction (:func:`activation`) to
    ``a_max``, then a bisection of the first collapsing interval until hi - lo <= rtol * hi
    (:func:`archrock.studies.curves.bisect_boundary`).  Bounded: n_scan + log2(1 / rtol) + 1
    runs at most, each estimated first (:func:`engine_run_cost_s`)."""
    from ..groundmotion import pulse

    kind, sign, tp, n_scan, run, model, thr, a_max = _first_collapse_inputs(
        arch, duration, kind, sign, a_max, n_scan, rtol, run, model)
    probe = pulse(kind, sign * a_max, tp)
    steps = n_scan + math.ceil(math.log2(1.0 / rtol)) + 1
    check_work("engine first collapse", steps, "engine runs",
               engine_run_cost_s(arch, float(probe.times[-1]), run),
               "raise rtol or lower n_scan", 1, kernel=False)
    t0 = time.perf_counter()
    cache: dict[float, bool] = {}

    def test(a):
        if a not in cache:
            cache[a] = run.respond(arch, pulse(kind, sign * a, tp), model).collapsed
            if progress is not None:
                progress(f"engine first collapse: |a| = {a:.4f} g "
                         f"{'collapsed' if cache[a] else 'survived'}")
        return cache[a]

    grid = np.geomspace(thr * (1 + 1e-6), a_max, n_scan)
    flags, bracket = _scan_then_bisect(test, grid, thr, rtol)
    return EngineFirstCollapse(tp, kind, sign, None if bracket is None else float(bracket[1]),
                               None if bracket is None else
                               (float(bracket[0]), float(bracket[1])), thr, float(a_max),
                               float(rtol), tuple(float(a) for a in grid[:len(flags)]),
                               tuple(bool(f) for f in flags), len(cache),
                               time.perf_counter() - t0, run)


def _first_collapse_inputs(arch, duration, kind, sign, a_max, n_scan, rtol, run, model):
    """The checked inputs of :func:`engine_first_collapse`, with the engine run, the dynamic
    model (the limit mechanisms) and the activation threshold [g] of the pulse's sign."""
    from ..dynamics.response import prepare
    from ..groundmotion import pulse_kind
    from .curves import _check_int, _check_real, _check_sign

    kind = pulse_kind(kind)
    sign = _check_sign(sign)
    tp = _check_real("duration", duration, 0.0, "a finite number > 0 s")
    n_scan = _check_int("n_scan", n_scan, 2)
    if isinstance(rtol, bool) or not isinstance(rtol, (int, float)) or not 1e-4 <= rtol <= 0.5:
        raise ArchInputError(f"rtol: {rtol!r}; allowed 1e-4 <= rtol <= 0.5 (relative to the "
                             f"amplitude)")
    run = EngineRun() if run is None else run
    if model is None:
        model = prepare(arch, "momentum")
    thr = activation(arch, model, run.settings.friction)["l" if sign < 0 else "r"]
    a_max = _check_real("a_max", a_max, None, "a finite number")
    if not thr * (1 + 1e-6) < a_max <= 100.0:
        raise ArchInputError(f"a_max: {a_max!r}; allowed above the activation threshold "
                             f"{thr:.4f} g and <= 100 g")
    return kind, sign, tp, n_scan, run, model, thr, a_max


def _scan_then_bisect(test, grid, thr: float, rtol: float):
    """The scan's outcomes up to its first collapse (the runs above it are not needed), and
    the bracket (last survival, first collapse) [g] bisected to ``rtol`` (None: no collapse;
    from the threshold where the lowest amplitude collapsed)."""
    from .curves import bisect_boundary

    flags = []
    for a in grid:
        flags.append(test(float(a)))
        if flags[-1]:
            break
    if not flags[-1]:
        return flags, None
    i0 = len(flags) - 1
    if i0 == 0:
        return flags, (thr, float(grid[0]))
    return flags, bisect_boundary(test, float(grid[i0 - 1]), float(grid[i0]), False, rtol,
                                  relative=True)


def engine_collapse_curve(arch, durations, kind: str = "oppenheim", sign: int = -1, *,
                          a_max: float = 3.0, n_scan: int = 8, rtol: float = 0.02,
                          run: EngineRun | None = None, progress=None):
    """:func:`engine_first_collapse` for each of ``durations`` [s], as a
    :class:`~archrock.studies.curves.CollapseCurve` (its points are
    :class:`EngineFirstCollapse`, ``how`` "contact engine"; no modes, no survival windows;
    cv None: the engine has no impact law), so the collapse-curve figure and table draw it."""
    from ..dynamics.response import prepare
    from .curves import CollapseCurve, _durations

    d = _durations(durations)
    model = prepare(arch, "momentum")
    pts = tuple(engine_first_collapse(arch, float(tp), kind, sign, a_max=a_max, n_scan=n_scan,
                                      rtol=rtol, run=run, model=model, progress=progress)
                for tp in d)
    amps = np.array([np.nan if p.amplitude is None else p.amplitude for p in pts])
    k = activation(arch, model, (EngineRun() if run is None else run).settings.friction)
    return CollapseCurve(d, amps, tuple(None for _ in pts), tuple(() for _ in pts), pts,
                         k["l"], k["r"], None)


def engine_curves_section(ctx, choice: DynamicsChoice):
    """The report's collapse-curve section (:func:`archrock.studies.assessment.section_curves`)
    for an arch that one degree of freedom cannot follow: the first-collapse amplitude of
    Oppenheim's pulse at each of the configuration's durations by the contact engine
    (:func:`engine_collapse_curve`, 2% relative), with the reason; no band over irregular
    arches (an engine run takes seconds)."""
    from .assessment_blocks import Figure, Paragraph, Section, Table

    from ..contact.settings import EngineSettings

    cfg = ctx.config
    # the report's one friction (the choice carries it; None: sliding excluded, the default)
    run = EngineRun(settings=EngineSettings(friction=choice.friction or cfg.friction
                                            or EngineSettings().friction))
    curve = engine_collapse_curve(ctx.arch, cfg.durations, "oppenheim", -1, run=run,
                                  progress=ctx.progress)
    rows = tuple((f"{d:g}", "no collapse up to 3 g" if not math.isfinite(a) else f"{a:.3f}",
                  "contact engine") for d, a in zip(curve.durations, curve.amplitudes))
    text = ("For each pulse duration, the smallest amplitude of Oppenheim's pulse (first push "
            "toward -x) that collapses the arch, computed by the contact engine (rigid blocks "
            "with contact and friction, archrock.contact; bisection to 2% of the amplitude), "
            "not by the four-link model: " + choice.reason + ". No band over irregular arches "
            "(each engine run takes seconds; archrock ensemble --dynamics auto runs them).")
    title = "Collapse-acceleration curve (contact engine)"
    return Section("curves", title,
                   (Paragraph(text), Figure("curves", "Collapse-acceleration curve by the "
                                            "contact engine.", (curve, None)),
                    Table(("t_p [s]", "first collapse |a| [g]", "computed by"), rows)),
                   {"nominal": curve.to_dict(), "how": "contact engine",
                    "dynamics": choice.to_dict()},
                   (("first collapse (engine)", ", ".join(r[1] for r in rows[:1])),))

"""The governing capacity of an arch: one decision among the analyses archrock holds.

:func:`governing_capacity` runs, each as a frozen :class:`Capacity` (what it computed, under
which hypotheses, and whether they hold in each direction):

* "limit analysis (no sliding)" -- Heyman's hypotheses (statics.limit): always;
* "limit analysis with friction mu" -- associative Coulomb friction at every joint
  (statics.friction.friction_analysis; with a finite compressive strength, friction and the
  stress blocks together on the graph of blocks, statics.graph): left out, with the reason,
  where the user excluded sliding (friction None);
* "contact engine ramp at mu" -- rigid blocks with non-associative Coulomb contacts
  (contact.ramp, archrock's own engine): only with ``engine=True``.

The decision, one place for every command and report:

* the no-sliding multiplier holds in a direction where mu >= the friction its collapse needs
  (statics.friction.friction_needed; with a finite strength: where friction together with
  crushing carries the same multiplier); elsewhere the joints slide first and the friction
  analysis gives that direction;
* an engine value within :data:`AGREEMENT` (2%) of the limit analysis at the same friction is
  the same answer within the engine's discretisation: the exact limit value is quoted;
* a larger disagreement is a *finding*: that direction's ramp is run again refined (twice the
  steps and a tighter solver; pymunk's: the fine contact outline and twice the steps); if the engine moves by more than 2% it is not converged
  on this arch and the limit analysis governs (exact within its hypotheses); if it stays, the
  engine holds and governs where lower (with non-associative friction the associative limit
  analysis is not a lower bound: Drucker 1954, Radenkovic 1961);
* governing = the least holding multiplier over both directions, with its analysis,
  direction, mechanism and hypotheses.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from ..errors import ArchrockError
from ..statics.friction import DEFAULT_FRICTION, check_friction

__all__ = ["Capacity", "Governing", "GoverningCapacity", "governing_capacity", "AGREEMENT",
           "engine_friction", "friction_with_crushing",
           "NO_SLIDING", "WITH_FRICTION", "ENGINE", "ENGINE_NOT_ASKED"]

#: Relative difference [-] below which the engine and the limit analysis agree (the engine's
#: accuracy on the documented arches, docs/verification.md), and by which a refined engine run
#: may move before the engine is called not converged on an arch.
AGREEMENT = 0.02
#: Relative tolerance [-] of a tie between analyses (LP optima agree to ~1e-10): on a tie the
#: analysis with fewer hypotheses to state (the first in the list) is named.
_TIE = 1e-7
#: With friction None (sliding excluded by the user) the engine runs at this multiple of the
#: largest friction the no-sliding collapse needs, at least DEFAULT_FRICTION, so that it does
#: not slide either.
_NO_SLIDE_FACTOR = 2.0

NO_SLIDING = "limit analysis (no sliding)"
WITH_FRICTION = "limit analysis with friction"
ENGINE = "contact engine ramp"
ENGINE_NOT_ASKED = "not asked for (engine=False)"
DIRS = ("l", "r")


@dataclass(frozen=True)
class Capacity:
    """One analysis's horizontal-load multipliers [g] and whether they hold.

    name: the analysis; hypotheses: short strings; k_l, k_r: its multipliers (None: none
    found); mechanism_l/_r: hinge or sliding labels; holds: {"l": bool, "r": bool}, whether its
    hypotheses hold in each direction; why: {"l": str, "r": str}, in words; details: what else
    it computed (JSON-ready)."""

    name: str
    hypotheses: tuple
    k_l: float | None
    k_r: float | None
    mechanism_l: str
    mechanism_r: str
    holds: dict
    why: dict
    details: dict = field(default_factory=dict)

    def k(self, d: str) -> float | None:
        return self.k_l if d == "l" else self.k_r

    def mechanism(self, d: str) -> str:
        return self.mechanism_l if d == "l" else self.mechanism_r

    def to_dict(self) -> dict:
        return {"name": self.name, "hypotheses": list(self.hypotheses), "k_l": self.k_l,
                "k_r": self.k_r, "mechanism_l": self.mechanism_l,
                "mechanism_r": self.mechanism_r, "holds": dict(self.holds),
                "why": dict(self.why), "details": dict(self.details)}


@dataclass(frozen=True)
class Governing:
    """The governing multiplier: value [g], direction ("l", "r" or "both"), the analysis, its
    mechanism and hypotheses, and why it governs."""

    value: float
    direction: str
    analysis: str
    mechanism: str
    hypotheses: tuple
    why: str

    @property
    def directions(self) -> str:
        return "both directions" if self.direction == "both" else f"M_{self.direction}"

    def line(self) -> str:
        """One line: 'k = 0.370010 (analysis, direction, hypotheses)'."""
        return (f"k = {self.value:.6f} g ({self.analysis}, {self.directions}, "
                f"{'; '.join(self.hypotheses)})")

    def to_dict(self) -> dict:
        return {"value": self.value, "direction": self.direction, "analysis": self.analysis,
                "mechanism": self.mechanism, "hypotheses": list(self.hypotheses),
                "why": self.why, "units": {"value": "g"}}


@dataclass(frozen=True)
class GoverningCapacity:
    """The decision of :func:`governing_capacity`: friction (mu, or None: sliding excluded by
    the user), the analyses that ran, what was left out and why, the findings (disagreements
    explained), and the governing multiplier (None, with ``why_none``, where nothing holds)."""

    friction: float | None
    analyses: tuple
    left_out: tuple
    findings: tuple
    governing: Governing | None
    why_none: str = ""

    def analysis(self, name_start: str) -> Capacity | None:
        """The analysis whose name starts with ``name_start`` (None: it did not run)."""
        return next((a for a in self.analyses if a.name.startswith(name_start)), None)

    @property
    def friction_words(self) -> str:
        if self.friction is None:
            return "sliding excluded by the user (Heyman's no-sliding hypothesis)"
        return f"Coulomb friction mu = {self.friction:g} at every joint"

    def line(self) -> str:
        """'governing: k = ... (analysis, direction, hypotheses)' or why there is none."""
        if self.governing is None:
            return f"governing: none ({self.why_none})"
        return "governing: " + self.governing.line()

    def to_dict(self) -> dict:
        return {"friction": self.friction, "friction_words": self.friction_words,
                "governing": None if self.governing is None else self.governing.to_dict(),
                "why_none": self.why_none or None,
                "analyses": [a.to_dict() for a in self.analyses],
                "left_out": [{"name": n, "why": w} for n, w in self.left_out],
                "findings": list(self.findings)}


def _one_line(exc) -> str:
    return " ".join(str(exc).split()) or type(exc).__name__


def _no_sliding(lim, needed, mu) -> Capacity:
    """The Heyman multipliers, holding where mu carries them without sliding."""
    holds, why = {}, {}
    for d in DIRS:
        need = None if needed is None else needed[d]
        if mu is None:
            holds[d], why[d] = True, "sliding excluded by the user (Heyman's hypothesis)"
        elif need is not None and need <= mu:
            holds[d], why[d] = True, f"mu = {mu:g} >= {need:.4f}, the friction it needs"
        elif need is None and needed is not None and needed.reasons.get(d, "").startswith(
                "no mechanism"):
            holds[d], why[d] = True, "no mechanism: no friction needed"
        else:
            what = "no finite friction" if need is None else f"mu >= {need:.4f}"
            holds[d], why[d] = False, (f"needs {what}, more than mu = {mu:g}: the joints slide "
                                       f"first")
    fc = getattr(lim.arch, "fc", None)
    hyp = ("no tension", "no crushing" if fc is None else f"crushing at f_c = {fc:g} MPa",
           "no sliding" + ("" if mu is None else f" (checked against mu = {mu:g})"))
    m = {d: lim.mechanism(d) for d in DIRS}
    return Capacity(NO_SLIDING, hyp, float(lim.k_l), float(lim.k_r),
                    "hinges " + m["l"].label, "hinges " + m["r"].label, holds, why,
                    {"friction_needed": None if needed is None else dict(needed),
                     "method": lim.method, "discrepancy": lim.discrepancy})


def _with_friction(arch, mu) -> Capacity:
    """The associative Coulomb multipliers at mu (0 where the arch cannot stand with mu)."""
    from ..errors import CannotStandError
    from ..statics.friction import friction_analysis

    name = f"{WITH_FRICTION} mu = {mu:g}"
    hyp = ("no tension", "no crushing", f"associative Coulomb friction mu = {mu:g}")
    try:
        fa = friction_analysis(arch, mu)
    except CannotStandError as exc:  # the joints slide under self-weight: capacity 0
        msg = _one_line(exc)
        return Capacity(name, hyp, 0.0, 0.0, "sliding under self-weight",
                        "sliding under self-weight", {"l": True, "r": True},
                        {"l": msg, "r": msg}, {"error": msg})
    mech, why = {}, {}
    for d in DIRS:
        fd = fa.direction(d)
        joints = " ".join(map(str, fd.joints))
        mech[d] = (f"sliding at joint(s) {joints}" if fd.sliding_governs
                   else f"hinges (no sliding; most friction at joint(s) {joints})")
        why[d] = ("sliding governs" if fd.sliding_governs else
                  "friction enough: the no-sliding mechanism")
    return Capacity(name, hyp, float(fa.l.multiplier), float(fa.r.multiplier), mech["l"],
                    mech["r"], {"l": True, "r": True}, why,
                    {"sliding_governs": {d: fa.direction(d).sliding_governs for d in DIRS},
                     "method": fa.method})


def friction_with_crushing(arch, mu) -> Capacity:
    """Coulomb friction ``mu`` together with the finite strength ``arch.fc``: the chain as a
    graph of blocks (statics.graph: its friction rows and the stress-block bracket in one
    program), so that neither hypothesis is assumed away."""
    from ..errors import CannotStandError
    from ..geometry.arcade import arcade_from_chain
    from ..statics.graph import graph_limit

    fc = arch.fc
    name = f"{WITH_FRICTION} mu = {mu:g}"
    hyp = ("no tension", f"crushing at f_c = {fc:g} MPa",
           f"associative Coulomb friction mu = {mu:g}")
    arc = arcade_from_chain(arch)
    res, mech, why = {}, {}, {}
    for d in DIRS:
        try:
            g = graph_limit(arc, d, friction=mu)
        except CannotStandError as exc:  # slides or crushes under self-weight: capacity 0
            msg = _one_line(exc)
            return Capacity(name, hyp, 0.0, 0.0, "sliding under self-weight",
                            "sliding under self-weight", {"l": True, "r": True},
                            {"l": msg, "r": msg}, {"error": msg})
        m = g.mechanism
        res[d] = float(g.k)
        slides = " ".join(map(str, m.sliding))
        mech[d] = (f"sliding at joint(s) {slides}" if m.sliding else
                   "hinges " + "-".join(str(h.contact) for h in m.hinges))
        why[d] = "sliding governs" if m.sliding else "friction enough: no joint slides"
    return Capacity(name, hyp, res["l"], res["r"], mech["l"], mech["r"],
                    {"l": True, "r": True}, why,
                    {"method": "graph of blocks: friction rows and the stress-block bracket "
                               "in one static program (statics.graph)"})


def _crushing_slides(no_sliding: Capacity, friction: Capacity) -> Capacity:
    """The finite-strength no-sliding analysis, holding in a direction only where friction
    together with crushing carries the same multiplier (no joint slides first): the friction
    Heyman's collapse needs is not the one of the crushing collapse."""
    holds, why = {}, {}
    for d in DIRS:
        k0, kf = no_sliding.k(d), friction.k(d)
        same = kf is not None and k0 is not None and kf >= k0 - 1e-6 * max(1.0, abs(k0))
        holds[d] = same
        why[d] = (f"friction together with crushing carries it ({kf:.4f})" if same else
                  f"friction together with crushing gives {kf:.4f} < {k0:.4f}: the joints "
                  f"slide first")
    return Capacity(no_sliding.name, no_sliding.hypotheses, no_sliding.k_l, no_sliding.k_r,
                    no_sliding.mechanism_l, no_sliding.mechanism_r, holds, why,
                    {**no_sliding.details, "friction_needed": None})


def engine_friction(mu, needed) -> tuple[float, str]:
    """(friction the engine runs at, note): mu, or with sliding excluded a friction high enough
    not to slide: max(DEFAULT_FRICTION, 2 x the largest friction needed)."""
    if mu is not None:
        return mu, ""
    need = [v for v in (needed or {}).values() if v is not None]
    run = max([DEFAULT_FRICTION] + [_NO_SLIDE_FACTOR * v for v in need])
    return run, (f"sliding excluded by the user: the engine runs at mu = {run:g} = "
                 f"max({DEFAULT_FRICTION:g}, {_NO_SLIDE_FACTOR:g} x the friction needed), "
                 f"enough not to slide")


def _ramp_label(rd) -> str:
    if rd.mode != "rocking":
        return "sliding at joint(s) " + " ".join(map(str, rd.sliding_joints))
    return "hinges at joint(s) " + " ".join(map(str, rd.hinges))


def _refinement(fine) -> str:
    if fine.engine == "archrock":
        return f"{fine.steps_per_T:g} steps per T, solver tolerance {fine.tolerance:g}"
    return f"fine contact outline, {fine.steps_per_T:g} steps per T"


def _refine(arch, d, settings, k_ref, progress):
    """That direction's ramp again refined: twice the steps and a ten times tighter solver
    (archrock's engine), or the fine contact outline and twice the steps (pymunk's)."""
    from ..contact import ramp_direction, ramp_range

    if settings.engine == "archrock":
        fine = settings.replace(steps_per_T=2 * settings.steps_per_T,
                                tolerance=max(1e-12, 0.1 * settings.tolerance))
    else:
        fine = settings.replace(outline_tol=0.0, steps_per_T=2 * settings.steps_per_T)
    start, lam_max = ramp_range(k_ref)
    return ramp_direction(arch, d, fine, lambda_start=start, lambda_max=lam_max,
                          progress=progress), fine


def _engine_direction(arch, d, k_ref, rd, settings, run_mu, progress):
    """(holds, why, findings, refined or None) of the engine's ramp ``rd`` in direction d,
    against the limit analysis's ``k_ref`` at the same friction, refined where they disagree."""
    k_eng = rd.multiplier
    if k_ref is None or not math.isfinite(k_ref) or k_ref <= 0:
        return True, "no limit value to compare with", [], None
    diff = k_eng / k_ref - 1
    if abs(diff) <= AGREEMENT:
        return True, (f"agrees with the limit analysis within {100 * AGREEMENT:g}% "
                      f"({100 * diff:+.1f}%): the same answer within the engine's "
                      f"discretisation, the exact limit value is quoted"), [], None
    fine_rd, fine = _refine(arch, d, settings, k_ref, progress)
    k_fine = fine_rd.multiplier
    moved = k_fine / k_eng - 1
    refined = {"multiplier": k_fine, "moved": moved, "settings": fine.to_dict(),
               "mode": fine_rd.mode, "hinges": list(fine_rd.hinges)}
    head = (f"M_{d}: the contact engine at mu = {run_mu:g} gives {k_eng:.4f}, the limit "
            f"analysis {k_ref:.4f} ({100 * diff:+.1f}%, more than {100 * AGREEMENT:g}%)")
    if abs(moved) > AGREEMENT:
        why = (f"not converged on this arch: refined ({_refinement(fine)}) it moves "
               f"from {k_eng:.4f} to "
               f"{k_fine:.4f} ({100 * moved:+.1f}%)")
        finding = (f"{head}; run again refined ({_refinement(fine)}) the engine "
                   f"gives {k_fine:.4f} ({100 * moved:+.1f}%): its value moves with its own "
                   f"discretisation, so it is not converged on this arch, and the limit analysis "
                   f"{k_ref:.4f} governs (exact within its hypotheses: kinematic = static LP).")
        return False, why, [finding], refined
    why = (f"converged: refined it gives {k_fine:.4f} ({100 * moved:+.1f}%), "
           f"a disagreement of the models, not of the discretisation")
    low = "the engine's value governs" if k_eng < k_ref else "the limit analysis governs"
    finding = (f"{head}; refined the engine gives {k_fine:.4f} ({100 * moved:+.1f}%, within "
               f"{100 * AGREEMENT:g}%): the models disagree, and {low} (the least: with "
               f"non-associative friction the associative limit analysis is not a lower "
               f"bound).")
    return True, why, [finding], refined


def _engine(arch, lim, mu, needed, ref, progress):
    """(Capacity, findings) of the engine's ramp at mu, compared with ``ref`` (the limit
    analysis at the same friction, per direction), refined where they disagree."""
    from ..contact import EngineSettings, ramp

    run_mu, note = engine_friction(mu, needed)
    settings = EngineSettings(friction=run_mu)
    res = ramp(arch, settings, progress, limit=lim)
    eng = {d: getattr(res, d) for d in DIRS}
    holds, why, findings, refined = {}, {}, [], {}
    fc = getattr(arch, "fc", None)
    for d in DIRS:
        k_fc = getattr(lim, f"k_{d}")
        if fc is not None and eng[d].multiplier > k_fc:
            # rigid blocks cannot crush: above the finite-strength limit the engine's value is
            # not this arch's (docs/crushing-dynamics.md)
            holds[d], why[d] = False, (f"rigid blocks of infinite strength: {eng[d].multiplier:.4f}"
                                       f" is above the limit analysis with f_c = {fc:g} MPa "
                                       f"({k_fc:.4f}); crushing governs")
            findings.append(f"M_{d}: the contact engine's blocks do not crush; with f_c = "
                            f"{fc:g} MPa the limit analysis {k_fc:.4f} governs, not the "
                            f"engine's {eng[d].multiplier:.4f}.")
            continue
        holds[d], why[d], found, refined_d = _engine_direction(
            arch, d, ref[d], eng[d], settings, run_mu, progress)
        findings.extend(found)
        if refined_d is not None:
            refined[d] = refined_d
    if arch.is_symmetric() and abs(eng["l"].multiplier / eng["r"].multiplier - 1) > AGREEMENT:
        findings.append(
            f"The arch is mirror-symmetric, yet the engine gives {eng['l'].multiplier:.4f} "
            f"(M_l) and {eng['r'].multiplier:.4f} (M_r): evidence that it is not converged on "
            f"this arch.")
    hyp = ("rigid blocks", f"non-associative Coulomb friction mu = {run_mu:g}",
           settings.describe())
    details = {"ramp": {d: eng[d].to_dict() for d in DIRS}, "settings": settings.to_dict(),
               "refined": refined, "friction_note": note or None,
               "compared_with": dict(ref)}
    cap = Capacity(f"{ENGINE} at mu = {run_mu:g}", hyp, float(eng["l"].multiplier),
                   float(eng["r"].multiplier), _ramp_label(eng["l"]), _ramp_label(eng["r"]),
                   holds, why, details)
    return cap, findings


def _engine_candidate(cap: Capacity, d: str) -> bool:
    """The engine competes for governing only where it disagrees and is converged (within 2%
    it is the limit answer within its discretisation)."""
    return cap.holds[d] and d in cap.details.get("refined", {})


def _decide(analyses) -> tuple[Governing | None, str]:
    best = {}
    for d in DIRS:
        cands = [a for a in analyses if a.holds[d] and a.k(d) is not None
                 and (not a.name.startswith(ENGINE) or _engine_candidate(a, d))]
        if not cands:
            continue
        low = min(a.k(d) for a in cands)
        best[d] = next(a for a in cands if a.k(d) <= low + _TIE * max(1.0, abs(low)))
    if not best:
        return None, "no analysis whose hypotheses hold gave a multiplier"
    vals = {d: best[d].k(d) for d in best}
    low = min(vals.values())
    ties = [d for d in DIRS if d in vals and vals[d] <= low + _TIE * max(1.0, abs(low))]
    d0 = ties[0]
    a = best[d0]
    both = len(ties) == 2 and best["l"] is best["r"]
    why = (f"the least multiplier among the analyses whose hypotheses hold ({a.why[d0]})")
    mech = (a.mechanism(d0) if not both or a.mechanism_l == a.mechanism_r
            else f"M_l {a.mechanism_l}; M_r {a.mechanism_r}")
    return Governing(float(vals[d0]), "both" if both else d0, a.name, mech, a.hypotheses,
                     why), ""


def _statics(arch, mu, limit):
    """The statical analyses of :func:`governing_capacity`: (the no-sliding LimitResult or None,
    the friction each direction needs or None, [no sliding, with friction] as they apply, the
    analyses left out with why)."""
    from ..errors import NoMechanismError
    from ..statics.friction import friction_needed
    from ..statics.limit import limit_analysis

    analyses, left_out = [], []
    try:
        lim = limit if limit is not None else limit_analysis(arch, verify=True)
    except NoMechanismError as exc:  # only friction brings this arch to a mechanism
        if mu is None:
            raise
        lim = None
        left_out.append((NO_SLIDING, _one_line(exc)))
    try:
        needed = friction_needed(arch)
    except ArchrockError as exc:
        needed = None
        left_out.append(("friction needed", _one_line(exc)))
    if lim is not None:
        analyses.append(_no_sliding(lim, needed, mu))
    if mu is None:
        left_out.append((WITH_FRICTION, "sliding excluded by the user (friction None, "
                                        "--friction none): Heyman's no-sliding hypothesis"))
    elif getattr(arch, "fc", None) is not None:
        try:  # Heyman's friction analysis assumes no crushing: the graph holds both
            fric = friction_with_crushing(arch, mu)
        except NoMechanismError as exc:
            left_out.append((WITH_FRICTION, _one_line(exc)))
        else:
            if lim is not None:
                analyses[-1] = _crushing_slides(analyses[-1], fric)
            analyses.append(fric)
    else:
        analyses.append(_with_friction(arch, mu))
    return lim, needed, analyses, left_out


def governing_capacity(arch, friction=DEFAULT_FRICTION, *, engine: bool = False, limit=None,
                       progress=None, engine_left_out: str = ENGINE_NOT_ASKED
                       ) -> GoverningCapacity:
    """The governing horizontal-load multiplier of ``arch`` [g] (:class:`GoverningCapacity`).

    friction: the joints' Coulomb coefficient (default the package's
    :data:`~archrock.statics.friction.DEFAULT_FRICTION`); None: sliding excluded by the user
    (the friction analysis is left out; NoMechanismError where no mechanism opens without
    sliding, else the no-sliding analysis is left out with the reason). engine: also ramp the contact engine (minutes; left out
    where pymunk does not import); limit: the arch's LimitResult if already computed;
    progress: a callback of the engine's lines; engine_left_out: why the engine is left out
    when ``engine`` is False."""
    mu = None if friction is None else check_friction(friction)
    lim, needed, analyses, left_out = _statics(arch, mu, limit)
    ref = {d: (analyses[-1].k(d) if analyses else None) for d in DIRS}
    findings = []
    if engine and lim is None:
        left_out.append((ENGINE, "no mechanism without sliding to set the ramp's range: "
                                 "archrock dem --ramp --ramp-max"))
    elif not engine:
        left_out.append((ENGINE, engine_left_out))
    else:
        try:
            from ..contact import require_engine

            require_engine()
        except ImportError:
            left_out.append((ENGINE, "pymunk is not installed: pip install 'archrock[dem]'"))
        else:
            cap, found = _engine(arch, lim, mu, needed, ref, progress)
            analyses.append(cap)
            findings.extend(found)
    gov, why_none = _decide(analyses)
    return GoverningCapacity(mu, tuple(analyses), tuple(left_out), tuple(findings), gov,
                             why_none)

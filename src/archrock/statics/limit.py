"""Limit analysis of voussoir arches under horizontal loads (Heyman's hypotheses).

Any :class:`~archrock.geometry.VoussoirArch`: only its joint contact segments, voussoir masses
(with their loads) and mass centres enter.  Loads: the weight W_i at each voussoir's mass centre
plus a horizontal force lambda*W_i there.
Direction 'l' means forces toward +x (mechanism M_l, activated by xg''/g <= -k_l, paper eq. 1);
direction 'r' means forces toward -x (M_r, activated by xg''/g >= k_r).

:func:`limit_analysis` gives the Heyman collapse multipliers, their mechanisms and lines of
thrust (:class:`LimitResult`) from two independent methods, each in its own module of
:mod:`archrock.statics`:

* :mod:`.hinges`: :class:`Hinge`, :class:`Mechanism` and the one enumeration order of the
  four-hinge candidates (4 joints out of n+1, each hinge at the intrados or extrados end);
* :mod:`.sums`: the virtual-work multipliers of candidates from prefix sums of W, W*x_G, W*y_G
  (O(1) per candidate, vectorised over candidates and arches);
* :mod:`.kinematic`: the four-hinge search (enumeration in numpy or numba, with its work
  estimate; above ENUMERATION_MAX_VOUSSOIRS voussoirs the static-guided search) and the
  governing mechanism;
* :mod:`.lp`: the static linear program on the three redundant reactions and lambda, and the
  line of thrust (:class:`ThrustLine`);
* :mod:`.liftoff`: mechanisms with lift-off read from the LP's dual, and the certificate that a
  four-hinge mechanism governs (its line of thrust fits the arch);
* :mod:`.thickness`: the minimum thickness under self-weight.

This module keeps :class:`LimitResult`, :func:`limit_analysis` and :func:`require_four_hinge`,
and re-exports the names above, so ``from archrock.statics.limit import X`` keeps working (the
same objects).  The module switches of the search (``_NUMBA_ENABLED``, ``_CONFIRM_RTOL``, ...)
live in :mod:`.kinematic` alone: patch them there.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..errors import ArchInputError, NotFourHingeError
from ..geometry import VoussoirArch
# re-exported (the same objects) for ``from archrock.statics.limit import ...`` and old pickles;
# the mutable switches of the search are not: they live in .kinematic alone
from .hinges import (DIRECTIONS, EDGES, HINGE_LABELS, Hinge, Mechanism, _active_candidates,
                     _candidate_index, _candidates, _mechanism_from_candidate, candidate_hinges)
from .kinematic import (ENUMERATION_MAX_VOUSSOIRS, MAX_ENUMERATION_SECONDS, SEARCH_CHOICES,
                        _disable_numba, _governing, enumeration_estimate,
                        kinematic_mechanisms, kinematic_multipliers_arches,
                        kinematic_multipliers_batch, limit_progress)
from .liftoff import (CERTIFY_TOL, GENERAL_MAX_VOUSSOIRS, LIFT_OFF_REASON, certify_candidates,
                      certify_four_hinge, general_mechanisms, mechanism_multiplier)
from .lp import (ThrustLine, _stands, _statics, _Statics, _thrust_from_x, static_multiplier,
                 thrust_line)
from .sums import _batch_sums, _enumerate, arch_sums, length_scale
from .thickness import MinimumThickness, minimum_thickness, thickness_bisection

__all__ = [
    "Hinge", "Mechanism", "ThrustLine", "LimitResult", "MinimumThickness",
    "limit_analysis", "kinematic_mechanisms", "kinematic_multipliers_batch",
    "kinematic_multipliers_arches",
    "static_multiplier", "thrust_line", "minimum_thickness", "thickness_bisection",
    "length_scale", "arch_sums", "general_mechanisms", "mechanism_multiplier",
    "certify_four_hinge", "CERTIFY_TOL", "GENERAL_MAX_VOUSSOIRS", "require_four_hinge",
    "certify_candidates", "LIFT_OFF_REASON", "limit_progress",
    "enumeration_estimate", "EDGES", "SEARCH_CHOICES", "ENUMERATION_MAX_VOUSSOIRS",
    "MAX_ENUMERATION_SECONDS",
]


@dataclass(frozen=True)
class LimitResult:
    """Result of :func:`limit_analysis`: multipliers, mechanisms and thrust lines, both directions.

    k_l, k_r: the Heyman collapse multipliers, the virtual-work values of the governing
    mechanisms (four-hinge where the line of thrust through the best four-hinge mechanism fits
    the arch, else the mechanism with lift-off from the static LP's dual); static_k_l,
    static_k_r: the linear program's optima (None when not solved); ``discrepancy`` the largest
    |kinematic - static| difference; four_hinge_l/_r: the best four-hinge mechanism of each
    direction (the governing one, or the one a four-link model would open; None where none).
    """

    arch: VoussoirArch = field(repr=False)
    k_l: float
    k_r: float
    mechanism_l: Mechanism
    mechanism_r: Mechanism
    thrust_l: ThrustLine = field(repr=False)
    thrust_r: ThrustLine = field(repr=False)
    static_k_l: float | None = None
    static_k_r: float | None = None
    discrepancy: float | None = None
    method: str = "kinematic enumeration (vectorised), checked by static LP (HiGHS)"
    four_hinge_l: Mechanism | None = None
    four_hinge_r: Mechanism | None = None
    #: finite f_c only (None under Heyman's hypotheses): (lower, upper) of each static optimum
    #: and the compressed zones' depths [m] at each joint at collapse (0 where it is open)
    k_bounds_l: tuple | None = None
    k_bounds_r: tuple | None = None
    zones_l: np.ndarray | None = field(default=None, repr=False)
    zones_r: np.ndarray | None = field(default=None, repr=False)

    @property
    def four_hinge(self) -> bool:
        """Whether four-hinge mechanisms govern both directions (the four-link model holds)."""
        return self.mechanism_l.is_four_hinge and self.mechanism_r.is_four_hinge

    def not_four_hinge(self, direction: str) -> str | None:
        """Why the four-link model does not hold in ``direction`` (None where it does): the
        governing mechanism and what the best four-hinge one would need."""
        m = self.mechanism(direction)
        if m.is_four_hinge:
            return None
        four = self.four_hinge_l if direction == "l" else self.four_hinge_r
        best = ("no four-hinge mechanism loads this direction" if four is None else
                f"the best four-hinge mechanism {four.label} would need k = "
                f"{four.multiplier:.4f}")
        return f"M_{direction} is governed by a {m.describe()} at k = {m.multiplier:.4f} ({best})"

    @property
    def k(self) -> float:
        """The smaller of the two multipliers (the arch's seismic capacity, in g)."""
        return min(self.k_l, self.k_r)

    def mechanism(self, direction: str) -> Mechanism:
        return self.mechanism_l if direction == "l" else self.mechanism_r

    def to_dict(self) -> dict:
        return {
            "k_l": self.k_l, "k_r": self.k_r,
            "mechanism_l": self.mechanism_l.to_dict(), "mechanism_r": self.mechanism_r.to_dict(),
            "static_k_l": self.static_k_l, "static_k_r": self.static_k_r,
            "discrepancy": self.discrepancy, "method": self.method,
            "four_hinge_l": None if self.four_hinge_l is None else self.four_hinge_l.to_dict(),
            "four_hinge_r": None if self.four_hinge_r is None else self.four_hinge_r.to_dict(),
            "thrust_l": _thrust_dict(self.thrust_l),
            "thrust_r": _thrust_dict(self.thrust_r),
            "arch": self.arch.to_dict(),
            **self._crushing_dict(),
        }

    def _crushing_dict(self) -> dict:
        """The crushing fields, only with finite f_c (Heyman's dict stays as it was)."""
        if self.k_bounds_l is None:
            return {}
        return {"fc": self.arch.fc, "k_bounds_l": list(self.k_bounds_l),
                "k_bounds_r": list(self.k_bounds_r), "zones_l": self.zones_l.tolist(),
                "zones_r": self.zones_r.tolist()}


def _thrust_dict(th: ThrustLine) -> dict:
    """Crossing points [m] of every arch, and radii [m] where the joints are radial."""
    out = {} if th.radii is None else {"radii": th.radii.tolist()}
    out["points"] = th.points.tolist()
    return out


def require_four_hinge(result: LimitResult, what: str = "the four-link model") -> None:
    """NotFourHingeError, naming the mechanism, where a direction of ``result`` is governed by
    a mechanism with lift-off: Oppenheim's four-link model (and every study built on it) holds
    only where four-hinge mechanisms govern."""
    for d in DIRECTIONS:
        why = result.not_four_hinge(d)
        if why is not None:
            raise NotFourHingeError(f"arch: {why}; {what} does not hold for this arch: the "
                                    f"contact engine follows it (archrock dem)")


_HOW = {"four-hinge": "four-hinge enumeration (vectorised), certified by its line of thrust",
        "lp-dual": "static LP (HiGHS) optimum; mechanism from its dual, confirmed by virtual work",
        "general-enumeration": "static LP (HiGHS) optimum; mechanism by enumeration of every "
                               "mechanism with lift-off, confirmed by virtual work"}


def limit_analysis(arch: VoussoirArch, verify: bool = True, method: str = "auto",
                   max_seconds: float | None = None) -> LimitResult:
    """k_l, k_r, their mechanisms and thrust lines of any arch: the Heyman collapse multiplier
    (the static LP's optimum) and the mechanism that attains it, four-hinge or with lift-off
    (docs/method.md, The Heyman optimum).  ``verify``: solve the LP also where a four-hinge
    mechanism is certified by its line of thrust, and report kinematic - static.

    ``method``: "auto" (four-hinge enumeration up to :data:`ENUMERATION_MAX_VOUSSOIRS`
    voussoirs, the static-guided search above), "enumeration" or "guided"; ``max_seconds``
    bounds a full enumeration's estimated time (see :func:`kinematic_multipliers_batch`).
    """
    if not isinstance(arch, VoussoirArch):
        raise ArchInputError(f"arch: expected a VoussoirArch (Arch, PolygonArch), got "
                             f"{type(arch).__name__}")
    if arch.fc is not None:
        return _crushing_limit(arch, method, max_seconds)
    gov = _governing(arch, method, max_seconds, static=verify)
    m_l, m_r = gov["l"].mechanism, gov["r"].mechanism
    th = {}
    for d, m in (("l", m_l), ("r", m_r)):
        th[d] = thrust_line(arch, m) if m.is_four_hinge else gov[d].thrust
    s_l, s_r = gov["l"].static, gov["r"].static
    disc = None
    if s_l is not None and s_r is not None:
        disc = max(abs(s_l - m_l.multiplier), abs(s_r - m_r.multiplier))
    guided = method == "guided" or (method == "auto" and arch.n > ENUMERATION_MAX_VOUSSOIRS)
    hows = []
    for d in DIRECTIONS:
        h = _HOW[gov[d].how]
        if gov[d].how == "four-hinge" and guided:
            h = "static-guided four-hinge search, certified by its line of thrust"
        hows.append(h)
    how = hows[0] if hows[0] == hows[1] else f"l: {hows[0]}; r: {hows[1]}"
    if disc is not None:
        how += f"; kinematic = static LP (HiGHS) to {disc:.1e}"
    f_l, f_r = gov["l"].four_hinge, gov["r"].four_hinge
    return LimitResult(arch, m_l.multiplier, m_r.multiplier, m_l, m_r, th["l"], th["r"], s_l, s_r,
                       disc, method=how, four_hinge_l=f_l, four_hinge_r=f_r)


_CRUSH_HOW = {
    "four-hinge": "finite f_c: LP bracket of tangent and secant planes, its optimum solved "
                  "exactly; four hinges at the stress blocks' centres, confirmed by virtual "
                  "work and by the four-hinge enumeration on the inset arch",
    "crushing-static": "finite f_c: LP bracket of tangent and secant planes; the static "
                       "optimum, its hinges where the thrust meets the stress blocks' centres "
                       "(no rigid-block mechanism: the blocks' depth changes as they turn)"}


def _crushing_limit(arch: VoussoirArch, method: str, max_seconds) -> LimitResult:
    """:func:`limit_analysis` with the arch's finite ``fc`` (:mod:`.crushing`)."""
    from .crushing import crushing_analysis

    ans = {d: crushing_analysis(arch, d, method, max_seconds) for d in DIRECTIONS}
    for d in DIRECTIONS:
        if ans[d].static <= 0:
            from ..errors import CannotStandError
            from .overload import cannot_stand_message

            raise CannotStandError(cannot_stand_message(
                arch, f"(with f_c = {arch.fc:g} MPa: k_{d} = {ans[d].static:.4g})"))
    k = {d: ans[d].kinematic if ans[d].kinematic is not None else ans[d].static
         for d in DIRECTIONS}
    gaps = [abs(k[d] - ans[d].static) for d in DIRECTIONS]
    gaps += [abs(k[d] - ans[d].enumeration) for d in DIRECTIONS
             if ans[d].enumeration is not None]
    hows = [_CRUSH_HOW[ans[d].how] for d in DIRECTIONS]
    how = hows[0] if hows[0] == hows[1] else f"l: {hows[0]}; r: {hows[1]}"
    checked = all(ans[d].kinematic is not None for d in DIRECTIONS)
    if checked:
        how += f"; kinematic = static to {max(gaps):.1e}"
    m = {d: ans[d].mechanism for d in DIRECTIONS}
    four = {d: m[d] if m[d].is_four_hinge else None for d in DIRECTIONS}
    return LimitResult(arch, k["l"], k["r"], m["l"], m["r"], ans["l"].thrust, ans["r"].thrust,
                       ans["l"].static, ans["r"].static, max(gaps) if checked else None,
                       method=how,
                       four_hinge_l=four["l"], four_hinge_r=four["r"],
                       k_bounds_l=ans["l"].bounds, k_bounds_r=ans["r"].bounds,
                       zones_l=ans["l"].zones, zones_r=ans["r"].zones)

"""The thrust range of an arch under its own weight and loads (no horizontal load).

The least and the greatest horizontal thrust H with which a line of thrust fits inside the arch,
in compression, at every joint (Heyman, *The Stone Skeleton*, 1995; Ochsendorf, PhD thesis,
Cambridge 2002, and "The masonry arch on spreading supports", The Structural Engineer 84, 2006).
The minimum thrust is the one an arch settles to when its supports spread, the maximum the one it
takes when they close; the joints where each extreme line of thrust touches the intrados or the
extrados are the hinges that open then.

Both extremes are linear programs (HiGHS) on the static program of :mod:`archrock.statics.lp`
(:func:`archrock.statics.lp._statics`, direction 'l'): the unknowns x = (F0x, F0y, M0, lambda) are the
reactions at the left springing per total weight W and per W times the reference length, lambda is
fixed at 0, and F0x, the horizontal force the left support exerts on the arch, is minimised and
maximised.  F0x > 0 is compression pushing the springings apart (the left support pushes the arch
toward +x, the arch pushes the right support toward +x too), so H = W F0x [N per metre of depth]
with W = g * sum(arch.masses) (docs/thrust.md).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import linprog

from ..errors import ArchInputError, CannotStandError, LimitExceededError
from ..geometry import VoussoirArch
from .hinges import EDGES, Hinge
from .lp import ThrustLine, _statics, _thrust_from_x
from ..units import G

__all__ = ["ThrustRange", "thrust_range", "TOUCH_TOL"]

#: A line of thrust touches an edge where its crossing lies within this fraction of the contact
#: segment's length from the segment's end (0 at the intrados end, 1 at the extrados end).
TOUCH_TOL = 1e-7


@dataclass(frozen=True)
class ThrustRange:
    """Least and greatest horizontal thrust under self-weight and loads (lambda = 0).

    thrust_min, thrust_max: H [N per metre of depth], > 0 for compression pushing the springings
    apart; thrust_max is inf where no bound exists (a flat arch wedged between its springings
    carries any thrust: ``line_max`` is then None and ``hinges_max`` empty).  line_min,
    line_max: the extreme lines of thrust (:class:`archrock.statics.limit.ThrustLine`, multiplier 0);
    hinges_min, hinges_max: the (joint, edge) pairs where each touches the intrados or the
    extrados (the hinges that open when the supports spread, or close), from the left springing;
    points_min, points_max: their crossing points [m] (k, 2); weight: the arch's total weight W
    [N/m], the unit of the nondimensional thrusts ``thrust_min / weight``.
    """

    thrust_min: float
    thrust_max: float
    line_min: ThrustLine
    line_max: ThrustLine | None
    hinges_min: tuple[Hinge, ...]
    hinges_max: tuple[Hinge, ...]
    points_min: np.ndarray
    points_max: np.ndarray
    weight: float

    def __post_init__(self):
        for name in ("points_min", "points_max"):
            a = np.array(getattr(self, name), float).reshape(-1, 2)
            a.setflags(write=False)
            object.__setattr__(self, name, a)

    @staticmethod
    def _extreme(H, hinges, points, line) -> dict:
        bounded = math.isfinite(H)
        return {
            "H": float(H) if bounded else None,
            "bounded": bounded,
            "hinges": [h.to_dict() for h in hinges],
            "points": [[float(p[0]), float(p[1])] for p in points],
            # where the line of thrust crosses each joint 0..n [m]
            "crossings": None if line is None else
            [[float(p[0]), float(p[1])] for p in line.points],
        }

    def to_dict(self) -> dict:
        """``{"thrust_min": {...}, "thrust_max": {...}, "weight": W}``, each extreme with ``H``
        [N/m] (null where unbounded), ``bounded``, ``hinges`` [{joint, edge}], ``points``
        [[x, y]] [m] and ``crossings`` (the line of thrust at every joint [m])."""
        return {
            "thrust_min": self._extreme(self.thrust_min, self.hinges_min, self.points_min,
                                        self.line_min),
            "thrust_max": self._extreme(self.thrust_max, self.hinges_max, self.points_max,
                                        self.line_max),
            "weight": float(self.weight),
        }


def _touching(line: ThrustLine, tol: float = TOUCH_TOL):
    """The (joint, edge) pairs where ``line`` touches an end of its contact segment, and their
    crossing points [m]."""
    hinges, points = [], []
    for j, f in enumerate(line.fractions):
        if not math.isfinite(f):  # a joint transmitting nothing (lift-off): no crossing
            continue
        if abs(f) <= tol:
            hinges.append(Hinge(j, EDGES[0]))
        elif abs(f - 1.0) <= tol:
            hinges.append(Hinge(j, EDGES[1]))
        else:
            continue
        points.append(line.points[j])
    return tuple(hinges), np.array(points, float).reshape(-1, 2)


def _solve(st, sign: float):
    """The linear program: minimise sign * F0x with lambda = 0 (scipy's OptimizeResult)."""
    return linprog(c=[sign, 0.0, 0.0, 0.0], A_ub=st.A_ub, b_ub=st.b_ub,
                  bounds=[(None, None)] * 3 + [(0.0, 0.0)], method="highs")


def thrust_range(arch: VoussoirArch) -> ThrustRange:
    """Least and greatest horizontal thrust [N/m] with which a line of thrust fits inside
    ``arch`` under its own weight and loads, their lines of thrust and the joints where they touch
    the intrados or extrados.  Raises CannotStandError where no line of thrust fits (the arch
    cannot stand under its own weight)."""
    if not isinstance(arch, VoussoirArch):
        raise ArchInputError(f"arch: expected a VoussoirArch, got {type(arch).__name__}")
    if arch.fc is not None:
        return _crushing_range(arch)
    st = _statics(arch, "l")
    weight = G * float(np.sum(arch.masses))
    out = {}
    for key, sign in (("min", 1.0), ("max", -1.0)):
        res = _solve(st, sign)
        if res.status == 2:
            raise CannotStandError(
                f"arch: no line of thrust fits inside the arch under its own weight (linear "
                f"program status {res.status}: {res.message}); the arch cannot stand")
        if res.status == 3:  # unbounded: any thrust in that direction fits
            out[key] = (-sign * math.inf, None, (), np.zeros((0, 2)))
            continue
        if res.status != 0:
            raise LimitExceededError(f"thrust range: the linear program for the {key}imum "
                                     f"thrust did not finish (status {res.status}: "
                                     f"{res.message})")
        x = np.array(res.x, float)
        x[3] = 0.0
        line = _thrust_from_x(st, x)
        hinges, points = _touching(line)
        out[key] = (weight * float(x[0]), line, hinges, points)
    (hmin, lmin, gmin, pmin), (hmax, lmax, gmax, pmax) = out["min"], out["max"]
    if lmin is None:  # H unbounded below: tension between the supports, never for masonry
        raise ArchInputError("arch: any tension between the springings fits a line of thrust "
                             "(no least thrust): no joint crosses the span, not an arch")
    return ThrustRange(hmin, hmax, lmin, lmax, gmin, gmax, pmin, pmax, weight)


def _crushing_range(arch: VoussoirArch) -> ThrustRange:
    """:func:`thrust_range` with the arch's finite ``fc`` (:mod:`.crushing`): the extremes of
    the convex program, bracketed to 1e-6; an extreme line of thrust touches the centres of the
    stress blocks (N / (2 f_c) from an edge) where the hinges open."""
    from .crushing import crushing_constant, crushing_thrust

    st = _statics(arch, "l", "joint-line")
    c = crushing_constant(arch)
    weight = G * float(np.sum(arch.masses))
    out = {}
    for key, sign in (("min", 1.0), ("max", -1.0)):
        h, x = crushing_thrust(arch, sign)
        if h == "infeasible":
            raise CannotStandError(
                f"arch: no line of thrust fits inside the arch under its own weight with f_c = "
                f"{arch.fc:g} MPa; the arch cannot stand")
        if h == "unbounded":
            out[key] = (-sign * math.inf, None, (), np.zeros((0, 2)))
            continue
        x = np.array(x, float)
        x[3] = 0.0
        line = _thrust_from_x(st, x)
        N = st.A_N @ x + st.b_N
        inset = np.where(st.L > 0, c * N / np.where(st.L > 0, st.L, 1.0), 0.0)
        shifted = (line.fractions - inset) / np.maximum(1.0 - 2.0 * inset, 1e-300)
        touch = ThrustLine(line.direction, line.multiplier, line.radii, line.points,
                           line.forces, line.polyline, shifted)
        hinges, points = _touching(touch, 1e-6)
        out[key] = (weight * float(x[0]), line, hinges, points)
    (hmin, lmin, gmin, pmin), (hmax, lmax, gmax, pmax) = out["min"], out["max"]
    if lmin is None:
        raise ArchInputError("arch: any tension between the springings fits a line of thrust "
                             "(no least thrust): no joint crosses the span, not an arch")
    return ThrustRange(hmin, hmax, lmin, lmax, gmin, gmax, pmin, pmax, weight)

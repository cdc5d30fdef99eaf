"""A support movement followed to its end (docs/supports.md): the displaced arch after a finite
movement (:func:`displace`, in steps with hinge migrations) and the displacement capacity, the
largest movement along a direction under which the arch still stands (bisection).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import ArchInputError, CannotStandError
from ..geometry import VoussoirArch
from ..geometry.displaced import MAX_ROTATION, SIDES, DisplacedArch, SupportMovement
from ..units import G
from .determinate import DisplacedState, _labels, _margin_at, _stands_at, _state
from .hinges import EDGES, Hinge
from .onset import CAPACITY_KINDS, _check, _magnitude, _onset, _work

__all__ = ["DisplacementCapacity", "displace", "displacement_capacity", "movement_capacity",
           "movement_size", "STEPS", "BISECT_TOL", "MAX_MOVEMENT"]

#: Steps per arch size [-] while following a movement: the step is size / STEPS.
STEPS = 200
#: Bisection tolerance on the capacity, relative to the arch's size.
BISECT_TOL = 1e-10
#: Largest movement followed, in units of the arch's size.
MAX_MOVEMENT = 2.0


@dataclass(frozen=True)
class DisplacementCapacity:
    """The movement at which the arch can no longer stand, pushing ``kind`` on ``side``.

    capacity: the movement's magnitude [m] (spread, closure, settlement or heave);
    fraction: capacity / span (the distance between the springings' mid-points); hinges: the
    three hinges at the onset; migrations: ((movement [m], hinges), ...) every hinge set
    followed, from the onset's at 0; mechanism: the hinges at capacity (the three and the fourth joint
    end where the line of thrust reaches the masonry's edge) or, where the three hinges come
    into line, the three; reason: "fourth hinge" or "linkage straight" or "bound" (no
    collapse up to MAX_MOVEMENT sizes); curve: (k, 5) rows of movement [m], H [N/m],
    V_left, V_right [N/m] and crown drop [m], from zero to the capacity; how: the method.
    """

    kind: str
    side: str
    capacity: float
    fraction: float
    hinges: tuple[Hinge, ...]
    mechanism: tuple[Hinge, ...]
    reason: str
    curve: np.ndarray
    how: str
    migrations: tuple = ()

    def __post_init__(self):
        a = np.array(self.curve, float).reshape(-1, 5)
        a.setflags(write=False)
        object.__setattr__(self, "curve", a)

    def to_dict(self) -> dict:
        return {"kind": self.kind, "side": self.side, "capacity": float(self.capacity),
                "fraction_of_span": None if self.fraction is None else float(self.fraction),
                "hinges": [h.to_dict() for h in self.hinges],
                "mechanism": [h.to_dict() for h in self.mechanism], "reason": self.reason,
                "curve": {"movement": self.curve[:, 0].tolist(), "H": self.curve[:, 1].tolist(),
                          "V_left": self.curve[:, 2].tolist(),
                          "V_right": self.curve[:, 3].tolist(),
                          "crown_drop": self.curve[:, 4].tolist()},
                "migrations": [{"movement": float(t), "hinges": [h.to_dict() for h in hs]}
                               for t, hs in self.migrations],
                "how": self.how}


def _bisect(arch, unit, hinges, points, lo, hi, tol) -> float:
    """The largest t in [lo, hi) (to ``tol``) at which the arch still stands under
    ``unit`` x t, given that it stands at lo and not at hi."""
    for _ in range(200):  # bounded: 200 halvings reach any tolerance a double can hold
        if hi - lo <= tol:
            break
        mid = 0.5 * (lo + hi)
        if _stands_at(arch, unit.scaled(mid), hinges, points):
            lo = mid
        else:
            hi = mid
    return lo


def _migrate(arch, unit, hinges, points, t, eps):
    """Where the line of thrust of ``hinges`` reaches a fourth joint end just past movement t:
    (new hinges, their base points, the fourth hinge) for the admissible three-hinge set that
    replaces one hinge by the fourth and stands at t + eps (the largest margin), or (None,
    None, fourth) where none does (collapse), fourth None where no joint end is reached (the
    linkage or a hinge's compression ends it)."""
    margin, where, disp = _margin_at(arch, unit.scaled(t + eps), hinges, points)
    if where is None or where == "closing" or where[1] == "point":
        return None, None, None
    fourth = Hinge(int(where[0]), where[1])
    if fourth.joint in {h.joint for h in hinges}:
        return None, None, fourth
    jp = np.asarray(arch.joint_points, float)
    best = None
    for k in range(3):
        trio = tuple(sorted([h for i, h in enumerate(hinges) if i != k] + [fourth],
                            key=lambda g: g.joint))
        pts = [jp[h.joint, EDGES.index(h.edge)] for h in trio]
        m, _, _ = _margin_at(arch, unit.scaled(t + eps), trio, pts)
        if m >= 0 and (best is None or m > best[0]):
            best = (m, trio, pts)
    if best is None:
        return None, None, fourth
    return best[1], best[2], fourth


@dataclass(frozen=True)
class _Path:
    """The followed movement: the curve rows, the hinge sets with the movement where each
    began, and how it ended (capacity, reason, mechanism; reason None where the target was
    reached)."""

    rows: list
    sets: list
    end: float
    reason: str | None
    mechanism: tuple


#: Most hinge migrations followed on one path (each is a hinge moving to another joint).
MAX_MIGRATIONS_PER_JOINT = 4


def _follow(arch, unit: SupportMovement, t_end: float, c_dir, line0, hinges, points) -> _Path:
    """Follow ``unit`` x t for t from 0 to ``t_end`` [m] (or to the capacity) in steps of
    size / STEPS, moving a hinge to the joint where a fourth hinge forms while a three-hinge set
    with it stands (hinge migration), else stopping there (collapse)."""
    size = arch.size
    W = G * float(np.sum(arch.masses))
    f0 = line0.forces[0]
    rows = [[0.0, W * float(f0[0]), W * float(f0[1]), W * (1.0 - float(f0[1])), 0.0]]
    sets = [(0.0, tuple(hinges))]
    h, t, eps = size / STEPS, 0.0, 1e3 * BISECT_TOL * size
    budget = MAX_MIGRATIONS_PER_JOINT * (arch.n + 1)
    while t < t_end:
        nxt = min(t + h, t_end)
        if _stands_at(arch, unit.scaled(nxt), hinges, points):
            st = _state(arch, unit.scaled(nxt), hinges, points, c_dir)
            rows.append([nxt, st.thrust, st.v_left, st.v_right, st.crown_drop])
            t = nxt
            continue
        cap = _bisect(arch, unit, hinges, points, t, nxt, BISECT_TOL * size)
        new, pts, fourth = _migrate(arch, unit, hinges, points, cap, eps)
        if cap > 0:
            st = _state(arch, unit.scaled(cap), hinges, points, c_dir)
            rows.append([cap, st.thrust, st.v_left, st.v_right, st.crown_drop])
        if new is None or budget <= 0:
            margin, where, disp = _margin_at(arch, unit.scaled(cap + eps), hinges, points)
            if disp is None:
                reason, mech = "linkage straight", tuple(hinges)
            elif where == "closing":
                reason, mech = "hinge closes", tuple(hinges)
            elif fourth is None:
                reason, mech = "hinge in tension", tuple(hinges)
            else:
                reason = "fourth hinge"
                mech = tuple(sorted(tuple(hinges) + (fourth,), key=lambda g: g.joint))
            return _Path(rows, sets, cap, reason, mech)
        budget -= 1
        hinges, points, t = new, pts, cap
        sets.append((cap, tuple(new)))
    return _Path(rows, sets, t_end, None, tuple(hinges))


def displace(arch: VoussoirArch, movement: SupportMovement) -> DisplacedState:
    """``arch`` under the prescribed support ``movement``: the hinges that open, the exact
    displaced arch, its line of thrust, thrust and reactions.  The movement is followed from
    zero in steps, with hinge migration (module docstring, 4), so that an arch that collapses
    on the way is caught: CannotStandError names the movement at which it can no longer stand.
    At zero movement the state holds the base arch itself (its results bit for bit)."""
    _check(arch, movement)
    if movement.is_zero:
        return DisplacedState(movement, (), np.zeros((0, 2)), arch, None, math.nan, math.nan,
                              math.nan, 0.0, math.nan)
    d = movement.relative
    if not np.any(d) and movement.rotation == 0.0:
        # both supports settle alike: a rigid translation, no hinge opens
        ul, _ = movement.supports
        n = arch.n
        disp = DisplacedArch(arch, (0.0,) * n, ((0.0, 0.0),) * n, (tuple(ul),) * n, (),
                             movement, ())
        return DisplacedState(movement, (), np.zeros((0, 2)), disp, None, math.nan, math.nan,
                              math.nan, float(-ul[1]), math.nan)
    if movement.rotation == 0.0:
        mag = float(np.hypot(movement.spread, movement.settlement))
    else:
        mag = _magnitude(arch, movement)
    unit = movement.scaled(1.0 / mag)
    hinges, points, line0 = _onset(arch, unit)
    c_dir = _work(arch, unit)
    path = _follow(arch, unit, mag, c_dir, line0, hinges, points)
    if path.reason is not None:
        raise CannotStandError(
            f"arch: it cannot stand under {movement.describe()}: it collapses at "
            f"{path.end:.6g} m of that movement ({path.reason}: hinges "
            f"{_labels(path.mechanism)})")
    _, hinges = path.sets[-1]
    pts = [arch.joint_points[h.joint, EDGES.index(h.edge)] for h in hinges]
    return _state(arch, movement, hinges, pts, c_dir)


def _span(arch) -> float:
    jp = np.asarray(arch.joint_points, float)
    a, b = jp[0].mean(axis=0), jp[-1].mean(axis=0)
    return float(np.hypot(*(b - a)))


def displacement_capacity(arch: VoussoirArch, kind: str = "spread",
                          side: str = "right", pivot_depth: float = 0.0) -> DisplacementCapacity:
    """The movement of ``kind`` ("spread", "closure", "settlement", "heave", or "rotation":
    outward, about the foot ``pivot_depth`` [m] below the springing's outer end) on ``side``
    ("right", "left", "both") at which ``arch`` can no longer stand (module docstring, 4),
    with its mechanism and the curve of thrust, reactions and crown drop against the movement
    (in m; for "rotation" in rad, and its ``fraction`` is None).  Bounded: an arch still
    standing at MAX_MOVEMENT sizes (for rotation: MAX_ROTATION) reports that bound (reason
    "bound")."""
    if kind not in CAPACITY_KINDS and kind != "rotation":
        raise ArchInputError(f"kind: {kind!r}; allowed {', '.join(CAPACITY_KINDS)}, rotation")
    if side not in SIDES:
        raise ArchInputError(f"side: {side!r}; allowed 'right', 'left' or 'both'")
    if kind == "rotation":
        # t in metres: the unit turns 1 / size rad per metre (a point one size from the foot
        # moves 1 m), so the steps and the tolerance are the translations'; reported in rad
        unit = SupportMovement(0.0, 0.0, side, 1.0 / arch.size, pivot_depth)
        _check(arch, unit)
        return _capacity(arch, unit, kind, arch.size,
                         min(MAX_MOVEMENT * arch.size, MAX_ROTATION * arch.size))
    s, v = CAPACITY_KINDS[kind]
    unit = SupportMovement(s, v, side)
    _check(arch, unit)
    if not np.any(unit.relative):
        raise ArchInputError(f"kind: {kind!r} on both supports is a rigid translation of the "
                             f"arch; allowed 'spread' or 'closure' with side 'both'")
    return _capacity(arch, unit, kind)


def movement_capacity(arch: VoussoirArch, movement: SupportMovement) -> DisplacementCapacity:
    """The displacement capacity along ``movement``'s direction (spread and settlement in its
    proportions, on its side): ``capacity`` is the magnitude hypot(spread, settlement) [m] at
    which ``arch`` can no longer stand, so capacity / that of ``movement`` is how many times the
    movement the arch takes (the assessment's "capacity remaining").  ``kind`` is the
    :data:`CAPACITY_KINDS` name of a pure movement, else "combined"."""
    _check(arch, movement)
    if not np.any(movement.relative) and movement.rotation == 0.0:
        raise ArchInputError(f"movement: {movement.describe()} is a rigid translation of the "
                             f"arch (no hinge opens, no capacity); allowed a movement that "
                             f"deforms it")
    if movement.spread == 0.0 and movement.settlement == 0.0:
        cap = displacement_capacity(arch, "rotation", movement.side, movement.pivot_depth)
        if movement.rotation > 0:
            return cap
        return _capacity(arch, SupportMovement(0.0, 0.0, movement.side, -1.0 / arch.size,
                                               movement.pivot_depth), "rotation inward",
                         arch.size, MAX_ROTATION * arch.size)
    mag = movement_size(arch, movement)
    unit = movement.scaled(1.0 / mag)
    kind = next((k for k, (a, b) in CAPACITY_KINDS.items()
                 if a == unit.spread and b == unit.settlement and unit.rotation == 0.0),
                "combined")
    return _capacity(arch, unit, kind)


def movement_size(arch: VoussoirArch, movement: SupportMovement) -> float:
    """The size of ``movement`` in the units of :func:`movement_capacity`'s capacity: |rotation|
    [rad] for a rotation alone, hypot(spread, settlement) [m] for a translation, and with both
    hypot(spread, settlement, rotation x the arch's size) [m]."""
    if movement.spread == 0.0 and movement.settlement == 0.0 and movement.rotation != 0.0:
        return abs(movement.rotation)
    if movement.rotation == 0.0:
        return float(np.hypot(movement.spread, movement.settlement))
    return float(np.hypot(np.hypot(movement.spread, movement.settlement),
                          movement.rotation * arch.size))


def _capacity(arch, unit: SupportMovement, kind: str, per: float = 1.0,
              bound: float | None = None) -> DisplacementCapacity:
    """The capacity along ``unit``, reported in units of 1 / ``per`` of its parameter (per =
    the size for a rotation: rad), followed up to ``bound`` (default MAX_MOVEMENT sizes)."""
    side = unit.side
    hinges, points, line0 = _onset(arch, unit)
    if unit.rotation == 0.0:
        rel = unit.relative / float(np.hypot(*unit.relative))
        c_dir = [float(rel[0]), float(rel[1]), 0.0, 0.0]
    else:
        c_dir = _work(arch, unit)
    path = _follow(arch, unit, MAX_MOVEMENT * arch.size if bound is None else bound, c_dir,
                   line0, hinges, points)
    how = (f"hinges from the LP (HiGHS) that minimises the work on the moving support; exact "
           f"two-bar linkage; followed in steps of size/{STEPS} with hinge migration, the "
           f"capacity bisected to {BISECT_TOL:g} of the size")
    if per == 1.0:
        return DisplacementCapacity(kind, side, float(path.end), float(path.end) / _span(arch),
                                    tuple(hinges), path.mechanism, path.reason or "bound",
                                    np.array(path.rows), how, tuple(path.sets))
    rows = np.array(path.rows)
    rows[:, 0] /= per
    how += (f"; the support turned about its foot {unit.pivot_depth:g} m below the springing's "
            f"outer end, 1 / size rad per step unit")
    return DisplacementCapacity(kind, side, float(path.end) / per, None, tuple(hinges),
                                path.mechanism, path.reason or "bound", rows, how,
                                tuple((t / per, hs) for t, hs in path.sets))

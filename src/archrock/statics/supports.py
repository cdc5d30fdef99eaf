"""Support movements: the hinges they open, the exact displaced arch, and the displacement
capacity (docs/supports.md).

Setting: Ochsendorf, "The masonry arch on spreading supports", The Structural Engineer 84
(2006); Coccia, Di Carlo & Rinaldi, "On the safety assessment of masonry arches on moving
supports" (Meccanica, 2015).  The numbers are archrock's.

1. **Which hinges open.**  Of the statically admissible states under self-weight (the static
   program of :mod:`archrock.statics.lp`, lambda = 0), the movement selects the one that
   minimises the work of the arch's forces on the supports, which for u_left, u_right is
   F_0 . (u_right - u_left) plus a constant (F_0: the force the left support exerts on the
   arch, per total weight W).  Pure spread gives the minimum thrust, closing the maximum,
   settling the right support the least vertical reaction there.  The joints where that line
   of thrust touches an edge are the candidate hinges; the three-hinge set is the kinematically
   admissible one (each hinge turns so that its joint opens on the side opposite its edge) under
   which the displaced arch stands after a first small step; ties (a symmetric arch with a
   keystone touches four points) go to the set whose hinges lie nearer the moving support.
2. **Finite displacement.**  Hinges h1 < h2 < h3 (joints, left to right): the voussoirs between
   the left support and h1 move with the left support, those between h3 and the right support
   with the right one, and the two middle bodies form a two-bar linkage: h2's new place is the
   intersection of the circles about h1 and h3 (moved), on the branch continuous with the
   start.  Exact: no small-angle approximation.  Open joints become point contacts
   (:class:`~archrock.geometry.displaced.DisplacedArch`).
3. **Statics of the displaced arch.**  With its three hinges as points, the line of thrust
   passes through them: three equations for the three redundants, so the displaced arch is
   statically determinate; it stands while that line lies inside every other joint in
   compression.  :func:`displace` re-solves the LP on the displaced geometry (HiGHS) and reports
   the thrust and reactions; the margin that decides standing is the smallest fraction of a
   contact segment between that line and the segment's ends.
4. **Capacity.**  The movement is followed in steps (1/200 of the arch's size) until the arch
   can no longer stand (a fourth hinge forms, or the linkage cannot close: h1, h2, h3 in line);
   the capacity is then found by bisection to 1e-10 of the size.
5. **A support that turns** (``SupportMovement(rotation=..., pivot_depth=...)``) moves rigidly
   about its foot: the objective of 1. adds the rotation times the moment about the foot of
   the force on that support (:func:`_work`), the bodies on its side of the nearer hinge turn
   with it and the linkage closes between the moved h1 and h3 (:func:`_build_rotated`);
   ``displacement_capacity(arch, "rotation")`` reports radians.
6. **Studies.**  :func:`study_sampler` gives a study's random arches on the nominal's moved
   supports (:class:`MovedSampler`, sample i = the ensemble's), or the plain ArchSampler on
   fixed supports; :func:`movement_capacity` is the capacity along any movement's direction.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from itertools import combinations

import numpy as np
from scipy.optimize import linprog

from ..errors import ArchInputError, CannotStandError, LimitExceededError, NoMechanismError
from ..geometry import VoussoirArch
from ..geometry.displaced import MAX_ROTATION, SIDES, DisplacedArch, SupportMovement
from ..geometry.sampling import ArchSampler, Spreads
from ..units import G
from .hinges import EDGES, Hinge
from .lp import ThrustLine, _statics, _thrust_from_x
from .thrust import _touching

__all__ = ["DisplacedState", "DisplacementCapacity", "onset_hinges", "displace",
           "displacement_capacity", "movement_capacity", "movement_size", "closing_hinges",
           "reclosed", "on_moved_supports",
           "point_contacts", "gap_closing",
           "GapClosing", "CAPACITY_KINDS", "STEPS",
           "BISECT_TOL", "moved_parts", "MovedSampler", "study_sampler", "SUPPORT_DRAWS"]

#: What ``displacement_capacity`` can push: the kind and the unit movement it follows.
CAPACITY_KINDS = {"spread": (1.0, 0.0), "closure": (-1.0, 0.0), "settlement": (0.0, 1.0),
                  "heave": (0.0, -1.0)}
#: Steps per arch size [-] while following a movement: the step is size / STEPS.
STEPS = 200
#: Bisection tolerance on the capacity, relative to the arch's size.
BISECT_TOL = 1e-10
#: Largest movement followed, in units of the arch's size.
MAX_MOVEMENT = 2.0
#: Trial step (relative to the size) that picks among tied three-hinge sets.
_TRIAL = 1e-6
_EDGE_SIGN = {"intrados": -1.0, "extrados": 1.0}


def _cross(a, b) -> float:
    return float(a[0] * b[1] - a[1] * b[0])


def _perp(r) -> np.ndarray:
    return np.array([-r[1], r[0]])


def _small_rotations(P1, P2, P3, d):
    """(omega1, omega2) of the two middle bodies under the small relative movement d of the
    right support; None where the hinges are in line."""
    A = np.column_stack([_perp(P2 - P1), _perp(P3 - P2)])
    if abs(np.linalg.det(A)) <= 1e-12 * np.hypot(*(P2 - P1)) * np.hypot(*(P3 - P2)):
        return None
    return np.linalg.solve(A, d)


def _admissible(hinges, points, d, motions=None) -> bool:
    """Whether every hinge of the three turns so that its joint opens (relative rotations
    omega1 - theta_l, omega2 - omega1, theta_r - omega2 of the signs its edges require; the
    supports' rotations theta zero unless ``motions``, SupportMovement.rigid_motions of a
    unit movement with a rotation)."""
    if motions is None:
        w = _small_rotations(*points, d)
        if w is None:
            return False
        rel = (w[0], w[1] - w[0], -w[1])
    else:
        (tl, cl, ul), (tr, cr, ur) = motions
        P1, _, P3 = points
        # the small motions of h1 and h3 with their supports' bodies
        w = _small_rotations(*points, (ur + tr * _perp(P3 - cr)) - (ul + tl * _perp(P1 - cl)))
        if w is None:
            return False
        rel = (w[0] - tl, w[1] - w[0], tr - w[1])
    scale = max(abs(w[0]), abs(w[1]))
    return all(_EDGE_SIGN[h.edge] * r > 1e-9 * scale for h, r in zip(hinges, rel))


def _linkage(P1, P2, P3, d):
    """(P2', theta1, theta2): h2's place and the rotations of the middle bodies when h3 moves by
    d with h1 fixed; None where the linkage cannot close."""
    return _close_linkage(P1, P2, P3, P1, P3 + d)


def _close_linkage(P1, P2, P3, Q1, Q3):
    """(Q2, theta1, theta2): the two-bar linkage h1-h2-h3 (hinge places P1, P2, P3) closed
    between the moved ends Q1, Q3, with h2 on the branch continuous with the start (the side of
    P1-P3 that P2 is on), and the rotations of the two bars; None where it cannot close."""
    a, b = float(np.hypot(*(P2 - P1))), float(np.hypot(*(P3 - P2)))
    D = float(np.hypot(*(Q3 - Q1)))
    if not (abs(a - b) < D < a + b):
        return None
    e = (Q3 - Q1) / D
    x = (a * a - b * b + D * D) / (2.0 * D)
    h = math.sqrt(max(a * a - x * x, 0.0))
    sigma = 1.0 if _cross(P3 - P1, P2 - P1) >= 0 else -1.0
    Q2 = Q1 + x * e + sigma * h * _perp(e)
    u, v = P2 - P1, Q2 - Q1
    t1 = math.atan2(_cross(u, v), float(u @ v))
    u, v = P3 - P2, Q3 - Q2
    t2 = math.atan2(_cross(u, v), float(u @ v))
    return Q2, t1, t2


def _build_rotated(arch: VoussoirArch, movement: SupportMovement, hinges, points):
    """:func:`_build` where a support also turns: the bodies between a support and its nearer
    hinge move with the support's rigid motion (SupportMovement.rigid_motions), h1 and h3 with
    them, and the two middle bodies close the linkage between the moved h1 and h3 (h2 on the
    branch continuous with the start)."""
    (tl, cl, ul), (tr, cr, ur) = movement.rigid_motions(arch.joint_points)
    P1, P2, P3 = (np.asarray(p, float) for p in points)
    Q1 = _rot(tl) @ (P1 - cl) + cl + ul
    Q3 = _rot(tr) @ (P3 - cr) + cr + ur
    link = _close_linkage(P1, P2, P3, Q1, Q3)
    if link is None:
        return None
    Q2, t1, t2 = link
    j1, j2, j3 = (h_.joint for h_ in hinges)
    n = arch.n
    angles, origins, images = np.zeros(n), np.zeros((n, 2)), np.zeros((n, 2))
    for i in range(n):
        if i < j1:
            angles[i], origins[i], images[i] = tl, cl, cl + ul
        elif i < j2:
            angles[i], origins[i], images[i] = t1, P1, Q1
        elif i < j3:
            angles[i], origins[i], images[i] = t2, P2, Q2
        else:
            angles[i], origins[i], images[i] = tr, cr, cr + ur
    pts = ((j1, *Q1), (j2, *Q2), (j3, *Q3))
    return DisplacedArch(arch, tuple(angles), tuple(origins), tuple(images), pts, movement,
                         tuple(hinges))


def _rot(a: float) -> np.ndarray:
    c, s_ = math.cos(a), math.sin(a)
    return np.array([[c, -s_], [s_, c]])


def _build(arch: VoussoirArch, movement: SupportMovement, hinges, points):
    """The DisplacedArch of ``arch`` under ``movement`` with three hinges (base points);
    None where the linkage cannot close."""
    if movement.rotation != 0.0:
        return _build_rotated(arch, movement, hinges, points)
    ul, ur = movement.supports
    d = ur - ul
    P1, P2, P3 = (np.asarray(p, float) for p in points)
    link = _linkage(P1, P2, P3, d)
    if link is None:
        return None
    Q2, t1, t2 = link
    j1, j2, j3 = (h.joint for h in hinges)
    n = arch.n
    angles, origins, images = np.zeros(n), np.zeros((n, 2)), np.zeros((n, 2))
    for i in range(n):
        if i < j1:
            images[i] = ul
        elif i < j2:
            angles[i], origins[i], images[i] = t1, P1, P1 + ul
        elif i < j3:
            angles[i], origins[i], images[i] = t2, P2, Q2 + ul
        else:
            images[i] = ur
    pts = ((j1, *(P1 + ul)), (j2, *(Q2 + ul)), (j3, *(P3 + ur)))
    return DisplacedArch(arch, tuple(angles), tuple(origins), tuple(images), pts, movement,
                         tuple(hinges))


def _determinate(disp: DisplacedArch):
    """(x, margin, where): the redundants of the line of thrust through the three point
    hinges (lambda = 0), the smallest margin of that line (fraction of a closed joint's contact
    segment from its nearer end; at a point hinge its normal force per total weight, which
    must stay positive) and the (joint, edge) where that margin is least."""
    st = _statics(disp, "l", "joint-line")
    rows, rhs = [], []
    for j in disp.open_joints:
        r, b = st.hinge(j, "intrados")
        rows.append(r)
        rhs.append(b)
    rows.append([0.0, 0.0, 0.0, 1.0])
    rhs.append(0.0)
    x = np.linalg.solve(np.array(rows), np.array(rhs))
    N = st.A_N @ x + st.b_N
    m = st.A_m @ x + st.b_m
    best, where = math.inf, None
    for j in range(disp.n + 1):
        if st.point[j]:
            v, e = N[j], "point"
        else:
            if N[j] <= 0:
                v, e = -1.0, "intrados"
            else:
                f = m[j] / (st.L[j] * N[j])
                v, e = (f, "intrados") if f <= 1.0 - f else (1.0 - f, "extrados")
        if v < best:
            best, where = float(v), (j, e)
    return x, best, where


@dataclass(frozen=True)
class DisplacedState:
    """An arch under a prescribed support movement (lambda = 0, self-weight and loads).

    movement: the :class:`SupportMovement`; hinges: the three open joints (Hinge, left to
    right; empty at zero movement); points: their displaced points [m] (3, 2); arch: the
    :class:`DisplacedArch` (the base arch itself at zero movement, so every result on it is the
    undisplaced arch's, bit for bit); line: its line of thrust (None at zero movement); thrust:
    H [N/m], the horizontal force across every joint (> 0 compression); v_left, v_right: the
    vertical reactions [N/m] (upward on the arch); crown_drop: the downward displacement [m] of
    the crown voussoir's (highest centroid) mass centre; margin: the smallest fraction of a
    closed joint's contact segment between the line and its nearer end.
    """

    movement: SupportMovement
    hinges: tuple[Hinge, ...]
    points: np.ndarray
    arch: VoussoirArch
    line: ThrustLine | None
    thrust: float
    v_left: float
    v_right: float
    crown_drop: float
    margin: float

    def __post_init__(self):
        a = np.array(self.points, float).reshape(-1, 2)
        a.setflags(write=False)
        object.__setattr__(self, "points", a)

    def to_dict(self) -> dict:
        return {"movement": self.movement.to_dict(),
                "hinges": [h.to_dict() for h in self.hinges],
                "points": self.points.tolist(),
                "H": float(self.thrust), "V_left": float(self.v_left),
                "V_right": float(self.v_right), "crown_drop": float(self.crown_drop),
                "margin": float(self.margin)}


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


def _check(arch, movement):
    if not isinstance(arch, VoussoirArch):
        raise ArchInputError(f"arch: expected a VoussoirArch, got {type(arch).__name__}")
    if isinstance(arch, DisplacedArch):
        raise ArchInputError("arch: already displaced; give the base arch and the whole "
                             "movement")
    if not isinstance(movement, SupportMovement):
        raise ArchInputError(f"movement: expected a SupportMovement, got "
                             f"{type(movement).__name__}")
    if (movement.rotation < 0.0 and movement.pivot_depth == 0.0 and movement.spread == 0.0
            and movement.settlement == 0.0):
        raise ArchInputError(
            f"rotation: {movement.rotation:g} rad (inward) about the springing's outer end: the "
            f"support turns away under the arch, which stays where it is on that corner (no "
            f"hinge opens in it); allowed an outward rotation (> 0), or an inward one about a "
            f"foot below the springing (pivot_depth > 0)")


def _work(arch: VoussoirArch, movement: SupportMovement) -> list:
    """The objective of the onset's program: the work of the arch's forces on the supports
    under ``movement``, linear in the redundants x (per total weight; module docstring, 1),
    normalised.  Without rotation it is F_0 . d (d = u_right - u_left).  A support turning by
    theta about its foot c adds theta times the moment about c of the force on it: the arch
    pushes the right support with F_n and the left one with -F_0, and with lambda = 0 the
    counter-clockwise moment about c of F_j is x[2] ref + (c_y - o_y) F_x - (c_x - o_x) F_y
    plus a constant (o the program's origin, ref its length: statics.lp's joint-line form)."""
    from .lp import _origin

    d = movement.relative
    if movement.rotation == 0.0:
        scale = float(np.hypot(*d))
        return [float(d[0]) / scale, float(d[1]) / scale, 0.0, 0.0]
    (tl, cl, _), (tr, cr, _) = movement.rigid_motions(arch.joint_points)
    o = np.asarray(_origin(arch), float)
    ref = float(arch.reference_length)
    c = np.array([d[0] + tr * (cr[1] - o[1]) - tl * (cl[1] - o[1]),
                  d[1] - tr * (cr[0] - o[0]) + tl * (cl[0] - o[0]),
                  ref * (tr - tl), 0.0])
    return [float(v) for v in c / float(np.hypot(np.hypot(c[0], c[1]), c[2]))]


def _onset_lp(arch: VoussoirArch, d: np.ndarray, c=None, what: str = "the movement"):
    """(x, line, touches, points) of the state the relative movement d (or the objective c,
    :func:`_work`) selects; ``what``: the movement in words, for the outcome where it opens no
    hinge."""
    if c is None:
        st = _statics(arch, "l")
        scale = float(np.hypot(*d))
        c = [float(d[0]) / scale, float(d[1]) / scale, 0.0, 0.0]
    else:  # the moments about the feet are the joint-line form's (statics.lp)
        st = _statics(arch, "l", "joint-line")
    res = linprog(c=c, A_ub=st.A_ub, b_ub=st.b_ub, bounds=[(None, None)] * 3 + [(0.0, 0.0)],
                  method="highs")
    if res.status == 2:
        raise CannotStandError(f"arch: no line of thrust fits inside the arch under its own "
                               f"weight (linear program status {res.status}); it cannot stand")
    if res.status == 3:
        # the program's ray is a state without weight: a straight line of thrust inside the
        # arch from one springing to the other, which carries any thrust; moving the supports
        # this way would shorten that strut, i.e. crush the masonry
        raise NoMechanismError(
            f"arch: {what} cannot bring this arch to a mechanism: a straight line of thrust "
            f"fits inside it from one springing to the other (a flat arch wedged between its "
            f"supports), so it carries any thrust and gives way only by crushing, which "
            f"Heyman's hypotheses exclude; no hinges open and there is no capacity to report")
    if res.status != 0:
        raise LimitExceededError(f"support movement: the linear program did not finish "
                                 f"(status {res.status}: {res.message})")
    x = np.array(res.x, float)
    x[3] = 0.0
    line = _thrust_from_x(st, x)
    touches, points = _touching(line)
    return x, line, touches, points


def onset_hinges(arch: VoussoirArch, movement: SupportMovement) -> tuple[Hinge, ...]:
    """The three hinges that open when ``movement`` starts (module docstring, 1)."""
    _check(arch, movement)
    return _onset(arch, movement)[0]


def _magnitude(arch, movement) -> float:
    """The size of a movement [m]: |u_right - u_left|, and with a rotation hypot of that and
    rotation x the arch's size (the metres a point one size from the foot moves)."""
    d = float(np.hypot(*movement.relative))
    if movement.rotation == 0.0:
        return d
    return float(np.hypot(d, movement.rotation * arch.size))


def _movement_words(movement) -> str:
    """The movement's kind in words ("a closure of the right support"), for outcomes."""
    signs = (float(np.sign(movement.spread)), float(np.sign(movement.settlement)))
    kind = next((k for k, v in CAPACITY_KINDS.items() if v == signs), None)
    if not any(signs) and movement.rotation:
        kind = "rotation"
    side = "both supports" if movement.side == "both" else f"the {movement.side} support"
    return f"a {kind} of {side}" if kind else f"the movement of {side}"


def _onset(arch, movement):
    d = movement.relative
    rotating = movement.rotation != 0.0
    if not np.any(d) and not rotating:
        return (), None, None
    motions = None
    if rotating:
        unit = movement.scaled(1.0 / _magnitude(arch, movement))
        motions = unit.rigid_motions(arch.joint_points)
        x, line, touches, _ = _onset_lp(arch, unit.relative, _work(arch, unit),
                                        _movement_words(movement))
    else:
        x, line, touches, _ = _onset_lp(arch, d, what=_movement_words(movement))
    jp = np.asarray(arch.joint_points, float)
    cands = []
    for trio in combinations(touches, 3):
        if len({h.joint for h in trio}) < 3:
            continue
        pts = [jp[h.joint, EDGES.index(h.edge)] for h in trio]
        if _admissible(trio, pts, None if rotating else d, motions):
            cands.append((trio, pts))
    if not cands:
        raise CannotStandError(
            f"arch: the line of thrust that the movement selects touches "
            f"{', '.join(f'{h.joint}{h.edge[0]}' for h in touches) or 'no joint end'}; no three "
            f"of them open as a three-hinge arch under this movement")
    if len(cands) > 1:
        # the set under which the arch stands after a small step; then nearer the moving support
        unit = movement.scaled(_TRIAL * arch.size / (_magnitude(arch, movement) if rotating
                                                     else float(np.hypot(*d))))
        moving_right = movement.side != "left"

        def key(c):
            margin = _margin_at(arch, unit, c[0], c[1])[0]
            joints = [h.joint for h in c[0]]
            near = [-j for j in joints[::-1]] if moving_right else joints
            return (-(margin > 0), near)
        cands.sort(key=key)
    return cands[0][0], cands[0][1], line


def _crown(arch) -> int:
    return int(np.argmax(np.asarray(arch.centroids, float)[:, 1]))


def _state(arch, movement, hinges, points, c_dir) -> DisplacedState:
    """The state at ``movement`` with the given hinges (base points); raises where it cannot
    stand."""
    W = G * float(np.sum(arch.masses))
    disp = _build(arch, movement, hinges, points)
    if disp is None:
        raise CannotStandError(f"arch: under {movement.describe()} its hinges "
                               f"{_labels(hinges)} cannot close (the two middle bodies would "
                               f"have to stretch): the arch has collapsed")
    x_det, margin, where = _determinate(disp)
    # the LP on the displaced geometry: the point hinges fix the line of thrust
    st = _statics(disp, "l")
    res = linprog(c=c_dir, A_ub=st.A_ub, b_ub=st.b_ub, bounds=[(None, None)] * 3 + [(0.0, 0.0)],
                  method="highs")
    if margin < 0:
        raise CannotStandError(
            f"arch: under {movement.describe()} no line of thrust fits the displaced arch "
            f"(least margin {margin:.3g} at joint {where[0]} {where[1]}; linear program status "
            f"{res.status}): a fourth hinge has formed and the arch has collapsed")
    # at a margin within the solver's feasibility tolerance (~1e-7) of zero, HiGHS may call
    # the program infeasible: the determinate line through the three hinges is then the answer
    x = np.array(res.x, float) if res.status == 0 else np.array(x_det, float)
    x[3] = 0.0
    line = _thrust_from_x(st, x)
    k = _crown(arch)
    drop = float(arch.centroids[k][1] - disp.centroids[k][1])
    pts = np.array([[x_, y_] for _, x_, y_ in disp.point_joints])
    return DisplacedState(movement, tuple(hinges), pts, disp, line, W * float(x[0]),
                          W * float(x[1]), W * (1.0 - float(x[1])), drop, float(margin))


def _labels(hinges) -> str:
    return ", ".join(f"{h.joint}{h.edge[0]}" for h in hinges)


def _opening(disp: DisplacedArch) -> bool:
    """Whether every hinge of a displaced arch has turned so that its joint opens (finite
    relative rotations theta1, theta2 - theta1, -theta2 of the signs its edges require)."""
    j1, j2, _ = (h.joint for h in disp.hinges)
    t1, t2 = float(disp.angles[j1]), float(disp.angles[j2])
    rel = (t1, t2 - t1, -t2)
    mv = disp.movement
    if mv is not None and mv.rotation != 0.0:  # relative to the turned supports
        (tl, _, _), (tr, _, _) = mv.rigid_motions(disp.base.joint_points)
        rel = (t1 - tl, t2 - t1, tr - t2)
    return all(_EDGE_SIGN[h.edge] * r > 0 for h, r in zip(disp.hinges, rel))


def _margin_at(arch, movement, hinges, points):
    """(margin, where, displaced arch): -inf where the linkage cannot close or a hinge would
    have to close."""
    disp = _build(arch, movement, hinges, points)
    if disp is None:
        return -math.inf, None, None
    if not _opening(disp):
        return -math.inf, "closing", disp
    _, margin, where = _determinate(disp)
    return margin, where, disp


def _stands_at(arch, movement, hinges, points) -> bool:
    return _margin_at(arch, movement, hinges, points)[0] >= 0


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


def closing_hinges(arch: DisplacedArch, mechanism) -> tuple[int, ...]:
    """The open joints of a displaced arch that ``mechanism`` (e.g. of
    :func:`archrock.statics.limit.limit_analysis` on it) turns back toward closing: it hinges
    there about the other edge's label (the same point, the opposite relative rotation).  Such
    a mechanism moves only until that joint's gap closes (a rotation of the order of the hinge's
    rotation so far), then the joint bears on its whole face again: limit analysis on the
    displaced configuration counts it, though it is not a collapse of the arch as a whole."""
    if not isinstance(arch, DisplacedArch):
        return ()
    opened = {h.joint: h.edge for h in arch.hinges}
    return tuple(h.joint for h in mechanism.hinges
                 if h.joint in opened and h.edge != opened[h.joint])


def reclosed(arch: DisplacedArch) -> DisplacedArch:
    """The displaced geometry with every open joint bearing on a whole face again: its contact
    segment is the face of the voussoir on its right as that voussoir now lies (at the right
    springing, the last voussoir's).  Limit analysis on it gives the effect of the changed
    geometry alone, without the point contacts (docs/supports.md): the open joints' gaps are
    small at small movements, and a mechanism that turns them back closes them at once."""
    if not isinstance(arch, DisplacedArch):
        raise ArchInputError(f"arch: expected a DisplacedArch, got {type(arch).__name__}")
    if not arch.point_joints:
        return arch
    return DisplacedArch(arch.base, tuple(arch.angles), tuple(arch.origins), tuple(arch.images),
                         (), arch.movement, arch.hinges, f"{arch.name} (joints re-closed)",
                         contacts=arch.point_joints)


def on_moved_supports(arch: VoussoirArch, movement: SupportMovement) -> VoussoirArch:
    """``arch`` as every analysis takes it after ``movement`` (docs/supports.md, "One answer:
    the re-closed arch"): the displaced arch of :func:`displace`, :func:`reclosed`; ``arch``
    itself at zero movement.  CannotStandError where it cannot stand there."""
    moved = displace(arch, movement).arch
    return reclosed(moved) if isinstance(moved, DisplacedArch) else moved


def point_contacts(arch: DisplacedArch) -> DisplacedArch:
    """The inverse of :func:`reclosed`: the displaced arch with its open joints as the point
    contacts they were (``arch`` itself if it has none to restore)."""
    if not isinstance(arch, DisplacedArch):
        raise ArchInputError(f"arch: expected a DisplacedArch, got {type(arch).__name__}")
    if arch.point_joints or not arch.contacts:
        return arch
    return DisplacedArch(arch.base, tuple(arch.angles), tuple(arch.origins), tuple(arch.images),
                         arch.contacts, arch.movement, arch.hinges, arch.base.name + " (displaced)")


@dataclass(frozen=True)
class GapClosing:
    """What the point contacts of a displaced arch's open joints allow before its collapse
    multipliers are reached: limit analysis of the point-contact geometry (``k_l``, ``k_r``,
    mechanisms) where it is lower than the re-closed arch's.  Such a mechanism turns open joints
    (``closing_l``, ``closing_r``) back toward closing, so it moves only until their gaps close,
    a rotation of the order of the hinges' rotation so far: a bounded motion, not a collapse
    (docs/supports.md, "One answer: the re-closed arch")."""

    k_l: float
    k_r: float
    closing_l: tuple
    closing_r: tuple

    def to_dict(self) -> dict:
        return {"k_l": self.k_l, "k_r": self.k_r, "closing_l": list(self.closing_l),
                "closing_r": list(self.closing_r)}


def gap_closing(arch: DisplacedArch) -> GapClosing | None:
    """:class:`GapClosing` of a (re-closed) displaced arch, or None when the point contacts
    allow nothing below the re-closed arch's multipliers or the arch has no open joint."""
    from .limit import limit_analysis

    pc = point_contacts(arch)
    if not pc.point_joints:
        return None
    r = limit_analysis(pc, verify=False)
    shut_l, shut_r = closing_hinges(pc, r.mechanism_l), closing_hinges(pc, r.mechanism_r)
    if not (shut_l or shut_r):
        return None
    return GapClosing(r.k_l, r.k_r, shut_l, shut_r)


# ---------------------------------------------------------------------------- studies
def moved_parts(arch: VoussoirArch) -> tuple[VoussoirArch, SupportMovement | None]:
    """(base arch, movement) of an arch on moved supports as the studies take it (the
    re-closed arch of :func:`on_moved_supports`, e.g. from ``--spread``/``--settlement``), or
    (arch, None) for an arch on fixed supports.  A displaced arch with open point contacts
    (``displace(...).arch``) is refused: the analyses take it re-closed (docs/supports.md)."""
    if not isinstance(arch, DisplacedArch):
        return arch, None
    if arch.point_joints:
        raise ArchInputError(f"nominal: {arch.name!r} has open joints as point contacts; allowed "
                             f"the arch re-closed on its moved supports "
                             f"(statics.supports.on_moved_supports(base, movement) or "
                             f"reclosed(displace(...).arch)), as every analysis takes it")
    if arch.movement is None:
        raise ArchInputError(f"nominal: {arch.name!r} is displaced without a recorded support "
                             f"movement; allowed an arch of on_moved_supports(base, movement)")
    return arch.base, arch.movement


#: How a study's random arches take the support movement: all of it, or U_i x it.
SUPPORT_DRAWS = ("fixed", "uniform")


@dataclass(frozen=True, eq=False)
class MovedSampler(ArchSampler):
    """The random arches of a study around a nominal arch on moved supports: sample i is
    ``ArchSampler(nominal, spreads, seed).arch(i)`` (``nominal`` is the base arch, on fixed
    supports) moved by ``movement`` (``support_draw='fixed'``) or by U_i x ``movement``
    (``'uniform'``, U_i of :meth:`ArchSampler.movement_fractions`), and re-closed
    (:func:`on_moved_supports`): the same arch as sample i of an ensemble with
    ``EnsembleConfig(support=movement, support_draw=...)``.  A draw that cannot stand on its
    moved supports is an InvalidSampleError ("cannot stand on its moved supports"), which the
    studies leave out as "cannot stand"."""

    movement: SupportMovement | None = None
    support_draw: str = "fixed"

    def __post_init__(self):
        super().__post_init__()
        if not isinstance(self.movement, SupportMovement):
            raise ArchInputError(f"movement: expected a SupportMovement, got "
                                 f"{type(self.movement).__name__}")
        if self.support_draw not in SUPPORT_DRAWS:
            raise ArchInputError(f"support_draw: {self.support_draw!r}; allowed "
                                 f"{', '.join(SUPPORT_DRAWS)}")

    @property
    def moved_nominal(self) -> VoussoirArch:
        """The nominal arch on the whole movement, as the study analyses it."""
        return on_moved_supports(self.nominal, self.movement)

    def movements(self, start: int, count: int) -> list:
        """The support movement of samples start .. start + count - 1."""
        if self.support_draw == "fixed":
            return [self.movement] * int(count)
        return [self.movement.scaled(float(u)) for u in self.movement_fractions(start, count)]

    def arch(self, index: int) -> VoussoirArch:
        return _moved_sample(super().arch(index), self.movements(index, 1)[0])

    def arches(self, start: int, count: int) -> list:
        return [a if isinstance(a, Exception) else _moved_sample(a, mv, raise_=False)
                for a, mv in zip(super().arches(start, count), self.movements(start, count))]

    def to_dict(self) -> dict:
        d = super().to_dict()
        d["support"] = self.movement.to_dict()
        if self.support_draw != "fixed":
            d["support_draw"] = self.support_draw
        return d


def _moved_sample(arch, movement, raise_=True):
    """``arch`` on ``movement`` re-closed, or the InvalidSampleError saying it cannot stand
    there (raised, or returned with ``raise_=False``, as ArchSampler.arches does)."""
    from ..errors import ArchrockError, InvalidSampleError

    try:
        return on_moved_supports(arch, movement)
    except ArchrockError as exc:
        err = InvalidSampleError(f"cannot stand on its moved supports ({movement.describe()}): "
                                 f"{' '.join(str(exc).split())}")
    if raise_:
        raise err
    return err


def study_sampler(nominal: VoussoirArch, spreads=None, seed: int = 0,
                  support_draw: str = "fixed") -> ArchSampler:
    """The sampler of a study's random arches around ``nominal``: an
    :class:`~archrock.geometry.sampling.ArchSampler` on fixed supports (the same object as
    before, so every fixed-support study is unchanged bit for bit), or a :class:`MovedSampler`
    around the base of a nominal on moved supports (:func:`moved_parts`)."""
    base, mv = moved_parts(nominal)
    spreads = Spreads.from_dict(spreads)
    if mv is None:
        if support_draw != "fixed":
            raise ArchInputError(f"support_draw: {support_draw!r} needs an arch on moved "
                                 f"supports (--spread/--settlement)")
        return ArchSampler(nominal, spreads, seed)
    return MovedSampler(base, spreads, seed, movement=mv, support_draw=support_draw)

"""Which hinges a support movement opens (docs/supports.md): of the admissible states under
self-weight, the one of least work of the arch's forces on the moving supports; its touch points
are the candidate hinges, and the admissible three-hinge set under which the arch stands after
a first small step is the one that opens.
"""

from __future__ import annotations

from itertools import combinations

import numpy as np
from scipy.optimize import linprog

from ..errors import ArchInputError, CannotStandError, LimitExceededError, NoMechanismError
from ..geometry import VoussoirArch
from ..geometry.displaced import DisplacedArch, SupportMovement
from .determinate import _margin_at
from .hinges import EDGES, Hinge
from .linkage import _admissible
from .lp import _statics, _thrust_from_x
from .thrust import _touching

__all__ = ["CAPACITY_KINDS", "onset_hinges"]

#: What ``displacement_capacity`` can push: the kind and the unit movement it follows.
CAPACITY_KINDS = {"spread": (1.0, 0.0), "closure": (-1.0, 0.0), "settlement": (0.0, 1.0),
                  "heave": (0.0, -1.0)}
#: Trial step (relative to the size) that picks among tied three-hinge sets.
_TRIAL = 1e-6


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

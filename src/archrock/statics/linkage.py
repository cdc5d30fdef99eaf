"""The three-hinge linkage of an arch on moving supports (docs/supports.md): which hinge sets
are kinematically admissible under a small movement, and the exact displaced geometry, the two
middle bodies closed as a two-bar linkage between the moved outer hinges (a support that turns
moves its side rigidly about its foot first).  No small-angle approximation.
"""

from __future__ import annotations

import math

import numpy as np

from ..geometry import VoussoirArch
from ..geometry.displaced import DisplacedArch, SupportMovement

#: The sign of the relative rotation that opens a joint about a hinge on each edge.
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
    return _assemble(arch, movement, hinges,
                     ((tl, cl, cl + ul), (t1, P1, Q1), (t2, P2, Q2), (tr, cr, cr + ur)),
                     (Q1, Q2, Q3))


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
    still = np.zeros(2)  # the supports' bodies translate only: no rotation about any origin
    return _assemble(arch, movement, hinges,
                     ((0.0, still, ul), (t1, P1, P1 + ul), (t2, P2, Q2 + ul), (0.0, still, ur)),
                     (P1 + ul, Q2 + ul, P3 + ur))


def _assemble(arch: VoussoirArch, movement: SupportMovement, hinges, groups, moved):
    """The DisplacedArch whose bodies move in four rigid groups split at the hinges' joints
    (left support to h1, h1 to h2, h2 to h3, h3 to the right support), each group's motion its
    (angle [rad], origin, image of the origin) in ``groups``; ``moved``: the hinges' new points."""
    joints = [h.joint for h in hinges]
    n = arch.n
    angles, origins, images = np.zeros(n), np.zeros((n, 2)), np.zeros((n, 2))
    for i in range(n):
        angles[i], origins[i], images[i] = groups[sum(i >= j for j in joints)]
    pts = tuple((j, *q) for j, q in zip(joints, moved))
    return DisplacedArch(arch, tuple(angles), tuple(origins), tuple(images), pts, movement,
                         tuple(hinges))

"""The displaced arch's statics (docs/supports.md): with its three hinges as points the line of
thrust passes through them, so the arch is statically determinate; it stands while that line lies
inside every other joint in compression.  :class:`DisplacedState` is one such state.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import linprog

from ..errors import CannotStandError
from ..geometry import VoussoirArch
from ..geometry.displaced import DisplacedArch, SupportMovement
from ..units import G
from .hinges import Hinge
from .linkage import _EDGE_SIGN, _build
from .lp import ThrustLine, _statics, _thrust_from_x

__all__ = ["DisplacedState"]


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

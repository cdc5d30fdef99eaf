"""The static linear program of an arch, and its line of thrust.

Unknowns x = [F0x, F0y, M0, lambda] (nondimensional: forces per total weight W, moments per
W L, L the reference length): the force and moment the left abutment transmits to voussoir 0,
and the horizontal load multiplier.  The rows keep the line of thrust inside every joint's
contact segment, in compression; maximising lambda gives the static (lower-bound) multiplier,
Heyman's collapse multiplier (:func:`static_multiplier`).  Direction 'l': loads toward +x,
'r': toward -x.  :func:`thrust_line` puts the thrust through a mechanism's four hinges;
:func:`_stands` decides whether any line of thrust fits under self-weight alone.  Lines of
thrust are returned in metres (:class:`ThrustLine`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.optimize import linprog

from .._records import readonly_arrays
from ..errors import ArchInputError, CannotStandError
from ..geometry import Arch, VoussoirArch
from .hinges import DIRECTIONS, EDGES, Mechanism
from .sums import _origin, _weights_centroids

__all__ = ["ThrustLine", "static_multiplier", "thrust_line"]


@dataclass(frozen=True)
class ThrustLine:
    """Line of thrust at a given multiplier, for one direction of the horizontal loads.

    points: where the thrust crosses each joint 0..n (n+1, 2) [m]; fractions: the same
    crossings as fractions of each joint's contact segment (0 at its intrados end, 1 at its
    extrados end); radii: their radii [m] on a circular arch's radial joints (None for other
    arches); forces: resultant transmitted across each joint by the part on its left, per unit
    total weight (n+1, 2); polyline: the funicular polygon (joint crossings and the vertices on
    the load lines), for drawing.
    """

    direction: str
    multiplier: float
    radii: np.ndarray | None
    points: np.ndarray
    forces: np.ndarray
    polyline: np.ndarray
    fractions: np.ndarray

    def __post_init__(self):
        readonly_arrays(self)

    def margins(self, arch: VoussoirArch, relative: bool = False) -> np.ndarray:
        """Distance from each crossing to the nearer end of its contact segment: [m], or as a
        fraction of the segment's length (``relative``; 0.5 at its middle)."""
        f = self.fractions
        near = np.minimum(f, 1.0 - f)
        if relative:
            return near
        jp = np.asarray(arch.joint_points, float)
        return near * np.hypot(*(jp[:, 1] - jp[:, 0]).T)

    def eccentricity_margin(self, arch: VoussoirArch, relative: bool = False) -> float:
        """Smallest distance [m] from the crossing points to the ends of the contact surfaces
        (negative: outside), or the smallest fraction of a contact length (``relative``)."""
        if self.radii is not None and isinstance(arch, Arch) and not relative:
            return float(np.min(np.minimum(self.radii - arch.contact_inner,
                                           arch.contact_outer - self.radii)))
        return float(np.min(self.margins(arch, relative)))


# Unknowns x = [F0x, F0y, M0, lambda] (nondimensional: forces per total weight W, moments per
# W L, L = the reference length): the force F_0 and moment M_0 (about the origin) that the left
# abutment transmits to voussoir 0, and the multiplier.  Across joint j the part on its left
# transmits F_j = (F0x + d lambda cw_j, F0y - cw_j) and M_j = M0 - cwx_j - d lambda cwy_j, with
# cw, cwx, cwy the prefix sums of w, w x_G, w y_G (d = +1 for 'l', -1 for 'r'); the resultant's
# line of action is the set of points X with X x F_j = M_j.

def _radial(arch) -> bool:
    """Whether the static program takes 0.1.0's radial form (circular arch, no loads), whose
    numbers stay bit for bit those of 0.1.0; every other arch takes the joint-line form."""
    return isinstance(arch, Arch) and not arch.loads


class _Statics:
    """The static program of one arch and direction: ``A_ub x <= b_ub`` (rows 0..n: the
    intrados end of each joint, rows n+1..2n+1: the extrados end) keeps the thrust inside every
    contact segment in compression; :meth:`hinge` gives 'the thrust passes through this end'."""

    def __init__(self, arch: VoussoirArch, direction: str):
        if direction not in DIRECTIONS:
            raise ArchInputError(f"direction: {direction!r}; allowed 'l' or 'r'")
        self.arch = arch
        self.d = 1.0 if direction == "l" else -1.0
        self.ref = arch.reference_length

    def hinge(self, joint: int, edge: str):
        """(row, rhs): the thrust passes through the ``edge`` end of ``joint``."""
        k = (self.arch.n + 1) * EDGES.index(edge) + joint
        return self.A_ub[k], self.b_ub[k]

    def forces(self, x):
        return np.column_stack([x[0] + self.d * x[3] * self.cw, x[1] - self.cw])


class _RadialStatics(_Statics):
    """Radial joints of a circular arch: the normal force N_j = F_j . (sin psi_j, -cos psi_j)
    and the moment M_j about O; the thrust crosses joint j at radius r = -M_j / N_j, and
    r_in N <= -M <= r_out N (0.1.0's arithmetic, unchanged)."""

    def __init__(self, arch: Arch, direction: str):
        super().__init__(arch, direction)
        d, ref = self.d, self.ref
        w = arch.areas / arch.areas.sum()
        g = arch.centroids / ref
        zero = np.zeros(1)
        cw = np.concatenate([zero, np.cumsum(w)])
        cwx = np.concatenate([zero, np.cumsum(w * g[:, 0])])
        cwy = np.concatenate([zero, np.cumsum(w * g[:, 1])])
        psi = arch.joint_angles
        s, c = np.sin(psi), np.cos(psi)
        nj = psi.size
        # F_j = (F0x + d lam cw, F0y - cw);  N_j = F_j . (sin psi, -cos psi)
        self.A_N = np.column_stack([s, -c, np.zeros(nj), d * cw * s])
        self.b_N = c * cw
        # M_j = M0 - cwx - d lam cwy
        self.A_M = np.column_stack([np.zeros(nj), np.zeros(nj), np.ones(nj), -d * cwy])
        self.b_M = -cwx
        self.r_in, self.r_out = arch.contact_inner / ref, arch.contact_outer / ref
        self.cw = cw
        A_N, b_N, A_M, b_M = self.A_N, self.b_N, self.A_M, self.b_M
        r_in, r_out = self.r_in, self.r_out
        # r_in N + M <= 0 and -M - r_out N <= 0
        self.A_ub = np.vstack([r_in[:, None] * A_N + A_M, -A_M - r_out[:, None] * A_N])
        self.b_ub = np.concatenate([-(r_in * b_N + b_M), b_M + r_out * b_N])

    def hinge(self, joint: int, edge: str):
        r = self.r_in[joint] if edge == "intrados" else self.r_out[joint]
        return self.A_M[joint] + r * self.A_N[joint], -(self.b_M[joint] + r * self.b_N[joint])

    def crossings(self, x):
        """(radii [m], points (n+1, 2) [m], fractions along the contact segments)."""
        arch = self.arch
        N = self.A_N @ x + self.b_N
        M = self.A_M @ x + self.b_M
        radii = -M / N * self.ref
        psi = arch.joint_angles
        pts = np.column_stack([radii * np.cos(psi), radii * np.sin(psi)])
        frac = (radii - arch.contact_inner) / (arch.contact_outer - arch.contact_inner)
        return radii, pts, frac


class _JointLineStatics(_Statics):
    """Any joint line: contact segment [P_in, P_out] of length L_j, u = (P_out - P_in) / L_j,
    the compressive normal nu = (u_y, -u_x) (u turned clockwise: along the arch, from the left
    part into the right one), N_j = F_j . nu.  m_j = P_in x F_j - M_j is the moment of the
    resultant about P_in, clockwise positive: m_j = t N_j for a crossing at distance t from
    P_in, so the thrust crosses inside the segment in compression iff 0 <= m_j <= L_j N_j."""

    def __init__(self, arch: VoussoirArch, direction: str):
        super().__init__(arch, direction)
        d, ref = self.d, self.ref
        origin = _origin(arch)
        w, g = _weights_centroids(arch)
        g = (g - origin) / ref
        P = (np.asarray(arch.joint_points, float) - origin) / ref
        zero = np.zeros(1)
        cw = np.concatenate([zero, np.cumsum(w)])
        cwx = np.concatenate([zero, np.cumsum(w * g[:, 0])])
        cwy = np.concatenate([zero, np.cumsum(w * g[:, 1])])
        px, py = P[:, 0, 0], P[:, 0, 1]
        e = P[:, 1] - P[:, 0]
        L = np.hypot(e[:, 0], e[:, 1])
        point = L == 0.0
        if point.any():
            # point contacts (a displaced arch's open hinges): the segment gives no direction;
            # the arch's joint_directions give the normal force's sign
            u = np.asarray(arch.joint_directions, float)
            e = np.where(point[:, None], u, e)
            Ld = np.where(point, 1.0, L)
            nux, nuy = e[:, 1] / Ld, -e[:, 0] / Ld
        else:
            nux, nuy = e[:, 1] / L, -e[:, 0] / L
        nj = L.size
        A_N = np.column_stack([nux, nuy, np.zeros(nj), d * cw * nux])
        b_N = -nuy * cw
        # m = px F_y - py F_x - M
        A_m = np.column_stack([-py, px, -np.ones(nj), d * (cwy - py * cw)])
        b_m = cwx - px * cw
        self.cw, self.A_N, self.b_N, self.A_m, self.b_m = cw, A_N, b_N, A_m, b_m
        # -m <= 0 (intrados end) and m - L N <= 0 (extrados end)
        self.A_ub = np.vstack([-A_m, A_m - L[:, None] * A_N])
        self.b_ub = np.concatenate([b_m, L * b_N - b_m])
        if point.any():
            # at a point contact the rows above say m = 0; compression, -N <= 0, is appended
            # after the 2(n+1) joint-end rows (absent, and nothing changes, on other arches)
            self.A_ub = np.vstack([self.A_ub, -A_N[point]])
            self.b_ub = np.concatenate([self.b_ub, b_N[point]])
        self.L = L
        self.point = point

    def crossings(self, x):
        arch = self.arch
        N = self.A_N @ x + self.b_N
        m = self.A_m @ x + self.b_m
        frac = m / (self.L * N)
        if self.point.any():  # a point contact: the crossing is the point itself
            frac = np.where(self.point, 0.0, frac)
        jp = np.asarray(arch.joint_points, float)
        pts = jp[:, 0] + frac[:, None] * (jp[:, 1] - jp[:, 0])
        radii = None
        if isinstance(arch, Arch):  # radial joints: the crossing radius, for existing users
            radii = arch.contact_inner + frac * (arch.contact_outer - arch.contact_inner)
        return radii, pts, frac


def _statics(arch: VoussoirArch, direction: str, form: str = "auto") -> _Statics:
    """The static program of ``arch`` for ``direction``; ``form``: "radial" (circular arches
    only), "joint-line" (any arch) or "auto" (radial for circular arches without loads)."""
    if form == "auto":
        form = "radial" if _radial(arch) else "joint-line"
    if form == "radial":
        if not isinstance(arch, Arch):
            raise ArchInputError(f"form: 'radial' needs a circular Arch, got {type(arch).__name__}")
        return _RadialStatics(arch, direction)
    if form != "joint-line":
        raise ArchInputError(f"form: {form!r}; allowed 'auto', 'radial' or 'joint-line'")
    return _JointLineStatics(arch, direction)


def static_multiplier(arch: VoussoirArch, direction: str,
                      form: str = "auto") -> tuple[float, ThrustLine]:
    """Maximum multiplier by the static linear program, and its line of thrust.

    Constraints: at every joint the thrust crosses the contact segment, in compression
    (docs/method.md, Limit analysis); ``form``: see :func:`_statics` (the default is right).
    """
    st = _statics(arch, direction, form)
    res = linprog(c=[0, 0, 0, -1.0], A_ub=st.A_ub, b_ub=st.b_ub, bounds=[(None, None)] * 4,
                  method="highs")
    if res.status != 0:
        raise CannotStandError(
            f"arch: no line of thrust fits inside the arch for direction {direction!r} "
            f"(linear program status {res.status}: {res.message}); the arch cannot stand")
    return float(res.x[3]), _thrust_from_x(st, res.x)


def _thrust_from_x(st: _Statics, x: np.ndarray) -> ThrustLine:
    """The line of thrust of the nondimensional redundants x (see :class:`_Statics`), in metres."""
    arch = st.arch
    with np.errstate(invalid="ignore", divide="ignore"):
        radii, pts, frac = st.crossings(x)
    lam = x[3]
    forces = st.forces(x)
    # a joint that lifts off transmits no normal force (per unit weight: rounding below 1e-9;
    # without a bound on the shear, only a force along the joint, which needs infinite
    # friction): its line of action does not cross the joint, so it has no crossing point,
    # whatever 0/0 gave
    free = np.abs(st.A_N @ x + st.b_N) < 1e-9 * np.maximum(1.0, np.hypot(*forces.T))
    if free.any():
        pts = np.where(free[:, None], np.nan, pts)
        frac = np.where(free, np.nan, frac)
        radii = None if radii is None else np.where(free, np.nan, radii)
    # funicular polygon: from each joint crossing along F_i to the load line of voussoir i
    poly = [pts[0]]
    g = arch.centroids
    load = np.array([st.d * lam, -1.0])
    for i in range(arch.n):
        f = forces[i]
        # solve pts[i] + s f = g_i + u load
        mat = np.column_stack([f, -load])
        try:
            s_u = np.linalg.solve(mat, g[i] - pts[i])
            poly.append(pts[i] + s_u[0] * f)
        except np.linalg.LinAlgError:
            pass
        poly.append(pts[i + 1])
    # a joint that lifts off transmits nothing: no crossing, no vertex (NaN) to draw
    poly = [p for p in poly if np.all(np.isfinite(p))]
    return ThrustLine("l" if st.d > 0 else "r", float(lam), radii, pts, forces, np.array(poly),
                      frac)


def thrust_line(arch: VoussoirArch, mechanism: Mechanism, form: str = "auto") -> ThrustLine:
    """Line of thrust through the four hinges of ``mechanism`` (equilibrium at collapse).

    Solves the four conditions 'the thrust passes through hinge h' for the three redundants and
    lambda; the lambda found this way is a third, independent value of the multiplier.
    """
    st = _statics(arch, mechanism.direction, form)
    rows, rhs = zip(*(st.hinge(h.joint, h.edge) for h in mechanism.hinges))
    x = np.linalg.solve(np.array(rows), np.array(rhs))
    return _thrust_from_x(st, x)


def _stands(arch: VoussoirArch) -> bool:
    """Whether a line of thrust fits inside the arch under self-weight alone.

    Maximises the smallest moment margin s (per W L, nondimensional as in :class:`_Statics`) of
    the joint conditions A_ub x + s <= b_ub; the arch stands when s >= 0.  Deciding on the sign
    of an optimum rather than on the solver's feasibility verdict makes the bisection of
    :func:`minimum_thickness` independent of the LP's absolute feasibility tolerance (~1e-7),
    which otherwise moved the minimum thickness by ~1e-6 with the arch's size.
    """
    st = _statics(arch, "l")
    A_ub = np.column_stack([st.A_ub[:, :3], np.ones(st.A_ub.shape[0])])
    # s <= 1 keeps the program bounded; any s >= 0 is enough to stand
    res = linprog(c=[0, 0, 0, -1.0], A_ub=A_ub, b_ub=st.b_ub,
                  bounds=[(None, None)] * 3 + [(None, 1.0)], method="highs")
    return res.status == 0 and res.x[3] >= 0.0

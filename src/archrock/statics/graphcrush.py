"""Finite compressive strength on the graph of blocks: the static program of
:mod:`archrock.statics.graph` with the stress-block condition at every contact whose blocks have
a finite f_c, solved exactly by a bracket of linear programs (docs/arcades.md).

The condition.  At a contact of length L_c [m] carrying the normal force N = N0 + N1 [N per m of
depth] the thrust crosses at L_c N1 / N from end 0; a rectangular stress block of depth
N / (f_c * 1 m) at an edge has its centre N / (2 f_c) in from that edge, and the thrust may come
no nearer an edge than that (Heyman 1982, The Masonry Arch, on the hinge moved in by crushing;
Gilbert 2007, "Limit analysis applied to masonry arch bridges: state-of-the-art and recent
developments", ARCH'07, and the RING theory manual, for the same stress block in bridge
practice).  Hence N^2 / (2 f_c) <= L_c N1 and N^2 / (2 f_c) <= L_c N0.  In the program's units
(forces per total weight W [N/m], lengths per the arcade's extent L [m]: n = N / W, l = L_c / L)
this is

    c s^2 <= l n1  and  c s^2 <= l n0,   s = n0 + n1,   c = W / (2 f_c L)

(f_c in Pa on a 1 m depth), convex in (n0, n1), and it bounds s by s_max = l / (2 c) = f_c L_c /
W (the whole joint at f_c).

The bracket (as Livesley 1978/1992 linearises yield conditions for the LP; Gilbert, Casapulla,
Ahmed 2006, Computers & Structures, for frictional joints in the same LP).  Tangent planes of
c s^2 at points s_i give linear rows c (2 s_i s - s_i^2) <= l n_e that every admissible state
meets: a relaxation, its optimum an upper bound on k.  Chords of c s^2 between consecutive
breakpoints 0 = b_0 < ... < b_m = s_max lie above the parabola on [0, s_max]: the rows
c (b_j + b_j+1) s - c b_j b_j+1 <= l n_e with s <= s_max restrict the program, its optimum a
lower bound (a state that meets the exact condition).  Each round adds a tangent at the
relaxation's s where its state breaks the exact condition, and a breakpoint there where the
chords refuse that state, until the bracket is narrower than :data:`BRACKET_RTOL` of k (at most
:data:`MAX_ROUNDS` rounds).

The mechanism (built by :func:`archrock.statics.graph.graph_limit`).  The lower bound's state is
in equilibrium at k_lower with its thrust inside every joint; the dual of that program gives the contacts that move (a contact that turns about a point
of itself is a hinge, one that opens everywhere lifts off).  The mechanism is rebuilt with each
hinge at the thrust's crossing, the stress block's centre (N / (2 f_c) in from the edge where the
condition holds with equality), so that the contact forces do no work on it and its own virtual
work gives k = k_lower.
"""

from __future__ import annotations

import numpy as np
from scipy.optimize import linprog

from ..errors import CannotStandError
from ..units import G

#: Relative width of the bracket [k_lower, k_upper] at which the refinement stops.
BRACKET_RTOL = 1e-6
#: Rounds of refinement at most (each: two linear programs).
MAX_ROUNDS = 40
#: Absolute floor of the bracket's width [g] where k is near 0.
BRACKET_ATOL = 1e-9


class CrushingRows:
    """The finite-strength contacts of a program (:class:`archrock.statics.graph._Program`) and
    their tangent points and breakpoints; builds the rows of each bound's program."""

    def __init__(self, prog):
        arc = prog.arc
        fc = np.asarray(arc.contact_fc, float)
        self.idx = np.flatnonzero(np.isfinite(fc))
        W = float(np.sum(arc.masses)) * G
        self.W = W
        pts = np.array([ct.points for ct in arc.contacts], float)
        self.length = np.hypot(*(pts[:, 1] - pts[:, 0]).T)  # [m]
        self.fc_pa = fc * 1e6
        self.l = self.length[self.idx] / prog.L
        self.c = W / (2.0 * self.fc_pa[self.idx] * prog.L)
        self.s_max = self.l / (2.0 * self.c)
        self.nv = 3 * prog.nc + 1
        self.tangents = [list(sm * np.array([0.25, 0.5, 1.0])) for sm in self.s_max]
        self.breaks = [[0.0] + list(t) for t in self.tangents]

    def _row(self, j: int, slope: float, end: int):
        """slope * (n0 + n1) - l n_end as a row of the program's variables."""
        c = int(self.idx[j])
        row = np.zeros(self.nv)
        row[3 * c] = row[3 * c + 1] = slope
        row[3 * c + end] -= self.l[j]
        return row

    def rows(self, which: str):
        """(A, b) of the relaxation ('upper': tangents) or restriction ('lower': chords and
        s <= s_max)."""
        A, b = [], []
        for j in range(len(self.idx)):
            c = self.c[j]
            if which == "upper":
                for s0 in self.tangents[j]:
                    for e in (0, 1):
                        A.append(self._row(j, 2.0 * c * s0, e))
                        b.append(c * s0 * s0)
            else:
                bk = sorted(self.breaks[j])
                for lo, hi in zip(bk[:-1], bk[1:]):
                    for e in (0, 1):
                        A.append(self._row(j, c * (lo + hi), e))
                        b.append(c * lo * hi)
            cap = np.zeros(self.nv)  # s <= s_max: the whole joint at f_c
            cap[3 * int(self.idx[j])] = cap[3 * int(self.idx[j]) + 1] = 1.0
            A.append(cap)
            b.append(self.s_max[j])
        return np.array(A), np.array(b)

    def violation(self, x: np.ndarray) -> np.ndarray:
        """Per finite contact, max over its ends of c s^2 - l n_e (> 0: the state crushes)."""
        n0 = x[3 * self.idx]
        n1 = x[3 * self.idx + 1]
        s = n0 + n1
        return self.c * s * s - self.l * np.minimum(n0, n1)

    def refine(self, x: np.ndarray) -> int:
        """At the relaxation's state x: a tangent at its s for every contact that it crushes,
        a breakpoint at its s for every contact that the chords forbid it (so that the next
        restriction admits it where the exact condition does); the number added."""
        added = 0
        n0, n1 = x[3 * self.idx], x[3 * self.idx + 1]
        s_all = np.clip(n0 + n1, 0.0, self.s_max)
        room = self.l * np.minimum(n0, n1)
        tol = 1e-12 * np.maximum(self.l * self.s_max, 1e-300)
        for j in range(len(self.idx)):
            s = float(s_all[j])
            near = 1e-13 * self.s_max[j]
            if self.c[j] * s * s - room[j] > tol[j] and \
                    min(abs(s - t) for t in self.tangents[j]) > near:
                self.tangents[j].append(s)
                added += 1
            if _chord(self.c[j], self.breaks[j], s) - room[j] > tol[j] and \
                    min(abs(s - t) for t in self.breaks[j]) > near:
                self.breaks[j].append(s)
                added += 1
        return added

    def zones(self, x: np.ndarray) -> np.ndarray:
        """(m,): each contact's stress block depth N / f_c [m] at state x (0 where open or
        infinitely strong)."""
        out = np.zeros(len(self.length))
        s = (x[3 * self.idx] + x[3 * self.idx + 1]) * self.W
        out[self.idx] = np.maximum(s, 0.0) / self.fc_pa[self.idx]
        return out


def _chord(c: float, breaks, s: float) -> float:
    """The chords' value over c s^2 at s (their piecewise-linear interpolation)."""
    bk = np.sort(np.asarray(breaks, float))
    return float(np.interp(s, bk, c * bk * bk))


def _crushed(direction: str) -> str:
    return (f"arcade: no set of contact forces within the masonry's compressive strength holds "
            f"the blocks in direction {direction!r} (with infinite strength they stand: their "
            f"weight crushes a joint); it cannot stand")


#: HiGHS's tolerances, well below the bracket's 1e-6 (its defaults, 1e-7, are not; as
#: statics.crushing)
_HIGHS = {"primal_feasibility_tolerance": 1e-10, "dual_feasibility_tolerance": 1e-10}


def _solve(prog, A, b):
    if prog.A_ub is not None:
        A, b = np.vstack([prog.A_ub, A]), np.concatenate([prog.b_ub, b])
    if not len(b):
        A = b = None
    return linprog(prog.c, A_ub=A, b_ub=b, A_eq=prog.A_eq, b_eq=prog.b_eq, bounds=prog.bounds,
                   method="highs", options=_HIGHS)


def crushing_bracket(prog, direction: str, check_status):
    """The bracket of the static optimum with crushing: (lower result, (k_lower, k_upper),
    rounds, rows).  ``check_status`` raises on a relaxation with no optimum (infeasible: no
    state holds the blocks even ignoring part of the condition; unbounded)."""
    rows = CrushingRows(prog)
    lower = None
    k_up = np.inf
    for rnd in range(1, MAX_ROUNDS + 1):
        up = _solve(prog, *rows.rows("upper"))
        if up.status == 2:  # infeasible: by the strength, or already without it?
            heyman = _solve(prog, np.zeros((0, rows.nv)), np.zeros(0))
            check_status(heyman, direction, prog)
            raise CannotStandError(_crushed(direction))
        check_status(up, direction, prog)
        k_up = min(k_up, float(up.x[-1]))  # every relaxation bounds k from above
        added = rows.refine(up.x)
        lo = _solve(prog, *rows.rows("lower"))
        if lo.status == 0 and (lower is None or lo.x[-1] > lower.x[-1]):
            lower = lo
        if lower is not None and k_up - float(lower.x[-1]) <= max(
                BRACKET_RTOL * abs(k_up), BRACKET_ATOL):
            break
        if not added:  # nothing left to refine: the bracket stays as it is
            break
    if lower is None:
        raise CannotStandError(_crushed(direction))
    return lower, (float(lower.x[-1]), max(k_up, float(lower.x[-1]))), rnd, rows


def classify(prog, v: np.ndarray, tol: float):
    """Hinges (contact, nearer end), lift-off, sliding and closed contacts of the dual's block
    velocities v: under finite strength a hinge turns about a point inside its contact (the
    associated flow turns it about the stress block's inner edge), so one end may close."""
    hinges, lift, slide, closed, slip_sign = [], [], [], [], {}
    for c in range(prog.nc):
        # the contact's own friction (a ring interface's), else the analysis's (nan: none)
        mu = float(prog.mu[c]) if np.isfinite(prog.mu[c]) else None
        dn, dt = prog.relative(v, c)
        slid = np.abs(dt) > tol
        if slid.any() and ((mu is not None and np.all(np.abs(dn - mu * np.abs(dt)) <= tol))
                           or (mu is None and np.all(np.abs(dn) <= tol))):
            slide.append(c)
            slip_sign[c] = float(np.sign(dt[np.argmax(np.abs(dt))]))
        elif np.all(np.abs(dn) <= tol) and not slid.any():
            closed.append(c)
        elif dn.min() > tol:
            lift.append(c)
        else:
            hinges.append((c, int(np.argmin(dn))))
    return hinges, lift, slide, closed, slip_sign

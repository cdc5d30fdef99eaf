"""Limit analysis with a finite compressive strength f_c (the arch's ``fc`` [MPa]).

The masonry carries compression up to f_c on a rectangular stress block (depth 1 m out of
plane): at a joint of length t under a normal force N [N/m] the compressed zone is a = N / f_c
deep and the thrust crosses the joint no nearer an edge than a / 2, so

    N^2 / (2 f_c) <= m <= N t - N^2 / (2 f_c)       (m: the moment about the intrados end)

(Heyman 1982, The Masonry Arch; Gilbert 2007, "Limit analysis applied to masonry arch bridges:
state-of-the-art and recent developments", ARCH'07, and the RING theory manual, where the same
block makes the hinges of flat bridge arches).  In the nondimensional joint-line form of
:mod:`.lp` (forces per total weight W [N/m], lengths per the reference length L_ref) this is
c N^2 <= m and c N^2 <= L N - m with c = W / (2 f_c L_ref): a convex program in the three
redundants and lambda (Livesley 1992 and Gilbert, Casapulla and Ahmed 2006 write the same
conditions for block structures).

It is solved by an LP bracket (:func:`crushing_bracket`): tangent planes of c N^2 at chosen
forces relax it (an upper bound on lambda), the chords between those forces restrict it (a
lower bound), and both are refined at the optima's forces until they agree to 1e-6.  The point
of the optimum is then found exactly by Newton's method on the four conditions that hold with
equality there (:func:`crushing_optimum`), and the mechanism has its hinges at the centres of
the stress blocks: a joint contact segment shortened at both ends by N / (2 f_c) at the
collapse force (:class:`InsetArch`) carries Heyman's analysis, whose multiplier is the same.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import linprog

from ..errors import ArchInputError, CannotStandError, LimitExceededError, NoMechanismError
from ..geometry import VoussoirArch
from .hinges import EDGES, Hinge, Mechanism
from .lp import ThrustLine, _JointLineStatics, _statics, _thrust_from_x

__all__ = ["CrushingBracket", "CrushingOptimum", "CrushingAnswer", "InsetArch",
           "crushing_bracket", "crushing_optimum", "crushing_analysis", "crushing_constant",
           "inset_arch", "virtual_work_multiplier", "crushing_stands", "crushing_thrust",
           "BRACKET_RTOL", "MAX_ROUNDS"]

#: Relative width of the bracket [lower, upper] at which the refinement stops.
BRACKET_RTOL = 1e-6
#: Most rounds of refinement; past it the bracket is reported as not converged.
MAX_ROUNDS = 80
MPA = 1e6  # Pa per MPa


def crushing_constant(arch: VoussoirArch) -> float:
    """c = W / (2 f_c L_ref): the conditions' coefficient in the units of :mod:`.lp` (W the
    arch's total weight with its loads [N/m], f_c [Pa] on a depth of 1 m, L_ref [m])."""
    if arch.fc is None:
        raise ArchInputError("fc: the arch has infinite compressive strength (None); allowed "
                             "0.1 to 1000 MPa for the crushing analysis")
    w_total = float(np.sum(arch.weights))
    return w_total / (2.0 * arch.fc * MPA * arch.reference_length)


@dataclass(frozen=True)
class CrushingBracket:
    """The bracket of one direction: ``lower`` (a restriction's optimum: a multiplier the arch
    carries) <= the optimum <= ``upper`` (a relaxation's optimum); ``x_lower``, ``x_upper`` the
    redundants [F0x, F0y, M0, lambda] of each (nondimensional, :mod:`.lp`); ``rounds`` of
    refinement."""

    direction: str
    lower: float
    upper: float
    x_lower: np.ndarray
    x_upper: np.ndarray
    rounds: int


def _line_rows(st: _JointLineStatics, joints, alpha, beta):
    """Rows 'alpha N + beta <= m' and 'alpha N + beta <= L N - m' at ``joints``."""
    A_N, b_N, A_m, b_m, L = st.A_N[joints], st.b_N[joints], st.A_m[joints], st.b_m[joints], \
        st.L[joints]
    rows_i = alpha[:, None] * A_N - A_m
    rhs_i = b_m - alpha * b_N - beta
    rows_e = (alpha - L)[:, None] * A_N + A_m
    rhs_e = -(alpha - L) * b_N - beta - b_m
    return np.vstack([rows_i, rows_e]), np.concatenate([rhs_i, rhs_e])


#: HiGHS's tolerances, well below the bracket's 1e-6 (its defaults, 1e-7, are not)
_HIGHS = {"primal_feasibility_tolerance": 1e-10, "dual_feasibility_tolerance": 1e-10}


def _programs(st, c, points, nmax, crushes):
    """(A, b) of the relaxation (tangents at every point) and of the restriction (chords
    between consecutive points, N within [0, N_max]); joints that are point contacts keep
    the rows of :mod:`.lp` (no segment to crush)."""
    tj, ta, tb, sj, sa, sb = [], [], [], [], [], []
    for j in np.flatnonzero(crushes):
        p = points[j]
        tj.append(np.full(p.size, j))
        ta.append(2.0 * c * p)
        tb.append(-c * p * p)
        sj.append(np.full(p.size - 1, j))
        sa.append(c * (p[:-1] + p[1:]))
        sb.append(-c * p[:-1] * p[1:])
    A_t, b_t = _line_rows(st, np.concatenate(tj), np.concatenate(ta), np.concatenate(tb))
    A_s, b_s = _line_rows(st, np.concatenate(sj), np.concatenate(sa), np.concatenate(sb))
    idx = np.flatnonzero(crushes)
    # the restriction's chords hold above c N^2 only on [0, N_max]
    A_s = np.vstack([A_s, -st.A_N[idx], st.A_N[idx]])
    b_s = np.concatenate([b_s, st.b_N[idx], nmax[idx] - st.b_N[idx]])
    rest = np.flatnonzero(~crushes)
    if rest.size:  # point contacts: the thrust through the point, in compression
        keep = np.concatenate([rest, rest + st.L.size])
        extra_A = np.vstack([st.A_ub[keep], -st.A_N[rest]])
        extra_b = np.concatenate([st.b_ub[keep], st.b_N[rest]])
        A_t, b_t = np.vstack([A_t, extra_A]), np.concatenate([b_t, extra_b])
        A_s, b_s = np.vstack([A_s, extra_A]), np.concatenate([b_s, extra_b])
    return (A_t, b_t), (A_s, b_s)


def _add_points(points, forces, nmax, crushes):
    """Each joint's breakpoints with the forces ``forces`` added (clipped to [0, N_max])."""
    for j in np.flatnonzero(crushes):
        f = min(max(float(forces[j]), 0.0), float(nmax[j]))
        p = points[j]
        if np.min(np.abs(p - f)) > 1e-13 * nmax[j]:
            points[j] = np.sort(np.append(p, f))


def _bracket(st, c, objective, lam_bounds=(None, None), rtol: float = BRACKET_RTOL,
             max_rounds: int = MAX_ROUNDS, sign_only: bool = False):
    """(lower, upper, x_lower, x_upper, rounds): the bracket of max -objective . x over the
    crushing conditions of statics ``st`` (lambda within ``lam_bounds``), refined until it
    closes to ``rtol`` or, with ``sign_only``, until the sign of the maximum is known.
    Status 'infeasible' or 'unbounded' (of the relaxation) as the first item instead."""
    crushes = st.L > 0.0
    nmax = np.where(crushes, st.L / (2.0 * c), 0.0)
    # breakpoints from 0 to N_max, denser toward 0 where the forces of a strong masonry lie
    init = np.concatenate([[0.0], 2.0 ** -np.arange(12.0, -1.0, -1.0)])
    points = [init * nmax[j] for j in range(st.L.size)]
    bounds = [(None, None)] * 3 + [lam_bounds]
    lower, upper, x_lo, x_hi = -math.inf, math.inf, None, None

    def solve(A, b):
        res = linprog(c=objective, A_ub=A, b_ub=b, bounds=bounds, method="highs", options=_HIGHS)
        return res.status, (np.asarray(res.x, float) if res.status == 0 else None)

    for rounds in range(1, max_rounds + 1):
        (A_t, b_t), (A_s, b_s) = _programs(st, c, points, nmax, crushes)
        status, x = solve(A_t, b_t)
        if status in (2, 3):
            return ("infeasible" if status == 2 else "unbounded"), None, None, None, rounds
        if status != 0:
            raise LimitExceededError(f"crushing analysis: the relaxed linear program did not "
                                     f"finish (status {status})")
        value = -float(np.dot(objective, x))
        if value <= upper:
            upper, x_hi = value, x
        _add_points(points, st.A_N @ x + st.b_N, nmax, crushes)
        status, xs = solve(A_s, b_s)
        if status == 0 and -float(np.dot(objective, xs)) >= lower:
            lower, x_lo = -float(np.dot(objective, xs)), xs
            _add_points(points, st.A_N @ xs + st.b_N, nmax, crushes)
        if sign_only and (lower >= 0.0 or upper < 0.0):
            return lower, upper, x_lo, x_hi, rounds
        # relative, but not below 1e-3 in absolute terms: near 0 the LPs' tolerance (1e-10)
        # is what limits the bracket
        if x_lo is not None and upper - lower <= rtol * max(abs(upper), 1e-3):
            return lower, upper, x_lo, x_hi, rounds
    if sign_only:  # the maximum is 0 to within the bracket: on the edge, counted as standing
        return max(lower, 0.0), upper, x_lo, x_hi, max_rounds
    raise LimitExceededError(
        f"crushing analysis: the bracket did not close to {rtol:g} in {max_rounds} rounds "
        f"({lower:.9g} to {upper:.9g})")


def crushing_bracket(arch: VoussoirArch, direction: str, rtol: float = BRACKET_RTOL,
                     max_rounds: int = MAX_ROUNDS) -> CrushingBracket:
    """The static multiplier of ``arch`` with its finite ``fc``, bracketed to ``rtol`` (module
    docstring): CannotStandError where even the relaxation has no line of thrust,
    NoMechanismError where it is unbounded, LimitExceededError where ``max_rounds`` rounds do
    not close the bracket."""
    st = _statics(arch, direction, "joint-line")
    lower, upper, x_lo, x_hi, rounds = _bracket(st, crushing_constant(arch), [0, 0, 0, -1.0],
                                                rtol=rtol, max_rounds=max_rounds)
    if lower == "unbounded":
        raise NoMechanismError(
            f"arch: no mechanism opens under horizontal forces toward "
            f"{'+x' if st.d > 0 else '-x'} even with f_c = {arch.fc:g} MPa (the relaxed "
            f"program is unbounded); sliding governs")
    if lower == "infeasible":
        raise CannotStandError(
            f"arch: no line of thrust fits inside the arch with f_c = {arch.fc:g} MPa "
            f"(direction {direction!r}); the arch cannot stand: it crushes under its own "
            f"weight or cannot carry it")
    return CrushingBracket(direction, lower, upper, x_lo, x_hi, rounds)


def crushing_stands(arch: VoussoirArch) -> bool:
    """Whether a line of thrust fits inside ``arch`` under its own weight with its finite
    ``fc``: the multipliers that fit form an interval [-k_r, k_l], which holds 0 when both
    are >= 0 (each bracket refined until its sign is known)."""
    c = crushing_constant(arch)
    for d in ("l", "r"):
        lower = _bracket(_statics(arch, d, "joint-line"), c, [0, 0, 0, -1.0],
                         sign_only=True)[0]
        if lower in ("infeasible",) or (lower != "unbounded" and lower < 0.0):
            return False
    return True


def crushing_thrust(arch: VoussoirArch, sign: float):
    """(H per total weight, x) at the least (``sign`` +1) or greatest (-1) horizontal thrust
    with lambda = 0 under the crushing conditions (the static optimum, bracketed to
    :data:`BRACKET_RTOL`; x the restriction's point, which satisfies them); ('infeasible' |
    'unbounded', None) where it has none."""
    st = _statics(arch, "l", "joint-line")
    lower, upper, x_lo, _, _ = _bracket(st, crushing_constant(arch), [sign, 0, 0, 0.0],
                                        lam_bounds=(0.0, 0.0))
    if isinstance(lower, str):
        return lower, None
    return float(x_lo[0]), x_lo


# ---------------------------------------------------------------------------- the optimum
@dataclass(frozen=True)
class CrushingOptimum:
    """The exact point of one direction's optimum: ``multiplier``, the redundants ``x``, the
    normal forces ``N`` [N/m] and compressed zones ``zones`` [m] (depth N / f_c, 0 where a
    joint is open) at every joint, the ``hinges`` where the thrust passes through the centre of
    a stress block at an edge, the joints ``crushed`` through (the block fills the joint), and
    ``exact``: whether Newton's method found the point where
    four such conditions hold (else x is the bracket's lower optimum)."""

    direction: str
    multiplier: float
    x: np.ndarray
    N: np.ndarray
    zones: np.ndarray
    hinges: tuple
    crushed: tuple
    exact: bool
    thrust: ThrustLine


def _conditions(st, c, x):
    """(g, jac): the 2 (n+1) conditions g <= 0 (intrados ends, then extrados ends) and their
    gradients in x."""
    N = st.A_N @ x + st.b_N
    m = st.A_m @ x + st.b_m
    g = np.concatenate([c * N * N - m, c * N * N - st.L * N + m])
    dN = st.A_N
    jac = np.vstack([2 * c * N[:, None] * dN - st.A_m,
                     (2 * c * N - st.L)[:, None] * dN + st.A_m])
    return g, jac


def _newton(st, c, rows, x0, iters: int = 50):
    x = np.array(x0, float)
    for _ in range(iters):
        g, jac = _conditions(st, c, x)
        try:
            dx = np.linalg.solve(jac[rows], -g[rows])
        except np.linalg.LinAlgError:
            return None
        x = x + dx
        if np.max(np.abs(dx)) <= 1e-15 * max(1.0, np.max(np.abs(x))):
            break
    g, _ = _conditions(st, c, x)
    return x if np.all(np.isfinite(x)) and np.max(np.abs(g[rows])) <= 1e-12 else None


def crushing_optimum(arch: VoussoirArch, bracket: CrushingBracket) -> CrushingOptimum:
    """The optimum of ``bracket``'s direction: the four conditions nearest equality at the
    bracket's optimum (four different joints) solved exactly by Newton's method, kept where the
    point satisfies every condition and lies within the bracket; else the bracket's lower
    optimum (``exact`` False)."""
    st = _statics(arch, bracket.direction, "joint-line")
    c = crushing_constant(arch)
    n1 = st.L.size
    x_lo = np.asarray(bracket.x_lower, float)
    # a point contact (L = 0) keeps Heyman's rows: its slack counts on the scale of 1
    scale = np.where(st.L > 0, st.L * np.maximum(st.A_N @ x_lo + st.b_N, 1e-300), 1.0)
    best = None
    for x_start in (bracket.x_upper, bracket.x_lower):
        g, _ = _conditions(st, c, np.asarray(x_start, float))
        slack = np.abs(g) / np.concatenate([scale, scale])
        # the four conditions nearest equality (both ends of one joint: crushed through)
        rows = [int(r) for r in np.argsort(slack)[:4]]
        x = _newton(st, c, sorted(rows), x_start)
        if x is None:
            continue
        gx, _ = _conditions(st, c, x)
        tol = 1e-9 * np.concatenate([scale, scale])
        lam = float(x[3])
        # the bracket's LPs hold their rows to HiGHS's tolerance (1e-10), so to ~1e-8 in lambda
        inside = bracket.lower - 1e-8 * abs(bracket.upper) <= lam <= \
            bracket.upper + 1e-8 * abs(bracket.upper)
        if np.all(gx <= tol) and inside:
            best = (x, sorted(rows))
            break
    exact = best is not None
    if exact:
        x, rows = best
    else:
        x = x_lo
        g, _ = _conditions(st, c, x)
        slack = np.abs(g) / np.concatenate([scale, scale])
        rows = sorted(int(r) for r in np.flatnonzero(slack <= 1e-6))
    N = np.maximum(st.A_N @ x + st.b_N, 0.0)
    w_total = float(np.sum(arch.weights))
    zones = np.where(st.L > 0, N * w_total / (arch.fc * MPA), 0.0)
    joints = [r % n1 for r in rows]
    crushed = tuple(sorted({j for j in joints if joints.count(j) > 1}))
    hinges = tuple(sorted((Hinge(r % n1, EDGES[r // n1]) for r in rows if r % n1 not in crushed),
                          key=lambda h: (h.joint, h.edge)))
    with np.errstate(invalid="ignore", divide="ignore"):
        thrust = _thrust_from_x(st, x)
    return CrushingOptimum(bracket.direction, float(x[3]), x, N * w_total, zones, hinges, crushed,
                           exact, thrust)


# ---------------------------------------------------------------------------- the inset arch
class InsetArch(VoussoirArch):
    """``base`` with each joint's contact segment shortened by ``insets[j]`` [m] at both ends
    (half the compressed zone at the collapse force): the masses, loads and outlines are the
    base's.  Heyman's analysis of it is the crushing analysis's kinematic check."""

    def __init__(self, base: VoussoirArch, insets):
        self.base = base
        d = np.asarray(insets, float)
        jp = np.asarray(base.joint_points, float)
        e = jp[:, 1] - jp[:, 0]
        length = np.hypot(e[:, 0], e[:, 1])
        if d.shape != (base.n + 1,) or np.any(d < 0) or np.any(2 * d >= length):
            raise ArchInputError(f"insets: {d.size} values; allowed one per joint, each >= 0 "
                                 f"and less than half its contact segment")
        u = e / np.where(length > 0, length, 1.0)[:, None]
        pts = np.stack([jp[:, 0] + d[:, None] * u, jp[:, 1] - d[:, None] * u], axis=1)
        pts.setflags(write=False)
        self._pts = pts
        self.density, self.name, self.loads = base.density, f"{base.name} (inset)", base.loads

    n = property(lambda self: self.base.n)
    joint_points = property(lambda self: self._pts)
    areas = property(lambda self: self.base.areas)
    area_centroids = property(lambda self: self.base.area_centroids)
    area_polar = property(lambda self: self.base.area_polar)
    size = property(lambda self: self.base.size)
    _mass_properties = property(lambda self: self.base._mass_properties)

    def outline(self, i: int) -> np.ndarray:
        return self.base.outline(i)

    def mirrored(self):
        raise NotImplementedError("an inset arch is a check, not an arch to transform")

    scaled = mirrored

    def to_dict(self) -> dict:
        return self.base.to_dict()


def inset_arch(arch: VoussoirArch, optimum: CrushingOptimum) -> InsetArch:
    """``arch`` with its contact segments shortened by half the compressed zones of
    ``optimum`` (the stress blocks' centres are the new ends)."""
    return InsetArch(arch, 0.5 * optimum.zones)


def virtual_work_multiplier(arch: VoussoirArch, optimum: CrushingOptimum) -> float:
    """The multiplier of the mechanism of ``optimum`` by its own virtual work, with its hinges
    at the stress blocks' centres (NaN where its hinges make no admissible mechanism)."""
    from .liftoff import mechanism_multiplier

    if optimum.crushed or len(optimum.hinges) != 4:
        return math.nan  # a joint crushed through shortens: no rigid-block mechanism
    mech = Mechanism(optimum.direction, optimum.hinges, optimum.multiplier)
    return mechanism_multiplier(inset_arch(arch, optimum), mech)


# ---------------------------------------------------------------------------- one direction
@dataclass(frozen=True)
class CrushingAnswer:
    """One direction of :func:`crushing_analysis`: the ``mechanism`` (hinges at the stress
    blocks' centres), the multipliers ``kinematic`` (its own virtual work; None where no
    rigid-block mechanism confirms the optimum) and ``static`` (the optimum's point),
    ``bounds`` (the bracket), ``enumeration`` (Heyman's four-hinge enumeration on the inset
    arch), the ``zones`` [m], the line of thrust and ``how`` it was found."""

    mechanism: Mechanism
    kinematic: float | None
    static: float
    bounds: tuple
    enumeration: float | None
    zones: np.ndarray
    thrust: ThrustLine
    how: str


def crushing_analysis(arch: VoussoirArch, direction: str, method: str = "auto",
                      max_seconds: float | None = None) -> CrushingAnswer:
    """The collapse multiplier of ``arch`` (finite ``fc``) in ``direction``: the bracket, the
    optimum's point, and where four hinges form, the mechanism confirmed by its virtual work
    and by the four-hinge enumeration on the inset arch (``method``, ``max_seconds``: as
    :func:`archrock.statics.limit.limit_analysis`).  Where a joint is crushed through, or
    fewer than four conditions hold at the optimum (the stress blocks' depth changes as the
    hinges turn: no rigid-block mechanism), the static optimum is the answer and the hinges are
    where its thrust meets the stress blocks' centres."""
    from .kinematic import _governing

    br = crushing_bracket(arch, direction)
    opt = crushing_optimum(arch, br)
    bounds = (br.lower, br.upper)
    vw = virtual_work_multiplier(arch, opt) if opt.exact else math.nan
    if math.isfinite(vw):
        mech = Mechanism(direction, opt.hinges, vw)
        gov = _governing(inset_arch(arch, opt), method, max_seconds, static=False)[direction]
        return CrushingAnswer(mech, vw, opt.multiplier, bounds, gov.mechanism.multiplier,
                              opt.zones, opt.thrust, "four-hinge")
    mech = Mechanism(direction, opt.hinges, opt.multiplier, crushed=opt.crushed)
    return CrushingAnswer(mech, None, opt.multiplier, bounds, None, opt.zones, opt.thrust,
                          "crushing-static")

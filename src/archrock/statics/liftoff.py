"""General mechanisms: four-hinge chains and mechanisms with lift-off, from the LP's dual.

Each row of the static program (:mod:`archrock.statics.lp`) is, by duality, a virtual relative
rotation of the parts either side of a joint about one end of its contact segment: one active
row at a joint is a hinge, both rows a lift-off (the parts separate, no sliding).  Multipliers
are per unit weight, directions 'l' (loads toward +x) and 'r' (toward -x), lengths divided by
the reference length about :func:`archrock.statics.sums._origin`.  :func:`certify_four_hinge`
decides whether a four-hinge mechanism governs (its line of thrust fits the arch).
"""

from __future__ import annotations

import math
from itertools import combinations

import numpy as np
from scipy.optimize import linprog

from ..errors import ArchInputError, CannotStandError, NoMechanismError
from ..geometry import VoussoirArch
from .hinges import (_ADMISSIBLE_TOL, DIRECTIONS, EDGES, Hinge, Mechanism, candidate_hinges,
                     quadruples)
from .lp import _statics, _thrust_from_x
from .overload import cannot_stand_message
from .sums import _origin, _weights_centroids, arch_sums

__all__ = ["general_mechanisms", "mechanism_multiplier", "certify_four_hinge",
           "certify_candidates", "LIFT_OFF_REASON", "CERTIFY_TOL", "GENERAL_MAX_VOUSSOIRS"]


# The static program has two rows per joint j: the thrust stays inside the intrados end (row j)
# and inside the extrados end (row n+1+j).  By linear-programming duality each row is a virtual
# motion of the part right of the joint relative to the part left of it: row j a rotation about
# the intrados end P_in that opens the joint at its extrados, row n+1+j a rotation about the
# extrados end that opens it at its intrados.  A joint with one active row is a hinge; with both,
# it opens at both ends: the parts separate across it (lift-off), without sliding, since the
# program bounds no shear.  A basic dual solution has at most four active rows (four redundants),
# so every vertex of the dual is a single-degree-of-freedom mechanism of at most four rows: the
# four-hinge chains (four joints, one row each) and those with lift-off (a joint with both rows).
# The smallest multiplier over all of them is the static optimum (the Heyman collapse
# multiplier), which :func:`general_mechanisms` enumerates kinematically, without the program.

#: Why a study leaves out an arch whose governing mechanism has lift-off (batch error text).
LIFT_OFF_REASON = ("limit analysis: a joint lifts off before any four-hinge mechanism opens (the "
                   "governing mechanism has lift-off); the four-link model does not hold (archrock "
                   "dem follows it)")

#: A four-hinge mechanism governs when the line of thrust through its hinges lies inside every
#: contact segment to this fraction of the segment's length (then its multiplier is both an
#: upper bound, kinematic theorem, and a lower bound, static theorem).  HiGHS's optimum lies
#: within ~1e-9 of the segment ends; a lift-off mechanism that beats a four-hinge one by less
#: than ~1e-7 of its multiplier is not told apart (the multipliers agree to that).
CERTIFY_TOL = 1e-7
# Rows whose dual rate is below this fraction of the largest are inactive (HiGHS rounds to ~1e-12).
_DUAL_TOL = 1e-9
# The kinematic multiplier of the LP's mechanism must equal the LP's optimum to this (relative
# for |lambda| >= 1, absolute below): HiGHS's default feasibility tolerance is 1e-7.
_DUAL_CONFIRM = 1e-7
# Rows of a degenerate dual (more than four active) above which the pool is not enumerated.
_POOL_MAX_ROWS = 24
#: Largest arch (voussoirs) :func:`general_mechanisms` enumerates: C(2n+2, 4) candidates
#: (1.7e6 at n = 40, about 2 s in numpy).
GENERAL_MAX_VOUSSOIRS = 40


def _kinematic_frame(arch: VoussoirArch):
    """(w, g, P): weights per unit total weight (n,), their points (n, 2) and the joint points
    (n+1, 2 edges, 2), lengths divided by the reference length about :func:`_origin` (the
    statics' frame)."""
    ref = arch.reference_length
    origin = _origin(arch)
    w, g = _weights_centroids(arch)
    P = np.asarray(arch.joint_points, float)
    return w, (g - origin) / ref, (P - origin) / ref


def _row_terms(w, g, P):
    """Per row (2(n+1) rows: intrados ends, then extrados ends): the twist (v_x, v_y, omega) at
    the origin of the unit relative motion (3, R), its joint (R,), and the work terms (X, Y) of
    the weights right of its joint: sum_i w_i v(G_i) over the voussoirs i >= joint."""
    n1 = P.shape[0]
    pts = np.concatenate([P[:, 0], P[:, 1]])
    om = np.concatenate([-np.ones(n1), np.ones(n1)])  # about P_in clockwise opens the extrados
    T = np.stack([om * pts[:, 1], -om * pts[:, 0], om])
    joint = np.concatenate([np.arange(n1), np.arange(n1)])
    suffix = lambda v: np.concatenate([np.cumsum(v[::-1])[::-1], [0.0]])  # noqa: E731
    Sw, Sx, Sy = suffix(w)[joint], suffix(w * g[:, 0])[joint], suffix(w * g[:, 1])[joint]
    X = T[0] * Sw - T[2] * Sy
    Y = T[1] * Sw + T[2] * Sx
    return T, joint, X, Y


def _null_rates(T4):
    """Rates (..., 4) of four rows whose twists are T4 (..., 3, 4) closing the chain
    (sum rate_k T_k = 0), from the signed 3x3 minors; ok where the null space is one line."""
    cols = [T4[..., k] for k in range(4)]

    def det3(a, b, c):
        return (a[..., 0] * (b[..., 1] * c[..., 2] - b[..., 2] * c[..., 1])
                - a[..., 1] * (b[..., 0] * c[..., 2] - b[..., 2] * c[..., 0])
                + a[..., 2] * (b[..., 0] * c[..., 1] - b[..., 1] * c[..., 0]))

    c0, c1, c2, c3 = cols
    rates = np.stack([det3(c1, c2, c3), -det3(c0, c2, c3), det3(c0, c1, c3), -det3(c0, c1, c2)],
                     axis=-1)
    norm = np.max(np.stack([np.abs(c).sum(axis=-1) for c in cols], axis=-1), axis=-1)
    big = np.max(np.abs(rates), axis=-1)
    ok = big > 1e-12 * norm ** 3
    return rates, ok, big


def _rows_multipliers(rows, T, X, Y, d, rates_out: bool = False):
    """Multipliers (K,) of the candidate mechanisms ``rows`` (K, 4) for direction d (+1 'l',
    -1 'r'): inf where the four rows do not close into one admissible mechanism (every rate of
    one sign; a rate that is zero leaves its row inactive, so three rows that close on their
    own, e.g. the whole arch turning about one springing while the other lifts off, count as
    well) or the horizontal loads do no work on it.  ``rates_out``: also the rates (K, 4),
    zero where a row is inactive."""
    T4 = T[:, rows]                       # (3, K, 4)
    rates, ok, big = _null_rates(np.moveaxis(T4, 0, -2))
    thr = (_ADMISSIBLE_TOL * np.where(ok, big, 1.0))[:, None]
    pos = np.all(rates > -thr, axis=1) & np.any(rates > thr, axis=1)
    neg = np.all(rates < thr, axis=1) & np.any(rates < -thr, axis=1)
    sigma = np.where(neg, -1.0, 1.0)
    rates = np.where(np.abs(rates) > thr, rates * sigma[:, None], 0.0)
    adm = ok & (pos | neg)
    Xc = np.sum(rates * X[rows], axis=1) * d
    Yc = np.sum(rates * Y[rows], axis=1)
    scale = np.sum(np.abs(rates * X[rows]) + np.abs(rates * Y[rows]), axis=1)
    good = adm & (Xc > 1e-12 * np.maximum(scale, 1e-300))
    lam = np.where(good, Yc / np.where(good, Xc, 1.0), np.inf)
    return (lam, rates) if rates_out else lam


def _set_multiplier(rows, T, X, Y, d):
    """(multiplier, rates) of one set of at most four rows by the SVD of their closure
    (3 x k): a mechanism where the null space is one line and its rates are of one sign (zeros
    allowed: inactive rows); (inf, None) otherwise.  Rows whose points are collinear (two
    springings on one bed line) make the 4-row minors of :func:`_null_rates` vanish; this
    does not need a fourth independent row."""
    rows = np.asarray(rows, dtype=np.int64)
    M = T[:, rows]
    _, sv, vt = np.linalg.svd(M, full_matrices=True)
    rank = int(np.sum(sv > 1e-10 * max(sv[0], 1e-300)))
    if rows.size - rank != 1:
        return math.inf, None
    v = vt[-1]
    big = np.max(np.abs(v))
    thr = _ADMISSIBLE_TOL * big
    if np.all(v < thr):
        v = -v
    if not (np.all(v > -thr) and np.any(v > thr)):
        return math.inf, None
    v = np.where(np.abs(v) > thr, v, 0.0)
    Xc, Yc = d * float(v @ X[rows]), float(v @ Y[rows])
    scale = float(np.abs(v * X[rows]).sum() + np.abs(v * Y[rows]).sum())
    if not Xc > 1e-12 * max(scale, 1e-300):
        return math.inf, None
    return Yc / Xc, v


def _active(rows, rates):
    """The rows of one candidate whose rate is not zero."""
    return [int(r) for r, v in zip(rows, rates) if v != 0.0]


def _mechanism_of_rows(arch: VoussoirArch, rows, direction: str, lam: float) -> Mechanism:
    """The :class:`Mechanism` of active rows (joint ends): one row a hinge, two a lift-off."""
    n1 = arch.n + 1
    by_joint: dict[int, set] = {}
    for r in rows:
        by_joint.setdefault(int(r) % n1, set()).add(int(r) // n1)
    hinges = tuple(Hinge(j, EDGES[next(iter(e))]) for j, e in sorted(by_joint.items())
                   if len(e) == 1)
    lift = tuple(j for j, e in sorted(by_joint.items()) if len(e) == 2)
    return Mechanism(direction, hinges, float(lam), lift)


def general_mechanisms(arch: VoussoirArch, direction: str) -> Mechanism:
    """The collapse mechanism of ``arch`` for ``direction`` by kinematic enumeration of every
    single-degree-of-freedom mechanism of at most four active joint ends (four-hinge chains and
    mechanisms with lift-off): the smallest virtual-work multiplier.  By linear-programming
    duality it equals the static optimum (:func:`static_multiplier`); this is the independent
    kinematic method that checks it.  Arches of up to :data:`GENERAL_MAX_VOUSSOIRS` voussoirs.
    NoMechanismError where no mechanism loads that direction."""
    if direction not in DIRECTIONS:
        raise ArchInputError(f"direction: {direction!r}; allowed 'l' or 'r'")
    if arch.n > GENERAL_MAX_VOUSSOIRS:
        raise ArchInputError(f"arch: {arch.n} voussoirs; general_mechanisms enumerates up to "
                             f"{GENERAL_MAX_VOUSSOIRS} (C(2n+2, 4) candidates)")
    w, g, P = _kinematic_frame(arch)
    T, _, X, Y = _row_terms(w, g, P)
    d = 1.0 if direction == "l" else -1.0
    best, best_rows = np.inf, None
    R = T.shape[1]
    for first in range(R - 3):  # blocks by first row: memory O(R^3)
        rest = np.array(list(combinations(range(first + 1, R), 3)), dtype=np.int64)
        rows = np.column_stack([np.full(len(rest), first), rest])
        lam, rates = _rows_multipliers(rows, T, X, Y, d, rates_out=True)
        k = int(np.argmin(lam))
        if lam[k] < best:
            best, best_rows = float(lam[k]), _active(rows[k], rates[k])
    if best_rows is None:
        raise NoMechanismError(f"arch: no mechanism opens under horizontal forces toward "
                               f"{'+x' if d > 0 else '-x'}")
    return _mechanism_of_rows(arch, best_rows, direction, best)


def mechanism_multiplier(arch: VoussoirArch, mechanism: Mechanism) -> float:
    """The virtual-work multiplier of any mechanism of :func:`general_mechanisms`'s family
    (four-hinge or with lift-off), from its joints alone: the relative motions that close the
    chain, their rates of one sign, and the work of the weights and of the horizontal loads.
    NaN where the joints do not make one admissible mechanism."""
    n1 = arch.n + 1
    rows = [EDGES.index(h.edge) * n1 + h.joint for h in mechanism.hinges]
    rows += [j for j in mechanism.lift_off] + [n1 + j for j in mechanism.lift_off]
    if len(rows) not in (3, 4):
        return math.nan
    w, g, P = _kinematic_frame(arch)
    T, _, X, Y = _row_terms(w, g, P)
    d = 1.0 if mechanism.direction == "l" else -1.0
    lam, _ = _set_multiplier(sorted(rows), T, X, Y, d)
    return float(lam) if np.isfinite(lam) else math.nan


def _lp_mechanism(arch: VoussoirArch, direction: str):
    """(LP optimum, its line of thrust, the mechanism read from the LP's dual and confirmed by
    its own virtual work, or None where it cannot be confirmed).  CannotStandError where no
    line of thrust fits; (inf, None, None) where the program is unbounded (no mechanism)."""
    st = _statics(arch, direction)
    res = linprog(c=[0, 0, 0, -1.0], A_ub=st.A_ub, b_ub=st.b_ub, bounds=[(None, None)] * 4,
                  method="highs")
    if res.status == 3:
        return math.inf, None, None
    if res.status != 0:
        raise CannotStandError(cannot_stand_message(
            arch, f"(no line of thrust fits inside it: direction {direction!r}, linear program "
                  f"status {res.status})"))
    lam_s = float(res.x[3])
    with np.errstate(invalid="ignore", divide="ignore"):
        thrust = _thrust_from_x(st, res.x)
    mu = -np.asarray(res.ineqlin.marginals, float)
    support = np.flatnonzero(mu > _DUAL_TOL * np.max(mu))
    # only joint-end rows name hinges (a point contact's compression row comes after them)
    support = support[support < 2 * (arch.n + 1)]
    w, g, P = _kinematic_frame(arch)
    T, _, X, Y = _row_terms(w, g, P)
    d = st.d
    if support.size <= 4:
        lam1, rates1 = _set_multiplier(support, T, X, Y, d)
        if abs(lam1 - lam_s) <= _DUAL_CONFIRM * max(1.0, abs(lam_s)):
            return lam_s, thrust, _mechanism_of_rows(arch, _active(support, rates1), direction,
                                                     float(lam1))
    if support.size == 4:
        pool = support[None]
    elif support.size < 4:
        # a degenerate vertex: complete it with any row (its rate comes out zero or not one
        # sign, and such candidates are not admissible), so search the rows of the joints
        # involved, both ends
        joints = np.unique(support % (arch.n + 1))
        cand = np.union1d(support, np.concatenate([joints, joints + arch.n + 1]))
        pool = quadruples(cand)
    elif support.size <= _POOL_MAX_ROWS:
        pool = quadruples(support)
    else:
        return lam_s, thrust, None
    if not len(pool):
        return lam_s, thrust, None
    lam, rates = _rows_multipliers(pool, T, X, Y, d, rates_out=True)
    k = int(np.argmin(lam))
    if not np.isfinite(lam[k]) or abs(lam[k] - lam_s) > _DUAL_CONFIRM * max(1.0, abs(lam_s)):
        return lam_s, thrust, None
    return lam_s, thrust, _mechanism_of_rows(arch, _active(pool[k], rates[k]), direction,
                                             float(lam[k]))


def _hinge_rows(cw, cwx, cwy, px, py, d):
    """Rows A (B, 2(n+1), 4) and right-hand sides b (B, 2(n+1)) of the joint-line statics of a
    batch (prefix sums (B, n+1), joint points (B, n+1, 2 edges)): A x <= b keeps the thrust
    inside every contact segment (rows 0..n the intrados ends, n+1..2n+1 the extrados ends),
    equality puts it through that end."""
    ex, ey = px[..., 1] - px[..., 0], py[..., 1] - py[..., 0]
    L = np.hypot(ex, ey)
    if np.any(L == 0.0):
        # point contacts (a displaced arch's open hinges): no normal from the segment; their
        # rows say only that the thrust passes through the point (the LP adds compression)
        Ld = np.where(L == 0.0, 1.0, L)
        nux, nuy = ey / Ld, -ex / Ld
    else:
        nux, nuy = ey / L, -ex / L
    x0, y0 = px[..., 0], py[..., 0]
    zero, one = np.zeros_like(cw), np.ones_like(cw)
    A_N = np.stack([nux, nuy, zero, d * cw * nux], axis=-1)
    b_N = -nuy * cw
    A_m = np.stack([-y0, x0, -one, d * (cwy - y0 * cw)], axis=-1)
    b_m = cwx - x0 * cw
    A = np.concatenate([-A_m, A_m - L[..., None] * A_N], axis=1)
    b = np.concatenate([b_m, L * b_N - b_m], axis=1)
    return A, b, L


def certify_four_hinge(cw, cwx, cwy, px, py, joints, edges, direction: str) -> np.ndarray:
    """Whether each arch's four-hinge mechanism (joints, edges (B, 4)) governs: the line of
    thrust through its four hinges lies inside every contact segment, in compression, to
    :data:`CERTIFY_TOL` of the segment's length (B,) bool.  Then its multiplier is the Heyman
    collapse multiplier (both limit theorems); where not, a mechanism outside the four-hinge
    family (lift-off) governs with a smaller one.  Inputs as :func:`arch_sums` (a batch)."""
    d = 1.0 if direction == "l" else -1.0
    A, b, L = _hinge_rows(cw, cwx, cwy, px, py, d)
    B, m = cw.shape
    j = np.asarray(joints, dtype=np.int64)
    e = np.asarray(edges, dtype=np.int64)
    rows = e * m + j                                   # (B, 4)
    bi = np.arange(B)[:, None]
    M, rhs = A[bi, rows], b[bi, rows]                  # (B, 4, 4), (B, 4)
    scale = np.prod(np.abs(M).sum(axis=2), axis=1)
    with np.errstate(all="ignore"):
        det = np.linalg.det(M)
        ok = np.isfinite(det) & (np.abs(det) > 1e-13 * scale)
        M = np.where(ok[:, None, None], M, np.eye(4))
        x = np.linalg.solve(M, rhs[..., None])[..., 0]
        resid = np.einsum("bkc,bc->bk", A, x) - b     # > 0: outside
        Fx = x[:, :1] + d * x[:, 3:] * cw
        Fy = x[:, 1:2] - cw
        F = np.hypot(Fx, Fy)
        if np.any(L == 0.0):  # a point contact: its tolerance scales with the force alone
            L = np.where(L == 0.0, 1.0, L)
        width = np.concatenate([L * F, L * F], axis=1)
        worst = np.max(resid / np.maximum(width, 1e-300 + 1e-12 * np.max(width, axis=1,
                                                                           keepdims=True)),
                       axis=1)
    return ok & (worst <= CERTIFY_TOL)


def certify_candidates(sums, n: int, cand_l, cand_r) -> tuple[np.ndarray, np.ndarray]:
    """:func:`certify_four_hinge` of a batch's best four-hinge candidates (indices of
    :func:`_candidates`, as :func:`kinematic_multipliers_batch` returns them) for both
    directions: (governs_l, governs_r), each (B,) bool."""
    out = []
    for d, cand in (("l", cand_l), ("r", cand_r)):
        uniq, inv = np.unique(np.asarray(cand, dtype=np.int64), return_inverse=True)
        je = [candidate_hinges(n, c) for c in uniq.tolist()]
        J = np.array([j for j, _ in je], dtype=np.int64)[inv.reshape(-1)]
        E = np.array([e for _, e in je], dtype=np.int64)[inv.reshape(-1)]
        out.append(certify_four_hinge(*sums, J, E, d))
    return out[0], out[1]


def _certify_arch(arch: VoussoirArch, mechanism: Mechanism) -> bool:
    if not mechanism.is_four_hinge:
        return False
    sums = arch_sums(arch)
    j = np.array([[h.joint for h in mechanism.hinges]])
    e = np.array([[EDGES.index(h.edge) for h in mechanism.hinges]])
    return bool(certify_four_hinge(*sums, j, e, mechanism.direction)[0])

"""Limit analysis of voussoir arches under horizontal loads (Heyman's hypotheses).

Loads: the weight W_i at each voussoir centroid plus a horizontal force lambda*W_i.
Direction 'l' means forces toward +x (mechanism M_l, activated by xg''/g <= -k_l, paper eq. 1);
direction 'r' means forces toward -x (M_r, activated by xg''/g >= k_r).

Two independent methods:

* kinematic: every four-hinge mechanism (4 joints out of n+1, each hinge at the intrados or
  extrados end of its contact surface) whose hinge rotations open the joints admissibly; the
  multiplier follows from virtual work and the collapse multiplier is the minimum.  Work sums use
  prefix sums of W, W*x_G, W*y_G, so each candidate costs O(1) and the enumeration is vectorised
  over candidates and over a batch of arches.
* static: a linear program on the three redundant reactions at the left springing and lambda:
  maximise lambda with the line of thrust inside every joint's contact surface.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import lru_cache
from itertools import combinations

import numpy as np
from scipy.optimize import linprog

from .errors import ArchInputError
from .geometry import Arch, sector_properties

__all__ = [
    "Hinge", "Mechanism", "ThrustLine", "LimitResult", "MinimumThickness",
    "limit_analysis", "kinematic_mechanisms", "kinematic_multipliers_batch",
    "static_multiplier", "thrust_line", "minimum_thickness", "EDGES",
]

EDGES = ("intrados", "extrados")
DIRECTIONS = ("l", "r")
# Sign s_e such that a hinge at edge e opens when s_e * (omega_right - omega_left) > 0.
_EDGE_SIGN = np.array([-1.0, 1.0])
_ADMISSIBLE_TOL = 1e-9


@dataclass(frozen=True)
class Hinge:
    """A hinge at the intrados or extrados end of joint ``joint`` (0 = left springing)."""

    joint: int
    edge: str

    def to_dict(self) -> dict:
        return {"joint": int(self.joint), "edge": self.edge}


@dataclass(frozen=True)
class Mechanism:
    """A four-hinge collapse mechanism; hinges ordered from the left springing.

    direction: 'l' (loads toward +x, M_l) or 'r' (loads toward -x, M_r).
    multiplier: the horizontal load multiplier lambda that activates it (kinematic theorem).
    """

    direction: str
    hinges: tuple[Hinge, Hinge, Hinge, Hinge]
    multiplier: float

    @property
    def joints(self) -> tuple[int, ...]:
        return tuple(h.joint for h in self.hinges)

    def mirrored(self, n: int) -> "Mechanism":
        """The same mechanism on the mirror image of an n-voussoir arch."""
        hinges = tuple(Hinge(n - h.joint, h.edge) for h in reversed(self.hinges))
        return Mechanism("r" if self.direction == "l" else "l", hinges, self.multiplier)

    def to_dict(self) -> dict:
        return {"direction": self.direction, "multiplier": self.multiplier,
                "hinges": [h.to_dict() for h in self.hinges]}


@dataclass(frozen=True)
class ThrustLine:
    """Line of thrust at a given multiplier, for one direction of the horizontal loads.

    radii: radius [m] at which the thrust crosses each joint 0..n (radial joints);
    points: those crossing points (n+1, 2) [m]; forces: resultant transmitted across each joint
    by the part on its left, per unit total weight (n+1, 2); polyline: the funicular polygon
    (joint crossings and the vertices on the load lines), for drawing.
    """

    direction: str
    multiplier: float
    radii: np.ndarray
    points: np.ndarray
    forces: np.ndarray
    polyline: np.ndarray

    def eccentricity_margin(self, arch: Arch) -> float:
        """Smallest distance [m] from the crossing points to the ends of the contact surfaces."""
        return float(np.min(np.minimum(self.radii - arch.contact_inner, arch.contact_outer - self.radii)))


@dataclass(frozen=True)
class LimitResult:
    """Result of :func:`limit_analysis`: multipliers, mechanisms and thrust lines, both directions.

    k_l, k_r come from the kinematic enumeration; static_k_l, static_k_r from the linear program
    (None when not checked); ``discrepancy`` is the largest |kinematic - static| difference.
    """

    arch: Arch = field(repr=False)
    k_l: float
    k_r: float
    mechanism_l: Mechanism
    mechanism_r: Mechanism
    thrust_l: ThrustLine = field(repr=False)
    thrust_r: ThrustLine = field(repr=False)
    static_k_l: float | None = None
    static_k_r: float | None = None
    discrepancy: float | None = None
    method: str = "kinematic enumeration (vectorised), checked by static LP (HiGHS)"

    @property
    def k(self) -> float:
        """The smaller of the two multipliers (the arch's seismic capacity, in g)."""
        return min(self.k_l, self.k_r)

    def mechanism(self, direction: str) -> Mechanism:
        return self.mechanism_l if direction == "l" else self.mechanism_r

    def to_dict(self) -> dict:
        return {
            "k_l": self.k_l, "k_r": self.k_r,
            "mechanism_l": self.mechanism_l.to_dict(), "mechanism_r": self.mechanism_r.to_dict(),
            "static_k_l": self.static_k_l, "static_k_r": self.static_k_r,
            "discrepancy": self.discrepancy, "method": self.method,
            "thrust_l": {"radii": self.thrust_l.radii.tolist()},
            "thrust_r": {"radii": self.thrust_r.radii.tolist()},
            "arch": self.arch.to_dict(),
        }


# ---------------------------------------------------------------------------- kinematic
@lru_cache(maxsize=64)
def _candidates(n: int):
    """All (joint quadruple, edge pattern) candidates for n voussoirs, as index arrays."""
    quads = np.array(list(combinations(range(n + 1), 4)), dtype=np.int64)
    edges = np.array([[(p >> k) & 1 for k in (3, 2, 1, 0)] for p in range(16)], dtype=np.int64)
    jq = np.repeat(quads, 16, axis=0)
    eq = np.tile(edges, (len(quads), 1))
    return jq, eq


def _batch_sums(spans, radii, thick):
    """Prefix sums of weight and first moments (weights normalised to total 1), joint points."""
    p = sector_properties(spans, radii, thick)
    w = p["area"] / p["area"].sum(axis=-1, keepdims=True)
    g = p["centroid"]
    zero = np.zeros(w.shape[:-1] + (1,))
    cw = np.concatenate([zero, np.cumsum(w, axis=-1)], axis=-1)
    cwx = np.concatenate([zero, np.cumsum(w * g[..., 0], axis=-1)], axis=-1)
    cwy = np.concatenate([zero, np.cumsum(w * g[..., 1], axis=-1)], axis=-1)
    r = np.stack([p["r_in"], p["r_out"]], axis=-1)  # (..., n+1, 2 edges)
    c, s = np.cos(p["psi"]), np.sin(p["psi"])
    px = r * c[..., None]
    py = r * s[..., None]
    return cw, cwx, cwy, px, py, p


def _enumerate(spans, radii, thick):
    """Kinematic enumeration for a batch of arches (B, n). Returns per-candidate arrays.

    Returns (lam, dir_mask_l, dir_mask_r, jq, eq) with lam (B, K) the virtual-work multiplier of
    each admissible candidate (inf where inadmissible or not loading that direction).
    """
    B, n = spans.shape
    jq, eq = _candidates(n)
    cw, cwx, cwy, px, py, _ = _batch_sums(spans, radii, thick)
    ja, jb, jc, jd = jq.T
    ea, eb, ec, ed = eq.T
    Ax, Ay = px[:, ja, ea], py[:, ja, ea]
    Bx, By = px[:, jb, eb], py[:, jb, eb]
    Cx, Cy = px[:, jc, ec], py[:, jc, ec]
    Dx, Dy = px[:, jd, ed], py[:, jd, ed]
    # omega1 = 1; loop closure  w2 (C-B) + w3 (D-C) = -(B-A)
    u2x, u2y = Cx - Bx, Cy - By
    u3x, u3y = Dx - Cx, Dy - Cy
    rx, ry = Ax - Bx, Ay - By
    det = u2x * u3y - u2y * u3x
    scale = np.maximum(np.abs(u2x) + np.abs(u2y), 1e-300) * np.maximum(np.abs(u3x) + np.abs(u3y), 1e-300)
    ok = np.abs(det) > 1e-12 * scale
    det = np.where(ok, det, 1.0)
    w2 = (rx * u3y - ry * u3x) / det
    w3 = (u2x * ry - u2y * rx) / det
    w1 = np.ones_like(w2)
    sA, sB, sC, sD = _EDGE_SIGN[ea], _EDGE_SIGN[eb], _EDGE_SIGN[ec], _EDGE_SIGN[ed]
    q = np.stack([sA * w1, sB * (w2 - w1), sC * (w3 - w2), sD * (-w3)], axis=0)
    qmag = np.max(np.abs(q), axis=0)
    pos = np.all(q > _ADMISSIBLE_TOL * qmag, axis=0)
    neg = np.all(q < -_ADMISSIBLE_TOL * qmag, axis=0)
    sigma = np.where(pos, 1.0, -1.0)
    admissible = ok & (pos | neg)

    def seg(c, i, j):
        return c[:, j] - c[:, i]

    W1, X1, Y1 = seg(cw, ja, jb), seg(cwx, ja, jb), seg(cwy, ja, jb)
    W2, X2, Y2 = seg(cw, jb, jc), seg(cwx, jb, jc), seg(cwy, jb, jc)
    W3, X3, Y3 = seg(cw, jc, jd), seg(cwx, jc, jd), seg(cwy, jc, jd)
    # velocity of B on link 1 (rotation w1 about A): k x (B - A)
    vBx, vBy = -(By - Ay) * w1, (Bx - Ax) * w1
    work_x = (-(Y1 - W1 * Ay) * w1
              + W2 * vBx - (Y2 - W2 * By) * w2
              - (Y3 - W3 * Dy) * w3)
    work_y = ((X1 - W1 * Ax) * w1
              + W2 * vBy + (X2 - W2 * Bx) * w2
              + (X3 - W3 * Dx) * w3)
    work_x = sigma * work_x
    work_y = sigma * work_y
    tiny = 1e-14
    lam_l = np.where(admissible & (work_x > tiny), work_y / np.where(work_x > tiny, work_x, 1.0), np.inf)
    lam_r = np.where(admissible & (work_x < -tiny), work_y / np.where(work_x < -tiny, -work_x, 1.0), np.inf)
    return lam_l, lam_r, jq, eq


def _validate_batch(spans, radii, thick):
    spans = np.atleast_2d(np.asarray(spans, float))
    radii = np.atleast_2d(np.asarray(radii, float))
    thick = np.atleast_2d(np.asarray(thick, float))
    if not (spans.shape == radii.shape == thick.shape):
        raise ArchInputError(f"spans, radii, thicknesses: shapes differ {spans.shape}, {radii.shape}, {thick.shape}")
    if spans.shape[1] < 3:
        raise ArchInputError(f"voussoirs: {spans.shape[1]}; allowed >= 3")
    for name, arr in (("spans", spans), ("radii", radii), ("thicknesses", thick)):
        if not np.all(np.isfinite(arr)):
            raise ArchInputError(f"{name}: every value must be finite")
    if np.any(spans <= 0) or np.any(radii <= 0) or np.any(thick <= 0) or np.any(thick >= 2 * radii):
        raise ArchInputError("voussoirs: spans > 0, radii > 0 and 0 < thickness < 2 radius required")
    return spans, radii, thick


def kinematic_multipliers_batch(spans, radii, thicknesses, chunk: int | None = None):
    """Collapse multipliers of a batch of arches with the same number of voussoirs.

    spans [rad], radii [m], thicknesses [m]: arrays (B, n). Returns (k_l, k_r, cand_l, cand_r)
    where cand_* index into the candidate list of :func:`_candidates` (joint quadruple, edges).
    """
    spans, radii, thick = _validate_batch(spans, radii, thicknesses)
    B, n = spans.shape
    K = len(_candidates(n)[0])
    if chunk is None:
        chunk = max(1, int(4_000_000 // K))
    k_l = np.empty(B)
    k_r = np.empty(B)
    i_l = np.empty(B, dtype=np.int64)
    i_r = np.empty(B, dtype=np.int64)
    for s in range(0, B, chunk):
        e = min(B, s + chunk)
        lam_l, lam_r, _, _ = _enumerate(spans[s:e], radii[s:e], thick[s:e])
        i_l[s:e] = np.argmin(lam_l, axis=1)
        i_r[s:e] = np.argmin(lam_r, axis=1)
        k_l[s:e] = lam_l[np.arange(e - s), i_l[s:e]]
        k_r[s:e] = lam_r[np.arange(e - s), i_r[s:e]]
    return k_l, k_r, i_l, i_r


def _mechanism_from_candidate(n: int, idx: int, direction: str, k: float) -> Mechanism:
    jq, eq = _candidates(n)
    hinges = tuple(Hinge(int(j), EDGES[int(e)]) for j, e in zip(jq[idx], eq[idx]))
    return Mechanism(direction, hinges, float(k))


def kinematic_mechanisms(arch: Arch) -> tuple[Mechanism, Mechanism]:
    """The governing mechanisms (M_l, M_r) of one arch by kinematic enumeration."""
    k_l, k_r, i_l, i_r = kinematic_multipliers_batch(arch.spans[None], arch.radii[None],
                                                     arch.thicknesses[None])
    if not (np.isfinite(k_l[0]) and np.isfinite(k_r[0])):
        raise ArchInputError("arch: no admissible four-hinge mechanism found; check the geometry")
    return (_mechanism_from_candidate(arch.n, int(i_l[0]), "l", k_l[0]),
            _mechanism_from_candidate(arch.n, int(i_r[0]), "r", k_r[0]))


# ---------------------------------------------------------------------------- static
def _statics(arch: Arch, direction: str):
    """Rows expressing the normal force N_j and moment M_j about O at each joint as linear
    functions of x = [F0x, F0y, M0, lambda]: N = A_N x + b_N, M = A_M x + b_M (unit total weight,
    lengths in metres)."""
    if direction not in DIRECTIONS:
        raise ArchInputError(f"direction: {direction!r}; allowed 'l' or 'r'")
    d = 1.0 if direction == "l" else -1.0
    w = arch.areas / arch.areas.sum()
    g = arch.centroids
    zero = np.zeros(1)
    cw = np.concatenate([zero, np.cumsum(w)])
    cwx = np.concatenate([zero, np.cumsum(w * g[:, 0])])
    cwy = np.concatenate([zero, np.cumsum(w * g[:, 1])])
    psi = arch.joint_angles
    s, c = np.sin(psi), np.cos(psi)
    nj = psi.size
    # F_j = (F0x + d lam cw, F0y - cw);  N_j = F_j . (sin psi, -cos psi)
    A_N = np.column_stack([s, -c, np.zeros(nj), d * cw * s])
    b_N = c * cw
    # M_j = M0 - cwx - d lam cwy
    A_M = np.column_stack([np.zeros(nj), np.zeros(nj), np.ones(nj), -d * cwy])
    b_M = -cwx
    return A_N, b_N, A_M, b_M, (cw, cwx, cwy, d)


def static_multiplier(arch: Arch, direction: str) -> tuple[float, ThrustLine]:
    """Maximum multiplier by the static linear program, and its line of thrust.

    Constraints: r_in_j N_j <= -M_j <= r_out_j N_j at every joint (the thrust crosses the joint
    inside its contact surface, in compression).
    """
    A_N, b_N, A_M, b_M, _ = _statics(arch, direction)
    r_in, r_out = arch.contact_inner[:, None], arch.contact_outer[:, None]
    # r_in N + M <= 0 and -M - r_out N <= 0
    A_ub = np.vstack([r_in * A_N + A_M, -A_M - r_out * A_N])
    b_ub = np.concatenate([-(arch.contact_inner * b_N + b_M), b_M + arch.contact_outer * b_N])
    res = linprog(c=[0, 0, 0, -1.0], A_ub=A_ub, b_ub=b_ub, bounds=[(None, None)] * 4, method="highs")
    if res.status != 0:
        raise ArchInputError(
            f"arch: no line of thrust fits inside the arch for direction {direction!r} "
            f"(linear program status {res.status}: {res.message}); the arch cannot stand")
    return float(res.x[3]), _thrust_from_x(arch, direction, res.x)


def _thrust_from_x(arch: Arch, direction: str, x: np.ndarray) -> ThrustLine:
    A_N, b_N, A_M, b_M, (cw, _, _, d) = _statics(arch, direction)
    N = A_N @ x + b_N
    M = A_M @ x + b_M
    radii = -M / N
    psi = arch.joint_angles
    pts = np.column_stack([radii * np.cos(psi), radii * np.sin(psi)])
    lam = x[3]
    forces = np.column_stack([x[0] + d * lam * cw, x[1] - cw])
    # funicular polygon: from each joint crossing along F_i to the load line of voussoir i
    poly = [pts[0]]
    g = arch.centroids
    load = np.array([d * lam, -1.0])
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
    return ThrustLine(direction, float(lam), radii, pts, forces, np.array(poly))


def thrust_line(arch: Arch, mechanism: Mechanism) -> ThrustLine:
    """Line of thrust through the four hinges of ``mechanism`` (equilibrium at collapse).

    Solves the four conditions 'the thrust passes through hinge h' for the three redundants and
    lambda; the lambda found this way is a third, independent value of the multiplier.
    """
    A_N, b_N, A_M, b_M, _ = _statics(arch, mechanism.direction)
    rows, rhs = [], []
    for h in mechanism.hinges:
        r = arch.contact_inner[h.joint] if h.edge == "intrados" else arch.contact_outer[h.joint]
        rows.append(A_M[h.joint] + r * A_N[h.joint])
        rhs.append(-(b_M[h.joint] + r * b_N[h.joint]))
    x = np.linalg.solve(np.array(rows), np.array(rhs))
    return _thrust_from_x(arch, mechanism.direction, x)


def limit_analysis(arch: Arch, verify: bool = True) -> LimitResult:
    """k_l, k_r, their mechanisms and thrust lines; ``verify`` adds the static LP cross-check."""
    if not isinstance(arch, Arch):
        raise ArchInputError(f"arch: expected an Arch, got {type(arch).__name__}")
    m_l, m_r = kinematic_mechanisms(arch)
    if m_l.multiplier <= 0 or m_r.multiplier <= 0:
        raise ArchInputError(
            f"arch: it cannot stand under its own weight (k_l = {m_l.multiplier:.4g}, "
            f"k_r = {m_r.multiplier:.4g}); increase the thickness")
    th_l, th_r = thrust_line(arch, m_l), thrust_line(arch, m_r)
    s_l = s_r = disc = None
    if verify:
        s_l, _ = static_multiplier(arch, "l")
        s_r, _ = static_multiplier(arch, "r")
        disc = max(abs(s_l - m_l.multiplier), abs(s_r - m_r.multiplier))
    return LimitResult(arch, m_l.multiplier, m_r.multiplier, m_l, m_r, th_l, th_r, s_l, s_r, disc)


# ---------------------------------------------------------------------------- minimum thickness
@dataclass(frozen=True)
class MinimumThickness:
    """Smallest thickness scale at which the arch stands under its own weight.

    factor: multiplier of every voussoir thickness; ratio: the resulting mean t/R.
    """

    factor: float
    ratio: float
    thicknesses: np.ndarray
    iterations: int


def _stands(arch: Arch) -> bool:
    A_N, b_N, A_M, b_M, _ = _statics(arch, "l")
    r_in, r_out = arch.contact_inner[:, None], arch.contact_outer[:, None]
    A_ub = np.vstack([r_in * A_N + A_M, -A_M - r_out * A_N])[:, :3]
    b_ub = np.concatenate([-(arch.contact_inner * b_N + b_M), b_M + arch.contact_outer * b_N])
    res = linprog(c=[0, 0, 0], A_ub=A_ub, b_ub=b_ub, bounds=[(None, None)] * 3, method="highs")
    return res.status == 0


def minimum_thickness(arch: Arch, tol: float = 1e-7) -> MinimumThickness:
    """Minimum thickness under self-weight alone (multiplier = 0), by bisection on a common
    thickness factor with the static feasibility LP (lambda = 0)."""
    max_factor = float(np.min(2 * arch.radii / arch.thicknesses)) * (1 - 1e-9)
    lo, hi = 1e-6, min(1.0, max_factor)
    while not _stands(arch.with_thickness_factor(hi)):
        if hi >= max_factor:
            raise ArchInputError("arch: it does not stand under its own weight at any thickness")
        hi = min(2 * hi, max_factor)
    it = 0
    while hi - lo > tol * hi:
        mid = 0.5 * (lo + hi)
        if _stands(arch.with_thickness_factor(mid)):
            hi = mid
        else:
            lo = mid
        it += 1
    t = arch.thicknesses * hi
    return MinimumThickness(hi, float(np.mean(t / arch.radii)), t, it)

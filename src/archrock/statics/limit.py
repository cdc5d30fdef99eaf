"""Limit analysis of voussoir arches under horizontal loads (Heyman's hypotheses).

Any :class:`~archrock.geometry.VoussoirArch`: only its joint contact segments, voussoir masses
(with their loads) and mass centres enter.  Loads: the weight W_i at each voussoir's mass centre
plus a horizontal force lambda*W_i there.
Direction 'l' means forces toward +x (mechanism M_l, activated by xg''/g <= -k_l, paper eq. 1);
direction 'r' means forces toward -x (M_r, activated by xg''/g >= k_r).

Two independent methods:

* kinematic: every four-hinge mechanism (4 joints out of n+1, each hinge at the intrados or
  extrados end of its contact surface) whose hinge rotations open the joints admissibly; the
  multiplier follows from virtual work and the collapse multiplier is the minimum.  Work sums use
  prefix sums of W, W*x_G, W*y_G, so each candidate costs O(1) and the enumeration is vectorised
  over candidates and over a batch of arches, in cache-sized blocks.  With the optional numba
  extra a compiled kernel runs the same arithmetic candidate by candidate (identical results;
  set ARCHROCK_NO_NUMBA=1 to use numpy only).
* static: a linear program on the three redundant reactions at the left springing and lambda:
  maximise lambda with the line of thrust inside every joint's contact segment, in compression
  (radial joints of a circular arch without loads keep 0.1.0's form, bit for bit; every other
  arch the general joint-line form, :class:`_JointLineStatics`).

Above ENUMERATION_MAX_VOUSSOIRS voussoirs the enumeration (O(n^4)) gives way to the
static-guided search: the hinges are read where the static optimum's line of thrust touches the
edges, and the mechanism is accepted when its kinematic multiplier equals the static one (the two
limit theorems); otherwise wider neighbourhoods, and last the full enumeration, whose work is
estimated before it starts (LimitExceededError beyond ``max_seconds``).
"""

from __future__ import annotations

import math
import time
from contextlib import contextmanager
from contextvars import ContextVar
from dataclasses import dataclass, field
from functools import lru_cache
from itertools import combinations

import numpy as np
from scipy.optimize import linprog

from .._jit import HAVE_NUMBA, maybe_njit, numba
from .._progress import check_progress
from .._records import readonly_arrays
from ..errors import (ArchInputError, CannotStandError, LimitExceededError, NoMechanismError,
                      NotFourHingeError)
from ..geometry import Arch, VoussoirArch, power_of_two_near, sector_properties

__all__ = [
    "Hinge", "Mechanism", "ThrustLine", "LimitResult", "MinimumThickness",
    "limit_analysis", "kinematic_mechanisms", "kinematic_multipliers_batch",
    "kinematic_multipliers_arches",
    "static_multiplier", "thrust_line", "minimum_thickness", "thickness_bisection",
    "length_scale", "arch_sums", "general_mechanisms", "mechanism_multiplier",
    "certify_four_hinge", "CERTIFY_TOL", "GENERAL_MAX_VOUSSOIRS", "require_four_hinge",
    "certify_candidates", "LIFT_OFF_REASON", "limit_progress",
    "enumeration_estimate", "EDGES", "SEARCH_CHOICES", "ENUMERATION_MAX_VOUSSOIRS",
    "MAX_ENUMERATION_SECONDS",
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


#: Hinge labels from the leading side of a mechanism (docs/method.md, Four-link equation).
HINGE_LABELS = ("A", "B", "C", "D")


@dataclass(frozen=True)
class Mechanism:
    """A collapse mechanism; hinges ordered from the left springing.

    direction: 'l' (loads toward +x, M_l) or 'r' (loads toward -x, M_r).
    multiplier: the horizontal load multiplier lambda that activates it (kinematic theorem).
    hinges: the joints that rotate about one end of their contact segment.
    lift_off: the joints that open at both ends (the parts separate across them, with no
    sliding); empty for the four-hinge rocking chain of Oppenheim's model.  A mechanism with
    lift-off has fewer than four hinges (kind 'lift-off'); the four-link model does not
    describe it (docs/method.md, The Heyman optimum).
    """

    direction: str
    hinges: tuple[Hinge, ...]
    multiplier: float
    lift_off: tuple[int, ...] = ()

    @property
    def kind(self) -> str:
        """'four-hinge' (a rocking chain of three links), 'lift-off', or 'three-hinge' (three
        hinges on one line: a degenerate chain the dual can give, no four-link model either)."""
        if self.lift_off:
            return "lift-off"
        return "four-hinge" if len(self.hinges) == 4 else f"{len(self.hinges)}-hinge".replace(
            "3-", "three-")

    @property
    def is_four_hinge(self) -> bool:
        return not self.lift_off and len(self.hinges) == 4

    @property
    def joints(self) -> tuple[int, ...]:
        return tuple(h.joint for h in self.hinges)

    @property
    def label(self) -> str:
        """Compact hinge label, joints from the left springing with their edge (i = intrados,
        e = extrados, s = separates: lift-off), e.g. '0i-3e-5i-7e' or '0s-4i-7e'."""
        parts = [(h.joint, f"{h.joint}{h.edge[0]}") for h in self.hinges]
        parts += [(j, f"{j}s") for j in self.lift_off]
        return "-".join(p for _, p in sorted(parts))

    def describe(self) -> str:
        """One line for people: the kind, the hinges and the joints that lift off."""
        if not self.lift_off:
            return f"{self.kind} mechanism {self.label}"
        lifts = ", ".join(str(j) for j in self.lift_off)
        return (f"mechanism with lift-off at joint{'s' if len(self.lift_off) > 1 else ''} "
                f"{lifts} ({self.label})")

    def labelled(self) -> list[tuple[str, Hinge]]:
        """(label, hinge) pairs: A..D from the mechanism's leading side (docs/method.md, Four-link equation): for
        M_l, A is the leftmost hinge; for M_r, A is the rightmost."""
        hinges = list(self.hinges)
        if self.direction == "r":
            hinges = hinges[::-1]
        return list(zip(HINGE_LABELS, hinges))

    def mirrored(self, n: int) -> "Mechanism":
        """The same mechanism on the mirror image of an n-voussoir arch."""
        hinges = tuple(Hinge(n - h.joint, h.edge) for h in reversed(self.hinges))
        return Mechanism("r" if self.direction == "l" else "l", hinges, self.multiplier,
                         tuple(sorted(n - j for j in self.lift_off)))

    def to_dict(self) -> dict:
        return {"direction": self.direction, "multiplier": self.multiplier,
                "hinges": [h.to_dict() for h in self.hinges], "kind": self.kind,
                "lift_off": [int(j) for j in self.lift_off], "label": self.label}


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


@dataclass(frozen=True)
class LimitResult:
    """Result of :func:`limit_analysis`: multipliers, mechanisms and thrust lines, both directions.

    k_l, k_r: the Heyman collapse multipliers, the virtual-work values of the governing
    mechanisms (four-hinge where the line of thrust through the best four-hinge mechanism fits
    the arch, else the mechanism with lift-off from the static LP's dual); static_k_l,
    static_k_r: the linear program's optima (None when not solved); ``discrepancy`` the largest
    |kinematic - static| difference; four_hinge_l/_r: the best four-hinge mechanism of each
    direction (the governing one, or the one a four-link model would open; None where none).
    """

    arch: VoussoirArch = field(repr=False)
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
    four_hinge_l: Mechanism | None = None
    four_hinge_r: Mechanism | None = None

    @property
    def four_hinge(self) -> bool:
        """Whether four-hinge mechanisms govern both directions (the four-link model holds)."""
        return self.mechanism_l.is_four_hinge and self.mechanism_r.is_four_hinge

    def not_four_hinge(self, direction: str) -> str | None:
        """Why the four-link model does not hold in ``direction`` (None where it does): the
        governing mechanism and what the best four-hinge one would need."""
        m = self.mechanism(direction)
        if m.is_four_hinge:
            return None
        four = self.four_hinge_l if direction == "l" else self.four_hinge_r
        best = ("no four-hinge mechanism loads this direction" if four is None else
                f"the best four-hinge mechanism {four.label} would need k = "
                f"{four.multiplier:.4f}")
        return f"M_{direction} is governed by a {m.describe()} at k = {m.multiplier:.4f} ({best})"

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
            "four_hinge_l": None if self.four_hinge_l is None else self.four_hinge_l.to_dict(),
            "four_hinge_r": None if self.four_hinge_r is None else self.four_hinge_r.to_dict(),
            "thrust_l": _thrust_dict(self.thrust_l),
            "thrust_r": _thrust_dict(self.thrust_r),
            "arch": self.arch.to_dict(),
        }


def _thrust_dict(th: ThrustLine) -> dict:
    """Crossing points [m] of every arch, and radii [m] where the joints are radial."""
    out = {} if th.radii is None else {"radii": th.radii.tolist()}
    out["points"] = th.points.tolist()
    return out


# ---------------------------------------------------------------------------- kinematic
@lru_cache(maxsize=64)
def _candidates(n: int):
    """All (joint quadruple, edge pattern) candidates for n voussoirs, as index arrays."""
    quads = np.array(list(combinations(range(n + 1), 4)), dtype=np.int64)
    edges = np.array([[(p >> k) & 1 for k in (3, 2, 1, 0)] for p in range(16)], dtype=np.int64)
    jq = np.repeat(quads, 16, axis=0)
    eq = np.tile(edges, (len(quads), 1))
    return jq, eq


@lru_cache(maxsize=64)
def _active_candidates(n: int):
    """Indices (into :func:`_candidates`) of the candidates that can ever be admissible, with
    precomputed gather indices.

    The four relative hinge rotations q = (w1, w2 - w1, w3 - w2, -w3) add up to zero, so they
    cannot all open a hinge at the same edge: the patterns with four intrados or four extrados
    hinges are never admissible and are dropped (2 of the 16 patterns).  The remaining order is
    the original one, so ties resolve to the same candidate as a full scan.
    Returns (idx, point index per hinge (4, K'), segment-pair index per link (3, K')) with point
    index = 2*joint + edge into the flattened (n+1, 2) point arrays and pair index = i*(n+1) + j
    into the flattened (n+1, n+1) table of prefix-sum differences.
    """
    jq, eq = _candidates(n)
    keep = ~(np.all(eq == 0, axis=1) | np.all(eq == 1, axis=1))
    idx = np.flatnonzero(keep)
    j, e = jq[idx], eq[idx]
    pt = (2 * j + e).T.copy()
    m = n + 1
    pair = np.stack([j[:, 0] * m + j[:, 1], j[:, 1] * m + j[:, 2], j[:, 2] * m + j[:, 3]])
    sign = _EDGE_SIGN[e].T.copy()
    for arr in (idx, pt, pair, sign):
        arr.setflags(write=False)
    return idx, pt, pair, sign


def length_scale(radii) -> np.ndarray:
    """Reference length [m] of each arch: the power of two nearest its mean radius, shape
    (..., 1) for radii (..., n).

    Limit analysis works on lengths divided by it, so that its tolerances are relative to the
    arch's size (a multiplier cannot depend on the units).  A power of two makes the division
    exact: the nondimensional numbers are those of the same arch in metres, bit for bit, when
    its size is a power of two away.
    """
    radii = np.asarray(radii, float)
    return power_of_two_near(np.mean(radii, axis=-1, keepdims=True))


def _batch_sums(spans, radii, thick):
    """Prefix sums of weight and first moments (weights normalised to total 1), joint points;
    lengths divided by :func:`length_scale` (nondimensional, so that the enumeration's absolute
    thresholds on work and determinants mean the same at any size)."""
    ref = length_scale(radii)
    p = sector_properties(spans, radii / ref, thick / ref)
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


# An arch whose points lie farther than this many sizes from the origin (surveyed coordinates)
# is analysed about the midpoint of its springings: moments about a distant origin would lose
# digits to cancellation (and the LP's absolute tolerances would mean less).
_FAR_ORIGIN_SIZES = 8.0


def _origin(arch: VoussoirArch) -> np.ndarray:
    """The point [m] about which moments are taken: (0, 0) unless the arch is far from it."""
    jp = np.asarray(arch.joint_points, float)
    if isinstance(arch, Arch) or np.max(np.abs(jp)) <= _FAR_ORIGIN_SIZES * arch.size:
        return np.zeros(2)
    return 0.25 * (jp[0, 0] + jp[0, 1] + jp[-1, 0] + jp[-1, 1])


def _weights_centroids(arch: VoussoirArch):
    """Weights per unit total weight (n,) and their points of application (n, 2) [m]: the
    voussoirs' areas and centroids without loads (density cancels: the same numbers as 0.1.0),
    their masses and mass centres with loads."""
    if arch.loads:
        m = np.asarray(arch.masses, float)
        return m / m.sum(), np.asarray(arch.centroids, float)
    a = np.asarray(arch.areas, float)
    return a / a.sum(), np.asarray(arch.area_centroids, float)


def arch_sums(arch: VoussoirArch):
    """(cw, cwx, cwy, px, py) of any arch as a batch of one, the enumeration's input: prefix
    sums of the weights (with loads, total 1) and of their first moments, (1, n+1); joint points
    (1, n+1, 2 edges); lengths divided by the reference length (a power of two near
    ``arch.size``), about :func:`_origin`.  For a circular arch without loads these are
    :func:`_batch_sums`'s arrays, bit for bit (dividing by a power of two is exact)."""
    ref = arch.reference_length
    origin = _origin(arch)
    w, g = _weights_centroids(arch)
    jp = np.asarray(arch.joint_points, float)
    if origin.any():
        g, jp = g - origin, jp - origin
    g = g / ref
    zero = np.zeros(1)
    cw = np.concatenate([zero, np.cumsum(w)])
    cwx = np.concatenate([zero, np.cumsum(w * g[:, 0])])
    cwy = np.concatenate([zero, np.cumsum(w * g[:, 1])])
    px, py = jp[..., 0] / ref, jp[..., 1] / ref
    return cw[None], cwx[None], cwy[None], px[None], py[None]


def _enumerate_sums(cw, cwx, cwy, px, py, cand=None):
    """Virtual-work multipliers of the candidates ``cand`` (slice of the active list) for a
    batch of arches given their prefix sums and joint points. Returns lam_l, lam_r (B, K')."""
    B, m = cw.shape
    _, pt, pair, sign = _active_candidates(m - 1)
    if cand is not None:
        pt, pair, sign = pt[:, cand], pair[:, cand], sign[:, cand]
    pxf = px.reshape(B, -1)
    pyf = py.reshape(B, -1)
    take = np.take
    points = [(take(pxf, pt[h], axis=1), take(pyf, pt[h], axis=1)) for h in range(4)]
    # prefix-sum differences for every joint pair, flattened (B, m*m)
    dW = (cw[:, None, :] - cw[:, :, None]).reshape(B, -1)
    dX = (cwx[:, None, :] - cwx[:, :, None]).reshape(B, -1)
    dY = (cwy[:, None, :] - cwy[:, :, None]).reshape(B, -1)
    links = [(take(dW, pair[k], axis=1), take(dX, pair[k], axis=1), take(dY, pair[k], axis=1))
             for k in range(3)]
    return _virtual_work(points, links, sign)


def _virtual_work(points, links, sign):
    """Multipliers (lam_l, lam_r) of four-hinge candidates from their hinge points
    [(Ax, Ay), .., (Dx, Dy)], the weight sums of their three links [(W, X, Y) per link] and the
    edge signs (4, K).  The one place the arithmetic lives: the full enumeration and the
    static-guided search call it, so both give bit-identical multipliers for a candidate."""
    (Ax, Ay), (Bx, By), (Cx, Cy), (Dx, Dy) = points
    (W1, X1, Y1), (W2, X2, Y2), (W3, X3, Y3) = links
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
    q0 = sign[0] * 1.0
    q1 = sign[1] * (w2 - 1.0)
    q2 = sign[2] * (w3 - w2)
    q3 = sign[3] * (-w3)
    qmag = np.maximum(np.maximum(np.abs(q0), np.abs(q1)), np.maximum(np.abs(q2), np.abs(q3)))
    thr = _ADMISSIBLE_TOL * qmag
    pos = (q0 > thr) & (q1 > thr) & (q2 > thr) & (q3 > thr)
    nthr = -thr
    neg = (q0 < nthr) & (q1 < nthr) & (q2 < nthr) & (q3 < nthr)
    sigma = np.where(pos, 1.0, -1.0)
    admissible = ok & (pos | neg)
    # velocity of B on link 1 (rotation w1 = 1 about A): k x (B - A)
    vBx, vBy = -(By - Ay), (Bx - Ax)
    work_x = (-(Y1 - W1 * Ay)
              + W2 * vBx - (Y2 - W2 * By) * w2
              - (Y3 - W3 * Dy) * w3)
    work_y = ((X1 - W1 * Ax)
              + W2 * vBy + (X2 - W2 * Bx) * w2
              + (X3 - W3 * Dx) * w3)
    work_x = sigma * work_x
    work_y = sigma * work_y
    tiny = 1e-14
    lam_l = np.where(admissible & (work_x > tiny), work_y / np.where(work_x > tiny, work_x, 1.0), np.inf)
    lam_r = np.where(admissible & (work_x < -tiny), work_y / np.where(work_x < -tiny, -work_x, 1.0), np.inf)
    return lam_l, lam_r


def _enumerate(spans, radii, thick):
    """Kinematic enumeration for a batch of arches (B, n). Returns per-candidate arrays.

    Returns (lam_l, lam_r, jq, eq): lam_* (B, K) the virtual-work multiplier of every candidate
    of :func:`_candidates` (inf where inadmissible or not loading that direction).
    """
    B, n = spans.shape
    jq, eq = _candidates(n)
    cw, cwx, cwy, px, py, _ = _batch_sums(spans, radii, thick)
    idx = _active_candidates(n)[0]
    lam_l = np.full((B, len(jq)), np.inf)
    lam_r = np.full((B, len(jq)), np.inf)
    lam_l[:, idx], lam_r[:, idx] = _enumerate_sums(cw, cwx, cwy, px, py)
    return lam_l, lam_r, jq, eq


# Optional compiled kernel (the "fast" extra).  The same arithmetic as _enumerate_sums, candidate
# by candidate, keeping the first minimum in candidate order (as numpy's argmin does).
_NUMBA_ENABLED = False
_numba_kernel = _numba_kernel_par = None
if HAVE_NUMBA:  # one switch for the whole package: ARCHROCK_NO_NUMBA=1 (see archrock._jit)
    _NUMBA_ENABLED = True

    @maybe_njit(nogil=True)
    def _numba_kernel(cw, cwx, cwy, pxf, pyf, k_l, k_r, i_l, i_r, ja0, ja1, rank0):
        """Nested loops over joint quadruples a < b < c < d and the 14 hinge-edge patterns
        that can be admissible, in the order of _candidates(n) (candidate index = rank of
        the quadruple * 16 + pattern): no candidate list is built, so memory stays O(n).
        Only first joints ja0 <= a < ja1 (rank0: rank of the first such quadruple), starting
        from the best values already in k_*, i_*: calls over consecutive ranges of a give the
        result of one call over all, and a long enumeration can report its progress."""
        for b in range(cw.shape[0]):
            _numba_arch(b, cw, cwx, cwy, pxf, pyf, k_l, k_r, i_l, i_r, ja0, ja1, rank0)

    @maybe_njit(parallel=True)
    def _numba_kernel_par(cw, cwx, cwy, pxf, pyf, k_l, k_r, i_l, i_r, ja0, ja1, rank0):
        """:func:`_numba_kernel` with the arches spread over the numba threads (each arch's
        enumeration is the same sequential loop, so the results are the serial ones, bit for
        bit)."""
        for b in numba.prange(cw.shape[0]):
            _numba_arch(b, cw, cwx, cwy, pxf, pyf, k_l, k_r, i_l, i_r, ja0, ja1, rank0)

    @maybe_njit(nogil=True)
    def _numba_arch(b, cw, cwx, cwy, pxf, pyf, k_l, k_r, i_l, i_r, ja0, ja1, rank0):
        """The enumeration of arch b (see :func:`_numba_kernel`)."""
        m = cw.shape[1]
        tol = 1e-9
        tiny = 1e-14
        best_l = k_l[b]
        best_r = k_r[b]
        arg_l = i_l[b]
        arg_r = i_r[b]
        rank = rank0 - 1
        for ja in range(ja0, ja1):
            for jb in range(ja + 1, m):
                W1 = cw[b, jb] - cw[b, ja]
                X1 = cwx[b, jb] - cwx[b, ja]
                Y1 = cwy[b, jb] - cwy[b, ja]
                for jc in range(jb + 1, m):
                    W2 = cw[b, jc] - cw[b, jb]
                    X2 = cwx[b, jc] - cwx[b, jb]
                    Y2 = cwy[b, jc] - cwy[b, jb]
                    for jd in range(jc + 1, m):
                        rank += 1
                        W3 = cw[b, jd] - cw[b, jc]
                        X3 = cwx[b, jd] - cwx[b, jc]
                        Y3 = cwy[b, jd] - cwy[b, jc]
                        for pat in range(1, 15):
                            ea = (pat >> 3) & 1
                            eb = (pat >> 2) & 1
                            ec = (pat >> 1) & 1
                            ed = pat & 1
                            Ax = pxf[b, 2 * ja + ea]
                            Ay = pyf[b, 2 * ja + ea]
                            Bx = pxf[b, 2 * jb + eb]
                            By = pyf[b, 2 * jb + eb]
                            Cx = pxf[b, 2 * jc + ec]
                            Cy = pyf[b, 2 * jc + ec]
                            Dx = pxf[b, 2 * jd + ed]
                            Dy = pyf[b, 2 * jd + ed]
                            u2x = Cx - Bx
                            u2y = Cy - By
                            u3x = Dx - Cx
                            u3y = Dy - Cy
                            rx = Ax - Bx
                            ry = Ay - By
                            det = u2x * u3y - u2y * u3x
                            scale = (max(abs(u2x) + abs(u2y), 1e-300)
                                     * max(abs(u3x) + abs(u3y), 1e-300))
                            if not abs(det) > 1e-12 * scale:
                                continue
                            w2 = (rx * u3y - ry * u3x) / det
                            w3 = (u2x * ry - u2y * rx) / det
                            q0 = _EDGE_SIGN[ea] * 1.0
                            q1 = _EDGE_SIGN[eb] * (w2 - 1.0)
                            q2 = _EDGE_SIGN[ec] * (w3 - w2)
                            q3 = _EDGE_SIGN[ed] * (-w3)
                            qmag = max(max(abs(q0), abs(q1)), max(abs(q2), abs(q3)))
                            thr = tol * qmag
                            if q0 > thr and q1 > thr and q2 > thr and q3 > thr:
                                sigma = 1.0
                            elif q0 < -thr and q1 < -thr and q2 < -thr and q3 < -thr:
                                sigma = -1.0
                            else:
                                continue
                            vBx = -(By - Ay)
                            vBy = Bx - Ax
                            work_x = (-(Y1 - W1 * Ay)
                                      + W2 * vBx - (Y2 - W2 * By) * w2
                                      - (Y3 - W3 * Dy) * w3)
                            work_y = ((X1 - W1 * Ax)
                                      + W2 * vBy + (X2 - W2 * Bx) * w2
                                      + (X3 - W3 * Dx) * w3)
                            work_x = sigma * work_x
                            work_y = sigma * work_y
                            if work_x > tiny:
                                lam = work_y / work_x
                                if lam < best_l:
                                    best_l = lam
                                    arg_l = rank * 16 + pat
                            elif work_x < -tiny:
                                lam = work_y / (-work_x)
                                if lam < best_r:
                                    best_r = lam
                                    arg_r = rank * 16 + pat
        k_l[b] = best_l
        k_r[b] = best_r
        i_l[b] = arg_l
        i_r[b] = arg_r


def _circular_sums_of(spans, radii, thick):
    """``sums_of`` for :func:`_full_enumeration` from the circular parameters (B, n)."""
    return lambda s, e: _batch_sums(spans[s:e], radii[s:e], thick[s:e])[:5]


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


def _disable_numba() -> None:
    global _NUMBA_ENABLED
    _NUMBA_ENABLED = False


# Elements per block of the numpy enumeration: blocks that stay in cache are several times
# faster than one big block (measured: ~10x at n = 7 against 4e6-element blocks).
_BLOCK_ELEMENTS = 16_384
# The numpy enumeration keeps index arrays of all candidates (14 C(n+1, 4)): 2 GB at n = 60.
_NUMPY_MAX_VOUSSOIRS = 48
# ... about this many bytes per candidate (cached candidate list and gather indices).
_NUMPY_BYTES_PER_CANDIDATE = 170

#: Up to this many voussoirs, ``method="auto"`` enumerates every candidate (0.1.0's results,
#: bit for bit); above it, the static-guided search.  Measured on one core: the numba
#: enumeration takes 3 ms per arch at n = 30, 10 ms at 40, 41 ms at 48 and grows as n^4 (50 s
#: at 300); the guided search takes about 5 ms at n = 40 (two LPs), 20 ms at 100.  Above 40 the
#: search is faster with numba; without numba it is faster from n ~ 20, but one threshold for
#: both keeps the two paths' results identical.
ENUMERATION_MAX_VOUSSOIRS = 40
#: Ways of finding the mechanisms: "auto" (enumeration up to ENUMERATION_MAX_VOUSSOIRS, the
#: guided search above), "enumeration" (every candidate, with a work estimate), "guided".
SEARCH_CHOICES = ("auto", "enumeration", "guided")
#: Default bound [s] on the estimated time of a full enumeration; beyond it LimitExceededError.
MAX_ENUMERATION_SECONDS = 300.0
# Candidates per second of the enumeration on one core (measured 1.0-1.4e8 with numba for
# n >= 20, 1.1-1.5e7 with numpy), rounded down so that estimates err on the long side.
_ENUMERATION_RATE = {"numba": 8e7, "numpy": 1e7}
# Seconds per arch of the guided search: a + b n (measured ~4 ms at n = 40, ~0.1 s at 1000).
_GUIDED_SECONDS = (5e-3, 1e-4)
# Work estimated above this many seconds prints progress lines on stderr.
_PROGRESS_SECONDS = 5.0
# A joint touches the line of thrust when its gap to an edge is below this fraction of its
# contact width: HiGHS's vertex puts the active joints at ~1e-12, while the neighbours of a
# hinge on a 1000-voussoir arch are ~1e-5 away.
_TOUCH_TOL = 1e-7
# The chosen mechanism's multiplier must equal the static one to this, relative (|lambda| >= 1)
# or absolute (|lambda| < 1): the two limit theorems bracket the collapse multiplier.
_CONFIRM_RTOL = 1e-9
# Neighbourhoods tried after the touching joints alone: every joint within k of a contact,
# hinges at both edges.
_WIDEN = (1, 2, 4)
# A neighbourhood with more candidates than this goes to the full enumeration instead.
_GUIDED_MAX_CANDIDATES = 2_000_000


def _check_method(method, max_seconds):
    if method not in SEARCH_CHOICES:
        raise ArchInputError(f"method: {method!r}; allowed "
                             f"{', '.join(map(repr, SEARCH_CHOICES))}")
    if max_seconds is not None:
        try:
            ok = float(max_seconds) > 0 and math.isfinite(float(max_seconds))
        except (TypeError, ValueError):
            ok = False
        if not ok:
            raise ArchInputError(f"max_seconds: {max_seconds!r}; allowed a number > 0 (seconds)")
    return MAX_ENUMERATION_SECONDS if max_seconds is None else float(max_seconds)


def enumeration_estimate(n: int, arches: int = 1) -> dict:
    """Work of the full enumeration of ``arches`` arches of ``n`` voussoirs: candidates,
    estimated seconds on one core with the current backend, and memory for numpy [bytes]."""
    per_arch = 14 * math.comb(n + 1, 4)
    backend = "numba" if _NUMBA_ENABLED else "numpy"
    return {"candidates": per_arch * arches, "seconds": per_arch * arches / _ENUMERATION_RATE[backend],
            "backend": backend, "bytes": per_arch * _NUMPY_BYTES_PER_CANDIDATE if backend == "numpy" else 0}


def _seconds(x: float) -> str:
    return f"{x:.0f}" if x >= 10 else f"{x:.2g}"


# Where the progress lines of long enumerations go: a callable given one line of text, set for
# a block of code by :func:`limit_progress` (the CLI prints them on stderr); the library itself
# never prints.  A context variable, so threads and nested calls each see their own.
_PROGRESS_SINK: ContextVar = ContextVar("archrock_limit_progress", default=None)


@contextmanager
def limit_progress(progress):
    """Within the block, the progress lines of long limit analyses (a full enumeration above
    about 5 s, a batch of guided searches) go to ``progress`` (a callable given one line of text;
    None: silent, the default)."""
    token = _PROGRESS_SINK.set(check_progress(progress))
    try:
        yield
    finally:
        _PROGRESS_SINK.reset(token)


def _say(msg: str) -> None:
    sink = _PROGRESS_SINK.get()
    if sink is not None:
        sink(f"archrock limit analysis: {msg}")


def _full_enumeration(sums_of, B, n, chunk, max_seconds, why="", parallel=False):
    """Every candidate of B arches of n voussoirs, after estimating the work: refused beyond
    ``max_seconds``, with progress lines on stderr when it will take a while.  ``sums_of(s, e)``
    gives the prefix sums and joint points (cw, cwx, cwy, px, py) of arches s..e-1: from the
    circular parameters (:func:`_batch_sums`) or from any arch (:func:`arch_sums`)."""
    est = enumeration_estimate(n, B)
    what = (f"{est['candidates']:.3g} candidate mechanisms ({B} arch{'es' if B > 1 else ''} "
            f"of {n} voussoirs)")
    if est["backend"] == "numpy" and n > _NUMPY_MAX_VOUSSOIRS:
        raise LimitExceededError(
            f"limit analysis: {why}the full enumeration without numba holds every candidate in "
            f"memory: {what}, about {est['bytes'] / 1e9:.1f} GB (allowed n <= {_NUMPY_MAX_VOUSSOIRS}); "
            "install the 'fast' extra (numba), or use method='auto' (the static-guided search)")
    if est["seconds"] > max_seconds:
        raise LimitExceededError(
            f"limit analysis: {why}the full enumeration of {what} would take about "
            f"{_seconds(est['seconds'])} s with {est['backend']} (bound {max_seconds:g} s); pass "
            f"max_seconds={math.ceil(2 * est['seconds'])} to run it anyway, or use method='auto' "
            "(the static-guided search)")
    progress = est["seconds"] > _PROGRESS_SECONDS
    if progress:
        _say(f"{why}full enumeration of {what}, about {_seconds(est['seconds'])} s with {est['backend']}")
    t0 = time.perf_counter()
    if _NUMBA_ENABLED:
        try:
            out = _enumerate_numba(sums_of, B, n, progress, t0, parallel)
        except Exception:  # noqa: BLE001 - a kernel that cannot compile here: use numpy
            _disable_numba()
            return _full_enumeration(sums_of, B, n, chunk, max_seconds, why, parallel)
    else:
        out = _enumerate_numpy(sums_of, B, n, chunk, progress, t0)
    if progress:
        _say(f"full enumeration done in {time.perf_counter() - t0:.1f} s")
    return out


def _enumerate_numba(sums_of, B, n, progress, t0, parallel=False):
    m = n + 1
    k_l = np.full(B, np.inf)
    k_r = np.full(B, np.inf)
    i_l = np.zeros(B, dtype=np.int64)
    i_r = np.zeros(B, dtype=np.int64)
    cw, cwx, cwy, px, py = sums_of(0, B)
    pxf = np.ascontiguousarray(px.reshape(B, -1))
    pyf = np.ascontiguousarray(py.reshape(B, -1))
    if not progress:
        # arches over the numba threads (no Python per arch); one arch alone stays serial
        kernel = _numba_kernel_par if parallel and B > 1 else _numba_kernel
        kernel(cw, cwx, cwy, pxf, pyf, k_l, k_r, i_l, i_r, 0, m, 0)
        return k_l, k_r, i_l, i_r
    # one arch at a time, the first joints in ranges of about a tenth of the work each
    total = math.comb(m, 4)
    for b in range(B):
        sl = slice(b, b + 1)
        ja = 0
        while ja < m - 3:
            done = total - math.comb(m - ja, 4)  # rank of the first quadruple with joint ja
            end = ja + 1
            while end < m - 3 and total - math.comb(m - end, 4) - done < total / 10:
                end += 1
            _numba_kernel(cw[sl], cwx[sl], cwy[sl], pxf[sl], pyf[sl], k_l[sl], k_r[sl],
                          i_l[sl], i_r[sl], ja, end, done)
            ja = end
            frac = (b + (total - math.comb(m - ja, 4)) / total) / B
            _say(f"full enumeration {100 * frac:.0f}% ({time.perf_counter() - t0:.0f} s)")
    return k_l, k_r, i_l, i_r


def _enumerate_numpy(sums_of, B, n, chunk, progress, t0):
    k_l = np.empty(B)
    k_r = np.empty(B)
    i_l = np.empty(B, dtype=np.int64)
    i_r = np.empty(B, dtype=np.int64)
    idx, pt, pair, sign = _active_candidates(n)
    K = len(idx)
    if chunk is None:
        chunk = max(1, _BLOCK_ELEMENTS // K)
    # candidates per sub-block when a single arch already exceeds the block size
    cstep = K if chunk > 1 else max(_BLOCK_ELEMENTS // 2, 1)
    last = t0
    for s in range(0, B, chunk):
        e = min(B, s + chunk)
        cw, cwx, cwy, px, py = sums_of(s, e)
        rows = np.arange(e - s)
        best_l = np.full(e - s, np.inf)
        best_r = np.full(e - s, np.inf)
        arg_l = np.zeros(e - s, dtype=np.int64)
        arg_r = np.zeros(e - s, dtype=np.int64)
        for c0 in range(0, K, cstep):
            c1 = min(K, c0 + cstep)
            lam_l, lam_r = _enumerate_sums(cw, cwx, cwy, px, py,
                                           None if (c0 == 0 and c1 == K) else slice(c0, c1))
            a_l = np.argmin(lam_l, axis=1)
            a_r = np.argmin(lam_r, axis=1)
            v_l = lam_l[rows, a_l]
            v_r = lam_r[rows, a_r]
            better_l = v_l < best_l  # strict: the first minimum in candidate order wins
            better_r = v_r < best_r
            best_l = np.where(better_l, v_l, best_l)
            best_r = np.where(better_r, v_r, best_r)
            arg_l = np.where(better_l, a_l + c0, arg_l)
            arg_r = np.where(better_r, a_r + c0, arg_r)
            if progress and time.perf_counter() - last > 0.1 * _PROGRESS_SECONDS:
                last = time.perf_counter()
                frac = (s + (e - s) * c1 / K) / B
                _say(f"full enumeration {100 * frac:.0f}% ({last - t0:.0f} s)")
        k_l[s:e] = best_l
        k_r[s:e] = best_r
        i_l[s:e] = np.where(np.isfinite(best_l), idx[arg_l], 0)
        i_r[s:e] = np.where(np.isfinite(best_r), idx[arg_r], 0)
    return k_l, k_r, i_l, i_r


def kinematic_multipliers_batch(spans, radii, thicknesses, chunk: int | None = None,
                                method: str = "auto", max_seconds: float | None = None, *,
                                parallel: bool = False, fallback: bool = True):
    """Collapse multipliers of a batch of arches with the same number of voussoirs.

    spans [rad], radii [m], thicknesses [m]: arrays (B, n). Returns (k_l, k_r, cand_l, cand_r)
    where cand_* index into the candidate list of :func:`_candidates` (joint quadruple, edges).
    ``method``: one of :data:`SEARCH_CHOICES`; "auto" enumerates every candidate up to
    :data:`ENUMERATION_MAX_VOUSSOIRS` voussoirs and runs the static-guided search above.
    ``max_seconds``: bound on the estimated time of a full enumeration (default
    :data:`MAX_ENUMERATION_SECONDS`), beyond which it raises LimitExceededError.
    ``chunk``: arches per block of the vectorised (numpy) enumeration (default: sized to stay in
    cache); it does not change the results.  ``parallel``: the compiled enumeration spreads
    the arches over the numba threads (the same numbers, bit for bit).  ``fallback``: where the
    guided search confirms no four-hinge mechanism (a mechanism with lift-off governs), run the
    full enumeration for the best four-hinge one (default) or give inf there (the batch engine,
    which leaves such arches out anyway: a full enumeration of 200 voussoirs takes minutes).
    A multiplier is inf where no mechanism loads that direction, and -inf (both directions)
    where the guided search finds no line of thrust at any horizontal load (cannot stand).
    """
    spans, radii, thick = _validate_batch(spans, radii, thicknesses)
    max_seconds = _check_method(method, max_seconds)
    B, n = spans.shape
    if method == "enumeration" or (method == "auto" and n <= ENUMERATION_MAX_VOUSSOIRS):
        return _full_enumeration(_circular_sums_of(spans, radii, thick), B, n, chunk, max_seconds,
                                 parallel=parallel)
    k_l = np.empty(B)
    k_r = np.empty(B)
    i_l = np.empty(B, dtype=np.int64)
    i_r = np.empty(B, dtype=np.int64)
    estimate = B * (_GUIDED_SECONDS[0] + _GUIDED_SECONDS[1] * n)
    progress = estimate > _PROGRESS_SECONDS
    if progress:
        _say(f"static-guided search on {B} arches of {n} voussoirs, about {_seconds(estimate)} s")
    t0 = last = time.perf_counter()
    for b in range(B):
        k_l[b], k_r[b], i_l[b], i_r[b] = _guided_arch(spans[b], radii[b], thick[b], max_seconds,
                                                      fallback)
        if progress and time.perf_counter() - last > 0.1 * _PROGRESS_SECONDS:
            last = time.perf_counter()
            _say(f"static-guided search {b + 1}/{B} arches ({last - t0:.0f} s)")
    return k_l, k_r, i_l, i_r


def kinematic_multipliers_arches(arches, method: str = "auto", max_seconds: float | None = None,
                                 *, parallel: bool = False, fallback: bool = True):
    """:func:`kinematic_multipliers_batch` for arches of any shape with the same number of
    voussoirs (a sequence of :class:`VoussoirArch`): their :func:`arch_sums` stacked into one
    enumeration (n <= :data:`ENUMERATION_MAX_VOUSSOIRS` with "auto"), or arch by arch the
    static-guided search of :func:`kinematic_mechanisms`.  Each row is that arch's
    ``kinematic_mechanisms`` result, bit for bit.  Returns (k_l, k_r, cand_l, cand_r)."""
    max_seconds = _check_method(method, max_seconds)
    arches = list(arches)
    if not arches or not all(isinstance(a, VoussoirArch) for a in arches):
        raise ArchInputError("arches: expected a non-empty sequence of VoussoirArch objects")
    n = arches[0].n
    if any(a.n != n for a in arches):
        raise ArchInputError("arches: different numbers of voussoirs; allowed one n per batch")
    B = len(arches)
    sums = [arch_sums(a) for a in arches]
    if method == "enumeration" or (method == "auto" and n <= ENUMERATION_MAX_VOUSSOIRS):
        stacked = tuple(np.ascontiguousarray(np.concatenate([sm[k] for sm in sums]))
                        for k in range(5))
        return _full_enumeration(lambda s, e: tuple(a[s:e] for a in stacked), B, n, None,
                                 max_seconds, parallel=parallel)
    k_l = np.empty(B)
    k_r = np.empty(B)
    i_l = np.empty(B, dtype=np.int64)
    i_r = np.empty(B, dtype=np.int64)
    for b, (arch, sm) in enumerate(zip(arches, sums)):
        k_l[b], k_r[b], i_l[b], i_r[b] = _guided(arch, sm, (lambda why, sm=sm: _full_enumeration(
            lambda s, e: sm, 1, n, None, max_seconds, why)) if fallback else None)
    return k_l, k_r, i_l, i_r


# ---------------------------------------------------------------------------- static-guided search
def _candidate_index(n: int, joints, edges) -> np.ndarray:
    """Indices in the order of :func:`_candidates` of candidates given by their joints (K, 4),
    increasing, and edges (K, 4): the inverse of :func:`candidate_hinges`, vectorised."""
    j = np.asarray(joints, dtype=np.int64)
    e = np.asarray(edges, dtype=np.int64)
    m = n + 1
    x = m - 1 - j  # combinations after a quadruple, counted by its complement (combinadic)
    after = (x[:, 0] * (x[:, 0] - 1) * (x[:, 0] - 2) * (x[:, 0] - 3) // 24
             + x[:, 1] * (x[:, 1] - 1) * (x[:, 1] - 2) // 6
             + x[:, 2] * (x[:, 2] - 1) // 2 + x[:, 3])
    rank = math.comb(m, 4) - 1 - after
    return rank * 16 + (e[:, 0] << 3 | e[:, 1] << 2 | e[:, 2] << 1 | e[:, 3])


_PATTERNS = np.array([[(p >> k) & 1 for k in (3, 2, 1, 0)] for p in range(16)], dtype=np.int64)


def _best_in_pool(sums, n: int, allowed: np.ndarray, direction: str):
    """Smallest multiplier, and its candidate index, over every candidate whose four hinges are
    allowed ((n+1, 2) bool over joints and edges); ties go to the first candidate in the
    enumeration's order, as there.  None when no candidate is admissible or there are too many."""
    pool = np.flatnonzero(allowed.any(axis=1))
    if pool.size < 4 or math.comb(pool.size, 4) * 16 > _GUIDED_MAX_CANDIDATES:
        return None
    quads = np.array(list(combinations(pool.tolist(), 4)), dtype=np.int64)
    # the 14 edge patterns that can be admissible, each hinge at an allowed edge
    ok = np.all(allowed[quads[:, None, :], _PATTERNS[None, :, :]], axis=-1)
    ok[:, [0, 15]] = False
    qi, pi = np.nonzero(ok)
    jq, eq = quads[qi], _PATTERNS[pi]
    cw, cwx, cwy, px, py = (a[0] for a in sums)
    points = [(px[jq[:, h], eq[:, h]], py[jq[:, h], eq[:, h]]) for h in range(4)]
    links = [(cw[jq[:, k + 1]] - cw[jq[:, k]], cwx[jq[:, k + 1]] - cwx[jq[:, k]],
              cwy[jq[:, k + 1]] - cwy[jq[:, k]]) for k in range(3)]
    lam_l, lam_r = _virtual_work(points, links, _EDGE_SIGN[eq].T)
    lam = lam_l if direction == "l" else lam_r
    if lam.size == 0 or not np.isfinite(lam.min()):
        return None
    best = np.flatnonzero(lam == lam.min())
    idx = _candidate_index(n, jq[best], eq[best])
    return float(lam[best[0]]), int(idx.min())


def _search(arch: VoussoirArch, sums, direction: str, lam: float, thrust: ThrustLine):
    """The mechanism of the static solution: candidates from the joints where its line of
    thrust touches an edge, then from wider neighbourhoods, until one's kinematic multiplier
    equals the static one.  Returns (multiplier, candidate index) or None."""
    if _radial(arch):
        # 0.1.0's arithmetic, so that the touching joints are decided on the same numbers
        width = arch.contact_outer - arch.contact_inner
        gap = np.column_stack([(thrust.radii - arch.contact_inner) / width,
                               (arch.contact_outer - thrust.radii) / width])  # intrados, extrados
    else:
        gap = np.column_stack([thrust.fractions, 1.0 - thrust.fractions])
    touch = gap <= _TOUCH_TOL
    tol = _CONFIRM_RTOL * max(1.0, abs(lam))
    contacts = np.flatnonzero(touch.any(axis=1))
    pools = [touch]
    for k in _WIDEN:
        near = np.zeros(arch.n + 1, dtype=bool)
        for j in contacts:
            near[max(0, j - k):j + k + 1] = True
        pools.append(np.column_stack([near, near]))
    for allowed in pools:
        found = _best_in_pool(sums, arch.n, allowed, direction)
        # by the kinematic theorem found[0] >= the collapse multiplier >= lam (static theorem),
        # so equality confirms it is the collapse mechanism
        if found is not None and abs(found[0] - lam) <= tol:
            return found
    return None


def _guided_arch(spans, radii, thick, max_seconds, fallback=True):
    """(k_l, k_r, cand_l, cand_r) of one circular arch (its parameters (n,)) by the
    static-guided search, the full enumeration (within ``max_seconds``) where the search cannot
    confirm its mechanism (``fallback=False``: inf there; a mechanism with lift-off governs)."""
    arch = Arch(spans, radii, thick)
    sums_of = _circular_sums_of(spans[None], radii[None], thick[None])
    return _guided(arch, sums_of(0, 1), (lambda why: _full_enumeration(
        sums_of, 1, arch.n, None, max_seconds, why)) if fallback else None)


def _guided(arch: VoussoirArch, sums, full):
    """(k_l, k_r, cand_l, cand_r) of any arch given its sums (a batch of one) by the
    static-guided search; ``full(why)`` runs the full enumeration where it cannot confirm
    (``full=None``: inf there, the four-hinge family does not attain the static optimum)."""
    lp = {}
    for d in DIRECTIONS:
        try:
            # a joint with no force across it (N = M = 0: the springing lifts off) has no
            # crossing radius (NaN): it touches no edge, and no mechanism can be confirmed
            with np.errstate(invalid="ignore", divide="ignore"):
                lp[d] = static_multiplier(arch, d)
        except CannotStandError:
            lp[d] = None
    if lp["l"] is None and lp["r"] is None and not _stands(arch):
        # no line of thrust at any horizontal load: the arch cannot stand, and there is no
        # static multiplier to confirm a mechanism with
        return -np.inf, -np.inf, 0, 0
    out, enumerated = [], None
    for d in DIRECTIONS:
        if lp[d] is None:
            # the LP is feasible (it stands, or the other direction solved) but unbounded: by
            # duality no admissible mechanism loads this direction
            out.append((np.inf, 0))
            continue
        found = _search(arch, sums, d, *lp[d])
        if found is None and full is None:
            # no four-hinge mechanism attains the static optimum: one with lift-off governs
            found = (np.inf, 0)
        if found is None:
            if enumerated is None:
                enumerated = full(
                    f"the static-guided search could not confirm the mechanism ({d}); ")
            e = enumerated
            found = (e[0][0], e[2][0]) if d == "l" else (e[1][0], e[3][0])
        out.append(found)
    return out[0][0], out[1][0], out[0][1], out[1][1]


def candidate_hinges(n: int, idx: int) -> tuple[tuple[int, ...], tuple[int, ...]]:
    """(joints, edges) of candidate ``idx`` in the order of :func:`_candidates` (quadruples
    a < b < c < d in lexicographic order, 16 edge patterns each), without building the list."""
    rank, pattern = divmod(int(idx), 16)
    m = n + 1
    joints = []
    x = 0
    for slot in range(4):
        left = 3 - slot
        while True:
            count = math.comb(m - x - 1, left)  # combinations whose slot-th joint is x
            if rank < count:
                joints.append(x)
                x += 1
                break
            rank -= count
            x += 1
    edges = tuple((pattern >> k) & 1 for k in (3, 2, 1, 0))
    return tuple(joints), edges


def _mechanism_from_candidate(n: int, idx: int, direction: str, k: float) -> Mechanism:
    joints, edges = candidate_hinges(n, idx)
    hinges = tuple(Hinge(j, EDGES[e]) for j, e in zip(joints, edges))
    return Mechanism(direction, hinges, float(k))


def _four_hinge_search(arch: VoussoirArch, method: str, max_seconds: float):
    """(sums, k_l, k_r, cand_l, cand_r): the best four-hinge mechanism per direction (inf where
    none loads it; -inf when the arch cannot stand), by the enumeration or, above
    :data:`ENUMERATION_MAX_VOUSSOIRS` voussoirs with "auto", the static-guided search (which
    never falls back to the full enumeration here: where it cannot confirm a four-hinge
    mechanism, one with lift-off governs and the LP's dual gives it)."""
    n = arch.n
    sums = arch_sums(arch)
    if method == "enumeration" or (method == "auto" and n <= ENUMERATION_MAX_VOUSSOIRS):
        (k_l,), (k_r,), (i_l,), (i_r,) = _full_enumeration(lambda s, e: sums, 1, n, None,
                                                           max_seconds)
    else:
        k_l, k_r, i_l, i_r = _guided(arch, sums, None)
    return sums, k_l, k_r, i_l, i_r


@dataclass(frozen=True)
class _Governing:
    """One direction's answer: the governing mechanism, the best four-hinge mechanism (None
    where none loads that direction), the LP optimum and line of thrust (None where not
    solved) and how the mechanism was found."""

    mechanism: Mechanism
    four_hinge: Mechanism | None
    static: float | None
    thrust: ThrustLine | None
    how: str


def _governing(arch: VoussoirArch, method: str = "auto", max_seconds: float | None = None,
               static: bool = True) -> dict:
    """The Heyman collapse mechanism of each direction ({'l': _Governing, 'r': ...}).

    The best four-hinge mechanism governs when the line of thrust through its hinges fits
    (:func:`certify_four_hinge`); otherwise the static LP's optimum does, with the mechanism
    read from its dual and confirmed by its own virtual work.  ``static``: solve the LP also
    where the four-hinge mechanism is certified (the cross-check)."""
    if not isinstance(arch, VoussoirArch):
        raise ArchInputError(f"arch: expected a VoussoirArch, got {type(arch).__name__}")
    max_seconds = _check_method(method, max_seconds)
    n = arch.n
    sums, k_l, k_r, i_l, i_r = _four_hinge_search(arch, method, max_seconds)
    if k_l == -np.inf:
        raise CannotStandError(
            "arch: no line of thrust fits inside the arch under any horizontal load; it cannot "
            "stand (increase the thickness)")
    if k_l <= 0 or k_r <= 0:
        # a four-hinge mechanism opens under its own weight (kinematic theorem: the Heyman
        # multiplier is at most this one)
        raise CannotStandError(
            f"arch: it cannot stand under its own weight (k_l = {k_l:.4g}, k_r = {k_r:.4g}); "
            f"increase the thickness")
    out = {}
    for d, k, i in (("l", k_l, i_l), ("r", k_r, i_r)):
        four = _mechanism_from_candidate(n, int(i), d, k) if np.isfinite(k) else None
        if four is not None and _certify_arch(arch, four):
            lp = static_multiplier(arch, d) if static else (None, None)
            out[d] = _Governing(four, four, lp[0], lp[1], "four-hinge")
            continue
        lam_s, thrust, mech = _lp_mechanism(arch, d)
        if lam_s == math.inf:
            raise NoMechanismError(
                f"arch: no mechanism opens under horizontal forces toward "
                f"{'+x' if d == 'l' else '-x'} (the arch is too flat or too thick to hinge or "
                f"lift off); sliding or crushing governs, which limit analysis under Heyman's "
                f"hypotheses does not cover")
        how = "lp-dual"
        if mech is None and n <= GENERAL_MAX_VOUSSOIRS:
            mech = general_mechanisms(arch, d)
            how = "general-enumeration"
            if abs(mech.multiplier - lam_s) > _DUAL_CONFIRM * max(1.0, abs(lam_s)):
                mech = None
        if mech is None:
            raise LimitExceededError(
                f"limit analysis: the static optimum ({lam_s:.6g}, direction {d!r}) is attained "
                f"by no mechanism archrock can confirm by virtual work (a degenerate linear "
                f"program); the multiplier is not reported")
        out[d] = _Governing(mech, four, lam_s, thrust, how)
    for d in DIRECTIONS:
        if out[d].mechanism.multiplier <= 0:
            raise CannotStandError(
                f"arch: it cannot stand under its own weight (k_l = "
                f"{out['l'].mechanism.multiplier:.4g}, k_r = {out['r'].mechanism.multiplier:.4g}); "
                f"increase the thickness")
    return out


def kinematic_mechanisms(arch: VoussoirArch, method: str = "auto",
                         max_seconds: float | None = None) -> tuple[Mechanism, Mechanism]:
    """The governing (Heyman) mechanisms (M_l, M_r) of any arch: the best four-hinge mechanism
    (enumeration, or the static-guided search for many voussoirs: ``method``, ``max_seconds``,
    see :func:`kinematic_multipliers_batch`) where the line of thrust through its hinges fits
    the arch, otherwise the mechanism with lift-off that the static LP's dual gives, confirmed
    by its virtual work (``Mechanism.kind``).  Works on :func:`arch_sums` (weights with loads)."""
    g = _governing(arch, method, max_seconds, static=False)
    return g["l"].mechanism, g["r"].mechanism


# ---------------------------------------------------------------------------- static
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
        self.L = L

    def crossings(self, x):
        arch = self.arch
        N = self.A_N @ x + self.b_N
        m = self.A_m @ x + self.b_m
        frac = m / (self.L * N)
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


# ---------------------------------------------------------------------------- general mechanisms
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
        raise CannotStandError(
            f"arch: it cannot stand under its own weight: no line of thrust fits inside it "
            f"(direction {direction!r}, linear program status {res.status}); increase the "
            f"thickness")
    lam_s = float(res.x[3])
    with np.errstate(invalid="ignore", divide="ignore"):
        thrust = _thrust_from_x(st, res.x)
    mu = -np.asarray(res.ineqlin.marginals, float)
    support = np.flatnonzero(mu > _DUAL_TOL * np.max(mu))
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
        pool = np.array(list(combinations(cand.tolist(), 4)), dtype=np.int64)
    elif support.size <= _POOL_MAX_ROWS:
        pool = np.array(list(combinations(support.tolist(), 4)), dtype=np.int64)
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


def thrust_line(arch: VoussoirArch, mechanism: Mechanism, form: str = "auto") -> ThrustLine:
    """Line of thrust through the four hinges of ``mechanism`` (equilibrium at collapse).

    Solves the four conditions 'the thrust passes through hinge h' for the three redundants and
    lambda; the lambda found this way is a third, independent value of the multiplier.
    """
    st = _statics(arch, mechanism.direction, form)
    rows, rhs = zip(*(st.hinge(h.joint, h.edge) for h in mechanism.hinges))
    x = np.linalg.solve(np.array(rows), np.array(rhs))
    return _thrust_from_x(st, x)


def require_four_hinge(result: LimitResult, what: str = "the four-link model") -> None:
    """NotFourHingeError, naming the mechanism, where a direction of ``result`` is governed by
    a mechanism with lift-off: Oppenheim's four-link model (and every study built on it) holds
    only where four-hinge mechanisms govern."""
    for d in DIRECTIONS:
        why = result.not_four_hinge(d)
        if why is not None:
            raise NotFourHingeError(f"arch: {why}; {what} does not hold for this arch: the "
                                    f"contact engine follows it (archrock dem)")


_HOW = {"four-hinge": "four-hinge enumeration (vectorised), certified by its line of thrust",
        "lp-dual": "static LP (HiGHS) optimum; mechanism from its dual, confirmed by virtual work",
        "general-enumeration": "static LP (HiGHS) optimum; mechanism by enumeration of every "
                               "mechanism with lift-off, confirmed by virtual work"}


def limit_analysis(arch: VoussoirArch, verify: bool = True, method: str = "auto",
                   max_seconds: float | None = None) -> LimitResult:
    """k_l, k_r, their mechanisms and thrust lines of any arch: the Heyman collapse multiplier
    (the static LP's optimum) and the mechanism that attains it, four-hinge or with lift-off
    (docs/method.md, The Heyman optimum).  ``verify``: solve the LP also where a four-hinge
    mechanism is certified by its line of thrust, and report kinematic - static.

    ``method``: "auto" (four-hinge enumeration up to :data:`ENUMERATION_MAX_VOUSSOIRS`
    voussoirs, the static-guided search above), "enumeration" or "guided"; ``max_seconds``
    bounds a full enumeration's estimated time (see :func:`kinematic_multipliers_batch`).
    """
    if not isinstance(arch, VoussoirArch):
        raise ArchInputError(f"arch: expected a VoussoirArch (Arch, PolygonArch), got "
                             f"{type(arch).__name__}")
    gov = _governing(arch, method, max_seconds, static=verify)
    m_l, m_r = gov["l"].mechanism, gov["r"].mechanism
    th = {}
    for d, m in (("l", m_l), ("r", m_r)):
        th[d] = thrust_line(arch, m) if m.is_four_hinge else gov[d].thrust
    s_l, s_r = gov["l"].static, gov["r"].static
    disc = None
    if s_l is not None and s_r is not None:
        disc = max(abs(s_l - m_l.multiplier), abs(s_r - m_r.multiplier))
    guided = method == "guided" or (method == "auto" and arch.n > ENUMERATION_MAX_VOUSSOIRS)
    hows = []
    for d in DIRECTIONS:
        h = _HOW[gov[d].how]
        if gov[d].how == "four-hinge" and guided:
            h = "static-guided four-hinge search, certified by its line of thrust"
        hows.append(h)
    how = hows[0] if hows[0] == hows[1] else f"l: {hows[0]}; r: {hows[1]}"
    if disc is not None:
        how += f"; kinematic = static LP (HiGHS) to {disc:.1e}"
    f_l, f_r = gov["l"].four_hinge, gov["r"].four_hinge
    return LimitResult(arch, m_l.multiplier, m_r.multiplier, m_l, m_r, th["l"], th["r"], s_l, s_r,
                       disc, method=how, four_hinge_l=f_l, four_hinge_r=f_r)


# ---------------------------------------------------------------------------- minimum thickness
# Largest thickness factor tried on an arch family (circular arches stop at t = 2 R).
_MAX_THICKNESS_FACTOR = 64.0
# Bound on the minimum-thickness bisection's steps (tol >= 1e-15 needs fewer than 70).
_MAX_BISECTIONS = 100


@dataclass(frozen=True)
class MinimumThickness:
    """Smallest thickness scale at which the arch stands under its own weight.

    factor: multiplier of every voussoir thickness; ratio: the resulting mean t/R (circular
    arches; for other families the mean thickness / size where the family has ``thicknesses``,
    else None); thicknesses [m] (None where the family has none).
    """

    factor: float
    ratio: float | None
    thicknesses: np.ndarray | None
    iterations: int

    def __post_init__(self):
        readonly_arrays(self)


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


def minimum_thickness(arch: VoussoirArch, tol: float = 1e-7) -> MinimumThickness:
    """Minimum thickness under self-weight alone (multiplier = 0), by bisection on a common
    thickness factor with the static feasibility LP (lambda = 0).  Needs an arch that can vary
    its thickness (``with_thickness_factor``: circular arches, families); a surveyed
    :class:`~archrock.geometry.PolygonArch` cannot (ArchInputError)."""
    return thickness_bisection(arch, _stands, tol)


def thickness_bisection(arch: VoussoirArch, stands, tol: float = 1e-7,
                        cannot: str = "arch: it does not stand under its own weight at any "
                                      "thickness") -> MinimumThickness:
    """Smallest common thickness factor f at which ``stands(arch.with_thickness_factor(f))``
    holds, by doubling from 1 then bisection to ``tol`` (relative); ``stands`` must be monotone
    in the thickness.  Raises CannotStandError with the message ``cannot`` when no thickness
    the arch allows stands.  :func:`minimum_thickness` and the friction-limited minimum
    thickness (:mod:`archrock.statics.friction`) share it."""
    if not isinstance(arch, VoussoirArch):
        raise ArchInputError(f"arch: expected a VoussoirArch, got {type(arch).__name__}")
    if isinstance(arch, Arch):
        max_factor = float(np.min(2 * arch.radii / arch.thicknesses)) * (1 - 1e-9)
    elif callable(getattr(arch, "with_thickness_factor", None)):
        max_factor = _MAX_THICKNESS_FACTOR
    else:
        raise ArchInputError(
            f"arch: the thickness cannot be varied for a surveyed polygon arch "
            f"({type(arch).__name__} has no with_thickness_factor); minimum thickness needs a "
            f"circular arch or an arch family")

    def at(f):
        try:
            a = arch.with_thickness_factor(f)
        except ArchInputError:  # thicker than the family allows
            return None
        return stands(a)

    try:
        tol = float(tol)
    except (TypeError, ValueError):
        tol = math.nan
    if not 1e-15 <= tol < 0.5:
        raise ArchInputError(f"tol: {tol!r}; allowed 1e-15 <= tol < 0.5 (relative width of the "
                             f"thickness bracket)")
    lo, hi = 1e-6, min(1.0, max_factor)
    while True:  # at most log2(max_factor) + 1 doublings (max_factor <= 64 or 2R/t)
        ok = at(hi)
        if ok:
            break
        if ok is None or hi >= max_factor:
            raise CannotStandError(cannot)
        hi = min(2 * hi, max_factor)
    it = 0
    while hi - lo > tol * hi:
        if it >= _MAX_BISECTIONS:  # a halving narrows by 2; 1e-15 from 1e-6 takes < 70
            raise LimitExceededError(f"minimum thickness: the bisection did not reach tol = "
                                     f"{tol:g} in {_MAX_BISECTIONS} steps ([{lo:.17g}, {hi:.17g}])")
        mid = 0.5 * (lo + hi)
        if at(mid):
            hi = mid
        else:
            lo = mid
        it += 1
    if isinstance(arch, Arch):
        t = arch.thicknesses * hi
        return MinimumThickness(hi, float(np.mean(t / arch.radii)), t, it)
    thin = arch.with_thickness_factor(hi)
    t = getattr(thin, "thicknesses", None)
    if t is None:
        return MinimumThickness(hi, None, None, it)
    t = np.array(t, float)
    return MinimumThickness(hi, float(np.mean(t)) / thin.size, t, it)

"""Limit analysis of voussoir arches under horizontal loads (Heyman's hypotheses).

Loads: the weight W_i at each voussoir centroid plus a horizontal force lambda*W_i.
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
  maximise lambda with the line of thrust inside every joint's contact surface.

Above ENUMERATION_MAX_VOUSSOIRS voussoirs the enumeration (O(n^4)) gives way to the
static-guided search: the hinges are read where the static optimum's line of thrust touches the
edges, and the mechanism is accepted when its kinematic multiplier equals the static one (the two
limit theorems); otherwise wider neighbourhoods, and last the full enumeration, whose work is
estimated before it starts (LimitExceededError beyond ``max_seconds``).
"""

from __future__ import annotations

import math
import sys
import time
from dataclasses import dataclass, field
from functools import lru_cache
from itertools import combinations

import numpy as np
from scipy.optimize import linprog

from ._jit import HAVE_NUMBA, maybe_njit
from ._records import readonly_arrays
from .errors import ArchInputError, CannotStandError, LimitExceededError, NoMechanismError
from .geometry import Arch, sector_properties

__all__ = [
    "Hinge", "Mechanism", "ThrustLine", "LimitResult", "MinimumThickness",
    "limit_analysis", "kinematic_mechanisms", "kinematic_multipliers_batch",
    "static_multiplier", "thrust_line", "minimum_thickness", "length_scale",
    "enumeration_estimate", "EDGES", "METHODS", "ENUMERATION_MAX_VOUSSOIRS",
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

    @property
    def label(self) -> str:
        """Compact hinge label, joints from the left springing with their edge (i = intrados,
        e = extrados), e.g. '0i-3e-5i-7e'."""
        return "-".join(f"{h.joint}{h.edge[0]}" for h in sorted(self.hinges, key=lambda h: h.joint))

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

    def __post_init__(self):
        readonly_arrays(self)

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
    mean = np.mean(radii, axis=-1, keepdims=True)
    return np.ldexp(1.0, np.round(np.log2(mean)).astype(np.int64))


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
_numba_kernel = None
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
        B = cw.shape[0]
        m = cw.shape[1]
        tol = 1e-9
        tiny = 1e-14
        for b in range(B):
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
METHODS = ("auto", "enumeration", "guided")
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
    if method not in METHODS:
        raise ArchInputError(f"method: {method!r}; allowed {', '.join(map(repr, METHODS))}")
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


def _say(msg: str) -> None:
    print(f"archrock limit analysis: {msg}", file=sys.stderr, flush=True)


def _full_enumeration(spans, radii, thick, chunk, max_seconds, why=""):
    """Every candidate of every arch (validated (B, n) arrays), after estimating the work:
    refused beyond ``max_seconds``, with progress lines on stderr when it will take a while."""
    B, n = spans.shape
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
            out = _enumerate_numba(spans, radii, thick, progress, t0)
        except Exception:  # noqa: BLE001 - a kernel that cannot compile here: use numpy
            _disable_numba()
            return _full_enumeration(spans, radii, thick, chunk, max_seconds, why)
    else:
        out = _enumerate_numpy(spans, radii, thick, chunk, progress, t0)
    if progress:
        _say(f"full enumeration done in {time.perf_counter() - t0:.1f} s")
    return out


def _enumerate_numba(spans, radii, thick, progress, t0):
    B, n = spans.shape
    m = n + 1
    k_l = np.full(B, np.inf)
    k_r = np.full(B, np.inf)
    i_l = np.zeros(B, dtype=np.int64)
    i_r = np.zeros(B, dtype=np.int64)
    cw, cwx, cwy, px, py, _ = _batch_sums(spans, radii, thick)
    pxf = np.ascontiguousarray(px.reshape(B, -1))
    pyf = np.ascontiguousarray(py.reshape(B, -1))
    if not progress:
        _numba_kernel(cw, cwx, cwy, pxf, pyf, k_l, k_r, i_l, i_r, 0, m, 0)
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


def _enumerate_numpy(spans, radii, thick, chunk, progress, t0):
    B, n = spans.shape
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
        cw, cwx, cwy, px, py, _ = _batch_sums(spans[s:e], radii[s:e], thick[s:e])
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
                                method: str = "auto", max_seconds: float | None = None):
    """Collapse multipliers of a batch of arches with the same number of voussoirs.

    spans [rad], radii [m], thicknesses [m]: arrays (B, n). Returns (k_l, k_r, cand_l, cand_r)
    where cand_* index into the candidate list of :func:`_candidates` (joint quadruple, edges).
    ``method``: one of :data:`METHODS`; "auto" enumerates every candidate up to
    :data:`ENUMERATION_MAX_VOUSSOIRS` voussoirs and runs the static-guided search above.
    ``max_seconds``: bound on the estimated time of a full enumeration (default
    :data:`MAX_ENUMERATION_SECONDS`), beyond which it raises LimitExceededError.
    ``chunk``: arches per block of the vectorised (numpy) enumeration (default: sized to stay in
    cache); it does not change the results.
    A multiplier is inf where no mechanism loads that direction, and -inf (both directions)
    where the guided search finds no line of thrust at any horizontal load (cannot stand).
    """
    spans, radii, thick = _validate_batch(spans, radii, thicknesses)
    max_seconds = _check_method(method, max_seconds)
    B, n = spans.shape
    if method == "enumeration" or (method == "auto" and n <= ENUMERATION_MAX_VOUSSOIRS):
        return _full_enumeration(spans, radii, thick, chunk, max_seconds)
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
        k_l[b], k_r[b], i_l[b], i_r[b] = _guided_arch(spans[b], radii[b], thick[b], max_seconds)
        if progress and time.perf_counter() - last > 0.1 * _PROGRESS_SECONDS:
            last = time.perf_counter()
            _say(f"static-guided search {b + 1}/{B} arches ({last - t0:.0f} s)")
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


def _search(arch: Arch, sums, direction: str, lam: float, thrust: ThrustLine):
    """The mechanism of the static solution: candidates from the joints where its line of
    thrust touches an edge, then from wider neighbourhoods, until one's kinematic multiplier
    equals the static one.  Returns (multiplier, candidate index) or None."""
    width = arch.contact_outer - arch.contact_inner
    gap = np.column_stack([(thrust.radii - arch.contact_inner) / width,
                           (arch.contact_outer - thrust.radii) / width])  # intrados, extrados
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


def _guided_arch(spans, radii, thick, max_seconds):
    """(k_l, k_r, cand_l, cand_r) of one arch by the static-guided search, the full enumeration
    (within ``max_seconds``) where the search cannot confirm its mechanism."""
    arch = Arch(spans, radii, thick)
    sums = _batch_sums(spans[None], radii[None], thick[None])[:5]
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
    out, full = [], None
    for d in DIRECTIONS:
        if lp[d] is None:
            # the LP is feasible (it stands, or the other direction solved) but unbounded: by
            # duality no admissible mechanism loads this direction
            out.append((np.inf, 0))
            continue
        found = _search(arch, sums, d, *lp[d])
        if found is None:
            if full is None:
                full = _full_enumeration(
                    spans[None], radii[None], thick[None], None, max_seconds,
                    why=f"the static-guided search could not confirm the mechanism ({d}); ")
            found = (full[0][0], full[2][0]) if d == "l" else (full[1][0], full[3][0])
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


def kinematic_mechanisms(arch: Arch, method: str = "auto",
                         max_seconds: float | None = None) -> tuple[Mechanism, Mechanism]:
    """The governing mechanisms (M_l, M_r) of one arch: by kinematic enumeration, or by the
    static-guided search for many voussoirs (``method``, ``max_seconds``: see
    :func:`kinematic_multipliers_batch`)."""
    k_l, k_r, i_l, i_r = kinematic_multipliers_batch(arch.spans[None], arch.radii[None],
                                                     arch.thicknesses[None], method=method,
                                                     max_seconds=max_seconds)
    if k_l[0] == -np.inf:
        raise CannotStandError(
            "arch: no line of thrust fits inside the arch under any horizontal load; it cannot "
            "stand (increase the thickness)")
    if not (np.isfinite(k_l[0]) and np.isfinite(k_r[0])):
        raise NoMechanismError(
            "arch: no four-hinge mechanism can open under horizontal forces (the arch is too flat "
            "or too thick to hinge); sliding or crushing governs, which limit analysis under "
            "Heyman's hypotheses does not cover")
    return (_mechanism_from_candidate(arch.n, int(i_l[0]), "l", k_l[0]),
            _mechanism_from_candidate(arch.n, int(i_r[0]), "r", k_r[0]))


# ---------------------------------------------------------------------------- static
def _statics(arch: Arch, direction: str):
    """Rows expressing the normal force N_j and moment M_j about O at each joint as linear
    functions of x = [F0x, F0y, M0, lambda]: N = A_N x + b_N, M = A_M x + b_M, nondimensional:
    forces per unit total weight W, moments per W L with L = :func:`length_scale` (the linear
    program's tolerances are absolute, so a size in metres would change its verdict).
    Returns the rows, the contact radii r_in / L, r_out / L of the joints, and
    (cw, cwx, cwy, d, L)."""
    if direction not in DIRECTIONS:
        raise ArchInputError(f"direction: {direction!r}; allowed 'l' or 'r'")
    d = 1.0 if direction == "l" else -1.0
    ref = float(length_scale(arch.radii)[0])
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
    A_N = np.column_stack([s, -c, np.zeros(nj), d * cw * s])
    b_N = c * cw
    # M_j = M0 - cwx - d lam cwy
    A_M = np.column_stack([np.zeros(nj), np.zeros(nj), np.ones(nj), -d * cwy])
    b_M = -cwx
    r_in, r_out = arch.contact_inner / ref, arch.contact_outer / ref
    return A_N, b_N, A_M, b_M, r_in, r_out, (cw, cwx, cwy, d, ref)


def _thrust_constraints(A_N, b_N, A_M, b_M, r_in, r_out):
    """(A_ub, b_ub): r_in N <= -M <= r_out N at every joint (the thrust crosses the joint
    inside its contact surface, in compression), as r_in N + M <= 0 and -M - r_out N <= 0."""
    A_ub = np.vstack([r_in[:, None] * A_N + A_M, -A_M - r_out[:, None] * A_N])
    b_ub = np.concatenate([-(r_in * b_N + b_M), b_M + r_out * b_N])
    return A_ub, b_ub


def static_multiplier(arch: Arch, direction: str) -> tuple[float, ThrustLine]:
    """Maximum multiplier by the static linear program, and its line of thrust.

    Constraints: r_in_j N_j <= -M_j <= r_out_j N_j at every joint (the thrust crosses the joint
    inside its contact surface, in compression).
    """
    A_N, b_N, A_M, b_M, r_in, r_out, _ = _statics(arch, direction)
    A_ub, b_ub = _thrust_constraints(A_N, b_N, A_M, b_M, r_in, r_out)
    res = linprog(c=[0, 0, 0, -1.0], A_ub=A_ub, b_ub=b_ub, bounds=[(None, None)] * 4, method="highs")
    if res.status != 0:
        raise CannotStandError(
            f"arch: no line of thrust fits inside the arch for direction {direction!r} "
            f"(linear program status {res.status}: {res.message}); the arch cannot stand")
    return float(res.x[3]), _thrust_from_x(arch, direction, res.x)


def _thrust_from_x(arch: Arch, direction: str, x: np.ndarray) -> ThrustLine:
    """The line of thrust of the nondimensional redundants x (see :func:`_statics`), in metres."""
    A_N, b_N, A_M, b_M, _, _, (cw, _, _, d, ref) = _statics(arch, direction)
    N = A_N @ x + b_N
    M = A_M @ x + b_M
    radii = -M / N * ref
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
    A_N, b_N, A_M, b_M, r_in, r_out, _ = _statics(arch, mechanism.direction)
    rows, rhs = [], []
    for h in mechanism.hinges:
        r = r_in[h.joint] if h.edge == "intrados" else r_out[h.joint]
        rows.append(A_M[h.joint] + r * A_N[h.joint])
        rhs.append(-(b_M[h.joint] + r * b_N[h.joint]))
    x = np.linalg.solve(np.array(rows), np.array(rhs))
    return _thrust_from_x(arch, mechanism.direction, x)


def limit_analysis(arch: Arch, verify: bool = True, method: str = "auto",
                   max_seconds: float | None = None) -> LimitResult:
    """k_l, k_r, their mechanisms and thrust lines; ``verify`` adds the static LP cross-check.

    ``method``: "auto" (full enumeration up to :data:`ENUMERATION_MAX_VOUSSOIRS` voussoirs, the
    static-guided search above), "enumeration" or "guided"; ``max_seconds`` bounds a full
    enumeration's estimated time (see :func:`kinematic_multipliers_batch`).
    """
    if not isinstance(arch, Arch):
        raise ArchInputError(f"arch: expected an Arch, got {type(arch).__name__}")
    m_l, m_r = kinematic_mechanisms(arch, method, max_seconds)
    if m_l.multiplier <= 0 or m_r.multiplier <= 0:
        raise CannotStandError(
            f"arch: it cannot stand under its own weight (k_l = {m_l.multiplier:.4g}, "
            f"k_r = {m_r.multiplier:.4g}); increase the thickness")
    th_l, th_r = thrust_line(arch, m_l), thrust_line(arch, m_r)
    s_l = s_r = disc = None
    if verify:
        s_l, _ = static_multiplier(arch, "l")
        s_r, _ = static_multiplier(arch, "r")
        disc = max(abs(s_l - m_l.multiplier), abs(s_r - m_r.multiplier))
    guided = method == "guided" or (method == "auto" and arch.n > ENUMERATION_MAX_VOUSSOIRS)
    how = ("static-guided four-hinge search (kinematic = static LP multiplier, HiGHS)" if guided
           else "kinematic enumeration (vectorised)")
    return LimitResult(arch, m_l.multiplier, m_r.multiplier, m_l, m_r, th_l, th_r, s_l, s_r, disc,
                       method=f"{how}, checked by static LP (HiGHS)")


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

    def __post_init__(self):
        readonly_arrays(self)


def _stands(arch: Arch) -> bool:
    """Whether a line of thrust fits inside the arch under self-weight alone.

    Maximises the smallest moment margin s (per W L, nondimensional as in :func:`_statics`) of
    r_in N <= -M - s and -M + s <= r_out N; the arch stands when s >= 0.  Deciding on the sign
    of an optimum rather than on the solver's feasibility verdict makes the bisection of
    :func:`minimum_thickness` independent of the LP's absolute feasibility tolerance (~1e-7),
    which otherwise moved the minimum thickness by ~1e-6 with the arch's size.
    """
    A_N, b_N, A_M, b_M, r_in, r_out, _ = _statics(arch, "l")
    A_ub, b_ub = _thrust_constraints(A_N, b_N, A_M, b_M, r_in, r_out)
    A_ub = np.column_stack([A_ub[:, :3], np.ones(A_ub.shape[0])])
    # s <= 1 keeps the program bounded; any s >= 0 is enough to stand
    res = linprog(c=[0, 0, 0, -1.0], A_ub=A_ub, b_ub=b_ub,
                  bounds=[(None, None)] * 3 + [(None, 1.0)], method="highs")
    return res.status == 0 and res.x[3] >= 0.0


def minimum_thickness(arch: Arch, tol: float = 1e-7) -> MinimumThickness:
    """Minimum thickness under self-weight alone (multiplier = 0), by bisection on a common
    thickness factor with the static feasibility LP (lambda = 0)."""
    max_factor = float(np.min(2 * arch.radii / arch.thicknesses)) * (1 - 1e-9)
    lo, hi = 1e-6, min(1.0, max_factor)
    while not _stands(arch.with_thickness_factor(hi)):
        if hi >= max_factor:
            raise CannotStandError("arch: it does not stand under its own weight at any thickness")
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

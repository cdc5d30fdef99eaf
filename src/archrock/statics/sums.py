"""Virtual-work sums of the four-hinge candidates: the arithmetic both searches share.

An arch enters as prefix sums of its weights (per unit total weight, with loads) and of their
first moments, cw, cwx, cwy (..., n+1), and its joint points px, py (..., n+1, 2 edges: intrados,
extrados); lengths are divided by a reference length, a power of two near the arch's size
(:func:`length_scale`), so that the tolerances are relative and the numbers are those of the
same arch in metres, bit for bit.  Moments are taken about the origin, or about the midpoint of
the springings for an arch far from it (:func:`_origin`).  :func:`_virtual_work` gives the
multipliers (lam_l, lam_r) of a batch of candidates: inf where the hinge rotations do not open
every hinge admissibly, or the horizontal loads do no work in that direction.
"""

from __future__ import annotations

import numpy as np

from ..geometry import Arch, VoussoirArch, power_of_two_near, sector_properties
from .hinges import _ADMISSIBLE_TOL, _active_candidates, _candidates

__all__ = ["length_scale", "arch_sums"]


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


def signed_work(sigma, W1, X1, Y1, W2, X2, Y2, W3, X3, Y3, Ax, Ay, Bx, By, Dx, Dy, w2, w3):
    """(horizontal, vertical) virtual work of a four-hinge candidate (hinges A, B, D; link k's
    weight W_k [N/m] and first moments X_k, Y_k [N]) in the motion w1 = 1, w2, w3 [rad] taken
    with the sign ``sigma`` that opens every hinge.  Plain arithmetic: numpy arrays here, the
    numba kernel's scalars in :mod:`.kinematic` (the same operations, so the same bits)."""
    # velocity of B on link 1 (rotation w1 = 1 about A): k x (B - A)
    vBx, vBy = -(By - Ay), (Bx - Ax)
    work_x = (-(Y1 - W1 * Ay)
              + W2 * vBx - (Y2 - W2 * By) * w2
              - (Y3 - W3 * Dy) * w3)
    work_y = ((X1 - W1 * Ax)
              + W2 * vBy + (X2 - W2 * Bx) * w2
              + (X3 - W3 * Dx) * w3)
    return sigma * work_x, sigma * work_y


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
    work_x, work_y = signed_work(sigma, W1, X1, Y1, W2, X2, Y2, W3, X3, Y3, Ax, Ay, Bx, By,
                                 Dx, Dy, w2, w3)
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

"""Exact convex decomposition of a simple polygon (a voussoir's outline) for the contact engine.

Ear clipping gives a triangulation that covers the polygon exactly (no vertex is moved or
added); Hertel and Mehlhorn's greedy merge then removes every diagonal whose two sides stay
convex without it, which leaves at most four times the minimum number of convex pieces
(Hertel & Mehlhorn 1983).  The pieces only carry the voussoir's contact geometry: its mass,
centroid and inertia are set on the body from the arch's exact values.

:func:`simplify_outline` first drops outline vertices within a stated distance of the
simplified outline (Douglas and Peucker), keeping given corners (the joints' ends) exactly: a
voussoir's curved faces, sampled at 60 points per radian, then take a few chords each and the
voussoir a few convex pieces instead of 20 to 60.  :func:`outline_deviation` measures the
largest distance between the two outlines.
"""

from __future__ import annotations

import numpy as np

from ..errors import ArchInputError

__all__ = ["convex_pieces", "strip_pieces", "signed_area", "simplify_outline",
           "outline_deviation"]


def signed_area(p: np.ndarray) -> float:
    """Twice-signed area / 2 of polygon ``p`` (k, 2): > 0 counter-clockwise [m^2]."""
    x, y = p[:, 0], p[:, 1]
    return 0.5 * float(np.dot(x, np.roll(y, -1)) - np.dot(np.roll(x, -1), y))


def _cross(o, a, b) -> float:
    return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])


def _clean(p: np.ndarray, tol: float) -> np.ndarray:
    """Drop repeated vertices, a closing copy of the first one, and vertices on a straight
    line between their neighbours (they would make zero-area ears)."""
    pts = [q for i, q in enumerate(p) if i == 0 or np.hypot(*(q - p[i - 1])) > tol]
    if len(pts) > 1 and np.hypot(*(pts[0] - pts[-1])) <= tol:
        pts.pop()
    changed = True
    while changed and len(pts) > 3:
        changed = False
        for i in range(len(pts)):
            a, b, c = pts[i - 1], pts[i], pts[(i + 1) % len(pts)]
            scale = max(np.hypot(*(c - a)), tol)
            if abs(_cross(a, b, c)) <= tol * scale:
                pts.pop(i)
                changed = True
                break
    return np.array(pts)


def _triangulate(p: np.ndarray, tol: float) -> list[tuple[int, int, int]]:
    """Ear clipping of a counter-clockwise simple polygon: triangles as vertex indices."""
    idx = list(range(len(p)))
    tris = []
    guard = 0
    while len(idx) > 3:
        guard += 1
        if guard > 10 * len(p) ** 2:
            raise ArchInputError("voussoir outline: not a simple polygon (ear clipping found no "
                                 "ear); allowed a simple polygon")
        m = len(idx)
        for k in range(m):
            i0, i1, i2 = idx[k - 1], idx[k], idx[(k + 1) % m]
            a, b, c = p[i0], p[i1], p[i2]
            if _cross(a, b, c) <= tol * tol:
                continue  # reflex or flat: not an ear
            inside = False
            for j in idx:
                if j in (i0, i1, i2):
                    continue
                q = p[j]
                if (_cross(a, b, q) >= -tol * tol and _cross(b, c, q) >= -tol * tol
                        and _cross(c, a, q) >= -tol * tol):
                    inside = True
                    break
            if not inside:
                tris.append((i0, i1, i2))
                idx.pop(k)
                break
        else:
            raise ArchInputError("voussoir outline: not a simple polygon (ear clipping found no "
                                 "ear); allowed a simple polygon")
    tris.append(tuple(idx))
    return tris


def _convex(poly: list[int], p: np.ndarray, tol: float) -> bool:
    m = len(poly)
    return all(_cross(p[poly[k - 1]], p[poly[k]], p[poly[(k + 1) % m]]) >= -tol * tol
               for k in range(m))


def _checked_outline(outline, tol):
    """(the outline counter-clockwise with repeated and collinear corners merged, the
    tolerance [m]: ``tol`` or 1e-9 times its size); ArchInputError for a bad polygon."""
    p = np.asarray(outline, float)
    if p.ndim != 2 or p.shape[1] != 2 or len(p) < 3 or not np.all(np.isfinite(p)):
        raise ArchInputError("voussoir outline: expected a polygon of >= 3 finite (x, y) points")
    size = float(np.ptp(p, axis=0).max())
    tol = 1e-9 * size if tol is None else tol
    p = _clean(p, tol)
    if len(p) < 3:
        raise ArchInputError("voussoir outline: degenerate polygon (fewer than 3 distinct corners)")
    if signed_area(p) < 0:
        p = p[::-1].copy()
    return p, tol


def convex_pieces(outline, tol: float | None = None) -> list[np.ndarray]:
    """Convex polygons (each (k, 2), counter-clockwise) that tile the simple polygon
    ``outline`` exactly, their vertices the outline's own; ``tol`` [m] (default 1e-9 times the
    outline's size) merges repeated and collinear vertices."""
    p, tol = _checked_outline(outline, tol)
    if _convex(list(range(len(p))), p, tol):
        return [p]
    pieces = [list(t) for t in _triangulate(p, tol)]
    # Hertel-Mehlhorn: merge two pieces across their shared diagonal while the union is convex
    merged = True
    while merged:
        merged = False
        for a in range(len(pieces)):
            for b in range(a + 1, len(pieces)):
                pa, pb = pieces[a], pieces[b]
                shared = None
                for k in range(len(pa)):
                    u, v = pa[k], pa[(k + 1) % len(pa)]
                    for kk in range(len(pb)):
                        if pb[kk] == v and pb[(kk + 1) % len(pb)] == u:
                            shared = (k, kk)
                            break
                    if shared:
                        break
                if not shared:
                    continue
                k, kk = shared
                # walk pa from v round to u, then pb from u (exclusive) round to v (exclusive)
                na, nb = len(pa), len(pb)
                union = [pa[(k + 1 + s) % na] for s in range(na)]
                union += [pb[(kk + 1 + s) % nb] for s in range(1, nb - 1)]
                if _convex(union, p, tol):
                    pieces[a] = union
                    pieces.pop(b)
                    merged = True
                    break
            if merged:
                break
    return [p[pc] for pc in pieces]


def _ray_hit(p: np.ndarray, i: int, d: np.ndarray, tol: float):
    """First crossing of the ray from vertex i of polygon p along d with an edge not at vertex
    i: (edge index j, point), or None."""
    m = len(p)
    b = p[i]
    best = None
    for j in range(m):
        if j == i or (j + 1) % m == i:
            continue
        a, c = p[j], p[(j + 1) % m]
        e = c - a
        den = d[0] * e[1] - d[1] * e[0]
        if abs(den) <= 1e-15 * np.hypot(*e):
            continue
        w = a - b
        t = (w[0] * e[1] - w[1] * e[0]) / den
        u = (w[0] * d[1] - w[1] * d[0]) / den
        if t > tol and -1e-12 <= u <= 1 + 1e-12 and (best is None or t < best[0]):
            best = (t, j, min(max(u, 0.0), 1.0))
    if best is None:
        return None
    t, j, u = best
    return j, u, b + t * d


def _split_at_reflex(p: np.ndarray, tol: float, depth: int = 0) -> list[np.ndarray]:
    m = len(p)
    ang = []
    for i in range(m):
        a, b, c = p[i - 1], p[i], p[(i + 1) % m]
        ang.append(_cross(a, b, c))
    reflex = [i for i in range(m) if ang[i] < -tol * tol]
    if not reflex:
        return [p]
    if depth > 4 * m:
        raise ArchInputError("voussoir outline: cuts at its reflex corners did not end")
    # the most reflex corner first (smallest signed turn), cut along its interior bisector
    i = min(reflex, key=lambda k: ang[k] / (np.hypot(*(p[k] - p[k - 1]))
                                             * np.hypot(*(p[(k + 1) % m] - p[k]))))
    e1 = p[i] - p[i - 1]
    e2 = p[(i + 1) % m] - p[i]
    n1 = np.array([-e1[1], e1[0]]) / np.hypot(*e1)
    n2 = np.array([-e2[1], e2[0]]) / np.hypot(*e2)
    d = n1 + n2
    d = d / np.hypot(*d)
    hit = _ray_hit(p, i, d, tol)
    if hit is None:
        raise ArchInputError("voussoir outline: a cut from a reflex corner found no edge")
    j, u, x = hit
    # the hit as a vertex: an existing one at either end of edge j, else a new one after j
    if u <= 1e-9:
        k, q = j, p
    elif u >= 1 - 1e-9:
        k, q = (j + 1) % m, p
    else:
        q = np.insert(p, j + 1, x, axis=0)
        k = j + 1
        if i > j:
            i += 1
    mq = len(q)
    first = [q[(i + s) % mq] for s in range((k - i) % mq + 1)]
    second = [q[(k + s) % mq] for s in range((i - k) % mq + 1)]
    out = []
    for part in (np.array(first), np.array(second)):
        if len(part) < 3 or signed_area(part) <= 0:
            raise ArchInputError("voussoir outline: a cut from a reflex corner left a "
                                 "degenerate piece")
        out += _split_at_reflex(part, tol, depth + 1)
    return out


def strip_pieces(outline, tol: float | None = None) -> list[np.ndarray]:
    """Convex polygons that tile the simple polygon ``outline`` exactly, cut from each reflex
    corner along its interior bisector to the opposite side (a new vertex there): on a
    voussoir, whose intrados alone is concave, one strip from intrados to extrados per chord of
    the intrados, each joint's face and both its ends in one piece, and a mirrored outline cut
    into mirrored pieces.  Falls back to :func:`convex_pieces` where a cut fails."""
    q, tol = _checked_outline(outline, tol)
    try:
        pieces = [_clean(x, tol) for x in _split_at_reflex(q, tol)]
    except ArchInputError:
        return convex_pieces(outline, tol)
    area = abs(signed_area(q))
    if (any(len(x) < 3 or not _convex(list(range(len(x))), x, tol) for x in pieces)
            or abs(sum(signed_area(x) for x in pieces) - area) > 1e-9 * area):
        return convex_pieces(outline, tol)
    return pieces


def _seg_dist(q: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Distances [m] of the points q (k, 2) to the segment a-b."""
    d = b - a
    den = float(d @ d)
    t = np.zeros(len(q)) if den == 0 else np.clip(((q - a) @ d) / den, 0.0, 1.0)
    return np.hypot(*(q - a - t[:, None] * d).T)


def _dp(p: np.ndarray, i: int, j: int, tol: float, keep: set) -> None:
    """Douglas-Peucker on the open chain p[i..j] (indices into a closed polygon, j > i, taken
    modulo len(p)): adds to ``keep`` the vertices needed to stay within ``tol`` of it."""
    m = len(p)
    stack = [(i, j)]
    while stack:
        a, b = stack.pop()
        if b - a < 2:
            continue
        idx = np.arange(a + 1, b) % m
        dist = _seg_dist(p[idx], p[a % m], p[b % m])
        k = int(np.argmax(dist))
        if dist[k] > tol:
            c = a + 1 + k
            keep.add(c % m)
            stack += [(a, c), (c, b)]


#: a vertex where the outline turns by more than this [deg] is a corner: always kept
SHARP_DEG = 30.0


def simplify_outline(outline, tol: float, corners=None) -> np.ndarray:
    """The closed polygon ``outline`` (k, 2) [m] with the vertices dropped that lie within
    ``tol`` [m] of the simplified polygon (Douglas-Peucker on each chain between two kept
    corners), its remaining vertices the outline's own.

    corners: points (c, 2) [m] to keep exactly (each the outline vertex nearest to it, e.g. the
    ends of the voussoir's joints, where its hinges turn); every vertex where the outline turns
    by more than :data:`SHARP_DEG` is kept too.  Every dropped vertex, and every point of the outline's edges,
    lies within ``tol`` of the result (:func:`outline_deviation`).  tol = 0 returns the outline
    unchanged."""
    p = np.asarray(outline, float)
    if p.ndim != 2 or p.shape[1] != 2 or len(p) < 3 or not np.all(np.isfinite(p)):
        raise ArchInputError("voussoir outline: expected a polygon of >= 3 finite (x, y) points")
    if isinstance(tol, bool) or not isinstance(tol, (int, float)) or not tol >= 0 \
            or not np.isfinite(tol):
        raise ArchInputError(f"outline tolerance: {tol!r} m; allowed a finite number >= 0")
    if tol == 0:
        return p.copy()
    # sharp corners (turning by more than SHARP_DEG) are kept whatever tol says
    d_in = p - np.roll(p, 1, axis=0)
    d_out = np.roll(p, -1, axis=0) - p
    cosang = (d_in * d_out).sum(axis=1) / np.maximum(
        np.hypot(*d_in.T) * np.hypot(*d_out.T), 1e-300)
    anchors = set(np.flatnonzero(cosang < np.cos(np.radians(SHARP_DEG))).tolist())
    if corners is not None and len(corners):
        c = np.asarray(corners, float).reshape(-1, 2)
        anchors |= {int(np.argmin(np.hypot(*(p - q).T))) for q in c}
    if not anchors:
        anchors = {0}
    if len(anchors) == 1:
        anchors.add(int(np.argmax(np.hypot(*(p - p[min(anchors)]).T))))
    order = sorted(anchors)
    keep = set(order)
    m = len(p)
    for a, b in zip(order, order[1:] + [order[0] + m]):
        _dp(p, a, b, tol, keep)
    return p[sorted(keep)].copy()


def outline_deviation(outline, simplified, samples: int = 8) -> float:
    """The largest distance [m] between the boundaries of two closed polygons (the symmetric
    Hausdorff distance, each boundary sampled at its vertices and ``samples`` points per edge)."""
    def boundary(p):
        p = np.asarray(p, float)
        q = np.roll(p, -1, axis=0)
        t = np.linspace(0.0, 1.0, samples, endpoint=False)
        return (p[:, None, :] + t[None, :, None] * (q - p)[:, None, :]).reshape(-1, 2)

    def one_way(pts, poly):
        poly = np.asarray(poly, float)
        return float(np.min([_seg_dist(pts, a, b) for a, b in zip(poly, np.roll(poly, -1, 0))],
                            axis=0).max())

    a, b = boundary(outline), boundary(simplified)
    return max(one_way(a, simplified), one_way(b, outline))


def inset(piece: np.ndarray, r: float) -> np.ndarray | None:
    """The convex counter-clockwise polygon ``piece`` with every edge moved inward by ``r`` [m]
    (its Minkowski sum with a disc of radius r is ``piece`` with corners rounded by r); None
    when the piece is too thin for that."""
    p = np.asarray(piece, float)
    k = len(p)
    d = np.roll(p, -1, axis=0) - p
    length = np.hypot(d[:, 0], d[:, 1])
    if np.any(length <= 0):
        return None
    nrm = np.column_stack([-d[:, 1], d[:, 0]]) / length[:, None]  # inward for CCW
    out = np.empty_like(p)
    for i in range(k):
        # vertex i joins edge i-1 and edge i: intersect their offset lines
        a0, da, na = p[i - 1] + r * nrm[i - 1], d[i - 1], nrm[i - 1]
        b0, db, nb = p[i] + r * nrm[i], d[i], nrm[i]
        den = da[0] * db[1] - da[1] * db[0]
        if abs(den) <= 1e-14 * length[i - 1] * length[i]:
            out[i] = p[i] + r * na
            continue
        s = ((b0[0] - a0[0]) * db[1] - (b0[1] - a0[1]) * db[0]) / den
        out[i] = a0 + s * da
    if signed_area(out) <= 0:
        return None
    # still the same convex polygon, each edge parallel to its original
    d2 = np.roll(out, -1, axis=0) - out
    if np.any((d2 * d).sum(axis=1) <= 0):
        return None
    return out

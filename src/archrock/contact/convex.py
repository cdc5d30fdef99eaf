"""Exact convex decomposition of a simple polygon (a voussoir's outline) for the contact engine.

Ear clipping gives a triangulation that covers the polygon exactly (no vertex is moved or
added); Hertel and Mehlhorn's greedy merge then removes every diagonal whose two sides stay
convex without it, which leaves at most four times the minimum number of convex pieces
(Hertel & Mehlhorn 1983).  The pieces only carry the voussoir's contact geometry: its mass,
centroid and inertia are set on the body from the arch's exact values.
"""

from __future__ import annotations

import numpy as np

from ..errors import ArchInputError

__all__ = ["convex_pieces", "signed_area"]


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


def convex_pieces(outline, tol: float | None = None) -> list[np.ndarray]:
    """Convex polygons (each (k, 2), counter-clockwise) that tile the simple polygon
    ``outline`` exactly, their vertices the outline's own; ``tol`` [m] (default 1e-9 times the
    outline's size) merges repeated and collinear vertices."""
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

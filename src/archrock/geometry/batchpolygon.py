"""The checks and mass properties of :class:`~archrock.geometry.PolygonArch`, compiled, for one
drawn arch's polylines (:func:`_arch_arrays`): whether each voussoir's outline is a simple
polygon with room to spare, and its area [m^2], centroid [m], polar moment [m^4] and joint
contact segments [m], the numbers ``PolygonArch`` gives for the same polylines.  Shared by the
family draws (:mod:`~archrock.geometry.batchdraw`) and the survey draws
(:mod:`~archrock.geometry.surveybatch`).
"""

from __future__ import annotations

import math

import numpy as np

from .._jit import maybe_njit
from .._pairwise import np_sum
from .polygon import FACE_TOLERANCE


# ---------------------------------------------------------------------------- the polygon arch
@maybe_njit
def _orient(ux, uy, vx, vy, wx, wy):
    return (vx - ux) * (wy - uy) - (vy - uy) * (wx - ux)


@maybe_njit
def _simple(poly, margin):
    """``polygon._simple``: no two non-adjacent edges of the closed polygon cross (the same
    strict test), skipping pairs of runs of 8 edges whose boxes lie more than ``margin`` [m]
    apart (they cannot cross)."""
    m = poly.shape[0]
    nb = (m + 7) // 8
    box = np.empty((nb, 4))
    for c in range(nb):
        x0 = y0 = np.inf
        x1 = y1 = -np.inf
        for e in range(8 * c, min(m, 8 * c + 8)):
            for v in (e, (e + 1) % m):
                x0 = min(x0, poly[v, 0])
                x1 = max(x1, poly[v, 0])
                y0 = min(y0, poly[v, 1])
                y1 = max(y1, poly[v, 1])
        box[c, 0], box[c, 1], box[c, 2], box[c, 3] = x0, x1, y0, y1
    for ca in range(nb):
        for cb in range(ca, nb):
            if box[ca, 0] > box[cb, 1] + margin or box[cb, 0] > box[ca, 1] + margin or \
                    box[ca, 2] > box[cb, 3] + margin or box[cb, 2] > box[ca, 3] + margin:
                continue
            for a in range(8 * ca, min(m, 8 * ca + 8)):
                pax, pay = poly[a, 0], poly[a, 1]
                qax, qay = poly[(a + 1) % m, 0], poly[(a + 1) % m, 1]
                for b in range(max(8 * cb, a + 2), min(m, 8 * cb + 8)):
                    if a == 0 and b == m - 1:
                        continue
                    pbx, pby = poly[b, 0], poly[b, 1]
                    qbx, qby = poly[(b + 1) % m, 0], poly[(b + 1) % m, 1]
                    if _orient(pbx, pby, qbx, qby, pax, pay) * \
                            _orient(pbx, pby, qbx, qby, qax, qay) < 0 and \
                            _orient(pax, pay, qax, qay, pbx, pby) * \
                            _orient(pax, pay, qax, qay, qbx, qby) < 0:
                        return False
    return True


@maybe_njit
def _polygon_properties(poly):
    """``base.polygon_properties``: (signed area, area [m^2], cx, cy [m], polar [m^4])."""
    m = poly.shape[0]
    x0, y0 = poly[0, 0], poly[0, 1]
    work = np.empty((4, m))
    cross, tx, ty, tj = work[0], work[1], work[2], work[3]
    for i in range(m):
        j = (i + 1) % m
        x, y = poly[i, 0] - x0, poly[i, 1] - y0
        x1, y1 = poly[j, 0] - x0, poly[j, 1] - y0
        cr = x * y1 - x1 * y
        cross[i] = cr
        tx[i] = (x + x1) * cr
        ty[i] = (y + y1) * cr
        tj[i] = cr * (x * x + x * x1 + x1 * x1 + y * y + y * y1 + y1 * y1)
    a = 0.5 * np_sum(cross)
    if a == 0.0:
        return a, 0.0, x0, y0, 0.0
    cx = np_sum(tx) / (6.0 * a)
    cy = np_sum(ty) / (6.0 * a)
    j0 = np_sum(tj) / 12.0
    area = abs(a)
    polar = abs(j0) - area * (cx * cx + cy * cy)
    return a, area, cx + x0, cy + y0, polar


@maybe_njit
def _arch_arrays(lines, n, big_l, areas, cen, polar, jp):
    """The checks and numbers of ``PolygonArch(intrados, extrados)`` from the 2 n lines of
    :func:`_draw`, written into areas, cen, polar, jp (this arch's rows); returns (certified,
    size [m], sum of areas [m^2])."""
    xlo = ylo = np.inf
    xhi = yhi = -np.inf
    for L in lines:
        for q in range(L.shape[0]):
            x, y = L[q, 0], L[q, 1]
            if not (math.isfinite(x) and math.isfinite(y)):
                return False, 0.0, 0.0
            if q > 0 and x == L[q - 1, 0] and y == L[q - 1, 1]:
                return False, 0.0, 0.0
            xlo, xhi = min(xlo, x), max(xhi, x)
            ylo, yhi = min(ylo, y), max(yhi, y)
    extent = max(xhi - xlo, yhi - ylo)
    if not (2e-9 <= extent <= 5e8):
        return False, 0.0, 0.0
    i0, e0 = lines[0], lines[1]
    il, el = lines[2 * n - 2], lines[2 * n - 1]
    ni, ne = il.shape[0], el.shape[0]
    ax, ay = 0.5 * (i0[0, 0] + e0[0, 0]), 0.5 * (i0[0, 1] + e0[0, 1])
    bx, by = 0.5 * (il[ni - 1, 0] + el[ne - 1, 0]), 0.5 * (il[ni - 1, 1] + el[ne - 1, 1])
    # PolygonArch._check_order, with a margin: voussoirs listed from right to left
    half_ext = 0.5 * extent
    if bx - ax < -0.5e-9 * half_ext:
        return False, 0.0, 0.0
    grev = 0.0
    for j in range(1, n):
        a, b = lines[2 * j], lines[2 * j - 2]
        grev = max(grev, np.hypot(a[a.shape[0] - 1, 0] - b[0, 0], a[a.shape[0] - 1, 1] - b[0, 1]))
    if grev < 2e-3 * half_ext:
        return False, 0.0, 0.0
    size = 0.5 * np.hypot(bx - ax, by - ay)
    if not size > 0:
        return False, 0.0, 0.0
    margin = 1e-9 * big_l
    for i in range(n):
        I, E = lines[2 * i], lines[2 * i + 1]
        mi, me = I.shape[0], E.shape[0]
        poly = np.empty((mi + me, 2))
        poly[:mi] = I
        for q in range(me):
            poly[mi + q] = E[me - 1 - q]
        if not _simple(poly, margin):
            return False, 0.0, 0.0
        sa, area, cx, cy, pol = _polygon_properties(poly)
        if sa <= 0 or area <= 2e-12 * size * size:
            return False, 0.0, 0.0
        areas[i] = area
        cen[i, 0] = cx
        cen[i, 1] = cy
        polar[i] = pol
    # PolygonArch.joint_points (its checks with margins)
    tol = FACE_TOLERANCE * min(1.0, 0.1 * size)
    jp[0, 0, 0], jp[0, 0, 1] = i0[0, 0], i0[0, 1]
    jp[0, 1, 0], jp[0, 1, 1] = e0[0, 0], e0[0, 1]
    jp[n, 0, 0], jp[n, 0, 1] = il[ni - 1, 0], il[ni - 1, 1]
    jp[n, 1, 0], jp[n, 1, 1] = el[ne - 1, 0], el[ne - 1, 1]
    for j in range(1, n):
        I0, E0 = lines[2 * j - 2], lines[2 * j - 1]
        I1, E1 = lines[2 * j], lines[2 * j + 1]
        ax, ay = I0[I0.shape[0] - 1, 0], I0[I0.shape[0] - 1, 1]
        bx, by = E0[E0.shape[0] - 1, 0], E0[E0.shape[0] - 1, 1]
        cx, cy = I1[0, 0], I1[0, 1]
        dx, dy = E1[0, 0], E1[0, 1]
        abx, aby = bx - ax, by - ay
        length = np.hypot(abx, aby)
        if not length > 0:
            return False, 0.0, 0.0
        ux, uy = abx / length, aby / length
        nx, ny = -uy, ux
        off = max(abs((cx - ax) * nx + (cy - ay) * ny), abs((dx - ax) * nx + (dy - ay) * ny))
        if not off <= 0.5 * tol:
            return False, 0.0, 0.0
        sc = (cx - ax) * ux + (cy - ay) * uy
        sd = (dx - ax) * ux + (dy - ay) * uy
        if sd <= sc:
            return False, 0.0, 0.0
        lo = sc if sc > 0.0 else 0.0
        hi = sd if sd < length else length
        if hi - lo <= 2e-9 * length:
            return False, 0.0, 0.0
        jp[j, 0, 0], jp[j, 0, 1] = ax + lo * ux, ay + lo * uy
        jp[j, 1, 0], jp[j, 1, 1] = ax + hi * ux, ay + hi * uy
    return True, size, np_sum(areas)

"""One irregular family arch's intrados and extrados polylines, compiled (numba, or plain
Python without it): the arithmetic of :func:`~archrock.geometry.irregular.perturb_family`
operation for operation -- the centreline's pieces and arc-length inversion, the offset lines,
the joint cuts -- in scalar loops, with ``math.dist`` as CPython computes it (:func:`_dist`).
:func:`_draw` is the kernel :mod:`~archrock.geometry.batchdraw` runs per draw.
"""

from __future__ import annotations

import math

import numpy as np

from .._jit import maybe_njit
from .._pairwise import np_sum
from .batchplan import ARC, ELLIPSE, LENGTH, OFFSET, ORDER, PARABOLA


_GL_X, _GL_W = np.polynomial.legendre.leggauss(8)


@maybe_njit
def _split(x):
    t = x * 134217729.0
    hi = t - (t - x)
    return hi, x - hi


@maybe_njit
def _dl_mul(x, y):
    xh, xl = _split(x)
    yh, yl = _split(y)
    p = xh * yh
    q = xh * yl + xl * yh
    z = p + q
    return z, p - z + q + xl * yl


@maybe_njit
def _dist(px, py, qx, qy):
    """``math.dist((px, py), (qx, qy))`` [m] as CPython 3.11 computes it (vector_norm: exact
    squares, a corrected square root); plain ``hypot`` differs in the last bit now and then."""
    a = abs(px - qx)
    b = abs(py - qy)
    mx = max(a, b)
    if mx == 0.0 or math.isinf(mx):
        return mx
    _, e = math.frexp(mx)
    scale = math.ldexp(1.0, -e)
    csum = 1.0
    f1 = 0.0
    f2 = 0.0
    for k in range(2):
        x = (a if k == 0 else b) * scale
        ph, pl = _dl_mul(x, x)
        s = csum + ph
        lo = ph - (s - csum)
        csum = s
        f1 += pl
        f2 += lo
    h = math.sqrt(csum - 1.0 + (f1 + f2))
    ph, pl = _dl_mul(-h, h)
    s = csum + ph
    lo = ph - (s - csum)
    csum = s
    f1 += pl
    f2 += lo
    x = csum - 1.0 + (f1 + f2)
    h += x / (2.0 * h)
    return h / scale


# ---------------------------------------------------------------------------- the centreline
@maybe_njit
def _p(typ, par, u):
    """Point (x, y) [m] of a centreline piece at parameter u (the families' p(u))."""
    if typ == ARC:
        th = par[3] + par[4] * u
        return par[0] + par[2] * math.cos(th), par[1] + par[2] * math.sin(th)
    if typ == ELLIPSE:
        th = par[2] * u
        return par[0] * math.cos(th), par[1] * math.sin(th)
    x = par[0] + par[1] * u
    if typ == PARABOLA:
        q = x / par[3]
        return x, par[2] * (1 - q * q)
    return x, par[2] - par[3] * math.cosh(x / par[3])


@maybe_njit
def _dp(typ, par, u):
    """Derivative dp/du [m] of a centreline piece (the families' dp(u))."""
    if typ == ARC:
        th = par[3] + par[4] * u
        return par[5] * math.sin(th), par[6] * math.cos(th)
    if typ == ELLIPSE:
        th = par[2] * u
        return par[3] * math.sin(th), par[4] * math.cos(th)
    x = par[0] + par[1] * u
    if typ == PARABOLA:
        return par[1], par[1] * (par[4] * x / par[5])
    return par[1], par[1] * -math.sinh(x / par[3])


@maybe_njit
def _pdp(typ, par, u):
    """(x, y, dx/du, dy/du) [m] of a centreline piece at u: :func:`_p` and :func:`_dp` with
    each cosine and sine taken once (the same numbers)."""
    if typ == ARC:
        th = par[3] + par[4] * u
        c, s = math.cos(th), math.sin(th)
        return par[0] + par[2] * c, par[1] + par[2] * s, par[5] * s, par[6] * c
    if typ == ELLIPSE:
        th = par[2] * u
        c, s = math.cos(th), math.sin(th)
        return par[0] * c, par[1] * s, par[3] * s, par[4] * c
    x, y = _p(typ, par, u)
    d0, d1 = _dp(typ, par, u)
    return x, y, d0, d1


@maybe_njit
def _gl(typ, par, a, b):
    """Arc length [m] from u = a to u = b (8-point Gauss-Legendre, summed as numpy sums)."""
    half = 0.5 * (b - a)
    mid = 0.5 * (b + a)
    v = np.empty(8)
    for k in range(8):
        d0, d1 = _dp(typ, par, mid + half * _GL_X[k])
        v[k] = np.hypot(d0, d1) * _GL_W[k]
    return half * (((v[0] + v[1]) + (v[2] + v[3])) + ((v[4] + v[5]) + (v[6] + v[7])))


@maybe_njit
def _search(a, n, x, right):
    """``np.searchsorted(a[:n], x, side)`` (side 'right' when ``right``)."""
    lo = 0
    hi = n
    while lo < hi:
        m = (lo + hi) // 2
        if a[m] < x or (right and a[m] == x):
            lo = m + 1
        else:
            hi = m
    return lo


@maybe_njit
def _put(p, t, i, pdp):
    """Row i of the points p and unit tangents t from (x, y, dx/du, dy/du) of :func:`_pdp`."""
    x, y, d0, d1 = pdp
    p[i, 0] = x
    p[i, 1] = y
    h = np.hypot(d0, d1)
    t[i, 0] = d0 / h
    t[i, 1] = d1 / h


@maybe_njit
def _eval(s, side, ptype, ppar, plen, pmode, tab_u, tab_s, tab_v, tab_n, bounds):
    """Points and unit tangents (m, 2) at arc lengths s [m] (``Centreline.eval``, the same
    arithmetic): arcs by u = s / length, other pieces by their Hermite tables."""
    m = s.size
    P = ptype.size
    p = np.empty((m, 2))
    t = np.empty((m, 2))
    const = True
    for j in range(P):
        const = const and pmode[j] == 1
    if const:  # arcs: u = s / length point by point, nothing shared between the points
        for i in range(m):
            j = min(max(_search(bounds, P + 1, s[i], side > 0) - 1, 0), P - 1)
            v = min(max(s[i] - bounds[j], 0.0), plen[j])
            _put(p, t, i, _pdp(ptype[j], ppar[j], v / plen[j]))
        return p, t
    k = np.empty(m, dtype=np.int64)
    for i in range(m):
        j = _search(bounds, P + 1, s[i], side > 0) - 1
        k[i] = min(max(j, 0), P - 1)
    idx = np.empty(m, dtype=np.int64)
    uu = np.empty(m)
    ss = np.empty(m)
    u0 = np.empty(m)
    s0 = np.empty(m)
    for j in range(P):
        c = 0
        for i in range(m):
            if k[i] == j:
                idx[c] = i
                c += 1
        if c == 0:
            continue
        length = plen[j]
        par = ppar[j]
        typ = ptype[j]
        for q in range(c):
            v = s[idx[q]] - bounds[j]
            ss[q] = min(max(v, 0.0), length)
        if pmode[j] == 1:
            for q in range(c):
                uu[q] = ss[q] / length
        else:
            G = tab_n[j]
            for q in range(c):
                # centreline._Piece.u_of_s: the cubic Hermite interpolant (centreline._hermite_u),
                # and one Newton step on the exact length where the table is not fine enough
                kk = min(max(_search(tab_s[j], G, ss[q], True) - 1, 0), G - 2)
                u0[q] = tab_u[j, kk]
                s0[q] = tab_s[j, kk]
                h = tab_s[j, kk + 1] - s0[q]
                w = (ss[q] - s0[q]) / max(h, 1e-300)
                du = tab_u[j, kk + 1] - u0[q]
                uu[q] = u0[q] + w * du + (w * (1.0 - w)) * (
                    (1.0 - w) * (h / tab_v[j, kk] - du) - w * (h / tab_v[j, kk + 1] - du))
                if pmode[j] == 2:
                    d0, d1 = _dp(typ, par, uu[q])
                    uu[q] = uu[q] - (s0[q] + _gl(typ, par, u0[q], uu[q]) - ss[q]) / \
                        np.hypot(d0, d1)
                uu[q] = min(max(uu[q], 0.0), 1.0)
        for q in range(c):
            _put(p, t, idx[q], _pdp(typ, par, uu[q]))
    return p, t


@maybe_njit
def _linspace(a, b, num):
    """``np.linspace(a, b, num)``."""
    out = np.empty(num)
    div = num - 1
    step = (b - a) / div
    for i in range(num):
        if step == 0:
            out[i] = (i / div) * (b - a) + a
        else:
            out[i] = i * step + a
    out[num - 1] = b
    return out


@maybe_njit
def _thick(s, scal, k):
    """The draw's thickness [m] at arc length s: the nominal's times k."""
    return (scal[3] + scal[4] * (1.0 - abs(2.0 * s / scal[0] - 1.0))) * k


@maybe_njit
def _arc_between(px, py, qx, qy, cx, cy, ppr):
    """``faces._arc_between``: points after p up to q on the arc about (cx, cy)."""
    a0 = math.atan2(py - cy, px - cx)
    a1 = math.atan2(qy - cy, qx - cx)
    r0 = _dist(px, py, cx, cy)
    r1 = _dist(qx, qy, cx, cy)
    m = max(1, int(math.ceil(abs(a1 - a0) * ppr)))
    out = np.empty((m, 2))
    for i in range(m):
        w = (i + 1) / m
        ang = a0 + (a1 - a0) * w
        rad = r0 + (r1 - r0) * w
        out[i, 0] = cx + rad * math.cos(ang)
        out[i, 1] = cy + rad * math.sin(ang)
    out[m - 1, 0] = qx
    out[m - 1, 1] = qy
    return out


@maybe_njit
def _segments(s0, s1, sign, ptype, ppar, plen, pmode, tab_u, tab_s, tab_v, tab_n, bounds, ppr):
    """Segments of an offset polyline over [s0, s1] as ``_sample_offset`` counts them: the
    turning of 65 unwrapped tangents (np.unwrap, then the sum of |diff|) times ppr."""
    ss = _linspace(s0, s1, 65)
    _, tt = _eval(ss, sign, ptype, ppar, plen, pmode, tab_u, tab_s, tab_v, tab_n, bounds)
    ang = np.empty(65)
    for i in range(65):
        ang[i] = math.atan2(tt[i, 1], tt[i, 0])
    # np.unwrap, then the sum of |diff|
    period = 2 * np.pi
    corr = 0.0
    prev = ang[0]
    diffs = np.empty(64)
    for i in range(64):
        dd = ang[i + 1] - ang[i]
        x = dd - (-np.pi)
        ddmod = x % period + (-np.pi)  # np.mod: fmod, moved to the divisor's sign
        if ddmod == -np.pi and dd > 0:
            ddmod = np.pi
        ph = ddmod - dd
        if abs(dd) < np.pi:
            ph = 0.0
        corr += ph
        cur = ang[i + 1] + corr
        diffs[i] = abs(cur - prev)
        prev = cur
    turn = np_sum(diffs)
    m = max(2, int(math.ceil(turn * ppr)))
    return m


@maybe_njit
def _segments_from_ends(s0, s1, sign, ptype, ppar, plen, pmode, tab_u, tab_s, tab_v, tab_n, bounds,
                        ppr):
    """:func:`_segments` from the tangents at the two ends (the centreline is convex), or -1
    where turning x ppr lies within 1e-6 of an integer (then only the 65 tangents decide)."""
    ends = np.empty(2)
    ends[0], ends[1] = s0, s1
    _, tt = _eval(ends, sign, ptype, ppar, plen, pmode, tab_u, tab_s, tab_v, tab_n, bounds)
    x = abs(math.atan2(tt[1, 1], tt[1, 0]) - math.atan2(tt[0, 1], tt[0, 0])) * ppr
    if not (x < 1e6) or abs(x - round(x)) <= 1e-6:
        return -1
    return max(2, int(math.ceil(x)))


@maybe_njit
def _centre(s0, s1, ptype, ppar, plen, pmode, tab_u, tab_s, tab_v, tab_n, bounds, scal):
    """The centreline samples of ``faces._sample_offset`` over [s0, s1] (not straddling a
    pointed crown): arc lengths s (m + 1,) [m], points and unit tangents (m + 1, 2).  They do
    not depend on the side or the thickness: the intrados and the extrados share them."""
    big_l = scal[0]
    kink = scal[1] != 0.0
    ppr = scal[5]
    mid = big_l / 2
    sign = -1 if (kink and s1 == mid) else 1
    # The polyline's segment count m = ceil(turning x ppr) is an integer: every family's
    # centreline turns one way (convex), so the turning summed over 65 tangents is the turn
    # between the ends to ~1e-13 rad; the 65 tangents are evaluated only where that product
    # lies within 1e-6 of an integer (where the last bits could change m).
    m = _segments_from_ends(s0, s1, sign, ptype, ppar, plen, pmode, tab_u, tab_s, tab_v, tab_n,
                            bounds, ppr)
    if m < 0:
        m = _segments(s0, s1, sign, ptype, ppar, plen, pmode, tab_u, tab_s,
                      tab_v, tab_n, bounds, ppr)
    s = _linspace(s0, s1, m + 1)
    p, t = _eval(s, sign, ptype, ppar, plen, pmode, tab_u, tab_s, tab_v, tab_n, bounds)
    return s, p, t


@maybe_njit
def _sample_plain(s0, s1, side, k, s, p, t, scal):
    """``faces._sample_offset`` over [s0, s1] not straddling a pointed crown, from its
    centreline samples (:func:`_centre`): (crossed, points); crossed is the
    _CrownOffsetCrossed case."""
    big_l = scal[0]
    kink = scal[1] != 0.0
    ppr = scal[5]
    mid = big_l / 2
    m = s.size - 1
    pts = np.empty((m + 1, 2))
    for i in range(m + 1):
        half = _thick(s[i], scal, k) / 2
        pts[i, 0] = p[i, 0] + (side * -t[i, 1]) * half
        pts[i, 1] = p[i, 1] + (side * t[i, 0]) * half
    if not (kink and (s1 == mid or s0 == mid)):
        return False, pts
    # the crown point of this side's offset arcs (faces._pointed_crown)
    t_c = _thick(mid, scal, k)
    pc, rho = scal[6], scal[7]
    r = rho + side * t_c / 2
    cpx, cpy = 0.0, math.sqrt(r * r - pc * pc)
    thr = 1e-12 * big_l
    left = s1 == mid
    cnt = 0
    for i in range(m + 1):
        if left and i < m and pts[i, 0] < -thr:
            cnt += 1
        elif not left and i > 0 and pts[i, 0] > thr:
            cnt += 1
    if cnt == 0:
        return True, pts
    kept = np.empty((cnt, 2))
    c = 0
    for i in range(m + 1):
        if (left and i < m and pts[i, 0] < -thr) or (not left and i > 0 and pts[i, 0] > thr):
            kept[c, 0] = pts[i, 0]
            kept[c, 1] = pts[i, 1]
            c += 1
    if left:
        arc = _arc_between(kept[cnt - 1, 0], kept[cnt - 1, 1], cpx, cpy, -pc, 0.0, ppr)
        out = np.empty((cnt + arc.shape[0], 2))
        out[:cnt] = kept
        out[cnt:] = arc
        return False, out
    arc = _arc_between(kept[0, 0], kept[0, 1], cpx, cpy, pc, 0.0, ppr)
    na = arc.shape[0]
    out = np.empty((1 + (na - 1) + cnt, 2))
    out[0, 0] = cpx
    out[0, 1] = cpy
    for i in range(na - 1):  # arc[::-1][1:]
        out[1 + i] = arc[na - 2 - i]
    out[na:] = kept
    return False, out


@maybe_njit
def _centres(s0, s1, ptype, ppar, plen, pmode, tab_u, tab_s, tab_v, tab_n, bounds, scal):
    """:func:`_centre` of [s0, s1], or of its two halves when it straddles a pointed crown."""
    mid = scal[0] / 2
    if scal[1] != 0.0 and s0 < mid < s1:
        sa, pa, ta = _centre(s0, mid, ptype, ppar, plen, pmode, tab_u, tab_s, tab_v, tab_n, bounds,
                             scal)
        sb, pb, tb = _centre(mid, s1, ptype, ppar, plen, pmode, tab_u, tab_s, tab_v, tab_n, bounds,
                             scal)
        return True, sa, pa, ta, sb, pb, tb
    sa, pa, ta = _centre(s0, s1, ptype, ppar, plen, pmode, tab_u, tab_s, tab_v, tab_n, bounds, scal)
    return False, sa, pa, ta, sa, pa, ta


@maybe_njit
def _sample(s0, s1, side, k, two, sa, pa, ta, sb, pb, tb, scal):
    """``faces._sample_offset`` from the samples of :func:`_centres`: (crossed, points
    (m, 2) [m])."""
    if two:
        mid = scal[0] / 2
        c1, a = _sample_plain(s0, mid, side, k, sa, pa, ta, scal)
        if c1:
            return True, a
        c2, b = _sample_plain(mid, s1, side, k, sb, pb, tb, scal)
        if c2:
            return True, b
        out = np.empty((a.shape[0] + b.shape[0] - 1, 2))
        out[:a.shape[0]] = a
        out[a.shape[0]:] = b[1:]
        return False, out
    return _sample_plain(s0, s1, side, k, sa, pa, ta, scal)


@maybe_njit
def _cut(poly, cx, cy, dx, dy, nx, ny):
    """``faces.cut_polyline``: (segment index or -1, x, y) of the crossing of the polyline with the
    line through (cx, cy) along (dx, dy) nearest (nx, ny)."""
    m = poly.shape[0]
    best = -1
    bd = 0.0
    bx = 0.0
    by = 0.0
    f1 = dx * (poly[0, 1] - cy) - dy * (poly[0, 0] - cx)
    for i in range(m - 1):
        f0 = f1
        f1 = dx * (poly[i + 1, 1] - cy) - dy * (poly[i + 1, 0] - cx)
        if f0 * f1 <= 0 and (f0 != 0 or f1 != 0):
            den = f0 - f1
            w = f0 / den if den != 0 else 0.0
            qx = poly[i, 0] + w * (poly[i + 1, 0] - poly[i, 0])
            qy = poly[i, 1] + w * (poly[i + 1, 1] - poly[i, 1])
            dist = np.hypot(qx - nx, qy - ny)
            if best < 0 or dist < bd:
                best, bd, bx, by = i, dist, qx, qy
    return best, bx, by


@maybe_njit
def _draw(u, sa, st, sr, tilt_rad, ptype, ppar, plen, pmode, tab_u, tab_s, tab_v, tab_n, bounds,
          base_len, scal):
    """One draw (``perturb_family``): (code, voussoir, side, lines) with lines the 2 n
    polylines, intrados of voussoir i at 2 i, extrados at 2 i + 1 (code 0: drawn)."""
    n = base_len.size
    big_l = scal[0]
    kink = scal[1] != 0.0
    vertical = scal[2] != 0.0
    lines = [np.empty((0, 2)) for _ in range(0)]
    lengths = np.empty(n)
    for i in range(n):
        lengths[i] = base_len[i] * (1.0 + sa * u[0, i])
    total = np_sum(lengths)
    bad = False
    for i in range(n):
        lengths[i] = lengths[i] * (big_l / total)
        if lengths[i] <= 0:
            bad = True
    if bad:
        return LENGTH, 0, 0, lines
    s_div = np.empty(n + 1)
    s_div[0] = 0.0
    acc = 0.0
    for i in range(n):
        acc += lengths[i]
        s_div[i + 1] = acc
    s_div[n] = big_l
    c, tang = _eval(s_div, 1, ptype, ppar, plen, pmode, tab_u, tab_s, tab_v, tab_n, bounds)
    d = np.empty((n + 1, 2))
    for j in range(n + 1):
        d0, d1 = -tang[j, 1], tang[j, 0]
        if 0 < j < n and (vertical or (kink and abs(s_div[j] - big_l / 2) <= 1e-12 * big_l)):
            d0, d1 = 0.0, 1.0
        tl = 0.0
        if tilt_rad != 0.0 and u.shape[0] == 4 and 0 < j < n:
            tl = tilt_rad * u[3, j - 1]
        cs, sn = math.cos(tl), math.sin(tl)
        d[j, 0] = cs * d0 - sn * d1
        d[j, 1] = sn * d0 + cs * d1
    tol = 1e-9 * big_l
    c_lo, c_hi = -1.0, -1.0
    two = False
    sa_ = sb_ = np.empty(0)
    pa_ = ta_ = pb_ = tb_ = np.empty((0, 2))
    for i in range(n):
        fac = 1.0 + st * u[1, i]
        off = sr * u[2, i]
        for side in (-1, 1):
            k = fac + 2.0 * side * off
            if k <= 0:
                return OFFSET, i, side, lines
            found = False
            pts = np.empty((0, 2))
            kl, kr = 0, 0
            qlx, qly, qrx, qry = 0.0, 0.0, 0.0, 0.0
            for widen in (False, True):
                if i == 0 or widen:
                    lo = 0.0
                else:
                    lo = max(0.0, s_div[i] - 0.5 * min(lengths[i - 1], lengths[i]))
                if i == n - 1 or widen:
                    hi = big_l
                else:
                    hi = min(big_l, s_div[i + 1] + 0.5 * min(lengths[i], lengths[i + 1]))
                if not (lo == c_lo and hi == c_hi):  # the other side's samples, if the same
                    two, sa_, pa_, ta_, sb_, pb_, tb_ = _centres(lo, hi, ptype, ppar, plen, pmode,
                                                                 tab_u, tab_s, tab_v, tab_n,
                                                                 bounds, scal)
                    c_lo, c_hi = lo, hi
                crossed, pts = _sample(lo, hi, side, k, two, sa_, pa_, ta_, sb_, pb_, tb_, scal)
                if crossed:
                    continue
                m = pts.shape[0]
                if i == 0:
                    kl, qlx, qly = 0, pts[0, 0], pts[0, 1]
                else:
                    kl, qlx, qly = _cut(pts, c[i, 0], c[i, 1], d[i, 0], d[i, 1],
                                        c[i, 0] + side * d[i, 0], c[i, 1] + side * d[i, 1])
                if i == n - 1:
                    kr, qrx, qry = m - 2, pts[m - 1, 0], pts[m - 1, 1]
                else:
                    kr, qrx, qry = _cut(pts, c[i + 1, 0], c[i + 1, 1], d[i + 1, 0], d[i + 1, 1],
                                        c[i + 1, 0] + side * d[i + 1, 0],
                                        c[i + 1, 1] + side * d[i + 1, 1])
                if kl >= 0 and kr >= 0 and kl <= kr:
                    found = True
                    break
            if not found:
                return ORDER, i, side, lines
            keep = np.zeros(pts.shape[0], dtype=np.bool_)
            cnt = 0
            for q in range(kl + 1, kr + 1):
                if np.hypot(pts[q, 0] - qlx, pts[q, 1] - qly) > tol and \
                        np.hypot(pts[q, 0] - qrx, pts[q, 1] - qry) > tol:
                    keep[q] = True
                    cnt += 1
            line = np.empty((cnt + 2, 2))
            line[0, 0], line[0, 1] = qlx, qly
            c2 = 1
            for q in range(kl + 1, kr + 1):
                if keep[q]:
                    line[c2, 0], line[c2, 1] = pts[q, 0], pts[q, 1]
                    c2 += 1
            line[c2, 0], line[c2, 1] = qrx, qry
            lines.append(line)
    return 0, 0, 0, lines

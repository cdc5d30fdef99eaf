"""Irregular family arches drawn for a whole batch, compiled: no Python per arch.

:func:`~archrock.geometry.irregular.perturb_family` draws one irregular arch of a family in numpy
(arc-length inversion, offset lines, joint cuts) and :class:`~archrock.geometry.PolygonArch`
checks it and computes its mass properties: 6-20 ms per arch.  This module does the same
arithmetic, operation for operation, in scalar loops that numba compiles (or that run as Python
without it), for one arch or a batch of them over the numba threads:

* :class:`FamilyPlan`: what a nominal family arch's draws share (its centreline's pieces, their
  arc-length tables, the nominal division points), built once in Python;
* :func:`draw_lines`: one draw's intrados and extrados polylines, the numbers of
  ``perturb_family`` (its sums in numpy's pairwise order, ``math.dist`` as CPython computes it);
* :func:`batch_properties`: for a batch of draws, without building polylines in Python: whether
  each is a valid polygon arch (the checks of ``PolygonArch``), and its voussoirs' areas [m^2],
  centroids [m], polar moments [m^4], joint contact segments [m] and size [m], the numbers of
  ``PolygonArch`` built from the same polylines.

A draw is reported in one of three states (``state``): 0 a valid arch whose arrays are given, 1
the draw itself is refused (``perturb_family`` would raise: the reason is in ``code``, ``index``,
``side``), 2 not certified (a check of ``PolygonArch`` fails or lies near its threshold): the
caller builds the ``PolygonArch`` from :func:`draw_lines` and lets it decide.

Nominals supported: a :class:`~archrock.geometry.FamilyArch` without loads and without fill
(:func:`supported`); other nominals go through ``perturb_family`` arch by arch.
"""

from __future__ import annotations

import math

import numpy as np

from .._jit import HAVE_NUMBA, maybe_njit, numba
from .._pairwise import np_sum
from ..errors import ArchInputError
from .centreline import _catenary_parameter, circular_radius, three_centred_radii
from .faces import _vertical_joints_that_cut
from .polygon import FACE_TOLERANCE

__all__ = ["FamilyPlan", "supported", "family_plan", "compiled_drawing", "draw_lines", "batch_properties", "refusal_message",
           "OK", "REFUSED", "UNCERTIFIED"]

OK, REFUSED, UNCERTIFIED = 0, 1, 2
ARC, ELLIPSE, PARABOLA, CATENARY = 0, 1, 2, 3
_GL_X, _GL_W = np.polynomial.legendre.leggauss(8)
# refusals of perturb_family (code): 1 a length <= 0, 2 an offset beyond half the thickness,
# 3 joints that do not cut a line in order
LENGTH, OFFSET, ORDER = 1, 2, 3


def refusal_message(code: int, index: int, side: int) -> str:
    """The ArchInputError message of ``perturb_family`` for a refused draw."""
    if code == LENGTH:
        return "geometry: a voussoir length is <= 0"
    if code == OFFSET:
        return f"geometry: voussoir {index}'s offset exceeds half its thickness"
    return (f"geometry: voussoir {index}'s joints do not cut its "
            f"{'intrados' if side < 0 else 'extrados'} in order")


def supported(nominal) -> bool:
    """Whether ``nominal`` is drawn by this module: a family arch (with a recipe) without
    loads or fill."""
    r = getattr(nominal, "recipe", None)
    return r is not None and r["fill"] is None and not r["loads"] and not nominal.loads


# ---------------------------------------------------------------------------- the plan
class FamilyPlan:
    """The per-nominal data of the compiled drawing (module docstring): built from the family's
    recipe with the expressions of :func:`~archrock.geometry.centreline.centreline`, its tables
    taken from the nominal's own centreline."""

    def __init__(self, nominal):
        if not supported(nominal):
            raise ArchInputError("nominal: the batch drawing takes family arches without loads "
                                 "or fill")
        r = nominal.recipe
        line, _ = nominal._frame
        shape, span, rise = r["shape"], r["span"], r["rise"]
        self.nominal = nominal
        a, f = span / 2, rise
        pieces = []  # (type, parameters)
        if shape == "circular":
            rr, yc = circular_radius(span, rise)
            th0 = math.atan2(-yc, -a)
            if th0 < 0:
                th0 += 2 * math.pi
            pieces.append(_arc_par(0.0, yc, rr, th0, math.pi - th0))
        elif shape == "pointed":
            c = (a * a - f * f) / span
            rho = a - c
            phi = math.atan2(f, -c)
            pieces += [_arc_par(-c, 0.0, rho, math.pi, math.pi - phi),
                       _arc_par(c, 0.0, rho, phi, 0.0)]
        elif shape == "elliptical":
            pieces.append((ELLIPSE, [-a, f, math.pi, math.pi * a, math.pi * f]))
        elif shape == "three-centred":
            r1, r2 = three_centred_radii(span, rise)
            c1 = a - r1
            yc2 = f - r2
            gamma = math.atan2(-yc2, -c1)
            pieces += [_arc_par(-c1, 0.0, r1, math.pi, gamma),
                       _arc_par(0.0, yc2, r2, gamma, math.pi - gamma),
                       _arc_par(c1, 0.0, r1, math.pi - gamma, 0.0)]
        elif shape == "parabolic":
            pieces.append((PARABOLA, [-a, 2 * a, f, a, -2 * f, a ** 2]))
        elif shape == "catenary":
            big_a = _catenary_parameter(a, f)
            pieces.append((CATENARY, [-a, 2 * a, f + big_a, big_a]))
        else:  # pragma: no cover - family_arch checks the shape
            raise ArchInputError(f"shape: {shape!r}")
        if len(pieces) != len(line.pieces):  # pragma: no cover - the two constructions agree
            raise ArchInputError("nominal: centreline pieces differ from the family's")
        P = len(pieces)
        grid = max(len(p._u) for p in line.pieces)
        self.ptype = np.array([t for t, _ in pieces], dtype=np.int64)
        self.ppar = np.zeros((P, 8))
        for j, (_, par) in enumerate(pieces):
            self.ppar[j, :len(par)] = par
        self.plen = np.array([p.length for p in line.pieces])
        # 1: an arc (u = s / length), 0: the Hermite table, 2: the table and a Newton step
        self.pmode = np.array([1 if p.constant_speed else (2 if p.newton else 0)
                               for p in line.pieces], dtype=np.int64)
        self.tab_u = np.zeros((P, grid))
        self.tab_s = np.zeros((P, grid))
        self.tab_n = np.array([len(p._u) for p in line.pieces], dtype=np.int64)
        self.tab_v = np.ones((P, grid))
        for j, p in enumerate(line.pieces):
            self.tab_u[j, :len(p._u)] = p._u
            self.tab_s[j, :len(p._s)] = p._s
            self.tab_v[j, :len(p._v)] = p._v
        self.bounds = np.asarray(line.bounds, float).copy()
        big_l = line.length
        base = big_l * np.arange(r["voussoirs"] + 1) / r["voussoirs"]
        if r["joints"] == "vertical":
            _, thick = nominal._frame
            base = _vertical_joints_that_cut(line, thick, base)
        self.base_len = np.ascontiguousarray(np.diff(base))
        self.n = len(base) - 1
        t0 = r["thickness"]
        tc = t0 if r["thickness_crown"] is None else r["thickness_crown"]
        pc = (span * span / 4 - rise * rise) / span  # _pointed_crown's centre and radius
        # scalars: L, kink, vertical, t0, tc - t0, ppr, crown centre c, crown radius rho
        self.scal = np.array([big_l, float(line.kink), float(r["joints"] == "vertical"), t0,
                              tc - t0, r["points_per_rad"], pc, span / 2 - pc])
        self.density = r["density"]

    def args(self):
        """The plan's arrays in the order the kernels take them."""
        return (self.ptype, self.ppar, self.plen, self.pmode, self.tab_u, self.tab_s,
                self.tab_v, self.tab_n, self.bounds, self.base_len, self.scal)


# the plans of the nominals seen lately (a study has one nominal)
_PLANS: list = []


def cached_plan(cache: list, nominal, build):
    """The plan in ``cache`` built for this very ``nominal`` object, or ``build(nominal)`` kept
    there (the last four nominals: a study has one)."""
    for plan in cache:
        if plan.nominal is nominal:
            return plan
    plan = build(nominal)
    cache.insert(0, plan)
    del cache[4:]
    return plan


def family_plan(nominal) -> "FamilyPlan":
    """The :class:`FamilyPlan` of ``nominal``, kept for reuse (:func:`cached_plan`)."""
    return cached_plan(_PLANS, nominal, FamilyPlan)


def compiled_drawing(sampler) -> bool:
    """Whether a sampler's family draws go through this module (numba present, a supported
    family nominal): :class:`~archrock.geometry.sampling.ArchSampler` and the ensemble's
    batches."""
    return HAVE_NUMBA and not sampler.circular and supported(sampler.nominal)


def _arc_par(cx, cy, r, th0, th1):
    """Parameters of an arc piece as :func:`~archrock.geometry.centreline._arc` evaluates them."""
    return (ARC, [cx, cy, r, th0, th1 - th0, -(th1 - th0) * r, (th1 - th0) * r])


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
            x, y, d0, d1 = _pdp(ptype[j], ppar[j], v / plen[j])
            p[i, 0] = x
            p[i, 1] = y
            h = np.hypot(d0, d1)
            t[i, 0] = d0 / h
            t[i, 1] = d1 / h
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
            i = idx[q]
            x, y, d0, d1 = _pdp(typ, par, uu[q])
            p[i, 0] = x
            p[i, 1] = y
            h = np.hypot(d0, d1)
            t[i, 0] = d0 / h
            t[i, 1] = d1 / h
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
    """``irregular._cut``: (segment index or -1, x, y) of the crossing of the polyline with the
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


@maybe_njit
def _batch_one(b, U, sa, st, sr, tilt_rad, ptype, ppar, plen, pmode, tab_u, tab_s, tab_v, tab_n,
               bounds, base_len, scal, state, code, where, side, areas, cen, polar, jp, size,
               asum):
    n = base_len.size
    c, i, sd, lines = _draw(U[b], sa, st, sr, tilt_rad, ptype, ppar, plen, pmode, tab_u, tab_s,
                            tab_v, tab_n, bounds, base_len, scal)
    if c != 0:
        state[b], code[b], where[b], side[b] = REFUSED, c, i, sd
        return
    ok, sz, tot = _arch_arrays(lines, n, scal[0], areas[b], cen[b], polar[b], jp[b])
    if ok:
        state[b], size[b], asum[b] = OK, sz, tot
    else:
        state[b] = UNCERTIFIED


def _batch_loop_py(U, sa, st, sr, tilt_rad, ptype, ppar, plen, pmode, tab_u, tab_s, tab_v, tab_n,
                   bounds, base_len, scal, state, code, where, side, areas, cen, polar, jp, size,
                   asum):
    for b in range(U.shape[0]):
        _batch_one(b, U, sa, st, sr, tilt_rad, ptype, ppar, plen, pmode, tab_u, tab_s, tab_v, tab_n,
                   bounds, base_len, scal, state, code, where, side, areas, cen, polar, jp, size,
                   asum)


if HAVE_NUMBA:
    @maybe_njit(parallel=True)
    def _batch_loop_nb(U, sa, st, sr, tilt_rad, ptype, ppar, plen, pmode, tab_u, tab_s,
                       tab_v, tab_n, bounds, base_len, scal, state, code, where, side, areas,
                       cen, polar, jp, size, asum):
        for b in numba.prange(U.shape[0]):
            _batch_one(b, U, sa, st, sr, tilt_rad, ptype, ppar, plen, pmode, tab_u, tab_s, tab_v,
                       tab_n, bounds, base_len, scal, state, code, where, side, areas, cen,
                       polar, jp, size, asum)

    _batch_loop_serial = maybe_njit(_batch_loop_py)
else:  # pragma: no cover - without numba
    _batch_loop_nb = _batch_loop_serial = _batch_loop_py


# ---------------------------------------------------------------------------- entry points
def _spread_args(u, spreads):
    u = np.ascontiguousarray(u, dtype=float)
    return u, float(spreads.span), float(spreads.thickness), float(spreads.radius), \
        (math.radians(spreads.tilt) if spreads.tilt else 0.0)


def draw_lines(plan: FamilyPlan, u, spreads):
    """One draw: (intrados, extrados) tuples of polylines (k, 2) [m] of ``perturb_family(
    plan.nominal, u, ...)``, or the :class:`~archrock.errors.ArchInputError` it would raise.
    ``u``: (3, n) or (4, n) uniforms; ``spreads``: a
    :class:`~archrock.geometry.sampling.Spreads`."""
    u, sa, st, sr, tilt = _spread_args(u, spreads)
    n = plan.n
    if u.ndim != 2 or u.shape[0] not in (3, 4) or u.shape[1] != n:
        raise ArchInputError(f"u: shape {u.shape}; allowed (3, {n}) or (4, {n})")
    c, i, sd, lines = _draw(u, sa, st, sr, tilt, *plan.args())
    if c != 0:
        return ArchInputError(refusal_message(c, i, sd))
    lines = list(lines)
    return tuple(lines[0::2]), tuple(lines[1::2])


def batch_properties(plan: FamilyPlan, U, spreads, parallel: bool = True) -> dict:
    """Draws ``U`` (B, rows, n) of the plan's nominal with ``spreads``, as arrays (module
    docstring): state (B,), code / index / side of refused draws, areas (B, n) [m^2],
    centroids (B, n, 2) [m], polar (B, n) [m^4], joint_points (B, n + 1, 2, 2) [m], size (B,)
    [m] and area_sum (B,) [m^2] (numpy's sum of the row's areas); rows not in state 0 hold
    garbage there.  ``parallel``: over the numba threads (the same numbers)."""
    U, sa, st, sr, tilt = _spread_args(U, spreads)
    B, n = U.shape[0], plan.n
    out = {"state": np.full(B, UNCERTIFIED, dtype=np.int64), "code": np.zeros(B, np.int64),
           "index": np.zeros(B, np.int64), "side": np.zeros(B, np.int64),
           "areas": np.zeros((B, n)), "centroids": np.zeros((B, n, 2)), "polar": np.zeros((B, n)),
           "joint_points": np.zeros((B, n + 1, 2, 2)), "size": np.zeros(B),
           "area_sum": np.zeros(B)}
    loop = (_batch_loop_nb if parallel else _batch_loop_serial) if HAVE_NUMBA else _batch_loop_py
    loop(U, sa, st, sr, tilt, *plan.args(), out["state"], out["code"], out["index"], out["side"],
         out["areas"], out["centroids"], out["polar"], out["joint_points"], out["size"],
         out["area_sum"])
    return out

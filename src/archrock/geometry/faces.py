"""The faces of a family arch's voussoirs: the centreline's offset lines (intrados, extrados)
sampled at a number of points per radian of turning, cut by the joint lines (normal to the
centreline, or vertical), and the fill above the extrados.  Used by
:func:`~archrock.geometry.families.family_arch` and
:func:`~archrock.geometry.irregular.perturb_family`.
"""

from __future__ import annotations

import math

import numpy as np

from ..errors import ArchInputError
from .base import Load, polygon_properties


def thickness_along(t_springing: float, t_crown: float, length: float):
    """t(s) [m]: the thickness at arc length s [m] of a centreline ``length`` [m] long, linear
    in s from ``t_springing`` at both springings to ``t_crown`` at the crown (s = length / 2)."""
    def thick(s):
        s = np.asarray(s, float)
        return t_springing + (t_crown - t_springing) * (1.0 - np.abs(2.0 * s / length - 1.0))
    return thick

def _check_curvature(line, thick, shape, span, rise):
    s, k = line.curvature()
    ratio = thick(s) * np.maximum(-k, 0.0) / 2.0
    j = int(np.argmax(ratio))
    if ratio[j] >= 1.0:
        rad = 1.0 / -k[j]
        raise ArchInputError(
            f"thickness: {float(thick(s[j])):g} m is too large for the curvature of the {shape} "
            f"centreline (the intrados would self-intersect where its radius of curvature is "
            f"{rad:.4g} m); allowed t < {2 * rad:.4g} m there")
    if shape == "pointed":
        # the two intrados arcs must still meet at the crown
        if thick(line.length / 2) >= span:
            raise ArchInputError(f"thickness_crown: {float(thick(line.length / 2)):g} m; allowed "
                                 f"< S = {span:g} m for a pointed arch (the intrados arcs must meet "
                                 f"at the crown)")


def _pointed_crown(span, rise, t_c, side):
    """(point, right arc's centre): the point at x = 0 of the offset arcs (radius rho -+ t_c/2)
    of a pointed arch, the crown end of its intrados (side -1) or extrados (+1)."""
    c = (span * span / 4 - rise * rise) / span
    rho = span / 2 - c
    r = rho + side * t_c / 2
    # with the right arc's centre (c, 0): the left arc's is its mirror image
    return np.array([0.0, math.sqrt(r * r - c * c)]), np.array([c, 0.0])


def _offset(line, thick, s, side, sign, pointed=None):
    """Offset points of the centreline at arc lengths s: side -1 intrados, +1 extrados; sign
    chooses the piece at a boundary (-1 left, +1 right)."""
    p, t = line.eval(s, sign)
    normal = np.column_stack([-t[:, 1], t[:, 0]])
    return p + side * normal * (thick(s)[:, None] / 2)


class _CrownOffsetCrossed(ArchInputError):
    """An offset range ending just past a pointed crown has no point on its own side."""


def _sample_offset(line, thick, s0, s1, side, ppr, crown):
    """The offset line (intrados: side -1, extrados: +1) between arc lengths s0 < s1, sampled
    so its tangent turns at most 1/ppr rad per segment; a pointed crown inside (s0, s1] or
    [s0, s1) is inserted as a vertex and the offsets clipped to their side of x = 0."""
    mid = line.length / 2
    if line.kink and s0 < mid < s1:
        left = _sample_offset(line, thick, s0, mid, side, ppr, crown)
        right = _sample_offset(line, thick, mid, s1, side, ppr, crown)
        return np.vstack([left, right[1:]])
    # turning of the tangent over [s0, s1]
    ss = np.linspace(s0, s1, 65)
    sign = -1 if (line.kink and s1 == mid) else 1
    _, tt = line.eval(ss, sign)
    ang = np.unwrap(np.arctan2(tt[:, 1], tt[:, 0]))
    turn = float(np.sum(np.abs(np.diff(ang))))
    m = max(2, int(math.ceil(turn * ppr)))
    s = np.linspace(s0, s1, m + 1)
    pts = _offset(line, thick, s, side, sign)
    if line.kink and (s1 == mid or s0 == mid):
        cp, centre = crown(side)
        part = pts[:-1] if s1 == mid else pts[1:]
        if not np.any(part[:, 0] * (-1 if s1 == mid else 1) > 1e-12 * line.length):
            raise _CrownOffsetCrossed(
                f"n: the joints beside the pointed crown cross each other before the "
                f"{'intrados' if side < 0 else 'extrados'} (voussoirs too short for this "
                f"thickness there); allowed fewer voussoirs, a thinner arch or an even number "
                f"of voussoirs (a joint at the crown)")
        if s1 == mid:
            kept = pts[:-1][pts[:-1, 0] < -1e-12 * line.length]
            pts = np.vstack([kept, _arc_between(kept[-1], cp, centre * [-1, 1], ppr)])
        else:
            kept = pts[1:][pts[1:, 0] > 1e-12 * line.length]
            pts = np.vstack([cp, _arc_between(kept[0], cp, centre, ppr)[::-1][1:], kept])
    return pts


def _arc_between(p, q, centre, ppr):
    """Points after p up to q (included) on the arc about ``centre`` from p to q (radius
    interpolated), about 1/ppr rad apart: the offset arcs of a pointed arch extended or trimmed
    to the crown, so their polylines keep the sampling's accuracy there."""
    a0 = math.atan2(p[1] - centre[1], p[0] - centre[0])
    a1 = math.atan2(q[1] - centre[1], q[0] - centre[0])
    r0, r1 = math.dist(p, centre), math.dist(q, centre)
    m = max(1, int(math.ceil(abs(a1 - a0) * ppr)))
    w = np.arange(1, m + 1) / m
    ang, rad = a0 + (a1 - a0) * w, r0 + (r1 - r0) * w
    out = np.column_stack([centre[0] + rad * np.cos(ang), centre[1] + rad * np.sin(ang)])
    out[-1] = q
    return out


def _vertical_cut(line, thick, x, side, sign_piece, lo, hi):
    """Arc length in [lo, hi] where the offset line's x equals ``x``."""
    from scipy.optimize import brentq

    def g(s):
        return float(_offset(line, thick, np.array([s]), side, sign_piece)[0, 0]) - x
    return brentq(g, lo, hi, xtol=1e-13 * line.length)


def _vertical_joints_that_cut(line, thick, s_div):
    """n + 1 division points (ends included) whose vertical lines cross the whole ring: the
    equal division ``s_div`` where every interior vertical crosses it; otherwise (near steep
    springings the vertical through a centreline point misses the intrados) each springing
    voussoir spans those joints (vertical stereotomy; Makris and Alexakis 2013) up to the first
    equal division that crosses, and the rest is divided equally, so that n is kept."""
    big_l = line.length
    p, _ = line.eval(s_div)
    keep = [0]
    for j in range(1, len(s_div) - 1):
        if line.kink and abs(s_div[j] - big_l / 2) < 1e-12 * big_l:
            keep.append(j)
            continue
        a, b = (0.0, big_l / 2) if line.kink and s_div[j] < big_l / 2 else \
            (big_l / 2, big_l) if line.kink else (0.0, big_l)
        xa = _offset(line, thick, np.array([a]), -1, 1)[0, 0]
        xb = _offset(line, thick, np.array([b]), -1, -1)[0, 0]
        if xa < p[j, 0] < xb:
            keep.append(j)
    keep.append(len(s_div) - 1)
    n = len(s_div) - 1
    if len(keep) < 4:
        raise ArchInputError(f"voussoirs: {n} with joints='vertical' leaves fewer than 2 vertical "
                             f"joints that cross the whole ring; allowed more voussoirs or "
                             f"joints='normal'")
    if len(keep) == n + 1:
        return s_div
    # Some joints near the springings miss the intrados: each springing voussoir reaches to the
    # first (last) equal division whose vertical crosses the ring, and the centreline between
    # those two joints is divided equally among the other n - 2 voussoirs, so the arch still has
    # exactly n voussoirs.  x grows along the centreline, so every point between two joints that
    # cross the ring crosses it too.
    s_a, s_b = s_div[keep[1]], s_div[keep[-2]]
    out = np.concatenate([[0.0], np.linspace(s_a, s_b, n - 1), [big_l]])
    out[1], out[-2] = s_a, s_b
    if line.kink:  # a joint at a pointed crown sits exactly on it
        out[np.abs(out - big_l / 2) < 1e-12 * big_l] = big_l / 2
    return out


def _voussoir_lines(line, thick, s_div, joints, shape, span, rise, ppr, t_crown):
    n = len(s_div) - 1
    big_l = line.length

    def crown(side):
        return _pointed_crown(span, rise, t_crown, side)

    if joints == "normal":
        lo = {side: s_div[:-1] for side in (-1, 1)}
        hi = {side: s_div[1:] for side in (-1, 1)}
    else:
        p, _ = line.eval(s_div)
        if np.any(np.diff(line.eval(np.linspace(0, big_l, 2001))[0][:, 0]) <= 0):
            raise ArchInputError("joints: 'vertical' needs a centreline whose x grows from the "
                                 "left springing to the right one (a circular arch with F <= S/2); "
                                 "allowed 'normal' here")
        cut = {}
        for side in (-1, 1):
            cs = [0.0]
            for j in range(1, n):
                x = p[j, 0]
                if line.kink and abs(s_div[j] - big_l / 2) < 1e-12 * big_l:
                    cs.append(big_l / 2)
                    continue
                piece = -1 if s_div[j] < big_l / 2 else 1
                a, b = (0.0, big_l / 2) if line.kink and piece < 0 else \
                    (big_l / 2, big_l) if line.kink else (0.0, big_l)
                xa = _offset(line, thick, np.array([a]), side, 1)[0, 0]
                xb = _offset(line, thick, np.array([b]), side, -1)[0, 0]
                if not (xa < x < xb):
                    raise ArchInputError(
                        f"joints: the vertical joint {j} (x = {x:.4g} m) misses the "
                        f"{'intrados' if side < 0 else 'extrados'}; allowed fewer voussoirs, a "
                        f"thinner arch or joints='normal'")
                cs.append(_vertical_cut(line, thick, x, side, piece, a, b))
            cs.append(big_l)
            cs = np.array(cs)
            if np.any(np.diff(cs) <= 0):
                raise ArchInputError("joints: vertical joints cross each other on the "
                                     f"{'intrados' if side < 0 else 'extrados'}; allowed fewer "
                                     "voussoirs or joints='normal'")
            cut[side] = cs
        lo = {side: cut[side][:-1] for side in (-1, 1)}
        hi = {side: cut[side][1:] for side in (-1, 1)}
    intr, extr = [], []
    for i in range(n):
        lines = {}
        for side in (-1, 1):
            pts = _sample_offset(line, thick, lo[side][i], hi[side][i], side, ppr, crown)
            if joints == "vertical" and 0 < i:
                pts[0, 0] = line.eval(s_div[i:i + 1])[0][0, 0]  # exactly on the vertical line
            if joints == "vertical" and i < n - 1:
                pts[-1, 0] = line.eval(s_div[i + 1:i + 2])[0][0, 0]
            lines[side] = pts
        intr.append(lines[-1])
        extr.append(lines[1])
    return intr, extr


def _fill(extr, fill):
    """(regions, loads): the fill above each voussoir's extrados up to fill['level']."""
    level, rho = fill["level"], fill["density"]
    regions, loads = [], []
    for i, e in enumerate(extr):
        if np.any(np.diff(e[:, 0]) < 0):
            raise ArchInputError(f"fill: the extrados of voussoir {i} turns back (x decreases, "
                                 f"as near the springings of a horseshoe or tall arch); allowed "
                                 f"a fill over an extrados whose x grows from left to right")
        area, mx, my = 0.0, 0.0, 0.0
        poly = []
        for (x0, y0), (x1, y1) in zip(e[:-1], e[1:]):
            pts = []
            if y0 < level and y1 < level:
                pts = [(x0, y0), (x1, y1), (x1, level), (x0, level)]
            elif y0 < level or y1 < level:
                xc = x0 + (level - y0) * (x1 - x0) / (y1 - y0)
                pts = [(x0, y0), (xc, level), (x0, level)] if y0 < level else \
                    [(xc, level), (x1, y1), (x1, level)]
            if pts:
                a, c, _ = polygon_properties(pts)
                area += a
                mx += a * c[0]
                my += a * c[1]
            poly.extend([(x0, min(y0, level)), (x1, min(y1, level))])
        if area <= 0.0:
            regions.append(None)
            continue
        poly = np.array(poly + [(e[-1, 0], level), (e[0, 0], level)])
        regions.append(poly)
        loads.append(Load(i, rho * area, (mx / area, my / area)))
    return tuple(regions), tuple(loads)


def cut_polyline(poly: np.ndarray, c, d, near):
    """Where the polyline ``poly`` (k, 2) [m] crosses the line through ``c`` along ``d``:
    (segment index k, point) of the crossing nearest ``near``, or None (a tilted joint of an
    irregular arch or of a defect, cut through its voussoirs' faces)."""
    f = d[0] * (poly[:, 1] - c[1]) - d[1] * (poly[:, 0] - c[0])
    k = np.flatnonzero((f[:-1] * f[1:] <= 0) & ((f[:-1] != 0) | (f[1:] != 0)))
    if k.size == 0:
        return None
    den = f[k] - f[k + 1]
    # a segment lying on the line (den = 0) crosses it at its start
    w = np.where(den != 0, f[k] / np.where(den != 0, den, 1.0), 0.0)
    q = poly[k] + w[:, None] * (poly[k + 1] - poly[k])
    j = int(np.argmin(np.hypot(q[:, 0] - near[0], q[:, 1] - near[1])))
    return int(k[j]), q[j]

"""The centrelines of the common arch families (docs/geometry.md, families), parametrised by
arc length.

Frame: the centreline springs at (-S/2, 0) and (S/2, 0) and reaches the crown (0, F); x to
the right, y up, metres.  Each shape (:data:`SHAPES`) is one or more pieces: circular arcs
(exact) or graphs and ellipses whose arc length is tabulated and inverted by cubic Hermite
interpolation (:data:`HERMITE_TOL`); :mod:`~archrock.geometry.families` builds the voussoirs
about it.
"""

from __future__ import annotations

import math

import numpy as np

from ..errors import ArchInputError

__all__ = ["Centreline", "centreline", "circular_radius", "three_centred_radii", "SHAPES",
           "HERMITE_TOL"]

SHAPES = ("circular", "pointed", "elliptical", "three-centred", "parabolic", "catenary")
_GL_X, _GL_W = np.polynomial.legendre.leggauss(8)

#: Arc-length tables of a non-circular piece: knots from 256, times 4 until the cubic Hermite
#: interpolant of u(s) is within this fraction of the piece's length of the exact inversion at
#: every interval's midpoint (where its error peaks), at most MAX_TABLE_KNOTS knots.  Beyond
#: that (no family in the tested ranges) the Hermite guess is refined by one Newton step.
HERMITE_TOL = 1e-14
MAX_TABLE_KNOTS = 65536


class _Piece:
    """A smooth piece of a centreline: p(u), p'(u) for u in [0, 1] (vectorised).

    Arc length s(u) is integrated exactly (8-point Gauss-Legendre per table interval); u(s) is
    the cubic Hermite interpolant of the table with the exact slopes du/ds = 1/|p'(u)| at the
    knots, on a table fine enough to be exact to HERMITE_TOL of the length (docs/geometry.md).
    """

    def __init__(self, p, dp, grid: int = 256, constant_speed: bool = False):
        self.p, self.dp = p, dp
        self.constant_speed = constant_speed
        self.newton = False
        while True:
            u = np.linspace(0.0, 1.0, grid + 1)
            self._u = u
            if constant_speed:  # the arcs' lengths as 0.6 summed them, to the bit
                seg = np.array([self._gl(a, b) for a, b in zip(u[:-1], u[1:])])
            else:
                seg = self._gl(u[:-1], u[1:])
            self._s = np.concatenate([[0.0], np.cumsum(seg)])
            self.length = float(self._s[-1])
            d = self.dp(u)
            self._v = np.hypot(d[0], d[1])  # speed |p'(u)| [m] at the knots: the slopes
            if constant_speed:
                break
            err = self._table_error()
            if err <= HERMITE_TOL * self.length or 4 * grid > MAX_TABLE_KNOTS:
                self.newton = err > HERMITE_TOL * self.length
                break
            grid *= 4

    def _gl(self, a, b):
        """Arc length from u = a to u = b (8-point Gauss-Legendre; a, b arrays or floats)."""
        a, b = np.asarray(a, float), np.asarray(b, float)
        half, mid = 0.5 * (b - a), 0.5 * (b + a)
        uu = mid[..., None] + half[..., None] * _GL_X
        d = self.dp(uu)
        return half * (np.hypot(d[0], d[1]) * _GL_W).sum(axis=-1)

    def _table_error(self) -> float:
        """Largest distance [m] between the point at u_Hermite(s) and at the exact u(s) (two
        Newton steps from it), over the table intervals' midpoints."""
        s = 0.5 * (self._s[:-1] + self._s[1:])
        k = np.arange(len(s))
        u0 = self._u[k]
        uh = _hermite_u(s, self._s[k], self._s[k + 1], u0, self._u[k + 1], self._v[k],
                        self._v[k + 1])
        u = uh
        for _ in range(2):
            d = self.dp(u)
            u = u - (self._s[k] + self._gl(u0, u) - s) / np.hypot(d[0], d[1])
        ph, pe = self.p(uh), self.p(u)
        return float(np.max(np.hypot(ph[0] - pe[0], ph[1] - pe[1])))

    def u_of_s(self, s):
        """Parameter u at arc length s from the piece's start (the class docstring)."""
        s = np.clip(np.asarray(s, float), 0.0, self.length)
        if self.constant_speed:  # a circular arc: the arc length is proportional to u
            return s / self.length
        k = np.clip(np.searchsorted(self._s, s, side="right") - 1, 0, len(self._u) - 2)
        u0, s0 = self._u[k], self._s[k]
        u = _hermite_u(s, s0, self._s[k + 1], u0, self._u[k + 1], self._v[k], self._v[k + 1])
        if self.newton:  # a table that could not be made fine enough: one Newton step
            d = self.dp(u)
            u = u - (s0 + self._gl(u0, u) - s) / np.hypot(d[0], d[1])
        return np.clip(u, 0.0, 1.0)


def _hermite_u(s, s0, s1, u0, u1, v0, v1):
    """u at arc length s between two knots (s0, u0), (s1, u1) of a piece's table: the cubic
    Hermite interpolant with the exact slopes du/ds = 1/v at the knots (v the speed |p'(u)|).
    :func:`archrock.geometry.batchlines._eval` repeats this arithmetic operation for operation."""
    h = s1 - s0
    w = (s - s0) / np.maximum(h, 1e-300)
    du = u1 - u0
    return u0 + w * du + (w * (1.0 - w)) * ((1.0 - w) * (h / v0 - du) - w * (h / v1 - du))


class Centreline:
    """A centreline from (-S/2, 0) to (S/2, 0), parametrised by arc length s in [0, L] [m]."""

    def __init__(self, pieces, kink: bool = False):
        self.pieces = pieces
        self.bounds = np.concatenate([[0.0], np.cumsum([p.length for p in pieces])])
        self.length = float(self.bounds[-1])
        self.kink = kink  # a pointed crown at s = L/2 (no tangent there)

    def _locate(self, s, side):
        s = np.atleast_1d(np.asarray(s, float))
        k = np.searchsorted(self.bounds, s, side="left" if side < 0 else "right") - 1
        return s, np.clip(k, 0, len(self.pieces) - 1)

    def eval(self, s, side: int = 1):
        """Points (m, 2) and unit tangents (m, 2) at arc lengths s; at a piece boundary the
        piece on the left (side -1) or on the right (side +1)."""
        s, k = self._locate(s, side)
        p = np.empty((s.size, 2))
        t = np.empty((s.size, 2))
        for j, piece in enumerate(self.pieces):
            sel = k == j
            if not sel.any():
                continue
            u = piece.u_of_s(s[sel] - self.bounds[j])
            p[sel] = np.column_stack(piece.p(u))
            d = np.column_stack(piece.dp(u))
            t[sel] = d / np.hypot(d[:, 0], d[:, 1])[:, None]
        return p, t

    def curvature(self, m: int = 2001):
        """(s, kappa): signed curvature [1/m] on a grid (negative: turning clockwise, the
        centre of curvature below the line, on the intrados side)."""
        out_s, out_k = [], []
        for j, piece in enumerate(self.pieces):
            u = np.linspace(0.0, 1.0, max(16, m // len(self.pieces)))
            h = 1e-6
            d = np.array(piece.dp(u))
            dd = (np.array(piece.dp(np.clip(u + h, 0, 1))) - np.array(piece.dp(np.clip(u - h, 0, 1)))) \
                / (np.clip(u + h, 0, 1) - np.clip(u - h, 0, 1))
            k = (d[0] * dd[1] - d[1] * dd[0]) / np.hypot(d[0], d[1]) ** 3
            s = np.array([piece._gl(0.0, x) for x in u]) + self.bounds[j]
            out_s.append(s)
            out_k.append(k)
        return np.concatenate(out_s), np.concatenate(out_k)


def _arc(cx, cy, r, th0, th1):
    def p(u):
        th = th0 + (th1 - th0) * np.asarray(u, float)
        return cx + r * np.cos(th), cy + r * np.sin(th)

    def dp(u):
        th = th0 + (th1 - th0) * np.asarray(u, float)
        return -(th1 - th0) * r * np.sin(th), (th1 - th0) * r * np.cos(th)
    return _Piece(p, dp, grid=8, constant_speed=True)  # exact lengths: the speed is constant


def _graph(f, df, a):
    """y = f(x), x from -a to a."""
    def p(u):
        x = -a + 2 * a * np.asarray(u, float)
        return x, f(x)

    def dp(u):
        x = -a + 2 * a * np.asarray(u, float)
        return np.full_like(x, 2 * a), 2 * a * df(x)
    return _Piece(p, dp)


def circular_radius(span: float, rise: float) -> tuple[float, float]:
    """(R, y of the centre) of the circle through (+-S/2, 0) and (0, F) [m]."""
    a = span / 2
    r = (a * a + rise * rise) / (2 * rise)
    return r, rise - r


def three_centred_radii(span: float, rise: float) -> tuple[float, float]:
    """(r1, r2) [m] of the classical three-centred arch (module docstring)."""
    a, f = span / 2, rise
    d = math.hypot(a, f)
    return d * (d - a + f) / (2 * a), d * (d + a - f) / (2 * f)


def _catenary_parameter(a: float, f: float) -> float:
    from scipy.optimize import brentq

    # A (cosh(a/A) - 1) decreases from infinity to 0 as A grows; solve in log A
    def g(la):
        big_a = math.exp(la)
        return big_a * (math.cosh(a / big_a) - 1.0) - f
    lo, hi = math.log(a) - 8.0, math.log(a) + 8.0
    lo = max(lo, math.log(a) - 6.0)  # cosh overflows below; there F > 1e100 a
    while g(lo) < 0:
        lo -= 1.0
    while g(hi) > 0:
        hi += 4.0
    return math.exp(brentq(lambda la: (g(la)) / f, lo, hi, xtol=1e-15, rtol=1e-15))


def centreline(shape: str, span: float, rise: float) -> Centreline:
    """The centreline of a family (module docstring); span, rise checked by the caller."""
    a, f = span / 2, rise
    if shape == "circular":
        r, yc = circular_radius(span, rise)
        th0 = math.atan2(-yc, -a)
        if th0 < 0:
            th0 += 2 * math.pi
        return Centreline([_arc(0.0, yc, r, th0, math.pi - th0)])
    if shape == "pointed":
        c = (a * a - f * f) / span
        rho = a - c
        phi = math.atan2(f, -c)  # polar angle of the crown seen from the right arc's centre
        left = _arc(-c, 0.0, rho, math.pi, math.pi - phi)
        right = _arc(c, 0.0, rho, phi, 0.0)
        return Centreline([left, right], kink=True)
    if shape == "elliptical":
        def p(u):
            th = math.pi * np.asarray(u, float)
            return -a * np.cos(th), f * np.sin(th)

        def dp(u):
            th = math.pi * np.asarray(u, float)
            return math.pi * a * np.sin(th), math.pi * f * np.cos(th)
        return Centreline([_Piece(p, dp)])
    if shape == "three-centred":
        r1, r2 = three_centred_radii(span, rise)
        c1 = a - r1
        yc2 = f - r2
        gamma = math.atan2(-yc2, -c1)  # direction from the crown centre to the left centre
        return Centreline([_arc(-c1, 0.0, r1, math.pi, gamma),
                           _arc(0.0, yc2, r2, gamma, math.pi - gamma),
                           _arc(c1, 0.0, r1, math.pi - gamma, 0.0)])
    if shape == "parabolic":
        return Centreline([_graph(lambda x: f * (1 - (x / a) ** 2), lambda x: -2 * f * x / a ** 2, a)])
    if shape == "catenary":
        big_a = _catenary_parameter(a, f)
        return Centreline([_graph(lambda x: f + big_a - big_a * np.cosh(x / big_a),
                                  lambda x: -np.sinh(x / big_a), a)])
    raise ArchInputError(f"shape: {shape!r}; allowed {', '.join(SHAPES)}")


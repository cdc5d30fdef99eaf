"""The common arch families, built as voussoir arches from span, rise and thickness.

:func:`family_arch` gives a :class:`FamilyArch` (a :class:`PolygonArch` that remembers how it
was built, so :meth:`FamilyArch.with_thickness_factor` can rebuild it with another thickness), or
the exact circular :class:`~archrock.geometry.Arch` for a circular arch with normal (radial)
joints, constant thickness and no fill.

Frame: the centreline (the mid-thickness line) springs at (-S/2, 0) and (S/2, 0) and reaches
the crown (0, F); x to the right, y up, metres.  The shapes of the centreline (a = S/2):

* ``circular``: an arc of radius R = (a^2 + F^2) / (2F), centre (0, F - R): segmental for
  F < a, a semicircle at F = a, a horseshoe (more than 180 deg) for a < F <= S (at most
  180 + 2 atan(3/4) = 253.7 deg);
* ``pointed``: two-centred, two arcs of radius rho = a - c with centres (c, 0) (right arc) and
  (-c, 0) (left arc), c = (a^2 - F^2) / S < 0, meeting at the crown in a point; needs F > a;
* ``elliptical``: x = -a cos(theta), y = F sin(theta), theta in [0, pi]; any F > 0;
* ``three-centred`` (basket handle, 0 < F <= a): side arcs of radius r1 with centres
  (+-(a - r1), 0) on the springing line, a crown arc of radius r2 with centre (0, F - r2),
  tangent to them.  r1 and r2 follow the classical construction from the diagonal of the
  a x F rectangle (the one used for an oval of given axes): with d = sqrt(a^2 + F^2),
  r1 = d (d - a + F) / (2a), r2 = d (d + a - F) / (2F); see e.g. P. L. Rosin, "A survey and
  comparison of traditional piecewise circular approximations to the ellipse", Computer Aided
  Geometric Design 16 (1999) 269-286.  A semicircle at F = a;
* ``parabolic``: y = F (1 - (x/a)^2); any F > 0;
* ``catenary``: y = F + A - A cosh(x/A), A > 0 solving A (cosh(a/A) - 1) = F; any F > 0.

Thickness t(s) [m] is measured along the normal of the centreline, symmetric about it, and
varies linearly with the arc length s from ``thickness`` at the springings to
``thickness_crown`` at the crown.  The centreline is divided into n voussoirs of equal length.
Joints: ``normal`` (faces along the centreline's normal at the division points: radial for
arcs; the crown joint of a pointed arch is vertical) or ``vertical`` (interior joints vertical
lines through the division points; the springing faces stay normal to the centreline).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import cached_property

import numpy as np

from ..errors import ArchInputError
from .base import (DEFAULT_DENSITY, Load, _check_density, _check_length, _check_scalar,
                   _check_voussoir_count,
                   polygon_properties)
from .polygon import PolygonArch

__all__ = ["family_arch", "FamilyArch", "SHAPES", "JOINTS", "centreline", "perturb_family"]

SHAPES = ("circular", "pointed", "elliptical", "three-centred", "parabolic", "catenary")
JOINTS = ("normal", "vertical")
#: Default sampling: segments of the intrados/extrados polylines per radian of turning of the
#: centreline.  The polygon's area is short of the exact one by about (1/ppr)^2 / 6: 7.4e-6
#: relative at 150 (a semicircle: 1e-5 needs at least 130).
POINTS_PER_RAD = 150.0
_GL_X, _GL_W = np.polynomial.legendre.leggauss(8)


# ---------------------------------------------------------------------------- centrelines
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
    :func:`archrock.geometry.batchdraw._eval` repeats this arithmetic operation for operation."""
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


# ---------------------------------------------------------------------------- the arch
#: allowed rise F for span S, per family: (lowest exclusive, highest, text)
_RISE_RANGE = {
    "circular": (lambda s: 0.0, lambda s: s, "0 < F <= S (a horseshoe of at most 253.7 deg)"),
    "pointed": (lambda s: s / 2, lambda s: math.inf, "F > S/2 (two-centred: taller than a semicircle)"),
    "elliptical": (lambda s: 0.0, lambda s: math.inf, "F > 0"),
    "three-centred": (lambda s: 0.0, lambda s: s / 2, "0 < F <= S/2 (a basket handle)"),
    "parabolic": (lambda s: 0.0, lambda s: math.inf, "F > 0"),
    "catenary": (lambda s: 0.0, lambda s: math.inf, "F > 0"),
}


@dataclass(frozen=True, eq=False)
class FamilyArch(PolygonArch):
    """A :class:`PolygonArch` built by :func:`family_arch`; ``recipe`` holds its arguments, so
    :meth:`with_thickness_factor` and :meth:`scaled` rebuild it from the family's formulas, and
    ``fill`` the fill's polygons (one per voussoir, (k, 2) [m] or None) for figures."""

    recipe: dict = field(default=None, compare=False, repr=False)
    fill_regions: tuple = field(default=(), compare=False, repr=False)

    def with_thickness_factor(self, factor: float) -> "FamilyArch":
        """The same family with both thicknesses (springing and crown) multiplied by ``factor``
        (span, rise, joints, loads and fill level unchanged; the fill's loads recomputed)."""
        f = _check_scalar("factor", factor, 0.0, None, allowed="> 0")
        r = dict(self.recipe)
        r["thickness"] = r["thickness"] * f
        if r["thickness_crown"] is not None:
            r["thickness_crown"] = r["thickness_crown"] * f
        return family_arch(**r, exact=False)

    def scaled(self, factor: float) -> "FamilyArch":
        """Every length multiplied by ``factor`` (loads by factor^2; the fill level by factor)."""
        f = _check_scalar("factor", factor, 0.0, None, allowed="> 0")
        r = dict(self.recipe)
        for key in ("span", "rise", "thickness"):
            r[key] = r[key] * f
        if r["thickness_crown"] is not None:
            r["thickness_crown"] *= f
        if r["fill"] is not None:
            r["fill"] = {**r["fill"], "level": r["fill"]["level"] * f}
        r["loads"] = tuple(Load(ld.voussoir, ld.mass * f * f, (ld.at[0] * f, ld.at[1] * f))
                           for ld in r["loads"])
        return family_arch(**r, exact=False)

    def to_dict(self) -> dict:
        """The polygon geometry format with the family's recipe under ``"family"`` (shape,
        span, rise, thicknesses, voussoirs, joints, density, user loads, fill, name,
        points_per_rad): :func:`~archrock.geometry.arch_from_dict` rebuilds the FamilyArch from
        it (the polylines stay for readers that only know polygons)."""
        d = super().to_dict()
        if self.recipe is not None:
            r = dict(self.recipe)
            r["loads"] = [ld.to_dict() for ld in r["loads"]]
            r["fill"] = None if r["fill"] is None else dict(r["fill"])
            d["family"] = r
        return d

    @classmethod
    def from_recipe(cls, recipe: dict, name: str | None = None) -> "FamilyArch":
        """Rebuild a family arch from its recipe (``to_dict()["family"]``)."""
        if not isinstance(recipe, dict) or not {"shape", "span", "rise", "thickness",
                                                 "voussoirs"} <= set(recipe):
            raise ArchInputError(f"family: {recipe!r}; allowed an object with shape, span, rise, "
                                 f"thickness, voussoirs (and the optional family_arch arguments)")
        r = dict(recipe)
        allowed = {"shape", "span", "rise", "thickness", "voussoirs", "thickness_crown", "joints",
                   "density", "loads", "fill", "name", "points_per_rad"}
        unknown = set(r) - allowed
        if unknown:
            raise ArchInputError(f"family: unknown key(s) {sorted(unknown)}; allowed "
                                 f"{', '.join(sorted(allowed))}")
        r["loads"] = tuple(r.get("loads") or ())
        if name is not None:  # as PolygonArch.from_dict: the reader's name wins
            r["name"] = name
        arch = family_arch(**r, exact=False)
        return arch

    @cached_property
    def _frame(self):
        """(centreline, thickness function t(s)) of the recipe, for :func:`perturb_family`."""
        r = self.recipe
        line = centreline(r["shape"], r["span"], r["rise"])
        t0 = r["thickness"]
        tc = t0 if r["thickness_crown"] is None else r["thickness_crown"]
        big_l = line.length

        def thick(s):
            s = np.asarray(s, float)
            return t0 + (tc - t0) * (1.0 - np.abs(2.0 * s / big_l - 1.0))
        return line, thick

    def __repr__(self) -> str:
        r = self.recipe
        return (f"FamilyArch(name={self.name!r}, shape={r['shape']!r}, S={r['span']:.4g} m, "
                f"F={r['rise']:.4g} m, n={self.n}, joints={r['joints']!r}"
                + (f", loads={len(self.loads)}" if self.loads else "") + ")")


def _positive_int(name, value, lo):
    if isinstance(value, bool) or not isinstance(value, (int, np.integer, float)) or \
            int(value) != value or value < lo:
        raise ArchInputError(f"{name}: {value!r}; allowed an integer >= {lo}")
    return int(value)


def family_arch(shape: str, span: float, rise: float, thickness: float, voussoirs: int, *,
                thickness_crown: float | None = None, joints: str = "normal",
                density: float = DEFAULT_DENSITY, loads=(), fill: dict | None = None,
                name: str | None = None, points_per_rad: float = POINTS_PER_RAD,
                exact: bool = True):
    """An arch of a common family (module docstring): span S [m] between the centreline's
    springings, rise F [m] of the centreline, thickness t [m] normal to the centreline at the
    springings (``thickness_crown`` at the crown, linear in arc length between; default t),
    n equal voussoirs along the centreline, ``joints`` 'normal' or 'vertical', density
    [kg/m^3], ``loads`` (:class:`Load` or dicts; points in this frame), ``fill``.

    Vertical joints pass through the centreline's division points; where such a vertical line
    would miss the intrados (near steep springings) the springing voussoir spans it, as vertical
    stereotomy does (Makris and Alexakis 2013), reaching to the first division whose vertical
    crosses the ring, and the centreline between the two springing voussoirs is divided equally
    among the other n - 2: the arch always has exactly n voussoirs (``.n``).

    ``fill = {"level": y [m], "density": rho [kg/m^3]}``: the fill above each voussoir's
    extrados up to y = level, cut by the vertical lines through the extrados ends of its
    joints, is carried as a :class:`Load` of that voussoir (mass rho x area at the area's
    centroid).  Assumption: the fill moves rigidly with its voussoir (no thrust of its own, no
    friction between neighbouring columns): it adds weight and inertia only.

    ``points_per_rad``: segments of the intrados/extrados polylines per radian of turning of
    the centreline (default: < 1e-5 relative area error on a semicircle).

    Returns the exact circular :class:`~archrock.geometry.Arch` (annular sectors) when shape is
    'circular', joints 'normal', the thickness constant, no fill and ``exact`` is true; its
    frame has the circle's centre at the origin, so its y = this frame's y - (F - R) (loads are
    moved with it).  Otherwise a :class:`FamilyArch` (a PolygonArch) in this frame.
    """
    if shape not in SHAPES:
        raise ArchInputError(f"shape: {shape!r}; allowed {', '.join(SHAPES)}")
    if joints not in JOINTS:
        raise ArchInputError(f"joints: {joints!r}; allowed 'normal' or 'vertical'")
    span = _check_length("span", _check_scalar("span", span, 0.0, None, allowed="S > 0 m"))
    lo, hi, text = _RISE_RANGE[shape]
    rise = _check_scalar("rise", rise, lo(span), hi(span), hi_open=False,
                         allowed=f"{text}; here S = {span:g} m")
    rise = _check_length("rise", rise)
    thickness = _check_length("thickness", _check_scalar("thickness", thickness, 0.0, None,
                                                         allowed="t > 0 m"))
    t_crown = thickness if thickness_crown is None else _check_length("thickness_crown", _check_scalar(
        "thickness_crown", thickness_crown, 0.0, None, allowed="> 0 m"))
    n = _check_voussoir_count(_positive_int("voussoirs", voussoirs, 3))
    ppr = _check_scalar("points_per_rad", points_per_rad, 0.0, None, allowed="> 0")
    density = _check_density(density)
    user_loads = tuple(ld if isinstance(ld, Load) else Load.from_dict(ld, i)
                       for i, ld in enumerate(loads or ()))
    if fill is not None:
        if not isinstance(fill, dict) or set(fill) != {"level", "density"}:
            raise ArchInputError(f"fill: {fill!r}; allowed {{'level': y [m], 'density': rho "
                                 f"[kg/m^3]}}")
        fill = {"level": _check_scalar("fill level", fill["level"], allowed="a finite y [m]"),
                "density": _check_density(fill["density"], "fill density")}
    name = name if name is not None else f"{shape} S={span:g} F={rise:g} t={thickness:g}"
    recipe = dict(shape=shape, span=span, rise=rise, thickness=thickness,
                  thickness_crown=thickness_crown if thickness_crown is None else t_crown,
                  voussoirs=n, joints=joints, density=density, loads=user_loads, fill=fill,
                  name=name, points_per_rad=ppr)

    if exact and shape == "circular" and joints == "normal" and t_crown == thickness and fill is None:
        from .circular import nominal_arch

        r, yc = circular_radius(span, rise)
        if thickness >= 2 * r:
            raise ArchInputError(f"thickness: {thickness:g} m is too large for the curvature (the "
                                 f"intrados would self-intersect); allowed t < 2 R = {2 * r:g} m")
        th0 = math.atan2(-yc, -span / 2) % (2 * math.pi)
        arch = nominal_arch(r, math.degrees(2 * th0 - math.pi), thickness, n, density, name)
        if user_loads:
            moved = tuple(Load(ld.voussoir, ld.mass, (ld.at[0], ld.at[1] - yc)) for ld in user_loads)
            arch = type(arch)(arch.spans, arch.radii, arch.thicknesses, density, name, moved)
        return arch

    line = centreline(shape, span, rise)
    big_l = line.length

    def thick(s):
        s = np.asarray(s, float)
        return thickness + (t_crown - thickness) * (1.0 - np.abs(2.0 * s / big_l - 1.0))

    _check_curvature(line, thick, shape, span, rise)
    s_div = big_l * np.arange(n + 1) / n
    if line.kink:  # a joint at a pointed crown sits exactly on it, not one ulp beside it
        s_div[np.abs(s_div - big_l / 2) < 1e-12 * big_l] = big_l / 2
    if joints == "vertical":
        s_div = _vertical_joints_that_cut(line, thick, s_div)
    intr, extr = _voussoir_lines(line, thick, s_div, joints, shape, span, rise, ppr, t_crown)
    regions, fill_loads = ((), ())
    if fill is not None:
        regions, fill_loads = _fill(extr, fill)
    return FamilyArch(tuple(intr), tuple(extr), density, name, user_loads + fill_loads,
                      recipe=recipe, fill_regions=regions)


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


# ---------------------------------------------------------------------------- irregular arches
def _cut(poly, c, d, near):
    """Where the polyline ``poly`` (k, 2) crosses the line through ``c`` along ``d``: (segment
    index k, point) of the crossing nearest ``near``, or None."""
    f = d[0] * (poly[:, 1] - c[1]) - d[1] * (poly[:, 0] - c[0])
    k = np.flatnonzero((f[:-1] * f[1:] <= 0) & ((f[:-1] != 0) | (f[1:] != 0)))
    if k.size == 0:
        return None
    den = f[k] - f[k + 1]
    w = np.where(den != 0, f[k] / np.where(den != 0, den, 1.0), 0.0)
    q = poly[k] + w[:, None] * (poly[k + 1] - poly[k])
    j = int(np.argmin(np.hypot(q[:, 0] - near[0], q[:, 1] - near[1])))
    return int(k[j]), q[j]


def perturb_family(nominal: "FamilyArch", u, spread_length: float, spread_thickness: float,
                   spread_offset: float, tilt_deg: float = 0.0, name: str = "arch"):
    """An irregular arch around a family arch, from uniform draws ``u`` (shape (3, n), or
    (4, n) with a tilt), each on [-1, 1]; the family's counterpart of
    :func:`~archrock.geometry.perturb_voussoirs`.

    Voussoir i covers the centreline's arc length [s_i, s_i+1] with lengths
    l_i = l0_i (1 + s_a U0_i) rescaled to the total L (l0_i the nominal's: L/n, or, with
    vertical joints that would miss the intrados near the springings, the nominal's longer
    springing voussoirs and equal ones between); its thickness is t(s)(1 + s_t U1_i) and
    its own centreline is offset along the normal by s_R U2_i t(s) (t(s): the nominal
    thickness, the circular family's R_i = R + s_R t U).  Joint j (1..n-1) is the nominal
    family's joint line at s_j (normal to the centreline, or vertical) rotated about the
    centreline point by U3_(j-1) x ``tilt_deg``; the springing faces stay normal.  Each
    voussoir's intrados and extrados are its offset lines (sampled as the family's) cut by its
    two joint lines, so neighbours' faces lie on one line.  A fill is recomputed over the new
    extrados; user loads stay where they are.

    Returns a :class:`PolygonArch` (no recipe: it is not a member of the family); raises
    :class:`~archrock.errors.ArchInputError` when the draw is not a valid arch.
    """
    r = nominal.recipe
    if r is None:
        raise ArchInputError("nominal: a polygon arch without a family recipe (e.g. a surveyed "
                             "arch) cannot be perturbed; allowed a circular Arch or an arch of "
                             "family_arch")
    line, thick = nominal._frame
    big_l, ppr = line.length, r["points_per_rad"]
    # the nominal's division points (with vertical joints: longer springing voussoirs where an
    # equal division's vertical would miss the intrados)
    base = big_l * np.arange(r["voussoirs"] + 1) / r["voussoirs"]
    if r["joints"] == "vertical":
        base = _vertical_joints_that_cut(line, thick, base)
    n = len(base) - 1
    u = np.asarray(u, float)
    if u.ndim != 2 or u.shape[0] not in (3, 4) or u.shape[1] != n:
        raise ArchInputError(f"u: shape {u.shape}; allowed (3, {n}) or (4, {n})")
    lengths = np.diff(base) * (1.0 + spread_length * u[0])
    lengths = lengths * (big_l / lengths.sum())
    if np.any(lengths <= 0):
        raise ArchInputError("geometry: a voussoir length is <= 0")
    s_div = np.concatenate([[0.0], np.cumsum(lengths)])
    s_div[-1] = big_l
    fac = 1.0 + spread_thickness * u[1]
    off = spread_offset * u[2]
    tilt = np.zeros(n + 1)
    if tilt_deg and u.shape[0] == 4:
        tilt[1:n] = math.radians(tilt_deg) * u[3, :n - 1]
    # joint lines: centreline point c_j and direction d_j (intrados -> extrados)
    c, tang = line.eval(s_div)
    d = np.column_stack([-tang[:, 1], tang[:, 0]])
    for j in range(1, n):
        if r["joints"] == "vertical" or (line.kink and abs(s_div[j] - big_l / 2) <= 1e-12 * big_l):
            d[j] = (0.0, 1.0)
    cs, sn = np.cos(tilt), np.sin(tilt)
    d = np.column_stack([cs * d[:, 0] - sn * d[:, 1], sn * d[:, 0] + cs * d[:, 1]])
    span, rise = r["span"], r["rise"]
    intr, extr = [], []
    for i in range(n):
        lines = {}
        for side in (-1, 1):
            k = fac[i] + 2.0 * side * off[i]
            if k <= 0:
                raise ArchInputError(f"geometry: voussoir {i}'s offset exceeds half its thickness")

            def te(s, k=k):
                return thick(s) * k
            t_mid = float(te(big_l / 2))

            def crown(sd, t_mid=t_mid):
                return _pointed_crown(span, rise, t_mid, sd)
            piece = None
            for widen in (False, True):
                lo = 0.0 if i == 0 else (0.0 if widen else max(0.0, s_div[i] - 0.5 * min(
                    lengths[i - 1], lengths[i])))
                hi = big_l if i == n - 1 else (big_l if widen else min(big_l, s_div[i + 1] + 0.5 * min(
                    lengths[i], lengths[i + 1])))
                try:
                    pts = _sample_offset(line, te, lo, hi, side, ppr, crown)
                except _CrownOffsetCrossed:  # a range ending just past a pointed crown: widen it
                    continue
                left = (0, pts[0]) if i == 0 else _cut(pts, c[i], d[i], c[i] + side * d[i])
                right = (len(pts) - 2, pts[-1]) if i == n - 1 else \
                    _cut(pts, c[i + 1], d[i + 1], c[i + 1] + side * d[i + 1])
                if left is not None and right is not None and left[0] <= right[0]:
                    piece = (pts, left, right)
                    break
            if piece is None:
                raise ArchInputError(f"geometry: voussoir {i}'s joints do not cut its "
                                     f"{'intrados' if side < 0 else 'extrados'} in order")
            pts, (kl, ql), (kr, qr) = piece
            mid = pts[kl + 1:kr + 1]
            tol = 1e-9 * big_l
            if len(mid):
                mid = mid[(np.hypot(*(mid - ql).T) > tol) & (np.hypot(*(mid - qr).T) > tol)]
            lines[side] = np.vstack([ql, mid, qr])
        intr.append(lines[-1])
        extr.append(lines[1])
    loads = tuple(r["loads"])
    if r["fill"] is not None:
        loads = loads + _fill(extr, r["fill"])[1]
    return PolygonArch(tuple(intr), tuple(extr), r["density"], name, loads)

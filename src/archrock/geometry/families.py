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
from .base import (DEFAULT_DENSITY, Load, _check_density, _check_fc, _check_length,
                   _check_scalar, _check_voussoir_count)
from .centreline import SHAPES, centreline, circular_radius
from .circular import nominal_arch
from .faces import (_check_curvature, _fill, _vertical_joints_that_cut, _voussoir_lines,
                    thickness_along)
from .polygon import PolygonArch

__all__ = ["family_arch", "FamilyArch", "SHAPES", "JOINTS", "centreline"]

JOINTS = ("normal", "vertical")
#: Default sampling: segments of the intrados/extrados polylines per radian of turning of the
#: centreline.  The polygon's area is short of the exact one by about (1/ppr)^2 / 6: 7.4e-6
#: relative at 150 (a semicircle: 1e-5 needs at least 130).
POINTS_PER_RAD = 150.0


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
        return family_arch(**r, exact=False, fc=self.fc)

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
        return family_arch(**r, exact=False, fc=self.fc)

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
        return line, thickness_along(t0, tc, line.length)

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


def _checked_fill(fill):
    """``fill`` checked: None, or {"level": y [m], "density": rho [kg/m^3]}."""
    if fill is None:
        return None
    if not isinstance(fill, dict) or set(fill) != {"level", "density"}:
        raise ArchInputError(f"fill: {fill!r}; allowed {{'level': y [m], 'density': rho "
                             f"[kg/m^3]}}")
    return {"level": _check_scalar("fill level", fill["level"], allowed="a finite y [m]"),
            "density": _check_density(fill["density"], "fill density")}


def _exact_circular(span, rise, thickness, n, density, name, user_loads):
    """The exact circular :class:`~archrock.geometry.Arch` of a circular family arch with normal
    joints, constant thickness and no fill: the circle's centre at the origin, the loads moved
    down by the centre's height."""
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


def family_arch(shape: str, span: float, rise: float, thickness: float, voussoirs: int, *,
                thickness_crown: float | None = None, joints: str = "normal",
                density: float = DEFAULT_DENSITY, loads=(), fill: dict | None = None,
                name: str | None = None, points_per_rad: float = POINTS_PER_RAD,
                exact: bool = True, fc: float | None = None):
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

    ``fc``: the masonry's compressive strength [MPa] (None: infinite); a property of the
    arch, not of the family, so it stays out of the recipe (files write it beside it).

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
    fc = _check_fc(fc)
    user_loads = tuple(ld if isinstance(ld, Load) else Load.from_dict(ld, i)
                       for i, ld in enumerate(loads or ()))
    fill = _checked_fill(fill)
    name = name if name is not None else f"{shape} S={span:g} F={rise:g} t={thickness:g}"
    recipe = dict(shape=shape, span=span, rise=rise, thickness=thickness,
                  thickness_crown=thickness_crown if thickness_crown is None else t_crown,
                  voussoirs=n, joints=joints, density=density, loads=user_loads, fill=fill,
                  name=name, points_per_rad=ppr)

    if exact and shape == "circular" and joints == "normal" and t_crown == thickness and fill is None:
        return _exact_circular(span, rise, thickness, n, density, name, user_loads).with_fc(fc)

    line = centreline(shape, span, rise)
    big_l = line.length
    thick = thickness_along(thickness, t_crown, big_l)
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
    return FamilyArch(tuple(intr), tuple(extr), density, name, user_loads + fill_loads, fc=fc,
                      recipe=recipe, fill_regions=regions)



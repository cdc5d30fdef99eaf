"""Circular voussoir arches, nominal or irregular: the circular family of :class:`VoussoirArch`,
with exact annular-sector formulas.

Conventions (docs/method.md, Geometry): centre O at the origin, x to the right, y up, SI units
(m, kg per metre of depth).  Voussoirs are numbered 0..n-1 from the left springing, joints
0..n; joint j lies on the radial line at polar angle ``psi_j`` and voussoir i lies between
joints i and i+1.  Voussoir i is an annular sector of span ``alpha_i`` (rad), mean radius
``R_i`` and thickness ``t_i``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import cached_property

import numpy as np

from ..errors import ArchInputError
from .base import (DEFAULT_DENSITY, MAX_VOUSSOIRS, Load, VoussoirArch, _check_length,
                   _check_density, _check_fc, _check_load_reach, _check_scalar, _check_size,
                   _check_voussoir_count, _file_fc,
                   _finite_array, _loads)
from .polygon import PolygonArch, as_polygon

__all__ = [
    "Arch",
    "nominal_arch",
    "oppenheim_arch",
    "OPPENHEIM",
    "sector_properties",
    "perturb_voussoirs",
    "random_spans_thicknesses_radii",
    "polygon_form",
    "ARC_STEP",
]

#: Nominal parameters of Oppenheim's arch (1992): R [m], embrace [deg], t [m], n.
OPPENHEIM = {"radius": 10.0, "embrace_deg": 157.5, "thickness": 1.5, "voussoirs": 7}


def sector_properties(spans, radii, thicknesses) -> dict:
    """Joint angles, contact radii and exact annular-sector properties, vectorised.

    Inputs have shape (..., n); outputs: ``psi``, ``r_in``, ``r_out`` (..., n+1) for the
    joints; ``area`` [m^2], ``centroid`` (..., n, 2) [m] and ``polar`` (..., n), the polar
    moment of area about the centroid [m^4], for the voussoirs.
    """
    spans = np.asarray(spans, float)
    radii = np.asarray(radii, float)
    thick = np.asarray(thicknesses, float)
    ri, ro = radii - thick / 2, radii + thick / 2
    embrace = spans.sum(axis=-1, keepdims=True)
    zero = np.zeros(spans.shape[:-1] + (1,))
    psi = np.pi / 2 + embrace / 2 - np.concatenate([zero, np.cumsum(spans, axis=-1)], axis=-1)
    r_in = np.concatenate([ri[..., :1], np.maximum(ri[..., :-1], ri[..., 1:]), ri[..., -1:]], axis=-1)
    r_out = np.concatenate([ro[..., :1], np.minimum(ro[..., :-1], ro[..., 1:]), ro[..., -1:]], axis=-1)
    half = spans / 2
    area = half * (ro**2 - ri**2)
    rg = (2.0 / 3.0) * (ro**3 - ri**3) / (ro**2 - ri**2) * np.sin(half) / half
    mid = psi[..., :-1] - half
    centroid = np.stack([rg * np.cos(mid), rg * np.sin(mid)], axis=-1)
    polar = spans * (ro**4 - ri**4) / 4.0 - area * rg**2
    return {"psi": psi, "r_in": r_in, "r_out": r_out, "area": area, "centroid": centroid,
            "polar": polar}


@dataclass(frozen=True, eq=False)
class Arch(VoussoirArch):
    """A circular voussoir arch, described voussoir by voussoir from the left springing.

    spans: angular span of each voussoir [rad]; radii: mean radius [m]; thicknesses [m];
    density [kg/m^3] (mass per metre of depth = density * area); loads: :class:`Load` objects
    (or their dicts), masses attached to voussoirs; fc: compressive strength [MPa] or None
    (infinite).
    """

    spans: np.ndarray
    radii: np.ndarray
    thicknesses: np.ndarray
    density: float = DEFAULT_DENSITY
    name: str = field(default="arch", compare=False)
    loads: tuple = ()
    fc: float | None = field(default=None, kw_only=True)

    def __post_init__(self):
        spans = _finite_array("spans", self.spans)
        radii = _finite_array("radii", self.radii)
        thick = _finite_array("thicknesses", self.thicknesses)
        n = spans.size
        if n < 3:
            raise ArchInputError(f"voussoirs: an arch needs at least 3 voussoirs, got {n}")
        if radii.size != n or thick.size != n:
            raise ArchInputError(
                f"voussoirs: spans, radii and thicknesses must have the same length "
                f"(got {n}, {radii.size}, {thick.size})")
        if np.any(spans <= 0):
            i = int(np.argmax(spans <= 0))
            raise ArchInputError(f"span of voussoir {i}: {math.degrees(spans[i]):g} deg; allowed > 0 deg")
        if spans.sum() >= 2 * math.pi:
            raise ArchInputError(
                f"spans: the voussoirs add up to {math.degrees(spans.sum()):g} deg; allowed < 360 deg")
        if np.any(radii <= 0):
            i = int(np.argmax(radii <= 0))
            raise ArchInputError(f"radius of voussoir {i}: {radii[i]:g} m; allowed > 0")
        if np.any(thick <= 0) or np.any(thick >= 2 * radii):
            i = int(np.argmax((thick <= 0) | (thick >= 2 * radii)))
            raise ArchInputError(
                f"thickness of voussoir {i}: {thick[i]:g} m; allowed 0 < t < 2 R = {2 * radii[i]:g} m")
        _check_voussoir_count(n)
        _check_size("radii", radii)
        _check_size("thicknesses", thick)
        density = _check_density(self.density)
        for arr in (spans, radii, thick):
            arr.setflags(write=False)
        object.__setattr__(self, "spans", spans)
        object.__setattr__(self, "radii", radii)
        object.__setattr__(self, "thicknesses", thick)
        object.__setattr__(self, "density", density)
        object.__setattr__(self, "fc", _check_fc(self.fc))
        object.__setattr__(self, "loads", _loads(self.loads, n))
        inner, outer = self.contact_inner, self.contact_outer
        if np.any(outer <= inner):
            j = int(np.argmax(outer <= inner))
            raise ArchInputError(
                f"joint {j}: the neighbouring voussoirs do not overlap radially "
                f"(contact from {inner[j]:g} m to {outer[j]:g} m); allowed: overlapping radial extents")
        _check_load_reach(self.loads, [self.outline(i) for i in range(n)])

    # ------------------------------------------------------------------ basic sizes
    @property
    def n(self) -> int:
        """Number of voussoirs."""
        return int(self.spans.size)

    @property
    def embrace(self) -> float:
        """Angle of embrace alpha [rad] (sum of the spans)."""
        return float(self.spans.sum())

    @cached_property
    def _props(self) -> dict:
        props = sector_properties(self.spans, self.radii, self.thicknesses)
        for arr in props.values():
            arr.setflags(write=False)
        return props

    @property
    def joint_angles(self) -> np.ndarray:
        """Polar angle psi_j of each joint j = 0..n [rad]; psi_0 is the left springing."""
        return self._props["psi"]

    @property
    def intrados_radii(self) -> np.ndarray:
        return self.radii - self.thicknesses / 2

    @property
    def extrados_radii(self) -> np.ndarray:
        return self.radii + self.thicknesses / 2

    @property
    def contact_inner(self) -> np.ndarray:
        """Radius of the intrados end of each joint's contact surface [m], joints 0..n."""
        return self._props["r_in"]

    @property
    def contact_outer(self) -> np.ndarray:
        """Radius of the extrados end of each joint's contact surface [m], joints 0..n."""
        return self._props["r_out"]

    @cached_property
    def joint_points(self) -> np.ndarray:
        """(n+1, 2, 2): intrados and extrados ends of each joint's contact surface [m]."""
        r = np.stack([self.contact_inner, self.contact_outer], axis=-1)
        psi = self.joint_angles
        pts = np.stack([r * np.cos(psi)[:, None], r * np.sin(psi)[:, None]], axis=-1)
        pts.setflags(write=False)
        return pts

    # ------------------------------------------------------------------ masonry regions
    @property
    def areas(self) -> np.ndarray:
        """Area of each voussoir [m^2]."""
        return self._props["area"]

    @property
    def area_centroids(self) -> np.ndarray:
        """Centroid of each voussoir's annular sector, shape (n, 2) [m] (exact)."""
        return self._props["centroid"]

    @property
    def area_polar(self) -> np.ndarray:
        """Polar moment of area of each voussoir about its centroid [m^4] (exact)."""
        return self._props["polar"]

    @property
    def size(self) -> float:
        """The mean radius [m]."""
        return float(np.mean(self.radii))

    def outline(self, i: int, points_per_rad: float = 60.0) -> np.ndarray:
        """Boundary polygon of voussoir i: intrados arc from its left joint to its right one,
        then the extrados arc back [m]."""
        psi = self.joint_angles
        m = max(4, int(math.ceil(points_per_rad * self.spans[i])))
        ang = np.linspace(psi[i], psi[i + 1], m)
        ri, ro = self.intrados_radii[i], self.extrados_radii[i]
        inner = np.column_stack([ri * np.cos(ang), ri * np.sin(ang)])
        outer = np.column_stack([ro * np.cos(ang[::-1]), ro * np.sin(ang[::-1])])
        return np.vstack([inner, outer])

    # ------------------------------------------------------------------ transformations
    def mirrored(self) -> "Arch":
        """The mirror image about the vertical axis through O (voussoir order reversed)."""
        n = self.n
        loads = tuple(Load(n - 1 - ld.voussoir, ld.mass, ld.mirrored()) for ld in self.loads)
        return Arch(self.spans[::-1].copy(), self.radii[::-1].copy(), self.thicknesses[::-1].copy(),
                    self.density, name=f"{self.name} (mirrored)", loads=loads, fc=self.fc)

    def scaled(self, factor: float) -> "Arch":
        """The same proportions, every length multiplied by ``factor`` (loads: masses by
        factor^2, like the voussoirs')."""
        f = _check_scalar("factor", factor, 0.0, None, allowed="> 0")
        loads = tuple(Load(ld.voussoir, ld.mass * f * f, (ld.at[0] * f, ld.at[1] * f))
                      for ld in self.loads)
        return Arch(self.spans.copy(), self.radii * f, self.thicknesses * f, self.density,
                    self.name, loads, fc=self.fc)

    def with_thickness_factor(self, factor: float) -> "Arch":
        """Every voussoir thickness multiplied by ``factor`` (radii, spans and loads unchanged)."""
        return Arch(self.spans.copy(), self.radii.copy(), self.thicknesses * factor, self.density,
                    self.name, self.loads, fc=self.fc)

    def is_symmetric(self, tol: float = 1e-12) -> bool:
        """Whether the arch is its own mirror image: spans to ``tol`` rad, radii and thicknesses
        to ``tol`` times the mean radius (relative, so the answer does not depend on units)."""
        m = self.mirrored()
        size = float(np.mean(self.radii))
        return bool(np.allclose(self.spans, m.spans, rtol=0.0, atol=tol)
                    and np.allclose(self.radii, m.radii, rtol=0.0, atol=tol * size)
                    and np.allclose(self.thicknesses, m.thicknesses, rtol=0.0, atol=tol * size)
                    and (not self.loads or super().is_symmetric()))

    # ------------------------------------------------------------------ serialisation
    def to_dict(self) -> dict:
        """The JSON geometry format: voussoirs from the left springing, spans in degrees."""
        return {
            "voussoirs": [
                {"span_deg": math.degrees(a), "radius": float(r), "thickness": float(t)}
                for a, r, t in zip(self.spans, self.radii, self.thicknesses)
            ],
            "density": self.density,
            **({"loads": [ld.to_dict() for ld in self.loads]} if self.loads else {}),
            **self._fc_dict(),
        }

    @classmethod
    def from_dict(cls, data, name: str = "arch") -> "Arch":
        """Build an arch from the JSON geometry format (see :meth:`to_dict`)."""
        if not isinstance(data, dict):
            raise ArchInputError("geometry: expected a JSON object with a 'voussoirs' list")
        vs = data.get("voussoirs")
        if not isinstance(vs, list) or not vs:
            raise ArchInputError("voussoirs: missing or empty; expected a list of "
                                 "{'span_deg', 'radius', 'thickness'} objects")
        spans, radii, thick = [], [], []
        for i, v in enumerate(vs):
            if not isinstance(v, dict):
                raise ArchInputError(f"voussoirs[{i}]: expected an object with span_deg, radius, thickness")
            for key, dest in (("span_deg", spans), ("radius", radii), ("thickness", thick)):
                if key not in v:
                    raise ArchInputError(f"voussoirs[{i}].{key}: missing")
                val = v[key]
                if isinstance(val, bool) or not isinstance(val, (int, float)):
                    raise ArchInputError(f"voussoirs[{i}].{key}: expected a number, got {val!r}")
                # bounded before any arithmetic (a 401-digit int overflows float()); a value
                # <= 0 is left to the arch's own check, which says what the voussoir allows
                field_ = f"voussoirs[{i}].{key}"
                val = _check_scalar(field_, val, allowed="0 < span_deg < 360" if key ==
                                    "span_deg" else "1e-08 m to 1e+08 m")
                if key == "span_deg" and val >= 360.0:
                    raise ArchInputError(f"{field_}: {val:g} deg is out of range; allowed "
                                         f"0 < span_deg < 360")
                dest.append(_check_length(field_, val) if key != "span_deg" and val > 0 else val)
        density = data.get("density", DEFAULT_DENSITY)
        if isinstance(density, bool) or not isinstance(density, (int, float)):
            raise ArchInputError(f"density: expected a number, got {density!r}")
        density = _check_density(density)
        loads = data.get("loads", ())
        if not isinstance(loads, (list, tuple)):
            raise ArchInputError("loads: expected a list of {voussoir, mass, at} objects")
        return cls(np.radians(spans), np.array(radii), np.array(thick), float(density), name=name,
                   loads=tuple(Load.from_dict(ld, i) for i, ld in enumerate(loads)),
                   fc=_file_fc(data))

    def __repr__(self) -> str:
        return (f"Arch(name={self.name!r}, n={self.n}, embrace={math.degrees(self.embrace):.4g} deg, "
                f"R={np.round(self.radii, 4).tolist()}, t={np.round(self.thicknesses, 4).tolist()}"
                + (f", loads={len(self.loads)}" if self.loads else "") + ")")


def nominal_arch(radius: float = 10.0, embrace_deg: float = 157.5, thickness: float = 1.5,
                 voussoirs: int = 7, density: float = DEFAULT_DENSITY, name: str = "nominal") -> Arch:
    """A regular arch: n equal voussoirs of mean radius R [m], thickness t [m], embrace [deg]."""
    radius = _check_scalar("radius", radius, 0.0, None, allowed="> 0 m")
    radius = _check_length("radius", radius)
    embrace_deg = _check_scalar("embrace", embrace_deg, 0.0, 360.0, allowed="0 < embrace < 360 deg")
    thickness = _check_scalar("thickness", thickness, 0.0, 2 * radius,
                              allowed=f"0 < t < 2 R = {2 * radius:g} m")
    thickness = _check_length("thickness", thickness)
    if isinstance(voussoirs, bool) or not isinstance(voussoirs, (int, float, np.integer)) or \
            not math.isfinite(voussoirs) or int(voussoirs) != voussoirs or voussoirs < 3:
        raise ArchInputError(f"voussoirs: {voussoirs!r}; allowed an integer from 3 to "
                             f"{MAX_VOUSSOIRS}")
    n = _check_voussoir_count(int(voussoirs))
    return Arch(np.full(n, math.radians(embrace_deg) / n), np.full(n, radius), np.full(n, thickness),
                density, name=name)


def oppenheim_arch(density: float = DEFAULT_DENSITY) -> Arch:
    """Oppenheim's arch: R = 10 m, embrace 157.5 deg, t = 1.5 m, 7 voussoirs."""
    return nominal_arch(**OPPENHEIM, density=density, name="Oppenheim")


def _check_spread(name: str, value: float, hi: float) -> float:
    return _check_scalar(name, value, 0.0, hi, lo_open=False, hi_open=True, allowed=f"0 <= {name} < {hi:g}")


def perturb_voussoirs(spans0, thick0, radii0, u, spread_span: float, spread_thickness: float,
                      spread_radius: float):
    """Map uniform draws ``u`` (shape (..., 3, n), on [-1, 1]) to (spans, thicknesses, radii),
    each (..., n), around per-voussoir values spans0 [rad], thick0 [m], radii0 [m] (shape (n,)).

    span_i = s0_i (1 + s_a U), t_i = t0_i (1 + s_t U), R_i = R0_i + s_R t0_i U (docs/method.md, Geometry),
    then the spans rescaled to add up to the nominal embrace.  One draw or a batch of draws.
    """
    spans0, thick0, radii0 = (np.asarray(a, float) for a in (spans0, thick0, radii0))
    u = np.asarray(u, float)
    spans = spans0 * (1.0 + spread_span * u[..., 0, :])
    spans = spans * (spans0.sum() / spans.sum(axis=-1, keepdims=True))
    thick = thick0 * (1.0 + spread_thickness * u[..., 1, :])
    radii = radii0 + spread_radius * thick0 * u[..., 2, :]
    return spans, thick, radii


def random_spans_thicknesses_radii(nominal: Arch, u: np.ndarray, spread_span: float,
                                   spread_thickness: float, spread_radius: float):
    """:func:`perturb_voussoirs` around ``nominal``'s own per-voussoir values (so a given arch
    can itself be perturbed); ``u`` of shape (3, n)."""
    return perturb_voussoirs(nominal.spans, nominal.thicknesses, nominal.radii, u, spread_span,
                             spread_thickness, spread_radius)


#: Largest angle [rad] of one polyline segment where a circular arch is written as a polygon
#: (piers beneath it, defects cut into it).
ARC_STEP = 0.002


def polygon_form(arch: VoussoirArch, step: float = ARC_STEP) -> PolygonArch:
    """``arch`` as polygon voussoirs: a :class:`PolygonArch` itself, a circular :class:`Arch`
    with its arcs as polylines of segments at most ``step`` [rad] of turning (at least 8 points
    per arc)."""
    if isinstance(arch, PolygonArch):
        return arch
    if isinstance(arch, Arch):
        per = max(8, int(math.ceil(float(np.max(arch.spans)) / step)) + 1)
        return as_polygon(arch, per)
    raise ArchInputError(f"arch: a {type(arch).__name__}; allowed an Arch or a PolygonArch")

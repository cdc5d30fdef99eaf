"""Arches of any shape: each voussoir a plane region bounded by its intrados and extrados lines
and two straight joint faces.

Voussoir i is given by two polylines ordered from left to right, ``intrados[i]`` and
``extrados[i]`` [m]; its left face is intrados[i][0]-extrados[i][0], its right face
intrados[i][-1]-extrados[i][-1], and its boundary polygon the intrados forward then the
extrados backward (polylines are straight segments).  Joint j (1..n-1) is the overlap of
voussoir j-1's right face and voussoir j's left face, which must lie on one line (tolerance
:data:`FACE_TOLERANCE`); a springing joint is its voussoir's own face.  Mass properties are exact
for the polygon.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property

import numpy as np

from ..errors import ArchInputError
from .base import (DEFAULT_DENSITY, Load, VoussoirArch, _check_density, _check_fc,
                   _check_load_reach, _check_points, _check_scalar, _check_size,
                   _check_voussoir_count, _file_fc, _loads, polygon_properties)

__all__ = ["PolygonArch", "FACE_TOLERANCE", "as_polygon"]

#: Largest distance [m] of a neighbour's face end from the line of the other face (1 mm), and at
#: most 1e-4 of the arch's size for small arches, so the check does not depend on the units.
FACE_TOLERANCE = 1e-3


def _polyline(name: str, values) -> np.ndarray:
    arr = _check_points(name, values)
    if arr.ndim != 2 or arr.shape[1] != 2:
        raise ArchInputError(f"{name}: expected a list of [x, y] points, got shape {arr.shape}")
    if arr.shape[0] < 2:
        raise ArchInputError(f"{name}: {arr.shape[0]} point(s); allowed at least 2")
    if np.any(np.all(np.diff(arr, axis=0) == 0, axis=1)):
        raise ArchInputError(f"{name}: two consecutive points coincide; allowed distinct points")
    arr.setflags(write=False)
    return arr


def _signed_area(poly: np.ndarray) -> float:
    """Signed area of a closed polygon (> 0 counter-clockwise), shifted to its first vertex."""
    p = np.asarray(poly, float) - poly[0]
    q = np.roll(p, -1, axis=0)
    return 0.5 * float(np.sum(p[:, 0] * q[:, 1] - q[:, 0] * p[:, 1]))


def _simple(poly: np.ndarray) -> bool:
    """No two non-adjacent edges of the closed polygon cross (vectorised over blocks of edges:
    the finely sampled voussoirs of the arch families have hundreds of vertices)."""
    p = np.asarray(poly, float)
    m = len(p)
    q = np.roll(p, -1, axis=0)
    idx = np.arange(m)
    for start in range(0, m, 256):
        a = idx[start:start + 256]
        pa, qa = p[a][:, None, :], q[a][:, None, :]
        pb, qb = p[None, :, :], q[None, :, :]

        def orient(u, v, w):
            return (v[..., 0] - u[..., 0]) * (w[..., 1] - u[..., 1]) - \
                (v[..., 1] - u[..., 1]) * (w[..., 0] - u[..., 0])
        cross = (orient(pb, qb, pa) * orient(pb, qb, qa) < 0) & \
            (orient(pa, qa, pb) * orient(pa, qa, qb) < 0)
        # only pairs b >= a + 2, and not the first edge with the closing one (adjacent)
        keep = idx[None, :] >= a[:, None] + 2
        keep &= ~((a[:, None] == 0) & (idx[None, :] == m - 1))
        if np.any(cross & keep):
            return False
    return True


@dataclass(frozen=True, eq=False)
class PolygonArch(VoussoirArch):
    """An arch of any shape (module docstring).  intrados, extrados: one polyline per voussoir
    from the left springing, each a sequence of [x, y] points [m] ordered from left to right;
    density [kg/m^3]; loads: :class:`Load` objects (or their dicts); fc: compressive strength
    [MPa] or None (infinite)."""

    intrados: tuple
    extrados: tuple
    density: float = DEFAULT_DENSITY
    name: str = field(default="arch", compare=False)
    loads: tuple = ()
    fc: float | None = field(default=None, kw_only=True)

    #: The subclass that reads blocks with a ``"kind"`` (:class:`~archrock.geometry.ArchOnPiers`,
    #: which names itself with ``reads_block_kinds=True``: piers sit above this module).
    _block_kinds_reader = None

    def __init_subclass__(cls, reads_block_kinds: bool = False, **kwargs):
        super().__init_subclass__(**kwargs)
        if reads_block_kinds:
            PolygonArch._block_kinds_reader = cls

    def __post_init__(self):
        if not isinstance(self.intrados, (list, tuple)) or not isinstance(self.extrados, (list, tuple)):
            raise ArchInputError("voussoirs: intrados and extrados must be lists of polylines")
        n = len(self.intrados)
        if n < 3:
            raise ArchInputError(f"voussoirs: an arch needs at least 3 voussoirs, got {n}")
        if len(self.extrados) != n:
            raise ArchInputError(f"voussoirs: {n} intrados lines and {len(self.extrados)} extrados "
                                 f"lines; allowed one of each per voussoir")
        intr = tuple(_polyline(f"voussoirs[{i}].intrados", p) for i, p in enumerate(self.intrados))
        extr = tuple(_polyline(f"voussoirs[{i}].extrados", p) for i, p in enumerate(self.extrados))
        object.__setattr__(self, "intrados", intr)
        object.__setattr__(self, "extrados", extr)
        _check_voussoir_count(n)
        pts = np.vstack(intr + extr)
        _check_size("voussoirs: the arch's extent", float(np.max(np.ptp(pts, axis=0))))
        object.__setattr__(self, "density", _check_density(self.density))
        object.__setattr__(self, "fc", _check_fc(self.fc))
        object.__setattr__(self, "loads", _loads(self.loads, n))
        self._check_order()
        for i in range(n):
            poly = self.outline(i)
            if not _simple(poly):
                raise ArchInputError(f"voussoirs[{i}]: its boundary intersects itself; allowed a "
                                     f"simple polygon (intrados and extrados left to right)")
            if self.areas[i] <= 1e-12 * self.size ** 2:
                raise ArchInputError(f"voussoirs[{i}]: zero area; allowed a region of positive area")
            if _signed_area(poly) < 0:
                # walking the intrados from the left springing to the right one, the masonry
                # lies on the left: the boundary (intrados forward, extrados back) turns
                # counter-clockwise.  Clockwise: the extrados was given as the intrados.
                raise ArchInputError(
                    f"voussoirs[{i}]: intrados and extrados swapped (its 'intrados' lies on the "
                    f"outer side of the ring); allowed the intrados on the inner side, both "
                    f"left to right")
        self.joint_points  # checks the faces of neighbours
        _check_load_reach(self.loads, [self.outline(i) for i in range(n)])

    def _check_order(self) -> None:
        """Voussoirs listed from right to left (the list, or the list and each line, reversed):
        the first voussoir's springing lies right of the last one's, or each voussoir's right
        end meets the next one's left end."""
        n = self.n
        first = 0.5 * (self.intrados[0][0] + self.extrados[0][0])
        last = 0.5 * (self.intrados[-1][-1] + self.extrados[-1][-1])
        size = 0.5 * float(np.max(np.ptp(np.vstack(self.intrados + self.extrados), axis=0)))
        # the list reversed, each line left to right: voussoir j's right end at j-1's left end
        gaps_fwd = [np.hypot(*(self.intrados[j][0] - self.intrados[j - 1][-1])) for j in range(1, n)]
        gaps_rev = [np.hypot(*(self.intrados[j][-1] - self.intrados[j - 1][0])) for j in range(1, n)]
        listed_back = max(gaps_rev) < 1e-3 * size < min(gaps_fwd)
        if listed_back or last[0] - first[0] < -1e-9 * size:
            raise ArchInputError(
                f"voussoirs: listed from right to left (voussoir 0 at x = {first[0]:.4g} m, "
                f"voussoir {n - 1} at x = {last[0]:.4g} m); allowed the list from the left "
                f"springing, each intrados and extrados from left to right")

    # ------------------------------------------------------------------ shape
    @property
    def n(self) -> int:
        return len(self.intrados)

    def outline(self, i: int) -> np.ndarray:
        """Boundary polygon of voussoir i: its intrados left to right, its extrados back [m]."""
        return np.vstack([self.intrados[i], self.extrados[i][::-1]])

    @cached_property
    def _regions(self):
        props = [polygon_properties(self.outline(i)) for i in range(self.n)]
        areas = np.array([p[0] for p in props])
        cents = np.array([p[1] for p in props])
        polar = np.array([p[2] for p in props])
        for arr in (areas, cents, polar):
            arr.setflags(write=False)
        return areas, cents, polar

    @property
    def areas(self) -> np.ndarray:
        return self._regions[0]

    @property
    def area_centroids(self) -> np.ndarray:
        return self._regions[1]

    @property
    def area_polar(self) -> np.ndarray:
        return self._regions[2]

    @cached_property
    def size(self) -> float:
        """Half the distance between the mid-points of the springing faces [m] (the radius of a
        semicircle), or half the arch's extent when the springings coincide."""
        a = 0.5 * (self.intrados[0][0] + self.extrados[0][0])
        b = 0.5 * (self.intrados[-1][-1] + self.extrados[-1][-1])
        half = 0.5 * float(np.hypot(*(b - a)))
        if half > 0:
            return half
        pts = np.vstack(self.intrados + self.extrados)
        return 0.5 * float(np.max(np.ptp(pts, axis=0)))

    @cached_property
    def joint_points(self) -> np.ndarray:
        """(n+1, 2, 2) contact segments; checks that neighbours' faces share a line and overlap."""
        n = self.n
        pts = np.empty((n + 1, 2, 2))
        pts[0] = self.intrados[0][0], self.extrados[0][0]
        pts[n] = self.intrados[-1][-1], self.extrados[-1][-1]
        tol = FACE_TOLERANCE * min(1.0, 0.1 * self.size)
        for j in range(1, n):
            a, b = self.intrados[j - 1][-1], self.extrados[j - 1][-1]
            c, d = self.intrados[j][0], self.extrados[j][0]
            ab = b - a
            length = float(np.hypot(*ab))
            if length == 0.0:
                raise ArchInputError(f"joint {j}: the right face of voussoir {j - 1} has zero length")
            u = ab / length
            normal = np.array([-u[1], u[0]])
            off = max(abs(float((c - a) @ normal)), abs(float((d - a) @ normal)))
            if off > tol:
                raise ArchInputError(
                    f"joint {j}: the faces of voussoirs {j - 1} and {j} are not on one line (an end "
                    f"is {off:.4g} m off); allowed at most {tol:.3g} m")
            sc, sd = float((c - a) @ u), float((d - a) @ u)
            if sd <= sc:
                raise ArchInputError(f"joint {j}: the left face of voussoir {j} runs from extrados "
                                     f"to intrados; allowed both faces from intrados to extrados")
            lo, hi = max(0.0, sc), min(length, sd)
            if hi - lo <= 1e-9 * length:
                raise ArchInputError(
                    f"joint {j}: the faces of voussoirs {j - 1} and {j} do not overlap (contact "
                    f"{lo:.4g}..{hi:.4g} m along the face); allowed overlapping faces")
            pts[j] = a + lo * u, a + hi * u
        pts.setflags(write=False)
        return pts

    # ------------------------------------------------------------------ transformations
    def mirrored(self) -> "PolygonArch":
        """The mirror image about x = 0 (voussoir order reversed; lines again left to right)."""
        flip = np.array([-1.0, 1.0])
        intr = tuple((p * flip)[::-1] for p in self.intrados[::-1])
        extr = tuple((p * flip)[::-1] for p in self.extrados[::-1])
        n = self.n
        loads = tuple(Load(n - 1 - ld.voussoir, ld.mass, ld.mirrored()) for ld in self.loads)
        return PolygonArch(intr, extr, self.density, f"{self.name} (mirrored)", loads,
                           fc=self.fc)

    def scaled(self, factor: float) -> "PolygonArch":
        f = _check_scalar("factor", factor, 0.0, None, allowed="> 0")
        loads = tuple(Load(ld.voussoir, ld.mass * f * f, (ld.at[0] * f, ld.at[1] * f))
                      for ld in self.loads)
        return PolygonArch(tuple(p * f for p in self.intrados), tuple(p * f for p in self.extrados),
                           self.density, self.name, loads, fc=self.fc)

    # ------------------------------------------------------------------ serialisation
    def to_dict(self) -> dict:
        """The polygon geometry format (docs/geometry.md)."""
        return {
            "voussoirs": [{"intrados": p.tolist(), "extrados": q.tolist()}
                          for p, q in zip(self.intrados, self.extrados)],
            "density": self.density,
            **({"loads": [ld.to_dict() for ld in self.loads]} if self.loads else {}),
            **self._fc_dict(),
        }

    @classmethod
    def from_dict(cls, data, name: str = "arch") -> "PolygonArch":
        """The polygon geometry format; blocks with a ``"kind"`` (written by an arch on piers)
        give an :class:`~archrock.geometry.ArchOnPiers`."""
        if cls is PolygonArch and isinstance(data, dict) and isinstance(data.get("voussoirs"), list) \
                and any(isinstance(v, dict) and "kind" in v for v in data["voussoirs"]) \
                and PolygonArch._block_kinds_reader is not None:
            return PolygonArch._block_kinds_reader.from_dict(data, name=name)
        intr, extr, density, loads = cls._parse_dict(data)
        return cls(intr, extr, density, name, loads, fc=_file_fc(data))

    @staticmethod
    def _parse_dict(data):
        """(intrados, extrados, density, loads) of the polygon geometry format."""
        if not isinstance(data, dict) or not isinstance(data.get("voussoirs"), list):
            raise ArchInputError("geometry: expected a JSON object with a 'voussoirs' list")
        intr, extr = [], []
        for i, v in enumerate(data["voussoirs"]):
            if not isinstance(v, dict) or "intrados" not in v or "extrados" not in v:
                raise ArchInputError(f"voussoirs[{i}]: expected an object with intrados and "
                                     f"extrados polylines")
            intr.append(v["intrados"])
            extr.append(v["extrados"])
        loads = data.get("loads", ())
        if not isinstance(loads, (list, tuple)):
            raise ArchInputError("loads: expected a list of {voussoir, mass, at} objects")
        return (tuple(intr), tuple(extr), data.get("density", DEFAULT_DENSITY),
                tuple(Load.from_dict(ld, i) for i, ld in enumerate(loads)))

    def __repr__(self) -> str:
        return (f"PolygonArch(name={self.name!r}, n={self.n}, size={self.size:.4g} m"
                + (f", loads={len(self.loads)}" if self.loads else "") + ")")


def as_polygon(arch, points_per_arc: int = 40) -> PolygonArch:
    """A circular :class:`~archrock.geometry.Arch` written as a polygon arch: each voussoir's
    intrados and extrados arcs as polylines of ``points_per_arc`` points (the sector's exact
    area is approached as 1/points^2)."""
    if isinstance(points_per_arc, bool) or int(points_per_arc) != points_per_arc or points_per_arc < 2:
        raise ArchInputError(f"points_per_arc: {points_per_arc!r}; allowed an integer >= 2")
    psi = arch.joint_angles
    intr, extr = [], []
    for i in range(arch.n):
        ang = np.linspace(psi[i], psi[i + 1], int(points_per_arc))
        ri, ro = arch.intrados_radii[i], arch.extrados_radii[i]
        intr.append(np.column_stack([ri * np.cos(ang), ri * np.sin(ang)]))
        extr.append(np.column_stack([ro * np.cos(ang), ro * np.sin(ang)]))
    return PolygonArch(tuple(intr), tuple(extr), arch.density, f"{arch.name} (polygon)", arch.loads,
                       fc=arch.fc)

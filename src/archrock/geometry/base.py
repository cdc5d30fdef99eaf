"""What every arch is, whatever its shape: a chain of n >= 3 rigid voussoirs between two abutments.

Voussoir i (0..n-1, from the left springing) is a plane region; joint j (0..n) is the contact
segment between voussoirs j-1 and j (a springing joint is its voussoir's own face), with an
intrados end and an extrados end, where hinges form.  Downstream (limit analysis, the four-link
model, impacts, plots) uses only this interface (:class:`VoussoirArch`):

* ``joint_points`` (n+1, 2, 2): [joint, edge (0 intrados, 1 extrados), (x, y)] [m];
* ``areas`` [m^2], ``area_centroids`` (n, 2) [m], ``area_polar`` [m^4] of the masonry;
* ``masses`` [kg/m], ``centroids`` (n, 2) [m], ``inertias`` [kg m^2/m]: each voussoir with its
  loads (:class:`Load`, masses rigidly attached to it), as one rigid body;
* ``outline(i)``: the boundary polygon of voussoir i (for figures);
* ``size`` [m]: a length that scales with the arch (nondimensional computations divide by it).

Conventions: x to the right, y up, SI units, masses per metre of arch depth.
"""

from __future__ import annotations

import math
from abc import ABC, abstractmethod
from dataclasses import dataclass, replace
from functools import cached_property

import numpy as np

from ..errors import ArchInputError
from ..units import G

__all__ = ["VoussoirArch", "Load", "polygon_properties", "power_of_two_near", "DEFAULT_DENSITY"]

DEFAULT_DENSITY = 2000.0  # kg/m^3; cancels from multipliers and from the equation of motion
EDGE_NAMES = ("intrados", "extrados")


def _digits(value: int) -> str:
    """'a 401-digit number': a huge int described without writing it out (str() of an int over
    4300 digits raises)."""
    return f"a {int(abs(value).bit_length() * math.log10(2)) + 1}-digit number"


def _finite_array(name: str, values, *, ndim: int = 1) -> np.ndarray:
    try:
        arr = np.asarray(values, dtype=float)
    except OverflowError:  # an int past double precision (a JSON file's 401-digit integer)
        raise ArchInputError(f"{name}: a number too large for double precision; allowed "
                             f"finite numbers") from None
    except (TypeError, ValueError):
        raise ArchInputError(f"{name}: expected numbers, got {values!r}") from None
    if arr.ndim != ndim:
        raise ArchInputError(f"{name}: expected a {ndim}-d list of numbers, got shape {arr.shape}")
    if not np.all(np.isfinite(arr)):
        raise ArchInputError(f"{name}: every value must be a finite number (got NaN or infinity)")
    return arr


def _check_scalar(name: str, value, lo: float | None = None, hi: float | None = None,
                  lo_open: bool = True, hi_open: bool = True, allowed: str = "") -> float:
    if isinstance(value, bool):
        raise ArchInputError(f"{name}: expected a number, got {value!r}")
    try:
        v = float(value)
    except OverflowError:  # an int past double precision, caught before any arithmetic
        raise ArchInputError(f"{name}: {_digits(value)} is out of range; allowed "
                             f"{allowed or 'a finite number'}") from None
    except (TypeError, ValueError):
        raise ArchInputError(f"{name}: expected a number, got {value!r}") from None
    if not math.isfinite(v):
        raise ArchInputError(f"{name}: must be a finite number, got {value!r}")
    bad = (lo is not None and (v <= lo if lo_open else v < lo)) or (
        hi is not None and (v >= hi if hi_open else v > hi))
    if bad:
        raise ArchInputError(f"{name}: {v:g} is out of range; allowed {allowed}")
    return v


#: Most voussoirs of an arch: a limit analysis of 2000 voussoirs takes about 2 s and a response
#: as long; 10^6 ran for minutes and then failed.  No masonry arch has more stones in a ring.
MAX_VOUSSOIRS = 2000
#: Range [m] of the lengths given to describe an arch (radius, span, rise, thickness): the
#: range over which archrock's results are tested scale-free (docs/verification.md, Scale: a
#: micrometre arch with a 0.15 micrometre ring to a 1,000 km one, with a margin of 100);
#: outside it the number is a units slip, and far outside it (1e-300, 1e300) the arithmetic
#: overflows.
MIN_LENGTH_M, MAX_LENGTH_M = 1e-8, 1e8
#: Range [m] of the size of a constructed arch (radii and thicknesses of a circular one, the
#: extent of a polygon one): wider than the inputs' range, so scaled and perturbed arches pass,
#: and well inside what double precision squares and cubes without overflow.
MIN_SIZE_M, MAX_SIZE_M = 1e-9, 1e9
#: Largest |x| or |y| [m] of a point of an arch, an arcade's block or a load: as far from the
#: origin as the largest arch is across, so that squares and cross products stay near 1e18,
#: far from overflow (coordinates of 1e200 overflowed in the arcade's arithmetic).
MAX_COORD_M = MAX_SIZE_M
#: Range of the masonry's density [kg/m^3] (stone is 1,500-3,000; the density cancels from the
#: multipliers, but 1e-300 or 1e300 under- or overflows the masses).
MIN_DENSITY, MAX_DENSITY = 1e-8, 1e8
#: Largest mass of a load given in a file or an option [kg per metre of depth]: a billion
#: tonnes on one metre of arch, more than any fill, pier or tower; past it the number is a slip.
MAX_LOAD_KG = 1e12


def _check_density(value, name: str = "density") -> float:
    """A density [kg/m^3] in [MIN_DENSITY, MAX_DENSITY]."""
    allowed = f"{MIN_DENSITY:g} to {MAX_DENSITY:g} kg/m^3"
    return _check_scalar(name, _check_scalar(name, value, 0.0, None, allowed=f"> 0 kg/m^3, "
                                             f"{allowed}"),
                         MIN_DENSITY, MAX_DENSITY, lo_open=False, hi_open=False, allowed=allowed)


#: Range of the masonry's compressive strength f_c [MPa] (weak brickwork is 2-5 MPa, granite
#: 100-200; below 0.1 MPa no arch stands, above 1000 MPa the answer is Heyman's to 1e-3).
MIN_FC, MAX_FC = 0.1, 1000.0


def _check_fc(value, name: str = "fc") -> float | None:
    """A compressive strength f_c [MPa] in [MIN_FC, MAX_FC], or None (infinite strength)."""
    if value is None:
        return None
    allowed = f"{MIN_FC:g} to {MAX_FC:g} MPa (or none: infinite strength)"
    return _check_scalar(name, value, MIN_FC, MAX_FC, lo_open=False, hi_open=False,
                         allowed=allowed)


def _file_fc(data) -> float | None:
    """The optional ``"fc"`` [MPa] of a geometry file's object, checked."""
    fc = data.get("fc") if isinstance(data, dict) else None
    if fc is not None and (isinstance(fc, bool) or not isinstance(fc, (int, float))):
        raise ArchInputError(f"fc: expected a number (MPa), got {fc!r}")
    return _check_fc(fc)


def _check_points(name: str, values,
                  shape: str = "a list of [x, y] points in metres") -> np.ndarray:
    """Points [m] as a float array, every coordinate finite and within MAX_COORD_M of the
    origin; checked before any arithmetic (an int too large for a double included)."""
    try:
        arr = np.asarray(values, dtype=float)
    except OverflowError:
        raise ArchInputError(f"{name}: a coordinate too large for double precision; allowed "
                             f"|x|, |y| <= {MAX_COORD_M:g} m") from None
    except (TypeError, ValueError):
        raise ArchInputError(f"{name}: expected {shape}") from None
    if not np.all(np.isfinite(arr)):
        raise ArchInputError(f"{name}: every coordinate must be a finite number")
    big = np.abs(arr) > MAX_COORD_M
    if np.any(big):
        raise ArchInputError(f"{name}: coordinate {float(arr[big].flat[0]):g} m is out of range; "
                             f"allowed |x|, |y| <= {MAX_COORD_M:g} m (units? lengths are in "
                             f"metres)")
    return arr


def _check_length(name: str, value, extra: str = "") -> float:
    """A length [m] given to describe an arch, in [MIN_LENGTH_M, MAX_LENGTH_M]."""
    v = _check_scalar(name, value, allowed=f"{MIN_LENGTH_M:g} m to {MAX_LENGTH_M:g} m{extra}")
    if not MIN_LENGTH_M <= v <= MAX_LENGTH_M:
        raise ArchInputError(f"{name}: {v:g} m is out of range; allowed {MIN_LENGTH_M:g} m to "
                             f"{MAX_LENGTH_M:g} m{extra} (units? lengths are in metres)")
    return v


def _check_voussoir_count(n: int, name: str = "voussoirs") -> int:
    if n > MAX_VOUSSOIRS:
        raise ArchInputError(f"{name}: {n}; allowed 3 to {MAX_VOUSSOIRS} (a limit analysis of "
                             f"{MAX_VOUSSOIRS} voussoirs takes seconds; no masonry ring has more)")
    return n


def _check_size(name: str, values) -> None:
    """Lengths of a constructed arch within [MIN_SIZE_M, MAX_SIZE_M]."""
    v = np.abs(np.asarray(values, float))
    bad = (v < MIN_SIZE_M) | (v > MAX_SIZE_M)
    if np.any(bad):
        i = int(np.argmax(bad))
        raise ArchInputError(f"{name}: {float(v.flat[i]):g} m is out of range; allowed "
                             f"{MIN_SIZE_M:g} m to {MAX_SIZE_M:g} m (units? lengths are in metres)")


def _check_point(name: str, value) -> np.ndarray:
    """One point [x, y] [m], bounded as by :func:`_check_points`, as a writable (2,) array."""
    p = np.array(_check_points(name, value, "a point [x, y] in metres"))
    if p.shape != (2,):
        raise ArchInputError(f"{name}: shape {p.shape}; allowed a point [x, y] in metres")
    return p


def power_of_two_near(x):
    """The power of two nearest ``x`` (> 0; a number or an array): nondimensional computations
    divide lengths and masses by it, which is exact, so an arch a power of two larger or smaller
    gives the same numbers bit for bit."""
    out = np.ldexp(1.0, np.round(np.log2(x)).astype(np.int64))
    return float(out) if np.ndim(out) == 0 else out


def polygon_properties(points) -> tuple[float, np.ndarray, float]:
    """(area [m^2], centroid (2,) [m], polar moment of area about the centroid [m^4]) of a simple
    polygon given by its vertices in order (either orientation; not closed)."""
    p = np.asarray(points, float)
    x, y = p[:, 0], p[:, 1]
    x1, y1 = np.roll(x, -1), np.roll(y, -1)
    # shift to the first vertex: the same formulas, far better conditioned for distant polygons
    x0, y0 = x[0], y[0]
    x, y, x1, y1 = x - x0, y - y0, x1 - x0, y1 - y0
    cross = x * y1 - x1 * y
    a = 0.5 * cross.sum()
    if a == 0.0:
        return 0.0, np.array([x0, y0]), 0.0
    cx = ((x + x1) * cross).sum() / (6.0 * a)
    cy = ((y + y1) * cross).sum() / (6.0 * a)
    j0 = (cross * (x * x + x * x1 + x1 * x1 + y * y + y * y1 + y1 * y1)).sum() / 12.0
    area = abs(a)
    polar = abs(j0) - area * (cx * cx + cy * cy)
    return area, np.array([cx + x0, cy + y0]), polar


@dataclass(frozen=True)
class Load:
    """A mass [kg per metre of depth] rigidly attached to voussoir ``voussoir`` at point ``at``
    (x, y) [m]: its weight enters the limit analysis, its horizontal inertia the multiplier, its
    mass and position the equation of motion and the impacts (a point mass: no own inertia)."""

    voussoir: int
    mass: float
    at: tuple[float, float]

    def __post_init__(self):
        if isinstance(self.voussoir, bool) or not isinstance(self.voussoir, (int, np.integer)):
            raise ArchInputError(f"load voussoir: {self.voussoir!r}; allowed an integer index")
        object.__setattr__(self, "voussoir", int(self.voussoir))
        mass = _check_scalar("load mass", self.mass, 0.0, None, lo_open=False,
                             allowed=">= 0 kg per metre of depth")
        object.__setattr__(self, "mass", mass)
        at = _finite_array("load at", self.at)
        if at.shape != (2,):
            raise ArchInputError(f"load at: {self.at!r}; allowed a point [x, y] in metres")
        object.__setattr__(self, "at", (float(at[0]), float(at[1])))

    def to_dict(self) -> dict:
        return {"voussoir": self.voussoir, "mass": self.mass, "at": list(self.at)}

    @classmethod
    def from_dict(cls, data, index: int = 0) -> "Load":
        if not isinstance(data, dict) or set(data) - {"voussoir", "mass", "at"} or not {
                "voussoir", "mass", "at"} <= set(data):
            raise ArchInputError(f"loads[{index}]: expected an object with voussoir, mass, at")
        # a file's numbers are bounded here, at the door (a constructed Load may be heavier:
        # the fill of a large family arch)
        mass = _check_scalar(f"loads[{index}].mass", data["mass"], 0.0, MAX_LOAD_KG,
                             lo_open=False, hi_open=False,
                             allowed=f"0 to {MAX_LOAD_KG:g} kg per metre of depth")
        return cls(data["voussoir"], mass, tuple(_check_point(f"loads[{index}].at", data["at"])))

    def mirrored(self) -> tuple[float, float]:
        return (-self.at[0], self.at[1])


def _loads(loads, n: int) -> tuple:
    out = []
    for i, ld in enumerate(loads or ()):
        ld = ld if isinstance(ld, Load) else Load.from_dict(ld, i)
        if not 0 <= ld.voussoir < n:
            raise ArchInputError(f"loads[{i}].voussoir: {ld.voussoir}; allowed 0..{n - 1} "
                                 f"(the arch has {n} voussoirs)")
        out.append(ld)
    return tuple(out)


#: How far a load's point may lie outside the arch's bounding box, in units of the arch's extent
#: (the box's larger side): beside or below it by LOAD_REACH (a load acts on its voussoir, so its
#: point lies over or near it), above it by LOAD_REACH_ABOVE (a deep fill over a culvert, a pier
#: or a tower on the extrados).  A point tens of metres beside the arch is a slip (another frame,
#: other units), and it left the arch "unable to stand" with no word of why.
LOAD_REACH = 0.5
LOAD_REACH_ABOVE = 5.0


def _check_load_reach(loads, outlines) -> None:
    """Refuse a load whose point lies outside the arch's bounding box (``outlines``: the
    voussoirs' boundary polygons) by more than LOAD_REACH x the extent beside or below it, or
    LOAD_REACH_ABOVE x the extent above it."""
    if not loads:
        return
    pts = np.vstack(outlines)
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    extent = float(np.max(hi - lo))
    for i, ld in enumerate(loads):
        x, y = (float(v) for v in ld.at)
        gaps = (("beside", max(lo[0] - x, x - hi[0]), LOAD_REACH),
                ("below", lo[1] - y, LOAD_REACH), ("above", y - hi[1], LOAD_REACH_ABOVE))
        for where, gap, reach in gaps:
            if gap > reach * extent:
                raise ArchInputError(
                    f"loads[{i}].at: ({x:.4g}, {y:.4g}) m is {gap:.4g} m {where} the arch (x "
                    f"{lo[0]:.4g}..{hi[0]:.4g} m, y {lo[1]:.4g}..{hi[1]:.4g} m, extent "
                    f"{extent:.4g} m); allowed within {reach * extent:.4g} m {where} it (the "
                    f"point where the load acts on its voussoir, in metres, in the geometry's "
                    f"frame)")


class VoussoirArch(ABC):
    """The interface of every arch (module docstring).  Subclasses are frozen dataclasses with
    ``density``, ``name``, ``loads`` and ``fc`` fields and provide the masonry's geometry.

    ``fc``: the masonry's compressive strength [MPa], or None for infinite strength (Heyman's
    no-crushing hypothesis, the default); the depth out of plane is 1 m, so a joint under a
    normal force N [N/m] has a compressed zone N / (f_c * 1 m) deep."""

    #: compressive strength [MPa]; None: infinite (the subclasses' dataclass field)
    fc = None

    def with_fc(self, fc) -> "VoussoirArch":
        """The same arch with compressive strength ``fc`` [MPa] (None: infinite), checked."""
        fc = _check_fc(fc)
        if fc == self.fc:
            return self
        return replace(self, fc=fc)

    def _fc_dict(self) -> dict:
        """{"fc": f_c} for :meth:`to_dict` when the strength is finite, else {} (so that the
        files of arches without it stay as they were, bit for bit)."""
        return {} if self.fc is None else {"fc": self.fc}

    # ------------------------------------------------------------------ provided by the shape
    @property
    @abstractmethod
    def n(self) -> int:
        """Number of voussoirs."""

    @property
    @abstractmethod
    def joint_points(self) -> np.ndarray:
        """(n+1, 2, 2): intrados and extrados ends of each joint's contact segment [m]."""

    @property
    @abstractmethod
    def areas(self) -> np.ndarray:
        """Area of each voussoir [m^2]."""

    @property
    @abstractmethod
    def area_centroids(self) -> np.ndarray:
        """Centroid of each voussoir's region (n, 2) [m]."""

    @property
    @abstractmethod
    def area_polar(self) -> np.ndarray:
        """Polar moment of area of each voussoir about its centroid [m^4]."""

    @abstractmethod
    def outline(self, i: int) -> np.ndarray:
        """Boundary polygon (k, 2) [m] of voussoir i (for figures)."""

    @property
    @abstractmethod
    def size(self) -> float:
        """A length [m] proportional to the arch (the mean radius of a circular arch)."""

    @abstractmethod
    def mirrored(self) -> "VoussoirArch":
        """The mirror image about x = 0 (voussoir order reversed)."""

    @abstractmethod
    def scaled(self, factor: float) -> "VoussoirArch":
        """Every length multiplied by ``factor`` (loads scaled by factor^2: same proportions)."""

    @abstractmethod
    def to_dict(self) -> dict:
        """The JSON geometry format (docs/geometry.md)."""

    # ------------------------------------------------------------------ derived, shared
    @property
    def reference_length(self) -> float:
        """The power of two nearest :attr:`size` [m]: the length that nondimensional
        computations (limit analysis, impact laws) divide by."""
        return power_of_two_near(self.size)

    def joint_point(self, joint: int, edge: str) -> np.ndarray:
        """Coordinates [m] of the intrados or extrados end of a joint's contact segment."""
        if edge not in EDGE_NAMES:
            raise ArchInputError(f"edge: {edge!r}; allowed 'intrados' or 'extrados'")
        if isinstance(joint, bool) or not 0 <= joint <= self.n:
            raise ArchInputError(f"joint: {joint!r}; allowed 0..{self.n}")
        return self.joint_points[int(joint), EDGE_NAMES.index(edge)].copy()

    @cached_property
    def _mass_properties(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        m = self.density * np.asarray(self.areas, float)
        c = np.array(self.area_centroids, float)
        inertia = self.density * np.asarray(self.area_polar, float)
        if not self.loads:
            out = (m.copy(), c, inertia.copy())
        else:
            mm, cc, ii = m.copy(), c.copy(), inertia.copy()
            for i in range(self.n):
                own = [ld for ld in self.loads if ld.voussoir == i and ld.mass > 0]
                if not own:
                    continue
                ms = np.array([m[i]] + [ld.mass for ld in own])
                ps = np.array([c[i]] + [ld.at for ld in own])
                total = ms.sum()
                g = (ms[:, None] * ps).sum(axis=0) / total
                ii[i] = inertia[i] + float((ms * ((ps - g) ** 2).sum(axis=1)).sum())
                mm[i], cc[i] = total, g
            out = (mm, cc, ii)
        for arr in out:
            arr.setflags(write=False)
        return out

    @property
    def masses(self) -> np.ndarray:
        """Mass of each voussoir with its loads [kg per metre of depth]."""
        return self._mass_properties[0]

    @property
    def centroids(self) -> np.ndarray:
        """Mass centre of each voussoir with its loads (n, 2) [m]."""
        return self._mass_properties[1]

    @property
    def inertias(self) -> np.ndarray:
        """Polar moment of inertia of each voussoir with its loads about its mass centre
        [kg m^2 per metre of depth]."""
        return self._mass_properties[2]

    @property
    def weights(self) -> np.ndarray:
        """Weight of each voussoir with its loads [N/m] (g = units.G)."""
        return self.masses * G

    def is_symmetric(self, tol: float = 1e-9) -> bool:
        """Whether the arch equals its mirror image (joint points and mass properties, lengths
        relative to :attr:`size`)."""
        m = self.mirrored()
        s = self.size
        return bool(np.allclose(self.joint_points, m.joint_points, rtol=0, atol=tol * s)
                    and np.allclose(self.centroids, m.centroids, rtol=0, atol=tol * s)
                    and np.allclose(self.masses, m.masses, rtol=tol, atol=0))

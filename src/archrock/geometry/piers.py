"""Arches on piers: rectangular piers under the springings, cut into courses by horizontal bed
joints, and the arch's voussoirs, as one chain of blocks (docs/piers.md).

:func:`with_piers` returns an :class:`ArchOnPiers`, a :class:`PolygonArch` whose blocks are, in
chain order, the left pier's courses from the foundation up (joint 0 is the left foundation),
the arch's voussoirs, and the right pier's courses from the top down (joint n is the right
foundation).  ``block_kinds`` names each block ``"pier"`` or ``"voussoir"``.

Each pier is a rectangle of width W [m], its inner face flush with the intrados springing point
and extending outward, from its top (the springing level) down to its foundation, H [m] lower.
A springing joint that is not horizontal (a segmental arch with radial joints, a horseshoe) is
carried on a horizontal pier top by the wedge between that top (at the lower end of the
springing joint) and the joint, built into the top course (as in
``shared/cases/heavy_piers.json``): the top course's intrados runs up the pier's inner face to
the intrados springing point, its extrados along the outer face, across the pier top and up
(or down) to the extrados springing point.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..errors import ArchInputError
from .base import Load, VoussoirArch, _check_scalar
from .polygon import PolygonArch

__all__ = ["ArchOnPiers", "with_piers", "MAX_COURSES", "BLOCK_KINDS", "MAX_BATTER",
           "joint_place", "hinge_place"]

#: Most courses a pier may be cut into.
MAX_COURSES = 200
#: The kinds of block in an :class:`ArchOnPiers`: a "buttress" is a pier with a battered outer
#: face (wider at its foundation than at its top).
BLOCK_KINDS = ("pier", "voussoir", "buttress")
#: Largest batter (horizontal run of the outer face per unit of height) a pier may have.
MAX_BATTER = 10.0


@dataclass(frozen=True, eq=False)
class ArchOnPiers(PolygonArch):
    """A :class:`PolygonArch` whose blocks are piers or voussoirs: ``block_kinds`` holds one of
    :data:`BLOCK_KINDS` per block, in chain order (empty: all voussoirs)."""

    block_kinds: tuple = field(default=(), compare=False)

    def __post_init__(self):
        super().__post_init__()
        kinds = tuple(self.block_kinds)
        if kinds and len(kinds) != self.n:
            raise ArchInputError(f"block_kinds: {len(kinds)} kinds for {self.n} blocks; allowed "
                                 f"one per block")
        for i, k in enumerate(kinds):
            if k not in BLOCK_KINDS:
                raise ArchInputError(f"block_kinds[{i}]: {k!r}; allowed {', '.join(BLOCK_KINDS)}")
        object.__setattr__(self, "block_kinds", kinds or ("voussoir",) * self.n)

    @property
    def pier_blocks(self) -> tuple:
        """Indices of the blocks that are not voussoirs (piers and buttresses)."""
        return tuple(i for i, k in enumerate(self.block_kinds) if k != "voussoir")

    def to_dict(self) -> dict:
        """The polygon geometry format with ``"kind"`` per block; :func:`archrock.geometry.
        arch_from_dict` reads it back as an :class:`ArchOnPiers`, the same to the bit."""
        data = super().to_dict()
        for v, k in zip(data["voussoirs"], self.block_kinds):
            v["kind"] = k
        return data

    @classmethod
    def from_dict(cls, data, name: str = "arch") -> "ArchOnPiers":
        """The polygon format with an optional ``"kind"`` per block (:data:`BLOCK_KINDS`; a
        block without one is a voussoir).  A kind not in the list is refused by name."""
        intr, extr, density, loads = cls._parse_dict(data)
        kinds = []
        for i, v in enumerate(data["voussoirs"]):
            k = v.get("kind", "voussoir")
            if not isinstance(k, str) or k not in BLOCK_KINDS:
                raise ArchInputError(f"voussoirs[{i}].kind: {k!r}; allowed "
                                     f"{', '.join(BLOCK_KINDS)}")
            kinds.append(k)
        return cls(intr, extr, density, name, loads, block_kinds=tuple(kinds))

    def mirrored(self) -> "ArchOnPiers":
        """The mirror image about x = 0, block kinds in the new order."""
        m = super().mirrored()
        return ArchOnPiers(m.intrados, m.extrados, m.density, m.name, m.loads,
                           block_kinds=self.block_kinds[::-1])

    def scaled(self, factor: float) -> "ArchOnPiers":
        m = super().scaled(factor)
        return ArchOnPiers(m.intrados, m.extrados, m.density, m.name, m.loads,
                           block_kinds=self.block_kinds)

    @property
    def piers(self) -> tuple:
        """(left, right): the block indices of the leading and trailing runs of pier or
        buttress blocks, in chain order (empty where that side has none)."""
        kinds = self.block_kinds
        left = []
        for i, k in enumerate(kinds):
            if k == "voussoir":
                break
            left.append(i)
        right = []
        for i in range(self.n - 1, len(left) - 1, -1):
            if kinds[i] == "voussoir":
                break
            right.append(i)
        return tuple(left), tuple(sorted(right))

    def __repr__(self) -> str:
        return (f"ArchOnPiers(name={self.name!r}, n={self.n}, piers={len(self.pier_blocks)} "
                f"blocks, size={self.size:.4g} m" + (f", loads={len(self.loads)}" if self.loads
                                                    else "") + ")")


def _length(name: str, value, hi: float) -> float:
    if isinstance(value, str):
        raise ArchInputError(f"{name}: expected a number in metres, got {value!r}")
    return _check_scalar(name, value, 0.0, hi, hi_open=False,
                         allowed=f"> 0 m, at most 100 times the arch's extent ({hi:.4g} m)")


def _courses(name: str, value) -> int:
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)):
        if not (isinstance(value, float) and value.is_integer()):
            raise ArchInputError(f"{name}: {value!r}; allowed an integer, 1 to {MAX_COURSES}")
    v = int(value)
    if not 1 <= v <= MAX_COURSES:
        raise ArchInputError(f"{name}: {v} is out of range; allowed an integer, 1 to {MAX_COURSES}")
    return v


def _dedupe(points, tol: float) -> np.ndarray:
    p = np.asarray(points, float)
    keep = [0]
    for k in range(1, len(p)):
        if np.hypot(*(p[k] - p[keep[-1]])) > tol:
            keep.append(k)
    out = p[keep]
    out[-1] = p[-1]  # the end points are the faces' ends: kept exactly
    return out


def _batter(name: str, value) -> float:
    if isinstance(value, (str, bool)):
        raise ArchInputError(f"{name}: expected a number (horizontal run per unit height), got "
                             f"{value!r}")
    return _check_scalar(name, value, 0.0, MAX_BATTER, lo_open=False, hi_open=False,
                         allowed=f"0 <= batter <= {MAX_BATTER:g} (horizontal run of the outer "
                                 f"face per unit of height; 0: a rectangular pier)")


def _left_pier(p_in, p_out, height: float, width: float, courses: int, side: str, tol: float,
               batter: float = 0.0):
    """The courses of a pier under a left springing joint p_in (intrados) - p_out (extrados),
    from the foundation up: a list of (intrados, extrados) polylines.  ``batter``: the outer
    face runs outward by ``batter`` per unit of depth below the pier top (width at the
    foundation W + batter H)."""
    xi, yi = float(p_in[0]), float(p_in[1])
    xe, ye = float(p_out[0]), float(p_out[1])
    reach = xi - xe
    if reach <= tol:
        raise ArchInputError(
            f"{side} springing: its extrados end is not outward of its intrados end (x = {xe:.4g} "
            f"and {xi:.4g} m); allowed a springing joint whose extrados lies outward, to carry "
            f"on a pier")
    if width < reach - tol:
        raise ArchInputError(
            f"width: {width:g} m is narrower than the {side} springing joint ({reach:.4g} m "
            f"wide); allowed a pier at least as wide as the springing it carries")
    top = min(yi, ye)
    foot = top - height
    levels = foot + height * np.arange(courses + 1) / courses
    levels[-1] = top
    xo = xi - width

    def outer(y):
        # the rectangular pier's outer face exactly as before a batter existed (bit for bit)
        return xo if batter == 0.0 else xo - batter * (top - y)
    blocks = []
    for c in range(courses):
        lo, hi = levels[c], levels[c + 1]
        if c < courses - 1 or abs(ye - yi) <= tol:
            intr = [(xi, lo), (xi, hi)]
            extr = [(outer(lo), lo), (outer(hi), hi)]
        else:  # the springing wedge on the top course
            intr = _dedupe([(xi, lo), (xi, top), (xi, yi)], tol)
            extr = _dedupe([(outer(lo), lo), (xo, top), (xe, top), (xe, ye)], tol)
        blocks.append((np.asarray(intr, float), np.asarray(extr, float)))
    return blocks


def _polygon_of(arch: VoussoirArch) -> PolygonArch:
    from .defect import _as_polygon

    return _as_polygon(arch)


def with_piers(arch: VoussoirArch, height: float, width: float, *, courses: int = 1,
               height_right: float | None = None, width_right: float | None = None,
               courses_right: int | None = None, batter: float = 0.0,
               batter_right: float | None = None, name: str | None = None,
               _trusted: bool = False) -> ArchOnPiers:
    """``arch`` on two rectangular piers (module docstring): ``height`` H [m] from the
    foundation to the springing, ``width`` W [m] outward of the intrados springing point (at
    the pier top), ``courses`` blocks each (equal heights, horizontal bed joints); the right
    pier takes ``height_right``, ``width_right``, ``courses_right``, ``batter_right`` when
    given (default: the left one's).  ``batter`` b >= 0: the outer face is battered, running
    outward b per unit of depth (the foundation W + b H wide: a buttress, its blocks of kind
    "buttress"); b = 0 is the rectangular pier, bit for bit.  Loads keep their voussoir
    (renumbered past the left pier's courses)."""
    if not isinstance(arch, VoussoirArch):
        raise ArchInputError(f"arch: expected an archrock arch (Arch or PolygonArch), got "
                             f"{type(arch).__name__}")
    if isinstance(arch, ArchOnPiers) and arch.pier_blocks:
        raise ArchInputError("arch: already on piers; allowed an arch without piers")
    poly = _polygon_of(arch)
    pts = np.vstack(poly.intrados + poly.extrados)
    extent = float(np.max(np.ptp(pts, axis=0)))
    hi = 100.0 * extent
    hl = _length("height", height, hi)
    wl = _length("width", width, hi)
    cl = _courses("courses", courses)
    hr = hl if height_right is None else _length("height_right", height_right, hi)
    wr = wl if width_right is None else _length("width_right", width_right, hi)
    cr = cl if courses_right is None else _courses("courses_right", courses_right)
    bl = _batter("batter", batter)
    br = bl if batter_right is None else _batter("batter_right", batter_right)
    tol = 1e-9 * max(extent, hl, hr, wl, wr)

    jp = poly.joint_points
    left = _left_pier(jp[0][0], jp[0][1], hl, wl, cl, "left", tol, bl)
    flip = np.array([-1.0, 1.0])
    try:
        right_m = _left_pier(jp[-1][0] * flip, jp[-1][1] * flip, hr, wr, cr, "right", tol, br)
    except ArchInputError as exc:
        msg = str(exc)
        if msg.startswith("width:"):
            msg = "width_right:" + msg[len("width:"):]
        raise ArchInputError(msg) from None
    # the mirror image of a left pier, foundation up, is the right pier top down
    right = [((i * flip)[::-1], (e * flip)[::-1]) for i, e in reversed(right_m)]

    intr = tuple(b[0] for b in left) + tuple(poly.intrados) + tuple(b[0] for b in right)
    extr = tuple(b[1] for b in left) + tuple(poly.extrados) + tuple(b[1] for b in right)
    kinds = (("buttress" if bl > 0 else "pier"),) * cl + ("voussoir",) * poly.n + \
        (("buttress" if br > 0 else "pier"),) * cr
    loads = tuple(Load(ld.voussoir + cl, ld.mass, ld.at) for ld in poly.loads)
    name = name or f"{arch.name} on piers"
    if _trusted and isinstance(arch, PolygonArch):
        return _unchecked(intr, extr, poly.density, name, loads, kinds)
    return ArchOnPiers(intr, extr, poly.density, name, loads, block_kinds=kinds)


def _unchecked(intr, extr, density, name, loads, kinds) -> ArchOnPiers:
    """An ArchOnPiers without the polygon checks of PolygonArch (each block a simple polygon of
    positive area, ...), for searches that rebuild the piers many times under voussoirs already
    checked (a validated PolygonArch): the pier blocks are rectangles or trapezoids by
    construction.  The joints are still checked when first used (``joint_points``)."""
    a = object.__new__(ArchOnPiers)
    ro = []
    for p in intr + extr:
        p = np.asarray(p, float)
        if p.flags.writeable:
            p = p.copy()
            p.setflags(write=False)
        ro.append(p)
    n = len(intr)
    for key, value in (("intrados", tuple(ro[:n])), ("extrados", tuple(ro[n:])),
                       ("density", float(density)), ("name", name), ("loads", tuple(loads)),
                       ("block_kinds", tuple(kinds))):
        object.__setattr__(a, key, value)
    return a


def joint_place(arch, j: int) -> str:
    """Where joint ``j`` of ``arch`` is, in words a user finds on the drawing: "left pier
    foot", "left pier bed joint 2" (counted from the foot up), "left springing (pier top)",
    "arch joint 3" (the arch's own numbering, from its left springing), ...; "joint j" for an
    arch without piers."""
    j = int(j)
    if not isinstance(arch, ArchOnPiers) or not arch.pier_blocks:
        return f"joint {j}"
    left, right = arch.piers
    n, cl, cr = arch.n, len(left), len(right)
    kl = arch.block_kinds[0] if cl else ""
    kr = arch.block_kinds[-1] if cr else ""
    if cl and j == 0:
        return f"left {kl} foot"
    if cl and j < cl:
        return f"left {kl} bed joint {j}"
    if cl and j == cl:
        return f"left springing ({kl} top)"
    if cr and j == n:
        return f"right {kr} foot"
    if cr and j > n - cr:
        return f"right {kr} bed joint {n - j}"
    if cr and j == n - cr:
        return f"right springing ({kr} top)"
    return f"arch joint {j - cl}"


def hinge_place(arch, joint: int, edge: str) -> str:
    """:func:`joint_place` and the end of the joint: a pier's "inner face" (towards the
    opening) or "outer face", an arch joint's "intrados" or "extrados"; e.g. "left pier foot,
    outer face"."""
    where = joint_place(arch, joint)
    if isinstance(arch, ArchOnPiers) and arch.pier_blocks:
        left, right = arch.piers
        if joint < len(left) or joint > arch.n - len(right):
            return f"{where}, {'inner' if edge == 'intrados' else 'outer'} face"
    return f"{where}, {edge}"

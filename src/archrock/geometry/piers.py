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
``tests/data/heavy_piers.json``): the top course's intrados runs up the pier's inner face to
the intrados springing point, its extrados along the outer face, across the pier top and up
(or down) to the extrados springing point.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..errors import ArchInputError
from .base import Load, VoussoirArch, _check_scalar, _file_fc
from .circular import polygon_form
from .polygon import PolygonArch, _signed_area, _simple

__all__ = ["ArchOnPiers", "with_piers", "MAX_COURSES", "BLOCK_KINDS", "MAX_BATTER",
           "joint_place", "hinge_place", "lean_pier", "reshape_piers", "pier_sizes", "MAX_LEAN",
           "parse_steps", "arch_without_piers"]

#: Most courses a pier may be cut into.
MAX_COURSES = 200
#: The kinds of block in an :class:`ArchOnPiers`: a "buttress" is a pier with a battered outer
#: face (wider at its foundation than at its top).
BLOCK_KINDS = ("pier", "voussoir", "buttress")
#: Largest batter (horizontal run of the outer face per unit of height) a pier may have.
MAX_BATTER = 10.0
#: Largest lean [deg] of a pier out of plumb (a tilt defect, a sampled lean).
MAX_LEAN = 15.0


@dataclass(frozen=True, eq=False)
class ArchOnPiers(PolygonArch, reads_block_kinds=True):
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
        return cls(intr, extr, density, name, loads, fc=_file_fc(data), block_kinds=tuple(kinds))

    def mirrored(self) -> "ArchOnPiers":
        """The mirror image about x = 0, block kinds in the new order."""
        m = super().mirrored()
        return ArchOnPiers(m.intrados, m.extrados, m.density, m.name, m.loads, fc=m.fc,
                           block_kinds=self.block_kinds[::-1])

    def scaled(self, factor: float) -> "ArchOnPiers":
        m = super().scaled(factor)
        return ArchOnPiers(m.intrados, m.extrados, m.density, m.name, m.loads, fc=m.fc,
                           block_kinds=self.block_kinds)

    @property
    def piers(self) -> tuple:
        """(left, right): the block indices of the leading and trailing runs of pier or
        buttress blocks, in chain order (empty where that side has none)."""
        return _pier_runs(self.block_kinds)

    def __repr__(self) -> str:
        return (f"ArchOnPiers(name={self.name!r}, n={self.n}, piers={len(self.pier_blocks)} "
                f"blocks, size={self.size:.4g} m" + (f", loads={len(self.loads)}" if self.loads
                                                    else "") + ")")


def _pier_runs(kinds) -> tuple:
    """(left, right) block indices of the leading and trailing runs of non-voussoir kinds."""
    left = []
    for i, k in enumerate(kinds):
        if k == "voussoir":
            break
        left.append(i)
    right = []
    for i in range(len(kinds) - 1, len(left) - 1, -1):
        if kinds[i] == "voussoir":
            break
        right.append(i)
    return tuple(left), tuple(sorted(right))


def _length(name: str, value, hi: float) -> float:
    if isinstance(value, str):
        raise ArchInputError(f"{name}: expected a number in metres, got {value!r}")
    # at least a millionth of the arch's extent: a pier of 1e-300 m left a voussoir's outline
    # with one point, and a message that named neither the flag nor the range
    v = _check_scalar(name, value, 0.0, hi, hi_open=False,
                      allowed=f"> 0 m, at most 100 times the arch's extent ({hi:.4g} m)")
    lo = hi * 1e-8
    if v < lo:
        raise ArchInputError(f"{name}: {v:g} m is out of range; allowed {lo:.4g} m (a millionth "
                             f"of the arch's extent) to {hi:.4g} m (100 times it)")
    return v


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
               batter: float = 0.0, steps=None):
    """The courses of a pier under a left springing joint p_in (intrados) - p_out (extrados),
    from the foundation up: a list of (intrados, extrados) polylines.  ``batter``: the outer
    face runs outward by ``batter`` per unit of depth below the pier top (width at the
    foundation W + batter H).  ``steps``: ((h, w), ...) from the foot up, one block per step
    (a stepped buttress; ``height``, ``width`` and ``courses`` are then the steps' total, the
    top step's width and their number)."""
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
    if steps is None:
        levels = foot + height * np.arange(courses + 1) / courses
        step_x = None
    else:  # a stepped buttress: a bed joint at every step, each step its own width
        levels = foot + np.concatenate([[0.0], np.cumsum([h for h, _ in steps])])
        step_x = [xi - w for _, w in steps]
    levels[-1] = top
    xo = xi - width

    def outer(y, c):
        if step_x is not None:
            return step_x[c]
        # the rectangular pier's outer face exactly as before a batter existed (bit for bit)
        return xo if batter == 0.0 else xo - batter * (top - y)
    blocks = []
    for c in range(courses):
        lo, hi = levels[c], levels[c + 1]
        if c < courses - 1 or abs(ye - yi) <= tol:
            intr = [(xi, lo), (xi, hi)]
            extr = [(outer(lo, c), lo), (outer(hi, c), hi)]
        else:  # the springing wedge on the top course
            intr = _dedupe([(xi, lo), (xi, top), (xi, yi)], tol)
            extr = _dedupe([(outer(lo, c), lo), (xo, top), (xe, top), (xe, ye)], tol)
        blocks.append((np.asarray(intr, float), np.asarray(extr, float)))
    return blocks


def _steps(name: str, value, hi: float) -> tuple:
    """Checked stepped-buttress steps: ((height, width), ...) from the foot up, widths that do
    not grow upward."""
    if isinstance(value, (str, bytes)) or not hasattr(value, "__len__") or not \
            1 <= len(value) <= MAX_COURSES:
        raise ArchInputError(f"{name}: {value!r}; allowed 1 to {MAX_COURSES} (height, width) "
                             f"pairs in metres, from the foot up")
    out = []
    for k, st in enumerate(value):
        if isinstance(st, (str, bytes)) or not hasattr(st, "__len__") or len(st) != 2:
            raise ArchInputError(f"{name}[{k}]: {st!r}; allowed a (height, width) pair in metres")
        h = _length(f"{name}[{k}] height", st[0], hi)
        w = _length(f"{name}[{k}] width", st[1], hi)
        if out and w > out[-1][1]:
            raise ArchInputError(f"{name}[{k}]: width {w:g} m is wider than the step below "
                                 f"({out[-1][1]:g} m); allowed widths that do not grow upward "
                                 f"(the outer face steps inward)")
        out.append((h, w))
    return tuple(out)


def _polygon_of(arch: VoussoirArch) -> PolygonArch:
    return polygon_form(arch)


def with_piers(arch: VoussoirArch, height: float, width: float, *, courses: int = 1,
               height_right: float | None = None, width_right: float | None = None,
               courses_right: int | None = None, batter: float = 0.0,
               batter_right: float | None = None, steps=None, steps_right=None,
               name: str | None = None, _trusted: bool = False) -> ArchOnPiers:
    """``arch`` on two rectangular piers (module docstring): ``height`` H [m] from the
    foundation to the springing, ``width`` W [m] outward of the intrados springing point (at
    the pier top), ``courses`` blocks each (equal heights, horizontal bed joints); the right
    pier takes ``height_right``, ``width_right``, ``courses_right``, ``batter_right`` when
    given (default: the left one's).  ``batter`` b >= 0: the outer face is battered, running
    outward b per unit of depth (the foundation W + b H wide: a buttress, its blocks of kind
    "buttress"); b = 0 is the rectangular pier, bit for bit.  ``steps`` ((h, w), ...) from the
    foot up: a stepped buttress, one block per step, w measured outward of the intrados
    springing point and not growing upward (``height`` and ``width`` then None; one step is
    the monolithic rectangle); ``steps_right`` the right one's (default: ``steps`` where the
    left is stepped and no right height or width is given).  Loads keep their voussoir
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
    sl = sr = None
    if steps is not None:
        sl = _steps("steps", steps, hi)
        for what, v, dflt in (("height", height, None), ("width", width, None),
                              ("courses", courses, 1), ("batter", batter, 0.0)):
            if v is not dflt and v != dflt:
                raise ArchInputError(f"{what}: {v!r} given with steps; allowed {dflt} (the "
                                     f"steps give the stepped pier's {what})")
        height, width, courses = sum(h for h, _ in sl), sl[-1][1], len(sl)
        if steps_right is None and height_right is None and width_right is None:
            steps_right = sl
    if steps_right is not None:
        sr = _steps("steps_right", steps_right, hi)
        for what, v in (("height_right", height_right), ("width_right", width_right),
                        ("courses_right", courses_right), ("batter_right", batter_right)):
            if v is not None:
                raise ArchInputError(f"{what}: {v!r} given with steps_right; allowed None (the "
                                     f"steps give it)")
        height_right, width_right = sum(h for h, _ in sr), sr[-1][1]
        courses_right, batter_right = len(sr), 0.0
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
    left = _left_pier(jp[0][0], jp[0][1], hl, wl, cl, "left", tol, bl, sl)
    flip = np.array([-1.0, 1.0])
    try:
        right_m = _left_pier(jp[-1][0] * flip, jp[-1][1] * flip, hr, wr, cr, "right", tol, br,
                             sr)
    except ArchInputError as exc:
        msg = str(exc)
        if msg.startswith("width:"):
            msg = "width_right:" + msg[len("width:"):]
        raise ArchInputError(msg) from None
    # the mirror image of a left pier, foundation up, is the right pier top down
    right = [((i * flip)[::-1], (e * flip)[::-1]) for i, e in reversed(right_m)]

    intr = tuple(b[0] for b in left) + tuple(poly.intrados) + tuple(b[0] for b in right)
    extr = tuple(b[1] for b in left) + tuple(poly.extrados) + tuple(b[1] for b in right)
    def kind(b, st):  # a stepped pier of one width throughout is a rectangular pier
        return "buttress" if b > 0 or (st is not None and st[0][1] != st[-1][1]) else "pier"
    kinds = (kind(bl, sl),) * cl + ("voussoir",) * poly.n + (kind(br, sr),) * cr
    loads = tuple(Load(ld.voussoir + cl, ld.mass, ld.at) for ld in poly.loads)
    name = name or f"{arch.name} on piers"
    if _trusted and isinstance(arch, PolygonArch):
        return _unchecked(intr, extr, poly.density, name, loads, kinds, poly.fc)
    return ArchOnPiers(intr, extr, poly.density, name, loads, fc=poly.fc, block_kinds=kinds)


def _unchecked(intr, extr, density, name, loads, kinds, fc=None) -> ArchOnPiers:
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
                       ("block_kinds", tuple(kinds)), ("fc", fc)):
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


# ---------------------------------------------------------------------------- irregular piers
_FLIP = np.array([-1.0, 1.0])


def _mirror(intr, extr, loads, n):
    """Polylines and loads mirrored about x = 0 (block order reversed), as PolygonArch.mirrored
    does: exact, so mirroring twice gives the same floats."""
    mi = [(p * _FLIP)[::-1] for p in intr[::-1]]
    me = [(p * _FLIP)[::-1] for p in extr[::-1]]
    ml = [Load(n - 1 - ld.voussoir, ld.mass, (-ld.at[0], ld.at[1])) for ld in loads]
    return mi, me, ml


def _face_fractions(line: np.ndarray) -> np.ndarray:
    s = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(line, axis=0).T))])
    return s / s[-1]


def _reshape_left(intr, extr, loads, cl, cr, *, width=1.0, height=1.0, shifts=None, lean=0.0,
                  side="left"):
    """The left pier (blocks 0..cl-1) of the chain in the lists ``intr``, ``extr`` changed in
    place: its bed joints moved by ``shifts`` [m] (the interior ones, foot up), its height
    scaled by ``height`` about its top (the foundation moves), its width by ``width`` about
    each course's inner face (the outer face moves), then the pier turned by ``lean`` [deg]
    outward (counter-clockwise here) as a rigid body about its outer foot corner, the
    voussoirs following (docs/piers.md, Irregular piers).  Returns the new loads."""
    n = len(intr)
    top = min(float(intr[cl][0][1]), float(extr[cl][0][1]))
    scale = float(np.max(np.ptp(np.vstack(intr + extr), axis=0)))
    tol = 1e-9 * scale
    levels = np.array([float(intr[k][0][1]) for k in range(cl)] + [top])
    for k in range(cl):
        if abs(float(extr[k][0][1]) - levels[k]) > tol:
            raise ArchInputError(f"{side} pier: bed joint {k} is not horizontal; allowed piers "
                                 f"with horizontal bed joints for a changed pier")
    new = levels.copy()
    if shifts is not None and cl > 1:
        new[1:-1] = levels[1:-1] + np.asarray(shifts, float)
        if np.any(np.diff(new) <= tol):
            raise ArchInputError(f"{side} pier: its bed joints cross (course shifts "
                                 f"{np.round(shifts, 6).tolist()} m); allowed shifts that keep "
                                 f"the courses in order")
    move_y = shifts is not None or height != 1.0
    xe = float(extr[cl][0][0])
    for k in range(cl):
        x_in = float(intr[k][0][0])
        for lines, outer in ((intr, False), (extr, True)):
            p = np.array(lines[k], float)
            y = p[:, 1]
            below = y <= top
            if move_y:
                yy = np.interp(y, levels, new) if shifts is not None else y
                if height != 1.0:
                    yy = top - (top - yy) * height
                p[:, 1] = np.where(below, yy, y)
            if outer and width != 1.0:
                keep = (k == cl - 1) & (y >= top - tol) & (p[:, 0] >= xe - tol)
                p[:, 0] = np.where(keep, p[:, 0], x_in - (x_in - p[:, 0]) * width)
                if k == cl - 1 and np.any(p[~keep & (y >= top - tol), 0] > xe + tol):
                    raise ArchInputError(f"{side} pier: narrower than its springing joint "
                                         f"(width factor {width:.6g}); allowed a pier at least "
                                         f"as wide as the springing it carries")
            lines[k] = p
    if lean == 0.0:
        return loads
    th = np.deg2rad(lean)
    rot = np.array([[np.cos(th), -np.sin(th)], [np.sin(th), np.cos(th)]])
    c = np.array(extr[0][0], float)

    def rigid(p):
        return c + (p - c) @ rot.T
    for k in range(cl):
        intr[k], extr[k] = rigid(intr[k]), rigid(extr[k])
    # the voussoirs follow: the pier top's rigid motion, fading along the arch (by the mean
    # face length) to nothing at the far springing, so the arch stays closed, joints straight
    vous = range(cl, n - cr)
    ell = np.array([0.5 * (np.sum(np.hypot(*np.diff(intr[i], axis=0).T)) +
                           np.sum(np.hypot(*np.diff(extr[i], axis=0).T))) for i in vous])
    cum = np.concatenate([[0.0], np.cumsum(ell)])
    wj = 1.0 - cum / cum[-1]
    wj[0], wj[-1] = 1.0, 0.0

    def follow(p, w):
        r = rigid(p)
        out = p + w[:, None] * (r - p)
        out[w == 1.0] = r[w == 1.0]
        out[w == 0.0] = p[w == 0.0]
        return out
    for m, i in enumerate(vous):
        for lines in (intr, extr):
            s = _face_fractions(lines[i])
            w = wj[m] + (wj[m + 1] - wj[m]) * s
            w[0], w[-1] = wj[m], wj[m + 1]
            lines[i] = follow(np.asarray(lines[i], float), w)
    out = []
    for ld in loads:
        at = np.array(ld.at, float)[None, :]
        if ld.voussoir < cl:
            at = rigid(at)
        elif ld.voussoir < n - cr:
            m = ld.voussoir - cl
            at = follow(at, np.array([0.5 * (wj[m] + wj[m + 1])]))
        out.append(Load(ld.voussoir, ld.mass, (float(at[0, 0]), float(at[0, 1]))))
    return out


def _check_lean(name: str, value) -> float:
    if isinstance(value, (str, bool)):
        raise ArchInputError(f"{name}: expected an angle in degrees, got {value!r}")
    return _check_scalar(name, value, -MAX_LEAN, MAX_LEAN, lo_open=False, hi_open=False,
                         allowed=f"-{MAX_LEAN:g} <= lean <= {MAX_LEAN:g} degrees (outward "
                                 f"positive: the pier top moves away from the opening)")


def reshape_piers(arch, kinds, left: dict | None = None, right: dict | None = None,
                  name: str | None = None, _trusted: bool = False) -> ArchOnPiers:
    """``arch`` (a polygon arch whose blocks have the ``kinds``, e.g. an ArchOnPiers or a
    sample drawn around one) with its piers changed: ``left`` / ``right`` dicts of
    ``width`` and ``height`` factors, ``shifts`` (the interior bed joints' moves [m], foot up)
    and ``lean`` [deg, outward positive] (docs/piers.md, Irregular piers).  Applied to the
    left pier, then to the right one (in the mirror image); an empty change leaves a side
    as it was, to the bit.  ``_trusted`` (the sampler, ``arch`` a checked polygon arch): only
    the changed piers' blocks are checked as polygons (the voussoirs, moved by a lean's
    near-rigid map, are not checked again: a draw with a 0.8 m voussoir would need to turn
    it by far more than the 15 degrees allowed to fold it)."""
    if len(kinds) != arch.n:
        raise ArchInputError(f"kinds: {len(kinds)} for {arch.n} blocks; allowed one per block")
    lrun, rrun = _pier_runs(kinds)
    cl, cr, n = len(lrun), len(rrun), arch.n
    intr, extr, loads = list(arch.intrados), list(arch.extrados), list(arch.loads)
    for side, change, run in (("left", left, cl), ("right", right, cr)):
        change = _check_change(side, change, run)
        if not change or all(change.get(k, d) == d for k, d in
                             (("width", 1.0), ("height", 1.0), ("lean", 0.0))) \
                and change.get("shifts") is None:
            continue
        if not run:
            raise ArchInputError(f"{side} pier: the arch has none; allowed a change of a pier "
                                 f"the arch stands on")
        if side == "right":
            intr, extr, loads = _mirror(intr, extr, loads, n)
        loads = _reshape_left(intr, extr, loads, run, cl if side == "right" else cr,
                              side=side, **change)
        if side == "right":
            intr, extr, loads = _mirror(intr, extr, loads, n)
    if _trusted and isinstance(arch, PolygonArch):
        for i in lrun + rrun:  # each pier block: a simple polygon of positive area
            poly = np.vstack([intr[i], extr[i][::-1]])
            if not _simple(poly) or _signed_area(poly) <= 1e-12 * arch.size ** 2:
                raise ArchInputError(f"voussoirs[{i}]: the changed pier block is not a simple "
                                     f"polygon of positive area")
        return _unchecked(intr, extr, arch.density, name or arch.name, loads, kinds, arch.fc)
    return ArchOnPiers(tuple(intr), tuple(extr), arch.density, name or arch.name, tuple(loads),
                       fc=arch.fc, block_kinds=tuple(kinds))


def _check_change(side: str, change, run) -> dict:
    """A pier change of :func:`reshape_piers`, checked: factors > 0, a lean within
    :data:`MAX_LEAN`, one shift [m] per interior bed joint."""
    if change is None:
        return {}
    if not isinstance(change, dict) or set(change) - {"width", "height", "shifts", "lean"}:
        raise ArchInputError(f"{side}: {change!r}; allowed a dict of width, height, shifts, lean")
    out = {k: v for k, v in change.items() if v is not None}
    for k in ("width", "height"):
        if k in out:
            out[k] = _check_scalar(f"{side} pier {k} factor", out[k], 0.0, None,
                                   allowed="a factor > 0")
    if "lean" in out:
        out["lean"] = _check_lean(f"{side} pier lean", out["lean"])
    if "shifts" in out:
        sh = np.asarray(out["shifts"], float)
        if sh.shape != (max(run - 1, 0),) or not np.all(np.isfinite(sh)):
            raise ArchInputError(f"{side} pier shifts: {out['shifts']!r}; allowed one finite "
                                 f"shift [m] per interior bed joint ({max(run - 1, 0)})")
        out["shifts"] = sh
    return out


def lean_pier(arch: ArchOnPiers, side: str, degrees: float) -> ArchOnPiers:
    """``arch`` with its ``side`` ('left' or 'right') pier out of plumb by ``degrees`` (outward
    positive): the pier turned rigidly about its outer foot corner, its foundation joint with
    it, and the voussoirs following (docs/piers.md, Irregular piers).  0 gives ``arch``."""
    if not isinstance(arch, ArchOnPiers) or not arch.pier_blocks:
        raise ArchInputError("pier tilt: the arch has no piers; allowed an arch on piers "
                             "(--pier-height/--pier-width, or a file with pier blocks)")
    if side not in ("left", "right"):
        raise ArchInputError(f"pier tilt side: {side!r}; allowed left, right")
    deg = _check_lean("pier tilt", degrees)
    if deg == 0.0:
        return arch
    return reshape_piers(arch, arch.block_kinds, **{side: {"lean": deg}})


def pier_sizes(arch) -> dict:
    """Each side's pier (``{"left": {...}, "right": {...}}``, a side without piers absent):
    kind, blocks (courses), ``lean_deg`` (out of plumb, outward positive: the turn of its
    foundation joint), and in the pier's own frame (turned back by that lean about its outer
    foot corner) ``height`` [m] from the foot to the springing level and the widths
    ``width_top`` and ``width_foot`` [m] (horizontal reach of the top course at the springing
    level, or at its own top where it rises above the springing, and of the foundation)."""
    if not isinstance(arch, ArchOnPiers) or not arch.pier_blocks:
        return {}
    out = {}
    jp = arch.joint_points
    left, right = arch.piers
    tol = 1e-9 * arch.size
    for side, run, j_foot, j_top in (("left", left, 0, len(left)),
                                     ("right", right, arch.n, arch.n - len(right))):
        if not run:
            continue
        sign = 1.0 if side == "left" else -1.0
        v = jp[j_foot][1] - jp[j_foot][0]  # inner to outer end of the foundation joint
        lean = float(np.arctan2(-v[1], -sign * v[0]))
        c = jp[j_foot][1]
        t = -sign * lean  # turn the pier back to plumb
        rot = np.array([[np.cos(t), -np.sin(t)], [np.sin(t), np.cos(t)]])

        def back(p):
            return c + (np.asarray(p, float) - c) @ rot.T
        foot, top = back(jp[j_foot]), back(jp[j_top])
        ylo = float(max(foot[0][1], foot[1][1]))
        ytop = float(min(top[0][1], top[1][1]))
        top_block = run[-1] if side == "left" else run[0]
        pts = back(np.vstack([arch.intrados[top_block], arch.extrados[top_block]]))
        near = np.abs(pts[:, 1] - ytop) <= tol
        if np.count_nonzero(near) < 2:  # a pier rising above its springing (a file's): its top
            near = np.abs(pts[:, 1] - pts[:, 1].max()) <= tol
        out[side] = {"kind": arch.block_kinds[run[0]], "blocks": len(run),
                     "lean_deg": float(np.degrees(lean)) + 0.0, "height": ytop - ylo,
                     "width_top": float(np.ptp(pts[near, 0])) if np.count_nonzero(near) > 1
                     else float("nan"),
                     "width_foot": float(np.hypot(*(foot[1] - foot[0]))),
                     "foot_level": float(min(jp[j_foot][:, 1]))}
    return out


def parse_steps(text: str, flag: str = "--pier-steps") -> tuple:
    """``'H:W,H:W,...'`` (metres, from the foot up) as ((H, W), ...)."""
    out = []
    for part in str(text).split(","):
        h, sep, w = part.partition(":")
        try:
            if not sep:
                raise ValueError
            out.append((float(h), float(w)))
        except ValueError:
            raise ArchInputError(f"{flag}: {part.strip()!r} in {text!r}; allowed HEIGHT:WIDTH "
                                 f"pairs in metres, comma-separated, from the foot up "
                                 f"(e.g. 2:3,2:2.5,1:2)") from None
    return tuple(out)


def arch_without_piers(arch: ArchOnPiers) -> PolygonArch:
    """The voussoirs of an arch on piers as a polygon arch on rigid ground (its loads
    renumbered), e.g. for :func:`archrock.statics.buttress.minimum_pier_width`."""
    if not isinstance(arch, ArchOnPiers) or not arch.pier_blocks:
        return arch
    left, right = arch.piers
    vous = range(len(left), arch.n - len(right))
    loads = tuple(Load(ld.voussoir - len(left), ld.mass, ld.at) for ld in arch.loads
                  if ld.voussoir in vous)
    return PolygonArch(tuple(arch.intrados[i] for i in vous),
                       tuple(arch.extrados[i] for i in vous), arch.density,
                       f"{arch.name} (voussoirs)", loads, fc=arch.fc)

"""Arcades: several arches on shared piers, as a graph of rigid blocks (docs/arcades.md).

A chain of voussoirs has one joint between consecutive blocks; an arcade does not: a pier that
carries two arches touches both springers and the course under it.  :class:`Arcade` holds the
blocks (polygons with a kind: "voussoir", "pier", "buttress" or "beam") and the contacts between
them as an explicit list, each contact a straight segment (its two end points) between block
``a`` and block ``b`` (``a = -1``: the ground).  Those types live in :mod:`~archrock.geometry.blockgraph` (and
are importable from here); this module builds arcades.

Conventions (x right, y up, SI, masses per metre of depth, as docs/method.md):

* :func:`arcade` puts n arches (any archrock arch: circular, a family's, a surveyed polygon; with
  its loads) on n + 1 rectangular piers, numbered 1..n+1 from the left; spans numbered 1..n.
  Every arch's springings rest on the same level (the pier tops, y of arch 1's springing); pier
  p's height H_p is measured from that level down to its foundation (so unequal heights are
  foundations at different levels, as a bridge over a valley).  An end pier is W wide outward
  of the intrados springing (as :func:`~archrock.geometry.with_piers`); an inner pier's width is
  the clear distance between the two intrados springings it carries.  A springing joint that is
  not horizontal is carried on a horizontal pier top by a wedge in the top course (as
  :func:`~archrock.geometry.with_piers`).
* Blocks in reading order: pier 1's courses from the foundation up, span 1's voussoirs, pier 2's
  courses from the top down, span 2's voussoirs, ...; contacts likewise (pier 1's foundation,
  its bed joints, span 1's left springing, its joints, its right springing, pier 2's bed joints
  from the top down, its foundation, span 2's left springing, ...).  A one-span arcade is then,
  block for block and joint for joint, the chain :func:`~archrock.geometry.with_piers` builds.
* Each contact's end 0 is a voussoir joint's intrados end or an end pier's inner face, end 1 the
  extrados or outer face; on an inner pier end 0 is its left face, end 1 its right face
  (``Contact.ends`` names them).  :meth:`Arcade.contact_normals` gives the unit normal pointing
  from block a into block b.
"""

from __future__ import annotations

import numpy as np

from ..errors import ArchInputError
from .base import DEFAULT_DENSITY, VoussoirArch, _check_scalar
from .blockgraph import ARCADE_KINDS, GROUND, Arcade, Block, Contact
from .piers import ArchOnPiers, _courses, _dedupe, _left_pier, _polygon_of, joint_place

__all__ = ["Arcade", "Block", "Contact", "arcade", "arcade_from_chain", "ARCADE_KINDS",
           "MAX_SPANS", "GROUND"]

#: Most spans :func:`arcade` builds.
MAX_SPANS = 50


# ---------------------------------------------------------------------- builders
def arcade_from_chain(arch: VoussoirArch, name: str | None = None) -> Arcade:
    """Any archrock chain (an arch, an :class:`~archrock.geometry.ArchOnPiers`) as a graph:
    block i = voussoir i (its outline, and the chain's own mass properties: a circular arch's
    exact sectors, loads included), contact j = joint j (joints 0 and n on the ground), end 0
    the intrados, end 1 the extrados.  The arch's compressive strength ``arch.fc`` [MPa] is
    every block's (voussoirs and piers: one masonry)."""
    if not isinstance(arch, VoussoirArch):
        raise ArchInputError(f"arch: expected an archrock arch, got {type(arch).__name__}")
    n = arch.n
    kinds = arch.block_kinds if isinstance(arch, ArchOnPiers) else ("voussoir",) * n
    loads = {i: [] for i in range(n)}
    for ld in arch.loads:
        loads[ld.voussoir].append((ld.mass, ld.at))
    m, g, inertia = arch.masses, arch.centroids, arch.inertias
    blocks = tuple(Block(arch.outline(i), kinds[i], f"block {i}", tuple(loads[i]),
                         (float(m[i]), g[i], float(inertia[i]))) for i in range(n))
    jp = np.asarray(arch.joint_points, float)
    contacts = tuple(Contact(GROUND if j == 0 else j - 1, j, jp[j], joint_place(arch, j),
                             ("intrados", "extrados")) for j in range(n))
    # the right springing: the last block rests on the ground
    contacts += (Contact(GROUND, n - 1, jp[n], joint_place(arch, n), ("intrados", "extrados")),)
    density = getattr(arch, "density", DEFAULT_DENSITY)
    fc = arch.fc
    return Arcade(blocks, contacts, density, name or arch.name, (tuple(range(n)),), (),
                  None if fc is None else {k: fc for k in set(kinds)})


def _per(name: str, values, count: int):
    """One value for all, or exactly ``count`` values."""
    if isinstance(values, (list, tuple, np.ndarray)):
        vals = list(values)
        if len(vals) == 1:
            return vals * count
        if len(vals) != count:
            raise ArchInputError(f"{name}: {len(vals)} values; allowed one for all, or "
                                 f"{count}")
        return vals
    return [values] * count


def _inner_pier(A, B, height: float, courses: int, p: int, tol: float):
    """Courses of an inner pier under the right springing (A_in, A_ex) of one arch and the left
    springing (B_in, B_ex) of the next, from the top down: (outline, ...)."""
    (ai, ae), (bi, be) = A, B
    xl, xr = float(ai[0]), float(bi[0])
    top = min(float(ai[1]), float(ae[1]))
    if ae[0] - ai[0] <= tol or bi[0] - be[0] <= tol:
        raise ArchInputError(f"pier {p}: a springing joint's extrados end is not outward of its "
                             f"intrados end; allowed springings whose extrados lies outward")
    if be[0] < ae[0] - tol:
        raise ArchInputError(
            f"widths[{p - 1}]: pier {p} is {xr - xl:.4g} m wide, narrower than the two "
            f"springing joints it carries ({(ae[0] - ai[0]) + (bi[0] - be[0]):.4g} m); allowed an inner pier at "
            f"least as wide as both")
    foot = top - height
    levels = foot + height * np.arange(courses + 1) / courses
    levels[-1] = top
    out = []
    for c in range(courses - 1, -1, -1):
        lo, hi = levels[c], levels[c + 1]
        if c < courses - 1:
            poly = [(xl, lo), (xr, lo), (xr, hi), (xl, hi)]
        else:
            poly = _dedupe([(xl, lo), (xr, lo), (xr, top), tuple(bi), tuple(be),
                            (float(be[0]), top), (float(ae[0]), top), tuple(ae), tuple(ai),
                            (xl, top)], tol)
            if np.hypot(*(poly[-1] - poly[0])) <= tol:
                poly = poly[:-1]
        out.append(np.asarray(poly, float))
    return out, levels


class _Placed:
    """A polygon arch moved by ``shift`` (joints, outlines and loads), without rebuilding it;
    unmoved (shift 0) it gives the arch's own arrays, bit for bit."""

    def __init__(self, poly, shift):
        self.poly, self.shift, self.n = poly, shift, poly.n
        moved = bool(np.any(shift != 0.0))
        jp = np.asarray(poly.joint_points, float)
        self.joint_points = jp + shift if moved else jp
        self.loads = tuple((ld.voussoir, ld.mass, np.asarray(ld.at, float) + shift)
                           for ld in poly.loads)
        self._moved = moved

    def outline(self, i):
        out = self.poly.outline(i)
        return out + self.shift if self._moved else out


def _arch_polygons(arches) -> list:
    """Each arch of ``arches`` checked and written as polygons (a repeated arch once), all of
    one density."""
    if isinstance(arches, VoussoirArch):
        arches = [arches]
    if not isinstance(arches, (list, tuple)) or not arches:
        raise ArchInputError("arches: expected a non-empty list of archrock arches")
    if len(arches) > MAX_SPANS:
        raise ArchInputError(f"arches: {len(arches)} spans; allowed 1 to {MAX_SPANS}")
    polys, seen = [], {}
    for s, a in enumerate(arches):
        if not isinstance(a, VoussoirArch):
            raise ArchInputError(f"arches[{s}]: expected an archrock arch, got "
                                 f"{type(a).__name__}")
        if isinstance(a, ArchOnPiers) and a.pier_blocks:
            raise ArchInputError(f"arches[{s}]: already on piers; allowed an arch without piers")
        if id(a) not in seen:  # a repeated arch is written as polygons once
            seen[id(a)] = _polygon_of(a)
        polys.append(seen[id(a)])
    density = polys[0].density
    for s, p in enumerate(polys):
        if p.density != density:
            raise ArchInputError(f"arches[{s}].density: {p.density:g} kg/m^3, arch 1's "
                                 f"{density:g}; allowed one density for the arcade")
    return polys


def _pier_sizes(polys, heights, widths, courses):
    """(heights [m], widths [m], courses, tol [m]) of the n + 1 piers, each checked against the
    largest arch's extent (1e-8 to 100 times it)."""
    n = len(polys)
    hs = _per("heights", heights, n + 1)
    ws = _per("widths", widths, n + 1)
    cs = [_courses(f"courses[{i}]", c) for i, c in enumerate(_per("courses", courses, n + 1))]
    extent = max(float(np.max(np.ptp(np.vstack(p.intrados + p.extrados), axis=0)))
                 for p in polys)
    hi = 100.0 * extent
    for key, vals in (("heights", hs), ("widths", ws)):
        for i, v in enumerate(vals):
            if isinstance(v, (str, bool)) or not isinstance(v, (int, float, np.floating,
                                                                np.integer)):
                raise ArchInputError(f"{key}[{i}]: expected a number in metres, got {v!r}")
            v = _check_scalar(f"{key}[{i}]", v, 0.0, hi, hi_open=False,
                              allowed=f"> 0 m, at most 100 times the largest arch's extent "
                                      f"({hi:.4g} m)")
            if v < 1e-8 * hi:  # as for one arch's piers (geometry.piers): a 1e-300 m pier
                raise ArchInputError(f"{key}[{i}]: {v:g} m is out of range; allowed "
                                     f"{1e-8 * hi:.4g} m (a millionth of the largest arch's "
                                     f"extent) to {hi:.4g} m (100 times it)")
    hs, ws = [float(v) for v in hs], [float(v) for v in ws]
    return hs, ws, cs, 1e-9 * max([extent] + hs + ws)


def _placed_arches(polys, ws) -> list:
    """Each arch a translated copy of its polygon form: its left intrados springing a pier
    width right of the previous arch's right one, on the same level; arch 1 where it is."""
    placed = [_Placed(polys[0], np.zeros(2))]
    for s in range(1, len(polys)):
        a_in, a_ex = placed[-1].joint_points[-1]
        b_in, b_ex = polys[s].joint_points[0]
        dx = (a_in[0] + ws[s]) - b_in[0]
        dy = min(a_in[1], a_ex[1]) - min(b_in[1], b_ex[1])
        placed.append(_Placed(polys[s], np.array([dx, dy])))
    return placed


_FLIP = np.array([-1.0, 1.0])
_JOINT_ENDS = ("intrados", "extrados")


class _Assembly:
    """The blocks and contacts of an arcade in reading order (module docstring), added pier by
    pier and span by span."""

    def __init__(self, n: int, tol: float):
        self.n, self.tol = n, tol
        self.blocks, self.contacts, self.spans, self.piers = [], [], [], []

    def block(self, outline, kind, label, loads=()) -> int:
        self.blocks.append(Block(np.asarray(outline, float), kind, label, tuple(loads),
                                 _checked=True))
        return len(self.blocks) - 1

    def contact(self, a, b, points, label, ends=_JOINT_ENDS) -> None:
        self.contacts.append(Contact(a, b, points, label, ends))

    def faces(self, p):  # end 0 / end 1 of a pier's contacts: an end pier's faces, an inner one's
        return ("inner face", "outer face") if p in (1, self.n + 1) else ("left face", "right face")

    def left_pier(self, jp0, height, width, courses) -> int:
        """Pier 1, foundation up (with_piers' own construction); the block its span rests on."""
        try:
            left = _left_pier(jp0[0], jp0[1], height, width, courses, "left", self.tol)
        except ArchInputError as exc:
            raise ArchInputError(str(exc).replace("width:", "widths[0]:", 1)) from None
        idx = []
        for c, (i_, e_) in enumerate(left):
            idx.append(self.block(np.vstack([i_, e_[::-1]]), "pier", f"pier 1 course {c + 1}"))
            if c == 0:
                self.contact(GROUND, idx[-1], np.array([i_[0], e_[0]]), "pier 1 foot",
                             self.faces(1))
            else:
                self.contact(idx[-2], idx[-1], np.array([i_[0], e_[0]]), f"pier 1 bed joint {c}",
                             self.faces(1))
        self.piers.append(tuple(idx))
        return idx[-1]

    def span(self, s: int, poly, below: int) -> list:
        """Span s + 1's voussoirs, the first on block ``below``; their block indices."""
        jp = np.asarray(poly.joint_points, float)
        loads = {i: [] for i in range(poly.n)}
        for v, mass, at in poly.loads:
            loads[v].append((mass, at))
        vidx = []
        for i in range(poly.n):
            vidx.append(self.block(poly.outline(i), "voussoir", f"span {s + 1} voussoir {i + 1}",
                                   loads[i]))
            if i == 0:
                self.contact(below, vidx[0], jp[0],
                             f"span {s + 1} left springing (pier {s + 1} top)")
            else:
                self.contact(vidx[-2], vidx[-1], jp[i], f"span {s + 1} joint {i}")
        self.spans.append(tuple(vidx))
        return vidx

    def right_pier(self, s: int, jp, last: int, height, width, courses) -> None:
        """The right end pier under span s + 1 (a mirrored left pier, top down: with_piers)."""
        n, p = self.n, s + 2
        try:
            right_m = _left_pier(jp[-1][0] * _FLIP, jp[-1][1] * _FLIP, height, width, courses,
                                 "right", self.tol)
        except ArchInputError as exc:
            raise ArchInputError(str(exc).replace("width:", f"widths[{n}]:", 1)) from None
        right = [((i_ * _FLIP)[::-1], (e_ * _FLIP)[::-1]) for i_, e_ in reversed(right_m)]
        pidx = []
        cr = len(right)
        for c, (i_, e_) in enumerate(right):
            pidx.append(self.block(np.vstack([i_, e_[::-1]]), "pier", f"pier {p} course {cr - c}"))
            if c == 0:
                self.contact(last, pidx[0], jp[-1], f"span {s + 1} right springing (pier {p} top)")
            else:
                self.contact(pidx[-2], pidx[-1], np.array([i_[0], e_[0]]),
                             f"pier {p} bed joint {cr - c}", self.faces(p))
        foot = right[-1]
        self.contact(GROUND, pidx[-1], np.array([foot[0][-1], foot[1][-1]]), f"pier {p} foot",
                     self.faces(p))
        self.piers.append(tuple(pidx))

    def inner_pier(self, s: int, jp, nxt, last: int, height, courses) -> int:
        """The pier between spans s + 1 and s + 2, top down; the block the next span rests on."""
        p = s + 2
        courses_out, levels = _inner_pier(jp[-1], nxt.joint_points[0], height, courses, p,
                                          self.tol)
        pidx = []
        xl, xr = float(jp[-1][0][0]), float(nxt.joint_points[0][0][0])
        for k, outline in enumerate(courses_out):
            course = courses - k  # counted from the foot up
            pidx.append(self.block(outline, "pier", f"pier {p} course {course}"))
            if k == 0:
                self.contact(last, pidx[0], jp[-1], f"span {s + 1} right springing (pier {p} top)")
            else:
                y = levels[course]
                self.contact(pidx[-2], pidx[-1], np.array([[xl, y], [xr, y]]),
                             f"pier {p} bed joint {course}", self.faces(p))
        self.contact(GROUND, pidx[-1], np.array([[xl, levels[0]], [xr, levels[0]]]),
                     f"pier {p} foot", self.faces(p))
        self.piers.append(tuple(pidx))
        return pidx[0]


def _arcade_fc(arches, fc):
    """The arcade's strengths: ``fc`` where given (None: from the arches), else the arches'
    common ``arch.fc`` for voussoirs and piers alike (as one arch on piers has)."""
    if fc is not None:
        return fc
    if isinstance(arches, VoussoirArch):
        arches = [arches]
    values = {a.fc for a in arches if isinstance(a, VoussoirArch)}
    if len(values) > 1:
        raise ArchInputError(f"arches: compressive strengths {sorted(values, key=str)} MPa "
                             f"differ; allowed one fc for every arch (or give fc per kind)")
    common = values.pop() if values else None
    return None if common is None else {"voussoir": common, "pier": common}


def arcade(arches, heights, widths, *, courses=1, name: str = "arcade", fc=None) -> Arcade:
    """``arches`` (a list of n archrock arches, left to right) on n + 1 piers (module
    docstring): ``heights`` and ``widths`` [m] one value for all piers or n + 1 values;
    ``courses`` (1..200) one for all or n + 1.  Every arch is written as polygons (a circular
    one with arcs of 0.002 rad, as :func:`~archrock.geometry.with_piers`) and moved so that its
    left intrados springing stands a pier width right of the previous arch's right one, on the
    same level; arch 1 stays where it is.  ``fc``: compressive strength [MPa] of every block,
    or {kind: MPa} (:class:`Arcade`); None: the arches' own ``arch.fc`` for voussoirs and
    piers."""
    fc = _arcade_fc(arches, fc)
    polys = _arch_polygons(arches)
    n = len(polys)
    hs, ws, cs, tol = _pier_sizes(polys, heights, widths, courses)
    placed = _placed_arches(polys, ws)
    out = _Assembly(n, tol)
    below = out.left_pier(placed[0].joint_points[0], hs[0], ws[0], cs[0])
    for s in range(n):
        jp = np.asarray(placed[s].joint_points, float)
        last = out.span(s, placed[s], below)[-1]
        if s == n - 1:
            out.right_pier(s, jp, last, hs[n], ws[n], cs[n])
        else:
            below = out.inner_pier(s, jp, placed[s + 1], last, hs[s + 1], cs[s + 1])
    return Arcade(tuple(out.blocks), tuple(out.contacts), polys[0].density, name,
                  tuple(out.spans), tuple(out.piers), fc)

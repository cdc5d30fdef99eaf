"""Arcades: several arches on shared piers, as a graph of rigid blocks (docs/arcades.md).

A chain of voussoirs has one joint between consecutive blocks; an arcade does not: a pier that
carries two arches touches both springers and the course under it.  :class:`Arcade` holds the
blocks (polygons with a kind: "voussoir", "pier", "buttress" or "beam") and the contacts between
them as an explicit list, each contact a straight segment (its two end points) between block
``a`` and block ``b`` (``a = -1``: the ground).

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

import math
from dataclasses import dataclass, field
from functools import cached_property

import numpy as np

from ..errors import ArchInputError
from .base import (DEFAULT_DENSITY, MAX_LOAD_KG, VoussoirArch, _check_density,
                   _check_point, _check_points, _check_scalar, polygon_properties)
from .piers import _courses, _dedupe, _left_pier, _polygon_of
from .polygon import FACE_TOLERANCE, _signed_area, _simple

__all__ = ["Arcade", "Block", "Contact", "arcade", "arcade_from_chain", "ARCADE_KINDS",
           "MAX_SPANS", "GROUND"]

#: Kinds of block in an arcade.
ARCADE_KINDS = ("voussoir", "pier", "buttress", "beam")
#: Most spans :func:`arcade` builds.
MAX_SPANS = 50
#: The index that stands for the ground in a contact.
GROUND = -1


@dataclass(frozen=True, eq=False)
class Block:
    """One rigid block: ``outline`` (m, 2) [m], its vertices in order (either orientation);
    ``kind`` one of :data:`ARCADE_KINDS`; ``label`` how outputs name it ("pier 2 course 1",
    "span 1 voussoir 4"); ``loads`` ((mass [kg/m], (x, y) [m]), ...) point masses on it;
    ``mass_properties`` (mass [kg/m], centre (x, y) [m], polar inertia [kg m^2/m]) where they are
    not the polygon's (a circular arch's exact sectors, loads included), else None."""

    outline: np.ndarray
    kind: str = "voussoir"
    label: str = ""
    loads: tuple = ()
    mass_properties: tuple | None = None
    #: set by the builders for a validated arch's voussoirs and their own pier polygons: the
    #: self-intersection check (the slow one on finely sampled arcs) is not repeated
    _checked: bool = field(default=False, repr=False, compare=False)

    def to_dict(self) -> dict:
        d = {"kind": self.kind, "outline": np.asarray(self.outline, float).tolist()}
        if self.label:
            d["label"] = self.label
        if self.loads:
            d["loads"] = [{"mass": float(m), "at": [float(p[0]), float(p[1])]}
                          for m, p in self.loads]
        if self.mass_properties is not None:
            m, c, i = self.mass_properties
            d["mass_properties"] = {"mass": float(m), "centre": [float(c[0]), float(c[1])],
                                    "inertia": float(i)}
        return d


@dataclass(frozen=True, eq=False)
class Contact:
    """A joint between block ``a`` (-1: the ground) and block ``b``: the straight segment
    ``points`` ((2, 2) [m], end 0 then end 1); ``label`` where it is ("pier 2 foot", "span 1
    joint 3"); ``ends`` the names of its two ends ("intrados"/"extrados", "inner face"/"outer
    face", "left face"/"right face")."""

    a: int
    b: int
    points: np.ndarray
    label: str = ""
    ends: tuple = ("end 0", "end 1")

    def to_dict(self) -> dict:
        d = {"a": int(self.a), "b": int(self.b),
             "points": np.asarray(self.points, float).tolist()}
        if self.label:
            d["label"] = self.label
        if tuple(self.ends) != ("end 0", "end 1"):
            d["ends"] = list(self.ends)
        return d

    def place(self, end: int) -> str:
        """Where end ``end`` (0 or 1) of this contact is, in words: "pier 2 foot, outer face"."""
        return f"{self.label or 'contact'}, {self.ends[int(end)]}"


def _point_in_polygon(pt, poly) -> bool:
    x, y = float(pt[0]), float(pt[1])
    p = np.asarray(poly, float)
    q = np.roll(p, -1, axis=0)
    cond = (p[:, 1] > y) != (q[:, 1] > y)
    with np.errstate(divide="ignore", invalid="ignore"):
        xs = p[:, 0] + (y - p[:, 1]) * (q[:, 0] - p[:, 0]) / (q[:, 1] - p[:, 1])
    return bool(np.count_nonzero(cond & (x < xs)) % 2)


def _boundary_distance(pt, poly) -> float:
    p = np.asarray(poly, float)
    q = np.roll(p, -1, axis=0)
    d = q - p
    L2 = np.maximum((d * d).sum(axis=1), 1e-300)
    t = np.clip(((pt - p) * d).sum(axis=1) / L2, 0.0, 1.0)
    c = p + t[:, None] * d
    return float(np.min(np.hypot(*(pt - c).T)))


@dataclass(frozen=True, eq=False)
class Arcade:
    """A graph of rigid blocks (module docstring): ``blocks``, ``contacts``, ``density``
    [kg/m^3], ``name``; ``spans`` and ``piers``: the block indices of each span's voussoirs and
    of each pier's courses (empty for an arcade read from blocks alone).  Validated by field:
    each block a simple polygon of positive area, each contact's blocks known and distinct, its
    two ends distinct and on both blocks' boundaries, every block touched by a contact and
    connected through contacts to the ground."""

    blocks: tuple
    contacts: tuple
    density: float = DEFAULT_DENSITY
    name: str = field(default="arcade", compare=False)
    spans: tuple = ()
    piers: tuple = ()

    def __post_init__(self):
        if not isinstance(self.blocks, (list, tuple)) or not self.blocks:
            raise ArchInputError("blocks: expected a non-empty list of blocks")
        if not isinstance(self.contacts, (list, tuple)) or not self.contacts:
            raise ArchInputError("contacts: expected a non-empty list of contacts")
        object.__setattr__(self, "density", _check_density(self.density))
        blocks = []
        for i, b in enumerate(self.blocks):
            if not isinstance(b, Block):
                raise ArchInputError(f"blocks[{i}]: expected a Block, got {type(b).__name__}")
            if b.kind not in ARCADE_KINDS:
                raise ArchInputError(f"blocks[{i}].kind: {b.kind!r}; allowed "
                                     f"{', '.join(ARCADE_KINDS)}")
            out = np.array(_check_points(f"blocks[{i}].outline", b.outline))
            if out.ndim != 2 or out.shape[1] != 2 or out.shape[0] < 3:
                raise ArchInputError(f"blocks[{i}].outline: shape {out.shape}; allowed at least "
                                     f"3 points [x, y]")
            if not b._checked and not _simple(out):
                raise ArchInputError(f"blocks[{i}].outline: its boundary intersects itself; "
                                     f"allowed a simple polygon")
            out.setflags(write=False)
            loads = []
            for k, ld in enumerate(b.loads):
                try:
                    m, at = ld
                except (TypeError, ValueError):
                    raise ArchInputError(f"blocks[{i}].loads[{k}]: expected (mass, (x, y))") \
                        from None
                at = _check_point(f"blocks[{i}].loads[{k}].at", at)
                m = _check_scalar(f"blocks[{i}].loads[{k}].mass", m, 0.0, None, lo_open=False,
                                  allowed=">= 0 kg per metre of depth")
                at.setflags(write=False)
                loads.append((m, at))
            mp = b.mass_properties
            if mp is not None:
                try:
                    m, g, ii = mp
                except (TypeError, ValueError):
                    raise ArchInputError(f"blocks[{i}].mass_properties: expected (mass, (x, y), "
                                         f"inertia)") from None
                m, ii = (_check_scalar(f"blocks[{i}].mass_properties.{k}", v,
                                       allowed="a finite number") for k, v in (("mass", m),
                                                                               ("inertia", ii)))
                g = _check_point(f"blocks[{i}].mass_properties.centre", g)
                if not (m > 0 and ii >= 0 and math.isfinite(m) and math.isfinite(ii)
                        and np.all(np.isfinite(g))):
                    raise ArchInputError(f"blocks[{i}].mass_properties: mass {m!r}, inertia "
                                         f"{ii!r}; allowed a finite mass > 0 and inertia >= 0")
                g.setflags(write=False)
                mp = (m, g, ii)
            blocks.append(Block(out, b.kind, str(b.label), tuple(loads), mp, b._checked))
        object.__setattr__(self, "blocks", tuple(blocks))
        ext = np.vstack([b.outline for b in blocks])
        extent = float(np.max(np.ptp(ext, axis=0)))
        if not extent > 0:
            raise ArchInputError("blocks: zero extent; allowed blocks of positive size")
        for i, b in enumerate(blocks):
            if abs(_signed_area(b.outline)) <= 1e-12 * extent ** 2:
                raise ArchInputError(f"blocks[{i}].outline: zero area; allowed a region of "
                                     f"positive area")
        nb = len(blocks)
        tol = FACE_TOLERANCE * min(1.0, 0.1 * extent)
        contacts = []
        for c, ct in enumerate(self.contacts):
            if not isinstance(ct, Contact):
                raise ArchInputError(f"contacts[{c}]: expected a Contact, got "
                                     f"{type(ct).__name__}")
            for key, v, lo in (("a", ct.a, GROUND), ("b", ct.b, 0)):
                if isinstance(v, bool) or not isinstance(v, (int, np.integer)) or \
                        not lo <= int(v) < nb:
                    raise ArchInputError(f"contacts[{c}].{key}: {v!r}; allowed a block index "
                                         f"{lo} to {nb - 1}" + (" (-1: the ground)"
                                                                if key == "a" else ""))
            a, b_ = int(ct.a), int(ct.b)
            if a == b_:
                raise ArchInputError(f"contacts[{c}]: block {a} against itself; allowed two "
                                     f"different blocks")
            pts = np.array(_check_points(f"contacts[{c}].points", ct.points, "two [x, y] points"))
            if pts.shape != (2, 2) or not np.all(np.isfinite(pts)):
                raise ArchInputError(f"contacts[{c}].points: expected two finite [x, y] points, "
                                     f"got shape {pts.shape}")
            if np.hypot(*(pts[1] - pts[0])) <= 1e-9 * extent:
                raise ArchInputError(f"contacts[{c}].points: its two ends coincide; allowed a "
                                     f"segment of positive length")
            for side in (a, b_):
                if side == GROUND:
                    continue
                off = max(_boundary_distance(p, blocks[side].outline) for p in pts)
                if off > tol:
                    raise ArchInputError(f"contacts[{c}].points: an end is {off:.4g} m off block "
                                         f"{side}'s boundary; allowed at most {tol:.3g} m")
            ends = tuple(ct.ends)
            if len(ends) != 2 or not all(isinstance(e, str) for e in ends):
                raise ArchInputError(f"contacts[{c}].ends: {ct.ends!r}; allowed two names")
            pts.setflags(write=False)
            contacts.append(Contact(a, b_, pts, str(ct.label), ends))
        object.__setattr__(self, "contacts", tuple(contacts))
        touched = {ct.a for ct in contacts} | {ct.b for ct in contacts}
        lone = sorted(set(range(nb)) - touched)
        if lone:
            what = blocks[lone[0]].label or "no label"
            raise ArchInputError(f"contacts: block {lone[0]} ({what}) touches nothing; allowed "
                                 f"every block in a contact")
        # every block must reach the ground through contacts (else it floats: no equilibrium)
        seen, front = set(), [GROUND]
        adj = {}
        for ct in contacts:
            adj.setdefault(ct.a, []).append(ct.b)
            adj.setdefault(ct.b, []).append(ct.a)
        while front:
            v = front.pop()
            for w in adj.get(v, ()):
                if w not in seen:
                    seen.add(w)
                    front.append(w)
        floating = sorted(set(range(nb)) - seen)
        if floating:
            raise ArchInputError(f"contacts: block {floating[0]} is not connected to the ground "
                                 f"(-1) through contacts; allowed blocks that rest on it")
        object.__setattr__(self, "spans", tuple(tuple(int(i) for i in s) for s in self.spans))
        object.__setattr__(self, "piers", tuple(tuple(int(i) for i in p) for p in self.piers))

    # ------------------------------------------------------------------ mass properties
    @property
    def n_blocks(self) -> int:
        return len(self.blocks)

    @cached_property
    def _mass(self):
        m, c, inertia = [], [], []
        for b in self.blocks:
            if b.mass_properties is not None:  # given: loads are in them
                m.append(b.mass_properties[0])
                c.append(b.mass_properties[1])
                inertia.append(b.mass_properties[2])
                continue
            a, g, polar = polygon_properties(b.outline)
            mi, gi, ii = self.density * a, g, self.density * polar
            if b.loads:
                ms = np.array([mi] + [ld[0] for ld in b.loads])
                ps = np.array([gi] + [ld[1] for ld in b.loads])
                tot = ms.sum()
                g2 = (ms[:, None] * ps).sum(axis=0) / tot
                ii = ii + float((ms * ((ps - g2) ** 2).sum(axis=1)).sum())
                mi, gi = tot, g2
            m.append(mi)
            c.append(gi)
            inertia.append(ii)
        out = (np.array(m, float), np.array(c, float), np.array(inertia, float))
        for arr in out:
            arr.setflags(write=False)
        return out

    @property
    def masses(self) -> np.ndarray:
        """Mass of each block with its loads [kg per metre of depth]."""
        return self._mass[0]

    @property
    def centroids(self) -> np.ndarray:
        """Mass centre of each block with its loads (n, 2) [m]."""
        return self._mass[1]

    @property
    def inertias(self) -> np.ndarray:
        """Polar moment of inertia of each block about its mass centre [kg m^2 per m]."""
        return self._mass[2]

    @property
    def kinds(self) -> tuple:
        return tuple(b.kind for b in self.blocks)

    @cached_property
    def extent(self) -> float:
        """The largest side of the arcade's bounding box [m] (the statics' reference length)."""
        pts = np.vstack([b.outline for b in self.blocks])
        return float(np.max(np.ptp(pts, axis=0)))

    @cached_property
    def size(self) -> float:
        """The contact engine's length scale [m]: the largest span's half distance between the
        mid-points of its springing contacts (a semicircle's radius) where spans are known,
        else half the extent."""
        best = 0.0
        for s in self.spans:
            if not s:
                continue
            sp = set(s)
            left = [c for c in self.contacts_of(s[0]) if self._other(c, s[0]) not in sp]
            right = [c for c in self.contacts_of(s[-1]) if self._other(c, s[-1]) not in sp]
            if left and right:
                pa = self.contacts[left[0]].points.mean(axis=0)
                pb = self.contacts[right[-1]].points.mean(axis=0)
                best = max(best, 0.5 * float(np.hypot(*(pb - pa))))
        return best if best > 0 else 0.5 * self.extent

    def _other(self, c: int, block: int) -> int:
        ct = self.contacts[c]
        return ct.a if ct.b == block else ct.b

    def contacts_of(self, block: int) -> list:
        """Indices of the contacts that touch ``block``."""
        return [c for c, ct in enumerate(self.contacts) if block in (ct.a, ct.b)]

    @cached_property
    def contact_normals(self) -> np.ndarray:
        """(m, 2): each contact's unit normal, pointing from block a into block b (found by
        which side of the segment's mid-point lies inside block b)."""
        out = []
        for c, ct in enumerate(self.contacts):
            p0, p1 = ct.points
            t = (p1 - p0) / np.hypot(*(p1 - p0))
            n = np.array([-t[1], t[0]])
            mid = 0.5 * (p0 + p1)
            eps = 1e-6 * self.extent
            inside_b = _point_in_polygon(mid + eps * n, self.blocks[ct.b].outline)
            inside_b_neg = _point_in_polygon(mid - eps * n, self.blocks[ct.b].outline)
            if inside_b == inside_b_neg:  # a sliver: the side of its centroid decides
                inside_b = float(np.dot(self.centroids[ct.b] - mid, n)) > 0
            out.append(n if inside_b else -n)
        arr = np.array(out, float)
        arr.setflags(write=False)
        return arr

    # ------------------------------------------------------------------ files
    def to_dict(self) -> dict:
        """The arcade document of the geometry files (``"kind": "arcade"``;
        :func:`archrock.geometry.files.write_arcade`)."""
        d = {"kind": "arcade", "density": self.density,
             "blocks": [b.to_dict() for b in self.blocks],
             "contacts": [c.to_dict() for c in self.contacts]}
        if self.spans:
            d["spans"] = [list(s) for s in self.spans]
        if self.piers:
            d["piers"] = [list(p) for p in self.piers]
        return d

    @classmethod
    def from_dict(cls, data, name: str = "arcade") -> "Arcade":
        """An arcade from its document (:meth:`to_dict`); every error names the field."""
        if not isinstance(data, dict):
            raise ArchInputError("arcade: expected a JSON object")
        if data.get("kind") != "arcade":
            raise ArchInputError(f"kind: {data.get('kind')!r}; allowed 'arcade' (an arcade "
                                 f"document)")
        unknown = set(data) - {"kind", "density", "blocks", "contacts", "spans", "piers",
                               "metadata", "name"}
        if unknown:
            raise ArchInputError(f"arcade: unknown fields {sorted(unknown)}; allowed kind, "
                                 f"density, blocks, contacts, spans, piers, metadata, name")
        bl = data.get("blocks")
        if not isinstance(bl, list) or not bl:
            raise ArchInputError("blocks: expected a non-empty list of blocks")
        blocks = []
        for i, b in enumerate(bl):
            if not isinstance(b, dict) or "outline" not in b:
                raise ArchInputError(f"blocks[{i}]: expected an object with an outline")
            kind = b.get("kind", "voussoir")
            if not isinstance(kind, str) or kind not in ARCADE_KINDS:
                raise ArchInputError(f"blocks[{i}].kind: {kind!r}; allowed "
                                     f"{', '.join(ARCADE_KINDS)}")
            loads = []
            for k, ld in enumerate(b.get("loads", []) or []):
                if not isinstance(ld, dict) or "mass" not in ld or "at" not in ld:
                    raise ArchInputError(f"blocks[{i}].loads[{k}]: expected {{mass, at}}")
                # a file's load is bounded at the door (a built arcade's fill may weigh more)
                loads.append((_check_scalar(f"blocks[{i}].loads[{k}].mass", ld["mass"], 0.0,
                                            MAX_LOAD_KG, lo_open=False, hi_open=False,
                                            allowed=f"0 to {MAX_LOAD_KG:g} kg per metre of "
                                                    f"depth"), ld["at"]))
            mp = b.get("mass_properties")
            if mp is not None:
                if not isinstance(mp, dict) or not {"mass", "centre", "inertia"} <= set(mp):
                    raise ArchInputError(f"blocks[{i}].mass_properties: expected {{mass, centre, "
                                         f"inertia}}")
                mp = (mp["mass"], mp["centre"], mp["inertia"])
            blocks.append(Block(b["outline"], kind, str(b.get("label", "")), tuple(loads), mp))
        cl = data.get("contacts")
        if not isinstance(cl, list) or not cl:
            raise ArchInputError("contacts: expected a non-empty list of contacts")
        contacts = []
        for c, ct in enumerate(cl):
            if not isinstance(ct, dict) or not {"a", "b", "points"} <= set(ct):
                raise ArchInputError(f"contacts[{c}]: expected an object with a, b and points")
            contacts.append(Contact(ct["a"], ct["b"], ct["points"], str(ct.get("label", "")),
                                    tuple(ct.get("ends", ("end 0", "end 1")))))
        spans, piers = data.get("spans", []), data.get("piers", [])
        for key, groups in (("spans", spans), ("piers", piers)):
            if not isinstance(groups, list) or not all(
                    isinstance(g, list) and all(isinstance(i, int) and not isinstance(i, bool)
                                                and 0 <= i < len(blocks) for i in g)
                    for g in groups):
                raise ArchInputError(f"{key}: expected lists of block indices 0 to "
                                     f"{len(blocks) - 1}")
        arc = cls(tuple(blocks), tuple(contacts), data.get("density", DEFAULT_DENSITY),
                  str(data.get("name", name)), tuple(map(tuple, spans)),
                  tuple(map(tuple, piers)))
        from .overlap import find_overlap, overlap_message  # a document is not built by arcade()

        hit = find_overlap([b.outline for b in arc.blocks],
                           FACE_TOLERANCE * min(1.0, 0.1 * arc.extent))
        if hit is not None:
            raise ArchInputError(overlap_message(arc, hit))
        return arc

    def mirrored(self) -> "Arcade":
        """The mirror image about x = 0 (blocks and contacts in the same order; each contact's
        ends keep their names)."""
        flip = np.array([-1.0, 1.0])
        blocks = tuple(Block(b.outline * flip, b.kind, b.label,
                             tuple((m, p * flip) for m, p in b.loads),
                             None if b.mass_properties is None else
                             (b.mass_properties[0], b.mass_properties[1] * flip,
                              b.mass_properties[2]), b._checked) for b in self.blocks)
        contacts = tuple(Contact(c.a, c.b, c.points * flip, c.label, c.ends)
                         for c in self.contacts)
        return Arcade(blocks, contacts, self.density, f"{self.name} mirrored", self.spans,
                      self.piers)

    def __repr__(self) -> str:
        return (f"Arcade(name={self.name!r}, {len(self.spans)} spans, {self.n_blocks} blocks, "
                f"{len(self.contacts)} contacts)")


# ---------------------------------------------------------------------- builders
def arcade_from_chain(arch: VoussoirArch, name: str | None = None) -> Arcade:
    """Any archrock chain (an arch, an :class:`~archrock.geometry.ArchOnPiers`) as a graph:
    block i = voussoir i (its outline, and the chain's own mass properties: a circular arch's
    exact sectors, loads included), contact j = joint j (joints 0 and n on the ground), end 0
    the intrados, end 1 the extrados."""
    from .piers import ArchOnPiers, joint_place

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
    return Arcade(blocks, contacts, density, name or arch.name, (tuple(range(n)),), ())


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


def arcade(arches, heights, widths, *, courses=1, name: str = "arcade") -> Arcade:
    """``arches`` (a list of n archrock arches, left to right) on n + 1 piers (module
    docstring): ``heights`` and ``widths`` [m] one value for all piers or n + 1 values;
    ``courses`` (1..200) one for all or n + 1.  Every arch is written as polygons (a circular
    one with arcs of 0.002 rad, as :func:`~archrock.geometry.with_piers`) and moved so that its
    left intrados springing stands a pier width right of the previous arch's right one, on the
    same level; arch 1 stays where it is."""
    if isinstance(arches, VoussoirArch):
        arches = [arches]
    if not isinstance(arches, (list, tuple)) or not arches:
        raise ArchInputError("arches: expected a non-empty list of archrock arches")
    if len(arches) > MAX_SPANS:
        raise ArchInputError(f"arches: {len(arches)} spans; allowed 1 to {MAX_SPANS}")
    from .piers import ArchOnPiers

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
    n = len(polys)
    density = polys[0].density
    for s, p in enumerate(polys):
        if p.density != density:
            raise ArchInputError(f"arches[{s}].density: {p.density:g} kg/m^3, arch 1's "
                                 f"{density:g}; allowed one density for the arcade")
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
    tol = 1e-9 * max([extent] + hs + ws)
    # place the arches: each a translated copy (joints, outlines, loads) of its polygon form
    placed = [_Placed(polys[0], np.zeros(2))]
    for s in range(1, n):
        a_in, a_ex = placed[-1].joint_points[-1]
        b_in, b_ex = polys[s].joint_points[0]
        dx = (a_in[0] + ws[s]) - b_in[0]
        dy = min(a_in[1], a_ex[1]) - min(b_in[1], b_ex[1])
        placed.append(_Placed(polys[s], np.array([dx, dy])))
    blocks, contacts, spans, piers = [], [], [], []
    flip = np.array([-1.0, 1.0])

    def add_block(outline, kind, label, loads=()):
        blocks.append(Block(np.asarray(outline, float), kind, label, tuple(loads),
                            _checked=True))
        return len(blocks) - 1

    def side_name(p):  # end 0 / end 1 of a pier's contacts: an end pier's faces, an inner one's
        return ("inner face", "outer face") if p in (1, n + 1) else ("left face", "right face")

    # pier 1: the left end pier, foundation up (with_piers' own construction)
    jp0 = placed[0].joint_points[0]
    try:
        left = _left_pier(jp0[0], jp0[1], hs[0], ws[0], cs[0], "left", tol)
    except ArchInputError as exc:
        msg = str(exc)
        raise ArchInputError(msg.replace("width:", "widths[0]:", 1)) from None
    idx = []
    for c, (i_, e_) in enumerate(left):
        idx.append(add_block(np.vstack([i_, e_[::-1]]), "pier", f"pier 1 course {c + 1}"))
        if c == 0:
            contacts.append(Contact(GROUND, idx[-1], np.array([i_[0], e_[0]]), "pier 1 foot",
                                    side_name(1)))
        else:
            contacts.append(Contact(idx[-2], idx[-1], np.array([i_[0], e_[0]]),
                                    f"pier 1 bed joint {c}", side_name(1)))
    piers.append(tuple(idx))
    below = idx[-1]  # the block the next span's left springing rests on
    for s in range(n):
        poly = placed[s]
        jp = np.asarray(poly.joint_points, float)
        loads = {i: [] for i in range(poly.n)}
        for v, mass, at in poly.loads:
            loads[v].append((mass, at))
        vidx = []
        for i in range(poly.n):
            vidx.append(add_block(poly.outline(i), "voussoir", f"span {s + 1} voussoir {i + 1}",
                                  loads[i]))
            if i == 0:
                contacts.append(Contact(below, vidx[0], jp[0],
                                        f"span {s + 1} left springing (pier {s + 1} top)",
                                        ("intrados", "extrados")))
            else:
                contacts.append(Contact(vidx[-2], vidx[-1], jp[i], f"span {s + 1} joint {i}",
                                        ("intrados", "extrados")))
        spans.append(tuple(vidx))
        p = s + 2  # the pier right of span s + 1
        if p == n + 1:  # the right end pier: a mirrored left pier, top down (with_piers)
            try:
                right_m = _left_pier(jp[-1][0] * flip, jp[-1][1] * flip, hs[n], ws[n], cs[n],
                                     "right", tol)
            except ArchInputError as exc:
                raise ArchInputError(str(exc).replace("width:", f"widths[{n}]:", 1)) from None
            right = [((i_ * flip)[::-1], (e_ * flip)[::-1]) for i_, e_ in reversed(right_m)]
            pidx = []
            cr = len(right)
            for c, (i_, e_) in enumerate(right):
                pidx.append(add_block(np.vstack([i_, e_[::-1]]), "pier",
                                      f"pier {p} course {cr - c}"))
                if c == 0:
                    contacts.append(Contact(vidx[-1], pidx[0], jp[-1],
                                            f"span {s + 1} right springing (pier {p} top)",
                                            ("intrados", "extrados")))
                else:
                    contacts.append(Contact(pidx[-2], pidx[-1], np.array([i_[0], e_[0]]),
                                            f"pier {p} bed joint {cr - c}", side_name(p)))
            foot = right[-1]
            contacts.append(Contact(GROUND, pidx[-1], np.array([foot[0][-1], foot[1][-1]]),
                                    f"pier {p} foot", side_name(p)))
            piers.append(tuple(pidx))
        else:
            nxt = placed[s + 1]
            courses_out, levels = _inner_pier(jp[-1], nxt.joint_points[0], hs[p - 1], cs[p - 1],
                                              p, tol)
            pidx = []
            cc = cs[p - 1]
            xl, xr = float(jp[-1][0][0]), float(nxt.joint_points[0][0][0])
            for k, outline in enumerate(courses_out):
                course = cc - k  # counted from the foot up
                pidx.append(add_block(outline, "pier", f"pier {p} course {course}"))
                if k == 0:
                    contacts.append(Contact(vidx[-1], pidx[0], jp[-1],
                                            f"span {s + 1} right springing (pier {p} top)",
                                            ("intrados", "extrados")))
                else:
                    y = levels[course]
                    contacts.append(Contact(pidx[-2], pidx[-1], np.array([[xl, y], [xr, y]]),
                                            f"pier {p} bed joint {course}", side_name(p)))
            contacts.append(Contact(GROUND, pidx[-1], np.array([[xl, levels[0]],
                                                                [xr, levels[0]]]),
                                    f"pier {p} foot", side_name(p)))
            piers.append(tuple(pidx))
            below = pidx[0]
    return Arcade(tuple(blocks), tuple(contacts), density, name, tuple(spans), tuple(piers))

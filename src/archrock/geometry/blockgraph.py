"""An arcade's masonry as a graph of rigid blocks (docs/arcades.md): :class:`Block` (a polygon
with a kind: "voussoir", "pier", "buttress" or "beam"), :class:`Contact` (a straight segment
between block ``a`` and block ``b``, ``a = -1``: the ground) and :class:`Arcade`, which checks
them and gives what the statics and the dynamics read (masses, centroids, inertias, contact
normals) and the file document.  The builders are in :mod:`~archrock.geometry.arcade`.

The masonry may have a finite compressive strength per kind of block (``Arcade.fc``: kind ->
MPa; a kind not named is infinitely strong, Heyman's hypothesis); a contact takes the weaker of
its two blocks' strengths (the ground is never the weaker).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import cached_property

import numpy as np

from ..errors import ArchInputError
from .base import (DEFAULT_DENSITY, MAX_FC, MAX_LOAD_KG, MIN_FC, _check_density, _check_point,
                   _check_points, _check_scalar, polygon_properties)
from .polygon import FACE_TOLERANCE, _signed_area, _simple

__all__ = ["Arcade", "Block", "Contact", "ARCADE_KINDS", "GROUND"]

#: Kinds of block in an arcade.
ARCADE_KINDS = ("voussoir", "pier", "buttress", "beam")
#: The index that stands for the ground in a contact.
GROUND = -1


def _check_kind_fc(fc) -> dict:
    """An arcade's strengths: None (every kind infinitely strong), one number [MPa] for every
    kind, or {kind: MPa or None}; returned as {kind: MPa} with only the finite ones."""
    if fc is None:
        return {}
    if not isinstance(fc, dict):
        return {k: _one_fc("fc", fc) for k in ARCADE_KINDS}
    out = {}
    for k, v in fc.items():
        if k not in ARCADE_KINDS:
            raise ArchInputError(f"fc: kind {k!r}; allowed {', '.join(ARCADE_KINDS)}")
        if v is not None:
            out[k] = _one_fc(f"fc.{k}", v)
    return {k: out[k] for k in ARCADE_KINDS if k in out}  # one order: equal dicts, equal files


def _one_fc(name: str, v) -> float:
    if isinstance(v, (str, bool)) or not isinstance(v, (int, float, np.floating, np.integer)):
        raise ArchInputError(f"{name}: expected a number (MPa), got {v!r}")
    return _check_scalar(name, v, MIN_FC, MAX_FC, lo_open=False, hi_open=False,
                         allowed=f"{MIN_FC:g} to {MAX_FC:g} MPa (or none: infinite strength)")


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
    face", "left face"/"right face"); ``friction`` this contact's own Coulomb coefficient (None:
    the analysis's, by default no sliding) and ``cohesion`` [Pa] its own (|V| <= mu N + c L, with
    ``friction`` only): a brick arch's ring interfaces (:mod:`~archrock.geometry.rings`)."""

    a: int
    b: int
    points: np.ndarray
    label: str = ""
    ends: tuple = ("end 0", "end 1")
    friction: float | None = None
    cohesion: float = 0.0

    def to_dict(self) -> dict:
        d = {"a": int(self.a), "b": int(self.b),
             "points": np.asarray(self.points, float).tolist()}
        if self.label:
            d["label"] = self.label
        if tuple(self.ends) != ("end 0", "end 1"):
            d["ends"] = list(self.ends)
        # written only where set: every existing document stays as it was
        if self.friction is not None:
            d["friction"] = float(self.friction)
        if self.cohesion:
            d["cohesion"] = float(self.cohesion)
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


def _checked_block(i: int, b) -> Block:
    """Block ``i`` of an arcade checked (kind, outline, loads, mass properties), its arrays
    read-only."""
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
    return Block(out, b.kind, str(b.label), tuple(loads), mp, b._checked)


def _extent_of(blocks) -> float:
    """The blocks' extent [m] (the larger side of the box around them), each of positive area."""
    ext = np.vstack([b.outline for b in blocks])
    extent = float(np.max(np.ptp(ext, axis=0)))
    if not extent > 0:
        raise ArchInputError("blocks: zero extent; allowed blocks of positive size")
    for i, b in enumerate(blocks):
        if abs(_signed_area(b.outline)) <= 1e-12 * extent ** 2:
            raise ArchInputError(f"blocks[{i}].outline: zero area; allowed a region of "
                                 f"positive area")
    return extent


def _checked_contact(c: int, ct, blocks, extent: float, tol: float) -> Contact:
    """Contact ``c`` checked against the blocks (indices, a segment of positive length whose
    ends lie within ``tol`` [m] of both blocks' boundaries, two end names)."""
    nb = len(blocks)
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
    mu = ct.friction
    if mu is not None:
        mu = _check_scalar(f"contacts[{c}].friction", mu, 0.0, None,
                           allowed="a finite friction coefficient > 0 (or none: no sliding)")
    coh = _check_scalar(f"contacts[{c}].cohesion", ct.cohesion, 0.0, None, lo_open=False,
                        allowed="a finite cohesion >= 0 Pa")
    if coh > 0 and mu is None:
        raise ArchInputError(f"contacts[{c}].cohesion: {coh:g} Pa without a friction; allowed "
                             f"cohesion only on a contact with its own friction")
    return Contact(a, b_, pts, str(ct.label), ends, mu, coh)


def _check_grounded(blocks, contacts) -> None:
    """Every block touches another and reaches the ground through contacts (else it floats:
    no equilibrium)."""
    nb = len(blocks)
    touched = {ct.a for ct in contacts} | {ct.b for ct in contacts}
    lone = sorted(set(range(nb)) - touched)
    if lone:
        what = blocks[lone[0]].label or "no label"
        raise ArchInputError(f"contacts: block {lone[0]} ({what}) touches nothing; allowed "
                             f"every block in a contact")
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


@dataclass(frozen=True, eq=False)
class Arcade:
    """A graph of rigid blocks (module docstring): ``blocks``, ``contacts``, ``density``
    [kg/m^3], ``name``; ``spans`` and ``piers``: the block indices of each span's voussoirs and
    of each pier's courses (empty for an arcade read from blocks alone).  Validated by field:
    each block a simple polygon of positive area, each contact's blocks known and distinct, its
    two ends distinct and on both blocks' boundaries, every block touched by a contact and
    connected through contacts to the ground.  ``fc``: compressive strength per kind of block
    (module docstring; None, one number [MPa] for all, or {kind: MPa}), held as {kind: MPa}."""

    blocks: tuple
    contacts: tuple
    density: float = DEFAULT_DENSITY
    name: str = field(default="arcade", compare=False)
    spans: tuple = ()
    piers: tuple = ()
    fc: dict | None = None

    def __post_init__(self):
        if not isinstance(self.blocks, (list, tuple)) or not self.blocks:
            raise ArchInputError("blocks: expected a non-empty list of blocks")
        if not isinstance(self.contacts, (list, tuple)) or not self.contacts:
            raise ArchInputError("contacts: expected a non-empty list of contacts")
        object.__setattr__(self, "density", _check_density(self.density))
        blocks = tuple(_checked_block(i, b) for i, b in enumerate(self.blocks))
        object.__setattr__(self, "blocks", blocks)
        extent = _extent_of(blocks)
        tol = FACE_TOLERANCE * min(1.0, 0.1 * extent)
        contacts = tuple(_checked_contact(c, ct, blocks, extent, tol)
                         for c, ct in enumerate(self.contacts))
        object.__setattr__(self, "contacts", contacts)
        _check_grounded(blocks, contacts)
        object.__setattr__(self, "spans", tuple(tuple(int(i) for i in s) for s in self.spans))
        object.__setattr__(self, "piers", tuple(tuple(int(i) for i in p) for p in self.piers))
        object.__setattr__(self, "fc", _check_kind_fc(self.fc))

    # ------------------------------------------------------------------ strength
    def with_fc(self, fc) -> "Arcade":
        """The same blocks and contacts with strengths ``fc`` (None, MPa for all kinds, or
        {kind: MPa}); the blocks and contacts are not checked again."""
        import copy

        out = copy.copy(self)
        out.__dict__.pop("contact_fc", None)  # the only cached value that reads fc
        object.__setattr__(out, "fc", _check_kind_fc(fc))
        return out

    @property
    def finite_strength(self) -> bool:
        """Whether any block has a finite compressive strength."""
        return bool(self.fc)

    @cached_property
    def contact_fc(self) -> np.ndarray:
        """(m,): each contact's compressive strength [MPa], the weaker of its two blocks' (the
        ground's is never less); inf where both are infinitely strong."""
        def of(blk):
            return np.inf if blk == GROUND else self.fc.get(self.blocks[blk].kind, np.inf)
        arr = np.array([min(of(ct.a), of(ct.b)) for ct in self.contacts], float)
        arr.setflags(write=False)
        return arr

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
        if self.fc:  # only when set: a Heyman arcade's document is what it was
            d["fc"] = dict(self.fc)
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
                               "metadata", "name", "fc"}
        if unknown:
            raise ArchInputError(f"arcade: unknown fields {sorted(unknown)}; allowed kind, "
                                 f"density, blocks, contacts, spans, piers, fc, metadata, name")
        fc = _check_kind_fc(data.get("fc"))  # checked before the (slower) blocks
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
                                    tuple(ct.get("ends", ("end 0", "end 1"))),
                                    ct.get("friction"), ct.get("cohesion", 0.0)))
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
                  tuple(map(tuple, piers)), fc)
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
        contacts = tuple(Contact(c.a, c.b, c.points * flip, c.label, c.ends, c.friction,
                                 c.cohesion) for c in self.contacts)
        return Arcade(blocks, contacts, self.density, f"{self.name} mirrored", self.spans,
                      self.piers, self.fc)

    def __repr__(self) -> str:
        strength = f", fc={self.fc}" if self.fc else ""
        return (f"Arcade(name={self.name!r}, {len(self.spans)} spans, {self.n_blocks} blocks, "
                f"{len(self.contacts)} contacts{strength})")

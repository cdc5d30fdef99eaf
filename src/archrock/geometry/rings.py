"""Brick arches of several rings as a graph of blocks (docs/rings.md).

A brick arch bridge is rarely one ring of voussoirs: it is built of several rings of bricks
(rowlock courses, "half-brick rings"), each a thin arch of its own, laid on the one below with a
mortar joint between them.  Where that joint is weak the rings separate and slide on one another,
and the arch carries less than the same depth of masonry bonded into one ring: the mechanism that
Gilbert's RING models (Gilbert 2007, "Limit analysis applied to masonry arch bridges:
state-of-the-art and recent developments", ARCH'07; the RING theory manual) beside the hinges of
Heyman (1982, The Masonry Arch).

:func:`ringed_arch` builds such an arch as an :class:`~archrock.geometry.arcade.Arcade`, analysed
by the static program on the graph of blocks (:func:`archrock.statics.graph.graph_limit`, after
Livesley 1978 and Gilbert, Casapulla & Ahmed 2006):

* a circular arch of centreline radius R [m], embrace [deg] and total thickness t [m], centred at
  the origin as :class:`~archrock.geometry.Arch` (the left springing first), split into N rings
  from the intrados out, of given thicknesses (default equal);
* every ring has the same number of bricks, n = round(embrace R / brick): the centreline's bricks
  are ``brick`` [m] long (a header's 0.1025 m in a rowlock ring), the inner rings' a little
  shorter and the outer ones' longer, as the mortar's wedge-shaped joints make them;
* bonded brickwork: the radial joints of every other ring sit half a brick along (that ring has
  n + 1 bricks, a half brick at each springing), so no joint runs through the whole depth
  (``stagger=False``: every ring's joints on the same radial lines);
* header courses (``headers=M``): every M-th brick place of the intrados ring, counted from
  each springing toward the crown, is one block through every ring, its two sides joints
  through the whole depth (the staggered rings get a closer beside it);
* each brick an annular sector with its exact area, centroid and polar inertia (as the circular
  arch's voussoirs: one ring is, block for block, :func:`~archrock.geometry.arcade.
  arcade_from_chain` of :func:`~archrock.geometry.nominal_arch`); its faces on a ring interface
  are the polylines through both rings' joints, so that each pair of overlapping bricks shares
  one straight contact;
* contacts: each ring's radial joints and its two springings on the ground (no sliding, as the
  voussoirs of an arch: Heyman's hypothesis), and the ring interfaces, one contact per
  overlapping brick pair, which carry compression only (they open: the rings separate) and shear
  up to Coulomb's mu N + c L where a friction ``friction`` (and cohesion ``cohesion`` [Pa]) is
  given, or any shear (no sliding: the rings are bonded in shear, but may still separate) where
  it is None.

Blocks are labelled "ring 2 brick 14" or "header 3" (kind "voussoir"), contacts "ring 1 joint
3", "ring 1 left springing", "rings 1-2 interface 5".  The arcade document
(:func:`archrock.geometry.files.write_arcade`) keeps each interface's friction and cohesion, so
a file gives the same answer.
"""

from __future__ import annotations

import math

import numpy as np

from ..errors import ArchInputError
from .base import (DEFAULT_DENSITY, MAX_VOUSSOIRS, _check_density, _check_length,
                   _check_scalar)
from .blockgraph import GROUND, Arcade, Block, Contact
from .circular import sector_properties

__all__ = ["ringed_arch", "ring_of", "interface_contacts", "MAX_RINGS", "MAX_RING_BLOCKS",
           "DEFAULT_RING_FRICTION"]

#: The ring interfaces' Coulomb friction unless stated: the package's masonry friction
#: (:data:`archrock.statics.friction.DEFAULT_FRICTION`, which this layer may not import).
DEFAULT_RING_FRICTION = 0.8

#: Most rings of a brick arch (bridges have up to about 8).
MAX_RINGS = 20
#: Most blocks in all the rings together (the graph program's time grows as their square).
MAX_RING_BLOCKS = 4000
#: Points per radian on the intrados and extrados arcs (as :meth:`Arch.outline`).
_ARC_POINTS_PER_RAD = 60.0


def _ring_thicknesses(thickness: float, rings, ring_thicknesses) -> np.ndarray:
    """Each ring's thickness [m], intrados first, summing to ``thickness``."""
    if isinstance(rings, bool) or not isinstance(rings, (int, np.integer)) or \
            not 1 <= int(rings) <= MAX_RINGS:
        raise ArchInputError(f"rings: {rings!r}; allowed an integer from 1 to {MAX_RINGS}")
    rings = int(rings)
    if ring_thicknesses is None:
        return np.full(rings, thickness / rings)
    vals = list(np.atleast_1d(np.asarray(ring_thicknesses, dtype=object)))
    if len(vals) != rings:
        raise ArchInputError(f"ring_thicknesses: {len(vals)} values for {rings} rings; allowed "
                             f"one per ring")
    ts = np.array([_check_scalar(f"ring_thicknesses[{k}]", v, 0.0, thickness, hi_open=False,
                                 allowed=f"> 0 m, at most the thickness {thickness:g} m")
                   for k, v in enumerate(vals)])
    if abs(ts.sum() - thickness) > 1e-9 * thickness:
        raise ArchInputError(f"ring_thicknesses: they add up to {ts.sum():.6g} m; allowed a sum "
                             f"equal to the thickness {thickness:.6g} m")
    return ts


def ring_of(label: str) -> int | None:
    """The ring number (1 = intrados) of a block labelled "ring K brick I", else None."""
    parts = str(label).split()
    if len(parts) >= 2 and parts[0] == "ring" and parts[1].isdigit():
        return int(parts[1])
    return None


def interface_contacts(arc: Arcade) -> list:
    """Indices of an arcade's ring-interface contacts (labelled "rings K-L interface I")."""
    return [c for c, ct in enumerate(arc.contacts) if ct.label.startswith("rings ")]


def _grid(n: int, embrace: float, staggered: bool, R: float, t: float):
    """(psi (m+1,), sector properties) of one ring's joints: n equal bricks, or n + 1 with
    half bricks at the springings."""
    spans = np.full(n, embrace / n)
    if staggered:
        spans = np.concatenate([[0.5 * embrace / n], np.full(n - 1, embrace / n),
                                [0.5 * embrace / n]])
    props = sector_properties(spans, np.full(spans.size, R), np.full(spans.size, t))
    return props["psi"].copy(), props


def _face(psi_a: float, psi_b: float, r: float, angles: np.ndarray, tol: float) -> np.ndarray:
    """Points of a face at radius r from angle psi_a to psi_b (either order): its two ends and
    the ``angles`` strictly between them."""
    lo, hi = min(psi_a, psi_b), max(psi_a, psi_b)
    inner = angles[(angles > lo + tol) & (angles < hi - tol)]
    ang = np.concatenate([[psi_a], np.sort(inner)[::(-1 if psi_a > psi_b else 1)], [psi_b]])
    return np.column_stack([r * np.cos(ang), r * np.sin(ang)])


def _arc(psi_a: float, psi_b: float, r: float) -> np.ndarray:
    m = max(4, int(math.ceil(_ARC_POINTS_PER_RAD * abs(psi_a - psi_b))))
    ang = np.linspace(psi_a, psi_b, m)
    return np.column_stack([r * np.cos(ang), r * np.sin(ang)])


def ringed_arch(radius: float, thickness: float, rings: int = 2, ring_thicknesses=None,
                brick: float = 0.1025, embrace_deg: float = 180.0,
                density: float = DEFAULT_DENSITY,
                friction: float | None = DEFAULT_RING_FRICTION,
                cohesion: float = 0.0, stagger: bool = True, headers: int = 0,
                name: str | None = None) -> Arcade:
    """A circular brick arch of ``rings`` rings (module docstring) as an Arcade: centreline
    radius [m], total ``thickness`` [m], ``ring_thicknesses`` [m] (intrados first; default
    equal), ``brick`` the bricks' length along the centreline [m], ``embrace_deg`` [deg],
    ``density`` [kg/m^3]; the ring interfaces' Coulomb ``friction`` (None: no sliding) and
    ``cohesion`` [Pa] (with a friction only); ``stagger`` the bond (False: joints run through);
    ``headers`` a header course through every ring every that many bricks (0: none).
    ``friction=None`` (no sliding at all) lets an open interface carry shear, which locks
    staggered bricks together: a bound, not masonry (docs/rings.md)."""
    radius = _check_length("radius", _check_scalar("radius", radius, 0.0, None,
                                                   allowed="> 0 m"))
    thickness = _check_length("thickness", _check_scalar(
        "thickness", thickness, 0.0, 2 * radius, allowed=f"0 < t < 2 R = {2 * radius:g} m"))
    embrace_deg = _check_scalar("embrace", embrace_deg, 0.0, 360.0,
                                allowed="0 < embrace < 360 deg")
    density = _check_density(density)
    ts = _ring_thicknesses(thickness, rings, ring_thicknesses)
    embrace = math.radians(embrace_deg)
    brick = _check_scalar("brick", brick, 0.0, embrace * radius / 3, hi_open=False,
                          allowed=f"> 0 m, at most a third of the centreline's length "
                                  f"({embrace * radius / 3:.4g} m)")
    if friction is not None:
        friction = _check_scalar("friction", friction, 0.0, None,
                                 allowed="a finite friction coefficient > 0")
    cohesion = _check_scalar("cohesion", cohesion, 0.0, None, lo_open=False,
                             allowed="a finite cohesion >= 0 Pa")
    if cohesion > 0 and friction is None:
        raise ArchInputError("cohesion: needs a friction (without one the interfaces do not "
                             "slide at all)")
    n = max(3, int(round(embrace * radius / brick)))
    nr = ts.size
    if n > MAX_VOUSSOIRS or nr * (n + 1) > MAX_RING_BLOCKS:
        raise ArchInputError(f"brick: {brick:g} m gives {n} bricks per ring, {nr * (n + 1)} "
                             f"blocks in {nr} rings; allowed at most {MAX_VOUSSOIRS} per ring "
                             f"and {MAX_RING_BLOCKS} in all (a longer brick)")
    edges = radius - thickness / 2 + np.concatenate([[0.0], np.cumsum(ts)])
    edges[-1] = radius + thickness / 2
    tol = 1e-9 * embrace / n
    grids = []
    for k in range(nr):
        psi, props = _grid(n, embrace, stagger and k % 2 == 1, 0.5 * (edges[k] + edges[k + 1]),
                           ts[k])
        if grids:  # one springing angle for every ring (the sums differ in the last bit)
            psi[0], psi[-1] = grids[0][0][0], grids[0][0][-1]
        grids.append((psi, props))
    base = grids[0][0]
    spans_h = [(base[i], base[i + 1]) for i in _header_positions(headers, n)]
    rings_ = [_cut(psi, props, spans_h, tol, 0.5 * (edges[k] + edges[k + 1]), ts[k])
              for k, (psi, props) in enumerate(grids)]
    blocks, index = [], []
    for k, (psi, props, cells) in enumerate(rings_):
        below = rings_[k - 1][0] if k > 0 else None
        above = rings_[k + 1][0] if k + 1 < nr else None
        index.append([])
        for i in range(psi.size - 1):
            if cells[i] >= 0:  # a header's place: one block through every ring, below
                index[-1].append(None)
                continue
            a, b = psi[i], psi[i + 1]
            inner = _arc(a, b, edges[k]) if below is None else _face(a, b, edges[k], below, tol)
            outer = (_arc(b, a, edges[k + 1]) if above is None
                     else _face(b, a, edges[k + 1], above, tol))
            mp = (density * float(props["area"][i]), props["centroid"][i],
                  density * float(props["polar"][i]))
            index[-1].append(len(blocks))
            blocks.append(Block(np.vstack([inner, outer]), "voussoir",
                                f"ring {k + 1} brick {sum(c < 0 for c in cells[:i + 1])}", (),
                                mp, _checked=True))
    first_header = len(blocks)
    blocks += [_header_block(h, a, b, edges, radius, thickness, density)
               for h, (a, b) in enumerate(spans_h)]

    def block_of(k, i):  # the block of cell i of ring k
        c = rings_[k][2][i]
        return index[k][i] if c < 0 else first_header + c

    contacts = []
    for k, (psi, _, _) in enumerate(rings_):
        m = psi.size - 1
        for j in range(m + 1):
            pts = np.array([[edges[k] * math.cos(psi[j]), edges[k] * math.sin(psi[j])],
                            [edges[k + 1] * math.cos(psi[j]), edges[k + 1] * math.sin(psi[j])]])
            a = GROUND if j in (0, m) else block_of(k, j - 1)  # both springings on the ground
            b = block_of(k, j) if j < m else block_of(k, m - 1)
            what = ("left springing" if j == 0 else "right springing" if j == m
                    else f"joint {j}")
            contacts.append(Contact(a, b, pts, f"ring {k + 1} {what}", ("intrados", "extrados")))
    for k in range(nr - 1):
        contacts += _interface(k, rings_[k][0], rings_[k + 1][0], edges[k + 1],
                               lambda kk, i: block_of(kk, i), friction, cohesion, tol)
    label = name or (f"{nr}-ring brick arch" if nr > 1 else "brick arch")
    return Arcade(tuple(blocks), tuple(contacts), density, label,
                  (tuple(range(len(blocks))),), ())


def _header_positions(headers, n: int) -> list:
    """The brick places (0-based, of the intrados ring) of the header courses: every
    ``headers``-th brick from each springing toward the crown (mirror-symmetric, so that a
    symmetric arch stays symmetric), never a springing one."""
    if headers is None or headers == 0:
        return []
    if isinstance(headers, bool) or not isinstance(headers, (int, np.integer)) or \
            not 2 <= int(headers) <= n - 1:
        raise ArchInputError(f"headers: {headers!r}; allowed 0 (none) or a header every 2 to "
                             f"{n - 1} bricks")
    m = int(headers)
    left = [i for i in range(m - 1, n - 1, m) if 2 * i <= n - 1]
    return sorted(set(left) | {n - 1 - i for i in left})


def _cut(psi, props, spans_h, tol, R, t):
    """(angles, sector properties, cells) of one ring with the header places cut in: its
    joints inside a header's place removed, the header's two sides added; ``cells[i]`` the
    header at cell i, or -1 for a brick of this ring."""
    if not spans_h:
        return psi, props, [-1] * (psi.size - 1)
    ang = [a for a in psi if not any(lo + tol < a < hi - tol for hi, lo in spans_h)]
    ang = np.array(sorted(set(ang) | {a for h in spans_h for a in h}, reverse=True))
    ang = ang[np.concatenate([[True], np.abs(np.diff(ang)) > tol])]
    props = sector_properties(-np.diff(ang), np.full(ang.size - 1, R),
                              np.full(ang.size - 1, t))
    cells = []
    for i in range(ang.size - 1):
        mid = 0.5 * (ang[i] + ang[i + 1])
        cells.append(next((h for h, (hi, lo) in enumerate(spans_h) if lo < mid < hi), -1))
    return ang, props, cells


def _header_block(h: int, a: float, b: float, edges, radius: float, thickness: float,
                  density: float) -> Block:
    """Header ``h`` (0-based): one block through every ring between angles a > b, its sides
    with a corner at every ring's edge (so that each ring's joint meets it)."""
    inner, outer = _arc(a, b, edges[0]), _arc(b, a, edges[-1])

    def side(psi, rs):
        return np.column_stack([rs * math.cos(psi), rs * math.sin(psi)])
    out = np.vstack([inner, side(b, edges[1:-1]), outer, side(a, edges[1:-1][::-1])])
    props = sector_properties([a - b], [radius], [thickness])  # a sector about the crown:
    rg, mid = float(np.hypot(*props["centroid"][0])), 0.5 * (a + b)  # turned to its place
    mp = (density * float(props["area"][0]), np.array([rg * math.cos(mid), rg * math.sin(mid)]),
          density * float(props["polar"][0]))
    return Block(out, "voussoir", f"header {h + 1}", (), mp, _checked=True)


def _interface(k: int, lower, upper, r: float, block_of, friction, cohesion, tol) -> list:
    """The contacts between ring k + 1 and ring k + 2 (1-based) at radius r: one per pair of
    overlapping bricks, from the left springing (none inside a header, one block there)."""
    ang = np.sort(np.concatenate([lower, upper]))[::-1]
    keep = np.concatenate([[True], np.abs(np.diff(ang)) > tol])
    ang = ang[keep]
    out = []
    for s in range(ang.size - 1):
        mid = 0.5 * (ang[s] + ang[s + 1])
        i = int(np.searchsorted(-lower, -mid)) - 1  # the brick of each ring around mid
        j = int(np.searchsorted(-upper, -mid)) - 1
        pts = np.array([[r * math.cos(ang[s]), r * math.sin(ang[s])],
                        [r * math.cos(ang[s + 1]), r * math.sin(ang[s + 1])]])
        lo_b, up_b = block_of(k, i), block_of(k + 1, j)
        if lo_b == up_b:
            continue
        out.append(Contact(lo_b, up_b, pts,
                           f"rings {k + 1}-{k + 2} interface {s + 1}", ("left end", "right end"),
                           friction, cohesion))
    return out

"""Blocks of an arcade document that overlap (docs/arcades.md, Files).

Rigid blocks touch along their contacts; two blocks that share area are not a structure (the
static program would still find forces for them and print a multiplier).  :func:`arcade` builds
blocks that do not overlap (it refuses an inner pier narrower than its two springings by name);
a document read from a file is checked here.

The test, for each pair of blocks whose bounding boxes overlap by more than the tolerance: a
vertex of one lies inside the other deeper than the tolerance, or an interior point of one (its
area centroid, where inside it; duplicated blocks share every vertex) lies inside the other.
Outlines that cross without either (two bars in a cross) are not detected; the common cases,
a block slid into its neighbour, a springer over a pier too narrow for it, a block given twice,
are.
"""

from __future__ import annotations

import numpy as np

__all__ = ["find_overlap", "overlap_message"]


class _Poly:
    """A block's outline with what the tests reuse: its edges, bounding box and centroid."""

    def __init__(self, outline):
        self.p = np.asarray(outline, float)
        self.d = np.roll(self.p, -1, axis=0) - self.p
        self.lo, self.hi = self.p.min(axis=0), self.p.max(axis=0)
        q = self.p + self.d
        cr = self.p[:, 0] * q[:, 1] - q[:, 0] * self.p[:, 1]
        self.centroid = np.array([((self.p[:, 0] + q[:, 0]) * cr).sum(),
                                  ((self.p[:, 1] + q[:, 1]) * cr).sum()]) / (3 * cr.sum())
        # a crescent's centroid may lie outside it: then only its vertices are tested
        self.centroid_inside = bool(self.inside(self.centroid[None])[0])

    def in_box(self, pts: np.ndarray, tol: float) -> np.ndarray:
        return np.all((pts > self.lo + tol) & (pts < self.hi - tol), axis=1)

    def inside(self, pts: np.ndarray) -> np.ndarray:
        """Whether each of ``pts`` (m, 2) lies inside (even-odd rule)."""
        p, d = self.p, self.d
        y0, y1 = p[None, :, 1], p[None, :, 1] + d[None, :, 1]
        y = pts[:, 1:]
        cond = (y0 > y) != (y1 > y)
        with np.errstate(divide="ignore", invalid="ignore"):
            xs = p[None, :, 0] + (y - y0) * d[None, :, 0] / d[None, :, 1]
        return (np.count_nonzero(cond & (pts[:, :1] < xs), axis=1) % 2).astype(bool)

    def depth(self, pts: np.ndarray) -> np.ndarray:
        """Distance [m] of each of ``pts`` to the boundary."""
        p, d = self.p, self.d
        L2 = np.maximum((d * d).sum(axis=1), 1e-300)
        rel = pts[:, None, :] - p[None, :, :]
        t = np.clip((rel * d[None]).sum(axis=2) / L2[None], 0.0, 1.0)
        off = rel - t[..., None] * d[None]
        return np.hypot(off[..., 0], off[..., 1]).min(axis=1)


def _deepest(a: _Poly, b: _Poly, tol: float):
    """(depth [m], point) of the vertex of ``a`` deepest inside ``b`` (None if none is inside
    deeper than ``tol``)."""
    near = a.p[b.in_box(a.p, tol)]
    if not len(near):
        return None
    near = near[b.inside(near)]
    if not len(near):
        return None
    dep = b.depth(near)
    k = int(np.argmax(dep))
    return (float(dep[k]), near[k]) if dep[k] > tol else None


def _pair(a: _Poly, b: _Poly, tol: float):
    """How blocks a and b overlap: (depth [m], point [m], duplicate) or None."""
    for one, two in ((a, b), (b, a)):
        hit = _deepest(one, two, tol)
        if hit is not None:
            return hit[0], hit[1], False
    for one, two in ((a, b), (b, a)):
        c = one.centroid[None]
        if one.centroid_inside and two.in_box(c, tol)[0] and two.inside(c)[0]:
            dep = float(two.depth(c)[0])
            if dep > tol:
                same = (one.p.shape == two.p.shape and
                        float(np.max(np.abs(one.p - two.p))) <= tol)
                return dep, one.centroid, same
    return None


def find_overlap(outlines, tol: float):
    """The first pair of overlapping blocks (module docstring) as (i, j, depth [m], point [m],
    duplicate), i < j, or None; ``outlines``: each block's (m, 2) vertices [m]; ``tol`` [m]:
    a depth below this is a touch, not an overlap."""
    polys = [_Poly(o) for o in outlines]
    lo = np.array([p.lo for p in polys])
    hi = np.array([p.hi for p in polys])
    order = np.argsort(lo[:, 0], kind="stable")
    xs = lo[order, 0]
    # sweep along x: only blocks whose boxes overlap (by more than tol) are compared
    for pos, i in enumerate(order):
        stop = int(np.searchsorted(xs, hi[i, 0] - tol, side="left"))
        cand = order[pos + 1:stop]
        cand = cand[(lo[cand, 1] < hi[i, 1] - tol) & (hi[cand, 1] > lo[i, 1] + tol)]
        for j in cand:
            hit = _pair(polys[i], polys[j], tol)
            if hit is not None:
                a, b = sorted((int(i), int(j)))
                return (a, b, *hit)
    return None


def overlap_message(arc, hit) -> str:
    """One line naming the overlapping blocks of ``hit`` (:func:`find_overlap`) in ``arc`` (an
    Arcade), and, where both rest on the same inner pier, that the pier is too narrow."""
    i, j, depth, point, duplicate = hit
    blocks = arc.blocks

    def name(k):
        return f"block {k} ({blocks[k].label})" if blocks[k].label else f"block {k}"

    if duplicate:
        return (f"blocks: {name(j)} duplicates {name(i)} (the same outline); allowed each "
                f"block once")
    where = f"({point[0]:.4g}, {point[1]:.4g}) m"
    pier = _common_pier(arc, i, j)
    if pier is not None:
        p, width, joints = pier
        return (f"blocks: {name(i)} and {name(j)} overlap by {depth:.3g} m at {where}: inner "
                f"pier {p} is {width:.4g} m wide, narrower than the two springing joints it "
                f"carries ({joints:.4g} m); allowed a pier at least as wide as both together")
    return (f"blocks: {name(i)} and {name(j)} overlap by {depth:.3g} m at {where}; allowed "
            f"blocks that touch only along their contacts")


def _common_pier(arc, i: int, j: int):
    """(number 1.., width [m], the two springing joints' length [m]) of an inner pier both
    blocks rest on, or None."""
    piers = arc.piers
    for p, courses in enumerate(piers):
        if p in (0, len(piers) - 1):
            continue
        members = set(courses)
        joints = {k: [c for c in arc.contacts if (c.a in members and c.b == k)
                      or (c.b in members and c.a == k)] for k in (i, j)}
        if all(joints.values()):
            xs = np.concatenate([arc.blocks[m].outline[:, 0] for m in courses])
            length = sum(float(np.hypot(*(c.points[1] - c.points[0])))
                         for cs in joints.values() for c in cs)
            return p + 1, float(np.ptp(xs)), length
    return None

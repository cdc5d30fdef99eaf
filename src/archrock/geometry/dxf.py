"""Surveyed arches from drawings: one closed polyline per voussoir in a DXF file -> a
:class:`~archrock.geometry.PolygonArch`.

:func:`read_dxf` reads the closed polylines (LWPOLYLINE, and 2-D/3-D POLYLINE; an open one whose
last vertex is its first counts as closed; arc segments (bulges) are flattened to straight
segments within 1e-4 of the polyline's size; z is dropped) of the model space on one layer, or
on every layer, scales them to metres (``units``) and hands them to :func:`arch_from_outlines`,
which needs no DXF and works on any list of outlines:

1. **Contacts.** Two voussoirs are neighbours when an edge of one and an edge of the other lie
   on one line (every point of their common stretch within ``tol`` of the other's line) and
   overlap along it by more than ``tol``; ``tol`` = :data:`~archrock.geometry.FACE_TOLERANCE`
   times min(1, size/10), size = half the drawing's extent (the same tolerance the arch applies
   to its joints).  A voussoir's face towards a neighbour is the run of its edges that touch it
   (collinear pieces are one face; an end that overhangs the neighbour's face stays in the face).
2. **Order.** The neighbours must form one chain: a voussoir with more than two neighbours, a
   ring, or a chain in pieces is refused (the message names the two voussoirs, by DXF handle,
   across the smallest gap, and the gap).  The voussoir of the chain's two ends whose centroid
   has the smaller x is the left springing.
3. **Springing faces.** The face of an end voussoir that has no neighbour runs between the two
   corners of its free boundary where the boundary turns most (its two sharpest convex corners:
   a face meets the intrados and the extrados at about a right angle, where the curved lines
   turn by a few degrees per vertex).
4. **Intrados and extrados.** Each outline is taken counter-clockwise; walking the arch from the
   left springing to the right one, the intrados is the line on the right-hand side: in each
   counter-clockwise outline, the boundary from the left face to the right face.  This needs no
   notion of "inside" and holds for any shape (inside a curved arch, below a flat one, and a
   horseshoe's legs too).

Every refusal is an :class:`~archrock.errors.ArchInputError` with a one-line message.
"""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np

from ..errors import ArchInputError
from .base import DEFAULT_DENSITY
from .inputfile import read_input
from .polygon import FACE_TOLERANCE, PolygonArch

__all__ = ["read_dxf", "read_dxf_outlines", "arch_from_outlines", "UNITS"]

#: drawing unit -> metres
UNITS = {"m": 1.0, "cm": 0.01, "mm": 0.001}
#: Extent [m] of a drawing (the larger side of the box around its voussoirs) accepted as an
#: arch: masonry arches span from laboratory models of a few decimetres to about 100 m (the
#: longest stone spans); beyond these bounds the drawing units are wrong (a drawing in mm read
#: as m gives a 10 km arch).
MIN_EXTENT_M = 0.01
MAX_EXTENT_M = 500.0
#: DXF header $INSUNITS codes of the drawing units offered by ``units``.
_INSUNITS = {6: "m", 5: "cm", 4: "mm"}

_TYPES = "LWPOLYLINE POLYLINE"


# ---------------------------------------------------------------------------- geometry helpers
def _clean(points) -> np.ndarray:
    """Vertices without repeats (consecutive, or the last one repeating the first), taken
    counter-clockwise."""
    p = np.asarray(points, float)[:, :2]
    keep = np.ones(len(p), bool)
    keep[1:] = np.any(np.diff(p, axis=0) != 0, axis=1)
    p = p[keep]
    while len(p) > 1 and np.all(p[-1] == p[0]):
        p = p[:-1]
    if len(p) >= 3 and _signed_area(p) < 0:
        p = p[::-1].copy()
    return p


def _signed_area(p: np.ndarray) -> float:
    q = p - p[0]
    x, y = q[:, 0], q[:, 1]
    return 0.5 * float(np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y))


def _contact_edges(p: np.ndarray, q: np.ndarray, tol: float) -> np.ndarray:
    """Which edges of polygon p lie on an edge of polygon q: along one line within ``tol`` over
    their common stretch, which is longer than ``tol``."""
    e0 = p
    d = np.roll(p, -1, axis=0) - p
    length = np.hypot(d[:, 0], d[:, 1])
    u = d / length[:, None]
    f0, f1 = q, np.roll(q, -1, axis=0)
    r0 = f0[None, :, :] - e0[:, None, :]
    r1 = f1[None, :, :] - e0[:, None, :]
    t0 = np.einsum("ijk,ik->ij", r0, u)
    t1 = np.einsum("ijk,ik->ij", r1, u)
    n0 = u[:, None, 0] * r0[..., 1] - u[:, None, 1] * r0[..., 0]
    n1 = u[:, None, 0] * r1[..., 1] - u[:, None, 1] * r1[..., 0]
    lo = np.maximum(0.0, np.minimum(t0, t1))
    hi = np.minimum(length[:, None], np.maximum(t0, t1))
    overlap = hi - lo > tol
    dt = np.where(t1 != t0, t1 - t0, 1.0)

    def off(t):
        return np.abs(n0 + (n1 - n0) * (t - t0) / dt)

    close = (off(lo) <= tol) & (off(hi) <= tol)
    return np.any(overlap & close, axis=1)


def _run(flags: np.ndarray):
    """(first, last) edge indices of the one cyclic run of True in ``flags``, or None if the
    True edges are not one run."""
    m = len(flags)
    if flags.all():
        return None
    starts = [k for k in range(m) if flags[k] and not flags[k - 1]]
    if len(starts) != 1:
        return None
    s = starts[0]
    e = s
    while flags[(e + 1) % m]:
        e = (e + 1) % m
    return s, e


def _point_distances(pts: np.ndarray, poly: np.ndarray) -> np.ndarray:
    """Distance of each point to the boundary of a polygon."""
    a = poly
    ab = np.roll(poly, -1, axis=0) - a
    ap = pts[:, None, :] - a[None, :, :]
    t = np.clip(np.einsum("ijk,jk->ij", ap, ab) / np.einsum("jk,jk->j", ab, ab), 0.0, 1.0)
    gap = ap - t[..., None] * ab[None]
    return np.min(np.hypot(gap[..., 0], gap[..., 1]), axis=1)


def _segment_distance(p: np.ndarray, q: np.ndarray) -> float:
    """Smallest distance between the boundaries of two polygons (0 where they cross)."""
    return float(min(_point_distances(p, q).min(), _point_distances(q, p).min()))


def _inside(pts: np.ndarray, poly: np.ndarray) -> np.ndarray:
    """Whether each point is inside the polygon (even-odd rule)."""
    x, y = pts[:, 0:1], pts[:, 1:2]
    xs, ys = poly[None, :, 0], poly[None, :, 1]
    xn, yn = np.roll(xs, -1, axis=1), np.roll(ys, -1, axis=1)
    cond = (ys > y) != (yn > y)
    with np.errstate(divide="ignore", invalid="ignore"):
        xc = xs + (y - ys) * (xn - xs) / (yn - ys)
    return np.count_nonzero(cond & (x < xc), axis=1) % 2 == 1


def _overlap_depth(p: np.ndarray, q: np.ndarray) -> float:
    """How far the boundary of one polygon enters the other (its vertices and the points at a
    quarter, half and three quarters of its edges; 0 if none is inside)."""
    depth = 0.0
    for a, b in ((p, q), (q, p)):
        d = np.roll(a, -1, axis=0) - a
        pts = np.vstack([a + f * d for f in (0.0, 0.25, 0.5, 0.75)])
        inside = _inside(pts, b)
        if inside.any():
            depth = max(depth, float(_point_distances(pts[inside], b).max()))
    return depth


def _turns(p: np.ndarray) -> np.ndarray:
    """Turning angle [rad] at each vertex of a counter-clockwise polygon (left turns > 0)."""
    d_in = p - np.roll(p, 1, axis=0)
    d_out = np.roll(p, -1, axis=0) - p
    cross = d_in[:, 0] * d_out[:, 1] - d_in[:, 1] * d_out[:, 0]
    dot = np.einsum("ij,ij->i", d_in, d_out)
    return np.arctan2(cross, dot)


def _chain(m: int, start: int, stop: int) -> list[int]:
    """Vertex indices from ``start`` to ``stop`` (inclusive) counter-clockwise."""
    k = (stop - start) % m
    return [(start + j) % m for j in range(k + 1)]


# ---------------------------------------------------------------------------- the arch
def _checked_polygons(outlines, labels):
    """The outlines as cleaned polygons, checked: (labels, polygons)."""
    outlines = list(outlines)
    labels = [str(i) for i in range(len(outlines))] if labels is None else [str(s) for s in labels]
    if len(labels) != len(outlines):
        raise ArchInputError(f"labels: {len(labels)} for {len(outlines)} outlines")
    polys = []
    for lab, o in zip(labels, outlines):
        p = _clean(o)
        if len(p) < 3:
            raise ArchInputError(f"voussoir {lab}: {len(p)} distinct vertices; allowed a closed "
                                 f"polyline with at least 3")
        if not np.all(np.isfinite(p)):
            raise ArchInputError(f"voussoir {lab}: a coordinate is not a finite number")
        if _signed_area(p) == 0.0:
            raise ArchInputError(f"voussoir {lab}: zero area; allowed a region of positive area")
        polys.append(p)
    n = len(polys)
    if n < 3:
        raise ArchInputError(f"found {n} closed polyline(s); an arch needs at least 3 voussoirs, "
                             f"one closed polyline each")
    return labels, polys


def _contacts(polys, labels, tol):
    """Step 1: (faces, nbrs); faces[(i, j)] = (first, last) edge of polygon i along polygon j."""
    n = len(polys)
    lo = np.array([p.min(axis=0) for p in polys]) - tol
    hi = np.array([p.max(axis=0) for p in polys]) + tol
    faces: dict[tuple[int, int], tuple[int, int]] = {}
    nbrs: list[list[int]] = [[] for _ in range(n)]
    for i in range(n):
        for j in range(i + 1, n):
            if np.any(lo[i] > hi[j]) or np.any(lo[j] > hi[i]):
                continue
            fi = _contact_edges(polys[i], polys[j], tol)
            if not fi.any():
                continue
            depth = _overlap_depth(polys[i], polys[j])
            if depth > tol:
                raise ArchInputError(f"voussoirs {labels[i]} and {labels[j]} overlap by "
                                     f"{depth:.4g} m; allowed neighbours that touch along a face "
                                     f"(overlapping by at most {tol:.3g} m)")
            fj = _contact_edges(polys[j], polys[i], tol)
            ri, rj = _run(fi), _run(fj)
            if ri is None or rj is None:
                bad = labels[i] if ri is None else labels[j]
                raise ArchInputError(f"voussoirs {labels[i]} and {labels[j]}: voussoir {bad} "
                                     f"touches the other along more than one stretch of its "
                                     f"boundary; allowed one straight face between neighbours")
            faces[i, j], faces[j, i] = ri, rj
            nbrs[i].append(j)
            nbrs[j].append(i)
    return faces, nbrs


def _components(nbrs) -> np.ndarray:
    """comp[i]: the lowest index of the polygons connected to polygon i."""
    comp = -np.ones(len(nbrs), int)
    for s in range(len(nbrs)):
        if comp[s] >= 0:
            continue
        stack = [s]
        comp[s] = s
        while stack:
            k = stack.pop()
            for j in nbrs[k]:
                if comp[j] < 0:
                    comp[j] = s
                    stack.append(j)
    return comp


def _chain_break(polys, labels, comp, n_parts, tol) -> ArchInputError:
    """The error for a chain in n_parts pieces, named by its closest pair across a break."""
    n = len(polys)
    best = None
    for i in range(n):
        for j in range(i + 1, n):
            if comp[i] != comp[j]:
                d = _segment_distance(polys[i], polys[j])
                if best is None or d < best[0]:
                    best = (d, i, j)
    d, i, j = best
    more = f" (and {n_parts - 2} more break(s) in the chain)" if n_parts > 2 else ""
    depth = _overlap_depth(polys[i], polys[j]) if d <= tol else 0.0
    if depth > 0:
        what = (f"overlap by {depth:.4g} m without a common face; allowed neighbours whose "
                f"faces lie on one line within {tol:.3g} m")
    elif d <= tol:
        what = "touch at a corner only; allowed neighbours that share a straight face"
    else:
        what = f"do not touch: a gap of {d:.4g} m; allowed at most {tol:.3g} m"
    return ArchInputError(f"voussoirs {labels[i]} and {labels[j]} {what}{more}")


def _chain_order(polys, labels, nbrs, tol) -> list[int]:
    """Step 2: the polygons' order along one open chain, from its leftmost end."""
    n = len(polys)
    for i in range(n):
        if len(nbrs[i]) > 2:
            others = ", ".join(labels[j] for j in nbrs[i])
            raise ArchInputError(f"voussoir {labels[i]} touches {len(nbrs[i])} others ({others}); "
                                 f"allowed at most two neighbours (one chain of voussoirs)")
    comp = _components(nbrs)
    roots = sorted(set(comp.tolist()))
    if len(roots) > 1:
        raise _chain_break(polys, labels, comp, len(roots), tol)
    ends = [i for i in range(n) if len(nbrs[i]) == 1]
    if not ends:
        raise ArchInputError("the voussoirs close into a ring; allowed an open chain between "
                             "two springings")
    cent = np.array([_centroid(p) for p in polys])
    first = min(ends, key=lambda i: cent[i, 0])
    order = [first]
    while len(order) < n:
        nxt = [j for j in nbrs[order[-1]] if j not in order[-2:]]
        order.append(nxt[0])
    return order


def _springing_face(p, own, lab):
    """The free face (two vertex indices) of a springing voussoir p whose face ``own`` touches
    its neighbour: the two sharpest corners of the rest of its boundary."""
    free = _chain(len(p), own[1], own[0])[1:-1]  # vertices of the free boundary
    if len(free) < 2:
        raise ArchInputError(f"voussoir {lab}: a springing voussoir needs at least "
                             f"two corners besides its face towards its neighbour")
    turn = _turns(p)[free]
    a, b = sorted(np.argsort(turn)[-2:])
    return (free[a], free[b])


def _intrados_extrados(polys, labels, faces, order):
    """Steps 3-4: each voussoir's faces, then its intrados and extrados (lists, in order)."""
    n = len(order)
    intr, extr = [], []
    for pos, i in enumerate(order):
        p = polys[i]
        m = len(p)
        left = right = None  # (extrados end, intrados end) of the left face; (intrados, extrados) of the right
        if pos > 0:
            s, e = faces[i, order[pos - 1]]
            left = (s, (e + 1) % m)
        if pos < n - 1:
            s, e = faces[i, order[pos + 1]]
            right = (s, (e + 1) % m)
        if left is not None and right is not None:
            used = set(_chain(m, *left)) & set(_chain(m, *right))
            if used:
                raise ArchInputError(f"voussoir {labels[i]}: its faces towards "
                                     f"{labels[order[pos - 1]]} and {labels[order[pos + 1]]} "
                                     f"meet; allowed a voussoir with an intrados and an extrados")
        elif left is None:
            left = _springing_face(p, right, labels[i])
        else:
            right = _springing_face(p, left, labels[i])
        li, ri = _chain(m, left[1], right[0]), _chain(m, right[1], left[0])
        if len(li) < 2 or len(ri) < 2:
            raise ArchInputError(f"voussoir {labels[i]}: its faces meet at a corner; allowed a "
                                 f"voussoir with an intrados and an extrados")
        intr.append(p[li])
        extr.append(p[ri][::-1])
    return intr, extr


def arch_from_outlines(outlines, labels=None, *, density: float = DEFAULT_DENSITY,
                       name: str = "arch", tol: float | None = None):
    """A :class:`PolygonArch` from one closed outline per voussoir, in any order, each a
    sequence of (x, y) vertices [m] in either direction from any vertex (module docstring).

    labels: one name per outline for the messages (the DXF handles; default its index).
    Returns ``(arch, order)``: ``order[i]`` is the index of the outline that became voussoir i.
    """
    labels, polys = _checked_polygons(outlines, labels)
    size = 0.5 * float(np.max(np.ptp(np.vstack(polys), axis=0)))
    if tol is None:
        tol = FACE_TOLERANCE * min(1.0, 0.1 * size)
    faces, nbrs = _contacts(polys, labels, tol)
    order = _chain_order(polys, labels, nbrs, tol)
    intr, extr = _intrados_extrados(polys, labels, faces, order)
    try:
        arch = PolygonArch(tuple(intr), tuple(extr), density, name)
    except ArchInputError as exc:
        msg = str(exc)
        for k, i in enumerate(order):
            msg = msg.replace(f"voussoirs[{k}]", f"voussoir {labels[i]}")
        raise ArchInputError(msg) from None
    return arch, tuple(order)


def _centroid(p: np.ndarray) -> np.ndarray:
    q = p - p[0]
    x, y = q[:, 0], q[:, 1]
    x1, y1 = np.roll(x, -1), np.roll(y, -1)
    c = x * y1 - x1 * y
    a = 0.5 * c.sum()
    return p[0] + np.array([((x + x1) * c).sum(), ((y + y1) * c).sum()]) / (6.0 * a)


# ---------------------------------------------------------------------------- DXF
def _ezdxf():
    try:
        import ezdxf
    except ImportError:
        raise ImportError("reading DXF drawings needs ezdxf: pip install 'archrock[dxf]'") from None
    return ezdxf


def _vertices(entity) -> np.ndarray:
    from ezdxf import path as ezpath

    if entity.dxftype() == "LWPOLYLINE":
        has_bulge = any(b != 0 for *_, b in entity.get_points("xyb"))
    else:
        has_bulge = any(v.dxf.get("bulge", 0) != 0 for v in entity.vertices)
    pth = ezpath.make_path(entity)
    if has_bulge:
        box = np.array([(v.x, v.y) for v in pth.control_vertices()])
        extent = float(np.max(np.ptp(box, axis=0))) if len(box) else 1.0
        pts = [(v.x, v.y) for v in pth.flattening(distance=1e-4 * extent)]
    else:
        pts = [(v.x, v.y) for v in pth.control_vertices()]
    return np.array(pts, float).reshape(-1, 2)


def _is_closed(entity, pts: np.ndarray) -> bool:
    closed = entity.closed if entity.dxftype() == "LWPOLYLINE" else entity.is_closed
    return bool(closed) or (len(pts) > 3 and np.all(pts[0] == pts[-1]))


def _dxf_document(ezdxf, data: bytes):
    """The ezdxf drawing of a DXF file's bytes, as ``ezdxf.readfile`` reads a file: binary DXF
    by its signature, else text in the encoding its header names (universal newlines)."""
    import io

    from ezdxf.document import Drawing
    from ezdxf.filemanagement import dxf_stream_info
    from ezdxf.lldxf.tagger import binary_tags_loader
    from ezdxf.lldxf.validator import is_dxf_stream

    if data[:22] == b"AutoCAD Binary DXF\r\n\x1a\x00":
        return Drawing.load(binary_tags_loader(data, errors="surrogateescape"))
    if not is_dxf_stream(io.StringIO(data.decode("utf-8", errors="ignore"), newline=None)):
        raise OSError("not a DXF file")
    info = dxf_stream_info(io.StringIO(data.decode("utf-8", errors="ignore"), newline=None))
    return ezdxf.read(io.StringIO(data.decode(info.encoding, errors="surrogateescape"),
                                  newline=None))


def read_dxf_outlines(path: str | os.PathLike, layer: str | None = None,
                      units: str = "m") -> list[tuple[str, np.ndarray]]:
    """(handle, vertices [m]) of each closed polyline of the model space on ``layer`` (every
    layer if None; names compared case-insensitively, as in DXF) in drawing units ``units``."""
    if units not in UNITS:
        raise ArchInputError(f"units: {units!r}; allowed one of {', '.join(UNITS)}")
    ezdxf = _ezdxf()
    p = Path(path)
    if not p.is_file():
        raise ArchInputError(f"{p}: DXF file not found" if not p.exists() else
                             f"{p}: not a file, expected a DXF drawing")
    data = read_input(p, "DXF")  # bounded by size before ezdxf parses it
    try:
        doc = _dxf_document(ezdxf, data)
    except ezdxf.DXFStructureError as exc:
        raise ArchInputError(f"{p}: not a valid DXF drawing ({exc})") from None
    except (OSError, UnicodeDecodeError, ValueError) as exc:
        raise ArchInputError(f"{p}: cannot read the DXF drawing ({exc})") from None
    by_layer: dict[str, list] = {}
    for e in doc.modelspace().query(_TYPES):
        if e.dxftype() == "POLYLINE" and not (e.is_2d_polyline or e.is_3d_polyline):
            continue  # meshes and polyface meshes
        pts = _vertices(e)
        if not _is_closed(e, pts):
            continue
        by_layer.setdefault(e.dxf.layer, []).append((e.dxf.handle, pts * UNITS[units]))
    if layer is None:
        found = [item for items in by_layer.values() for item in items]
        if not found:
            raise ArchInputError(f"{p}: no closed polylines in the drawing; allowed one closed "
                                 f"LWPOLYLINE or POLYLINE per voussoir")
    else:
        found = [item for name, items in by_layer.items() if name.lower() == layer.lower()
                 for item in items]
        if not found:
            have = ", ".join(repr(k) for k in sorted(by_layer)) or "none"
            raise ArchInputError(f"{p}: layer {layer!r} has no closed polylines; layers with "
                                 f"closed polylines: {have}")
    try:
        header_units = _INSUNITS.get(int(doc.header.get("$INSUNITS", 0)))
    except (TypeError, ValueError):
        header_units = None
    _check_extent(p, found, units, header_units)
    return found


def _check_extent(p: Path, found, units: str, header_units: str | None) -> None:
    """Refuse a drawing whose size in metres cannot be an arch (wrong drawing units), naming
    the ``--units`` that would make it one (and what the DXF header says)."""
    pts = np.vstack([q for _, q in found])
    extent = float(np.max(np.ptp(pts, axis=0)))
    if MIN_EXTENT_M <= extent <= MAX_EXTENT_M:
        return
    raw = extent / UNITS[units]  # the size in the drawing's own numbers
    fits = [u for u in UNITS if u != units and MIN_EXTENT_M <= raw * UNITS[u] <= MAX_EXTENT_M]
    fits.sort(key=lambda u: (u != header_units, abs(np.log10(raw * UNITS[u] / 10.0))))
    hint = "; ".join(f"drawn in {u}? give --units {u} ({raw * UNITS[u]:.4g} m)" for u in fits[:1])
    said = f"; the DXF header says {header_units}" if header_units and header_units != units else ""
    raise ArchInputError(f"{p}: the arch is {extent:.4g} m across read in {units}; allowed "
                         f"{MIN_EXTENT_M:g} m to {MAX_EXTENT_M:g} m (units? "
                         f"{hint or 'check the drawing units'}{said})")


def read_dxf(path: str | os.PathLike, layer: str | None = None, units: str = "m", *,
             density: float = DEFAULT_DENSITY, name: str | None = None):
    """The arch drawn in a DXF file, one closed polyline per voussoir (module docstring).
    Returns ``(arch, handles)``: a :class:`PolygonArch` (named after the file unless ``name``)
    and the DXF handle of each voussoir from the left springing."""
    found = read_dxf_outlines(path, layer, units)
    handles = [h for h, _ in found]
    try:
        arch, order = arch_from_outlines([pts for _, pts in found], handles, density=density,
                                         name=name or Path(path).stem)
    except ArchInputError as exc:
        raise ArchInputError(f"{Path(path)}: {exc}") from None
    return arch, tuple(handles[i] for i in order)

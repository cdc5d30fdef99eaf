"""The drawing blocks of every figure (matplotlib, imported lazily: the core modules never
import this one): the colours (:data:`STYLE`), an arch's voussoirs, joints, loads, supports and
hinges (:func:`draw_arch`, :func:`draw_hinges`), a line of thrust clipped to the arch, and the
figure files: :func:`new_figure` and :func:`save_figure` render with the Agg canvas directly, so
scripts and the CLI never depend on an interactive backend.

Lengths in metres, angles in radians unless a name says ``_deg``.
"""

from __future__ import annotations

import math
import os
from pathlib import Path

import numpy as np

from ..errors import ArchInputError
from ..geometry import Arch


# Colours shared by every figure so that later figures look like Fig. 3.
STYLE = {
    "voussoir_face": "#e8dcc4",
    "voussoir_edge": "#5a4a32",
    "joint": "#2b2b2b",
    "thrust": "#c0392b",
    "hinge": "#1f4e9c",
    "ground": "#777777",
    "fill": "#d9cfa6",
    "load": "#7d3c98",
    # the blocks of an arch on piers that are not voussoirs (docs/piers.md): a greyer stone
    "pier_face": "#c9c3b6",
    "buttress_face": "#b3aa96",
}


def block_faces(arch, facecolor: str | None = None) -> list:
    """The fill colour of each block: ``facecolor`` for all when given, else the voussoir
    colour, and on an arch on piers the pier (or buttress) colour for those blocks."""
    if facecolor is not None:
        return [facecolor] * arch.n
    kinds = getattr(arch, "block_kinds", None) or ("voussoir",) * arch.n
    return [STYLE.get(f"{k}_face", STYLE["voussoir_face"]) for k in kinds]


def _require_matplotlib():
    try:
        import matplotlib  # noqa: F401
    except ImportError:
        raise ImportError("matplotlib is required for figures: pip install 'archrock[plot]'") from None


# ---------------------------------------------------------------------------- building blocks
def voussoir_outline(arch, i: int, points_per_rad: float = 60.0) -> np.ndarray:
    """Closed outline (m, 2) [m] of voussoir ``i`` of any arch (``arch.outline(i)``, first
    point repeated at the end); a circular arch's arcs with ``points_per_rad`` points a radian.

    Uses the voussoir's own shape, so irregular arches are drawn as they are.
    """
    out = arch.outline(i, points_per_rad) if isinstance(arch, Arch) else arch.outline(i)
    return np.vstack([out, out[:1]])


def _face(arch, j: int):
    """(intrados end, extrados end, unit vector from the first to the second) of joint j."""
    p0, p1 = (np.asarray(q, float) for q in arch.joint_points[j])
    d = p1 - p0
    return p0, p1, d / max(float(np.hypot(*d)), 1e-300)


def draw_arch(ax, arch, *, facecolor: str | None = None, edgecolor: str | None = None,
              alpha: float = 1.0, joints: bool = True, ground: bool = True,
              label_joints=False, loads: bool = True, zorder: float = 1.0):
    """Draw the voussoirs of any arch and, optionally, the joint contact segments, the
    springing supports, the joint numbers 0..n and the loads (markers, area ~ mass) with the
    fill above the extrados where the arch has one.  Sets an equal aspect ratio.

    ``label_joints``: False, True (numbers outside the extrados) or a collection of joints
    whose numbers go inside the intrados instead (to keep clear of extrados hinge labels).

    Returns the list of voussoir patches (reusable, e.g. to move them in an animation).
    """
    _require_matplotlib()
    from matplotlib.patches import Polygon

    faces = block_faces(arch, facecolor)
    edge = STYLE["voussoir_edge"] if edgecolor is None else edgecolor
    if loads:
        for region in getattr(arch, "fill_regions", ()) or ():
            if region is not None:
                ax.add_patch(Polygon(region, closed=True, facecolor=STYLE["fill"], edgecolor="none",
                                     alpha=0.8 * alpha, zorder=zorder - 0.2))
    patches = []
    # many voussoirs: thinner lines (500 joints at the usual width paint the arch black)
    thin = min(1.0, _DENSE_JOINTS / max(arch.n, 1))
    named = set()
    for i in range(arch.n):
        kind = arch.block_kinds[i] if facecolor is None and hasattr(arch, "block_kinds") else None
        # a legend entry for the piers (once per kind), none for the voussoirs
        label = kind if kind not in (None, "voussoir") and kind not in named else None
        named.add(kind)
        poly = Polygon(voussoir_outline(arch, i), closed=True, facecolor=faces[i], edgecolor=edge,
                       linewidth=0.8 * thin, alpha=alpha, zorder=zorder, label=label)
        ax.add_patch(poly)
        patches.append(poly)
    if joints:
        # The contact segment of a joint is the overlap of its neighbours' faces; draw that
        # part darker so steps between irregular voussoirs stay visible.
        for j in range(arch.n + 1):
            (x0, y0), (x1, y1) = arch.joint_points[j]
            ax.plot([x0, x1], [y0, y1], color=STYLE["joint"], lw=max(0.1, 1.4 * thin),
                    solid_capstyle="butt", zorder=zorder + 0.1)
    if ground:
        for j in (0, arch.n):
            _draw_support(ax, arch, j, zorder)
    if label_joints:
        inside = set(label_joints) if isinstance(label_joints, (set, frozenset, list, tuple)) else set()
        step = _label_step(arch.n)
        for j in range(arch.n + 1):
            if j % step == 0 or j == arch.n or j in inside:
                label_joint(ax, arch, j, inside=j in inside, zorder=zorder + 0.2)
    if loads and arch.loads:
        fill = {id(ld) for ld in _fill_loads(arch)}
        m_max = max(ld.mass for ld in arch.loads) or 1.0
        for k, ld in enumerate(arch.loads):
            is_fill = id(ld) in fill
            ax.plot([ld.at[0]], [ld.at[1]], "v" if not is_fill else "o",
                    ms=4.0 + 8.0 * math.sqrt(ld.mass / m_max), mfc=STYLE["load"],
                    mec="white", mew=0.6, alpha=0.9, zorder=zorder + 3,
                    label=None if k else "loads (area ~ mass)")
    ax.set_aspect("equal")
    ax.autoscale_view()
    return patches


#: Above this many voussoirs the joints are drawn thinner and only some are numbered.
_DENSE_JOINTS = 40


def springing_level(arch) -> float:
    """The height of the ground the arch stands on [m]: the lowest point of its two springing
    joints (an arch whose centre is at the origin springs above y = 0)."""
    jp = np.asarray(arch.joint_points, float)
    return float(min(jp[0, :, 1].min(), jp[-1, :, 1].min()))


def _label_step(n: int) -> int:
    """Number every joint up to _DENSE_JOINTS voussoirs, else every 5th, 10th, 20th, 25th,
    50th, 100th, ... joint: at most about 12 numbers."""
    if n <= _DENSE_JOINTS:
        return 1
    for base in (1, 10, 100, 1000, 10000, 100000):
        for m in (5, 10, 20, 25, 50):
            if m * base >= n / 12 and (m * base) % 10 in (0, 5):
                return m * base
    return max(1, n // 12)


def _fill_loads(arch) -> list:
    """The loads of an arch that stand for its fill (a FamilyArch's loads after the user's)."""
    recipe = getattr(arch, "recipe", None)
    if not recipe or not recipe.get("fill"):
        return []
    return list(arch.loads[len(recipe.get("loads", ())):])


def label_joint(ax, arch, j: int, inside: bool = False, zorder: float = 1.2):
    """Write the number of joint ``j`` just beyond its extrados end (or its intrados end),
    along the joint's face."""
    p0, p1, u = _face(arch, j)
    gap = 0.06 * arch.size
    x, y = p0 - gap * u if inside else p1 + gap * u
    ax.text(x, y, str(j), ha="center", va="center", fontsize=8, color="#555555", zorder=zorder)


def _draw_support(ax, arch, j: int, zorder: float):
    """Hatched strip under a springing joint (the ground the end voussoir rests on)."""
    from matplotlib.patches import Polygon

    p0, p1, u = _face(arch, j)
    width = float(np.hypot(*(p1 - p0)))
    # normal of the springing face, pointing away from its voussoir
    normal = np.array([-u[1], u[0]])
    own = arch.area_centroids[0 if j == 0 else arch.n - 1]
    if normal @ (own - p0) > 0:
        normal = -normal
    depth = 0.3 * width
    # widen the strip a little beyond the contact segment, as a support block
    along = u * 0.15 * width
    pts = np.array([p0 - along, p1 + along, p1 + along + depth * normal, p0 - along + depth * normal])
    ax.add_patch(Polygon(pts, closed=True, facecolor="white", edgecolor=STYLE["ground"],
                         hatch="////", linewidth=0.6, zorder=zorder - 0.1))


def draw_hinges(ax, arch, mechanism, *, color: str | None = None, labels: bool = True,
                zorder: float = 5.0):
    """Mark the four hinges of ``mechanism`` and label them A, B, C, D.

    Labels sit on the side of the edge away from the masonry (beyond the intrados or the
    extrados end, along the joint's face) so they never cover the voussoirs.
    """
    _require_matplotlib()
    col = STYLE["hinge"] if color is None else color
    for label, h in mechanism.labelled():
        x, y = arch.joint_point(h.joint, h.edge)
        ax.plot([x], [y], "o", ms=8, mfc="white", mec=col, mew=2.0, zorder=zorder)
        if labels:
            _, _, u = _face(arch, h.joint)
            off = 0.075 * arch.size * (1.0 if h.edge == "extrados" else -1.0)
            ax.text(x + off * u[0], y + off * u[1], label, ha="center", va="center",
                    fontsize=12, fontweight="bold", color=col, zorder=zorder + 0.1)


def _thrust_points(thrust, arch) -> np.ndarray:
    """Where the line of thrust crosses each joint (n+1, 2) [m]: ``thrust.points`` (any arch),
    else from its radii on the radial joints of a circular arch."""
    pts = getattr(thrust, "points", None)
    if pts is not None:
        return np.asarray(pts, float)
    psi = arch.joint_angles
    r = np.asarray(thrust.radii, float)
    return np.column_stack([r * np.cos(psi), r * np.sin(psi)])


def clip_thrust_polyline(poly, arch, crossings) -> np.ndarray:
    """The polyline ``poly`` (m, 2) [m] of a line of thrust (its funicular polygon: the joint
    crossings and, between them, the vertices on the load lines) as drawn: from the crossing of
    joint 0 to that of joint n, every vertex kept only if it lies within its voussoir, between
    the lines of the two joints whose crossings enclose it.

    A vertex is where the lines of action of the forces on both sides of a voussoir meet; near a
    springing, or on a thin voussoir (hundreds of voussoirs), that point can lie far outside the
    voussoir (two nearly parallel lines), below the springing: drawn, the line runs into the
    abutment or zigzags out of the masonry.  Dropping it draws the thrust straight from one
    crossing to the next there.  ``crossings``: the thrust's (n+1, 2) joint crossings; a
    polyline that does not pass through them is only cut at the springing joints."""
    poly = np.asarray(poly, float)
    pts = np.asarray(crossings, float)
    if poly.ndim != 2 or len(poly) < 2 or len(pts) != arch.n + 1:
        return poly
    jp = np.asarray(arch.joint_points, float)
    cen = np.asarray(arch.centroids, float)
    tol = 1e-9 * max(1.0, float(np.ptp(jp.reshape(-1, 2), axis=0).max()))

    def inside(p, joint, voussoir):
        """Whether the points p lie on voussoir ``voussoir``'s side of joint ``joint``'s line."""
        a, b = jp[joint]
        u = (b - a) / max(np.hypot(*(b - a)), 1e-300)
        side = u[0] * (p[:, 1] - a[1]) - u[1] * (p[:, 0] - a[0])
        ref = u[0] * (cen[voussoir][1] - a[1]) - u[1] * (cen[voussoir][0] - a[0])
        return (side if ref >= 0 else -side) >= -tol

    # a joint that lifts off has no crossing (NaN): the line runs from the last crossing before
    # it to the first after it
    joints = [j for j in range(arch.n + 1) if np.all(np.isfinite(pts[j]))]
    if len(joints) < 2:
        return poly
    # the polyline's index of each crossing, in order (None where it does not pass through it)
    where, k = [], 0
    for j in joints:
        d = np.hypot(*(poly[k:] - pts[j]).T)
        hit = np.flatnonzero(d <= 1e-7 * max(1.0, arch.size))
        if len(hit) == 0:
            where = None
            break
        k += int(hit[0])
        where.append(k)
    if where is None:  # not a funicular polygon through the crossings: cut at the springings
        keep = inside(poly, 0, 0) & inside(poly, arch.n, arch.n - 1)
        first = int(np.argmax(keep)) if keep.any() else 0
        last = len(poly) - int(np.argmax(keep[::-1])) if keep.any() else len(poly)
        return np.vstack([pts[joints[0]], poly[first:last], pts[joints[-1]]])
    out = [pts[joints[0]]]
    for (ja, wa), (jb, wb) in zip(zip(joints, where), zip(joints[1:], where[1:])):
        between = poly[wa + 1:wb]
        if len(between):
            ok = inside(between, ja, ja) & inside(between, jb, jb - 1)
            out.extend(between[ok])
        out.append(pts[jb])
    return np.vstack(out)


def voussoir_bounds(arch) -> np.ndarray:
    """All outline points of all voussoirs (and of the fill, if any), (m, 2) [m] (for axis
    limits)."""
    pts = [voussoir_outline(arch, i, points_per_rad=10.0) for i in range(arch.n)]
    pts += [r for r in getattr(arch, "fill_regions", ()) or () if r is not None]
    return np.vstack(pts)


def new_figure(nrows: int = 1, ncols: int = 1, figsize=(7.0, 4.6), **kwargs):
    """A (figure, axes) pair on the Agg canvas, independent of pyplot's global state."""
    _require_matplotlib()
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    fig = Figure(figsize=figsize, layout="constrained")
    FigureCanvasAgg(fig)
    axes = fig.subplots(nrows, ncols, squeeze=False, **kwargs)
    return fig, axes


#: Largest figure written, width x height in pixels. Agg holds 4 bytes a pixel in memory, so
#: 50 Mpx is 200 MB; a full-page print at 600 dpi is about 35 Mpx. Above it a huge --dpi would
#: exhaust memory (or hit Agg's 2^23-pixel side limit with a traceback).
MAX_FIGURE_PIXELS = 50_000_000
#: Smallest resolution: below it text is unreadable and a figure may round to zero pixels.
MIN_DPI = 10


def output_file(path, what: str, example: str) -> Path:
    """``path`` as the name of a file to write, checked before any work: a non-empty name, not a
    folder (``what`` names the field in the message, ``example`` a valid name)."""
    text = os.fspath(path) if isinstance(path, (str, os.PathLike)) else None
    if not text or not text.strip():
        raise ArchInputError(f"{what}: {path!r}; allowed a file name such as {example}")
    p = Path(text)
    if text.endswith(("/", os.sep)) or p.is_dir():
        raise ArchInputError(f"{what}: {text!r} is a folder; allowed a file name such as "
                             f"{(p / example).as_posix()!r}")
    return p


def figure_path(path: str | os.PathLike) -> Path:
    """The file a figure written to ``path`` lands in, checked before any work is done: the
    extension names a format matplotlib can write (no extension: '.png' is added, as
    matplotlib itself would do), and the path is not a folder."""
    _require_matplotlib()
    from matplotlib.backend_bases import FigureCanvasBase

    p = output_file(path, "figure file", "fig.png")
    text = os.fspath(path)
    formats = FigureCanvasBase.get_supported_filetypes()
    if not p.suffix:
        return p.with_name(p.name + ".png")
    if p.suffix[1:].lower() not in formats:
        raise ArchInputError(f"figure file: {text!r}: format {p.suffix!r} cannot be written; "
                             f"allowed extensions {', '.join('.' + f for f in sorted(formats))}")
    return p


def save_figure(fig, path: str | os.PathLike, dpi: int = 150) -> Path:
    """Write ``fig`` to ``path`` (format from the extension, '.png' when there is none; parent
    folders are created) and return the path written. The pixel count is bounded
    (:data:`MAX_FIGURE_PIXELS`)."""
    p = figure_path(path)
    w, h = fig.get_size_inches()
    if not (isinstance(dpi, (int, float)) and math.isfinite(dpi)) or dpi < MIN_DPI \
            or w * h * dpi * dpi > MAX_FIGURE_PIXELS:
        top = int(math.sqrt(MAX_FIGURE_PIXELS / (w * h)))
        raise ArchInputError(f"dpi: {dpi!r}; allowed {MIN_DPI} to {top} for this "
                             f"{w:g} x {h:g} in figure (at most {MAX_FIGURE_PIXELS:,} pixels)")
    try:
        p.parent.mkdir(parents=True, exist_ok=True)
        fig.savefig(p, dpi=dpi)
    except OSError as exc:
        raise ArchInputError(f"{p}: cannot write the figure ({exc.strerror or exc})") from None
    return p

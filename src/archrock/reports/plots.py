"""Figures (matplotlib, imported lazily: the core modules never import this one).

Organisation:

* building blocks: :func:`voussoir_outline`, :func:`draw_arch`, :func:`draw_hinges`;
* limit analysis: :func:`plot_limit` (the paper's Fig. 3 for any arch),
  :func:`save_limit_figure` (PNG, one panel per direction);
* defect maps: :func:`plot_defect_map` (the arch coloured by the capacity lost);
* saving: :func:`new_figure` and :func:`save_figure` render with the Agg canvas directly, so
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

__all__ = [
    "voussoir_outline",
    "voussoir_bounds",
    "label_joint",
    "draw_arch",
    "draw_hinges",
    "plot_limit",
    "save_limit_figure",
    "new_figure",
    "save_figure",
    "figure_t_end",
    "figure_path",
    "MAX_FIGURE_PIXELS",
    "plot_ground_motion",
    "plot_response",
    "save_response_figure", "PAPER_FIGURES",
    "draw_displaced",
    "displaced_outlines",
    "displaced_hinges",
    "plot_defect_map",
    "defect_norm",
    "plot_k_against_pier_height",
    "block_faces",
]


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


# ---------------------------------------------------------------------------- limit analysis
def plot_limit(result, direction: str = "l", ax=None, *, show_loads: bool = True,
               label_joints: bool = True):
    """The paper's Fig. 3 for any arch: voussoirs, joints, line of thrust at collapse and the
    hinges A-D of mechanism M_l (``direction='l'``) or M_r (``'r'``); title with k.

    ``result`` is a :class:`archrock.statics.limit.LimitResult`. Returns the axes.
    """
    _require_matplotlib()
    if direction not in ("l", "r"):
        raise ArchInputError(f"direction: {direction!r}; allowed 'l' or 'r'")
    if ax is None:
        import matplotlib.pyplot as plt

        _, ax = plt.subplots(figsize=(7, 4.6))
    arch = result.arch
    mech = result.mechanism(direction)
    thrust = result.thrust_l if direction == "l" else result.thrust_r
    k = result.k_l if direction == "l" else result.k_r

    # joint numbers go inside where an extrados hinge label sits outside, and vice versa
    ext = {h.joint for h in mech.hinges if h.edge == "extrados"}
    draw_arch(ax, arch, label_joints=ext if label_joints else False)
    poly = getattr(thrust, "polyline", None)
    pts = _thrust_points(thrust, arch)
    poly = clip_thrust_polyline(pts if poly is None else poly, arch, pts)
    ax.plot(poly[:, 0], poly[:, 1], "-", color=STYLE["thrust"], lw=1.6, zorder=4,
            label="line of thrust at collapse")
    ax.plot(pts[:, 0], pts[:, 1], ".", color=STYLE["thrust"], ms=4, zorder=4)
    draw_hinges(ax, arch, mech)
    jp = np.asarray(arch.joint_points, float)
    for i, j in enumerate(getattr(mech, "lift_off", ())):
        # the joint opens at both ends: drawn as a thick dashed line across it
        ax.plot(jp[j, :, 0], jp[j, :, 1], "--", color=STYLE["thrust"], lw=3.0, zorder=5,
                label="joint that lifts off" if i == 0 else None)

    bounds = voussoir_bounds(arch)
    (xmin, ymin), (xmax, ymax) = bounds.min(axis=0), bounds.max(axis=0)
    size = 0.5 * max(xmax - xmin, ymax - ymin)
    xc = 0.5 * (xmin + xmax)
    if show_loads:
        # Direction of the horizontal forces lambda*W (toward +x for M_l, -x for M_r).
        sgn = 1.0 if direction == "l" else -1.0
        y0 = ymin + 0.25 * (ymax - ymin)
        x0 = xc - 0.18 * size * sgn
        ax.annotate("", xy=(x0 + 0.36 * size * sgn, y0), xytext=(x0, y0),
                    arrowprops=dict(arrowstyle="-|>", color="#444444", lw=1.5))
        ax.text(xc, y0 - 0.07 * size, rf"$\lambda W$, $\lambda = k_{direction}$", ha="center",
                va="top", fontsize=9, color="#444444")

    seq = ", ".join(f"{lab} = {h.joint}{'i' if h.edge == 'intrados' else 'e'}"
                    for lab, h in mech.labelled())
    if getattr(mech, "lift_off", ()):
        seq += f"; lifts off at joint {', '.join(map(str, mech.lift_off))}"
    title = (f"{arch.name}: mechanism $M_{direction}$, $k_{direction}$ = {k:.4f}\n"
             f"hinges (joint, i = intrados / e = extrados): {seq}")
    if getattr(arch, "pier_blocks", ()):
        from ..geometry.piers import hinge_place

        # where the hinges are, in words: a pier's faces are not an intrados and an extrados
        title += "\n" + "; ".join(f"{lab}: {hinge_place(arch, h.joint, h.edge)}"
                                  for lab, h in mech.labelled())
    ax.set_title(title, fontsize=10 if not getattr(arch, "pier_blocks", ()) else 8)
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.legend(loc="lower center", fontsize=8, frameon=False)
    pad = 0.12 * size
    ax.set_xlim(xmin - pad, xmax + pad)
    # room below for the legend and above for the joint numbers, not the empty space down to y = 0
    # (a flat arch)
    ax.set_ylim(ymin - 0.45 * size, ymax + 0.2 * size)
    ax.grid(True, lw=0.3, alpha=0.4)
    return ax


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


def save_limit_figure(result, path: str | os.PathLike, directions=("l", "r"), dpi: int = 150) -> Path:
    """Write a PNG with one :func:`plot_limit` panel per direction ('l', 'r'). Returns the path."""
    directions = tuple(directions)
    if not directions or any(d not in ("l", "r") for d in directions):
        raise ArchInputError(f"directions: {directions!r}; allowed a non-empty sequence of 'l', 'r'")
    fig, axes = new_figure(1, len(directions), figsize=(6.4 * len(directions), 4.8))
    for ax, d in zip(axes[0], directions):
        plot_limit(result, d, ax=ax)
    return save_figure(fig, path, dpi=dpi)


def plot_k_against_pier_height(table, path: str | os.PathLike | None = None, *, ax=None,
                               dpi: int = 150):
    """k_l and k_r of an arch on piers against the piers' height over the clear span (a
    :class:`~archrock.statics.buttress.PierHeightTable`; height 0: the arch on rigid ground),
    each point marked where hinge D leaves the pier's foot.  Writes ``path`` when given and
    returns it, else the axes."""
    _require_matplotlib()
    if ax is None:
        fig, axes = new_figure(figsize=(6.4, 4.4))
        ax = axes[0][0]
    else:
        fig = None
    x = np.asarray(table.heights, float) / table.span
    ax.plot(x, table.k_l, "o-", color=STYLE["thrust"], ms=4, lw=1.4, label="$k_l$")
    ax.plot(x, table.k_r, "s--", color=STYLE["hinge"], ms=3, lw=1.0, mfc="none", label="$k_r$")
    foot = np.array(["foot" in p for p in table.places_l])
    if foot.any() and not foot.all():
        ax.plot(x[~foot], np.asarray(table.k_l)[~foot], "o", ms=8, mfc="none", mec="#444444",
                label="hinge D not at a pier's foot")
    if x.size and x[0] == 0:
        ax.axhline(table.k_l[0], color="#777777", lw=0.8, ls=":", label="rigid ground")
    ax.set_xlabel("pier height / clear span")
    ax.set_ylabel("collapse multiplier k [g]")
    extra = f", batter {table.batter:g}" if table.batter else ""
    ax.set_title(f"{table.arch_name} on piers {table.width:g} m wide ({table.courses} "
                 f"course{'s' if table.courses != 1 else ''}{extra}); span {table.span:.4g} m",
                 fontsize=10)
    ax.set_ylim(bottom=0)
    ax.grid(True, lw=0.3, alpha=0.4)
    ax.legend(fontsize=8, frameon=False)
    if path is not None and fig is not None:
        return save_figure(fig, path, dpi=dpi)
    return ax


# ---------------------------------------------------------------------------- dynamics
#: the figure of a response runs to its end (rest or collapse) but at most this much past the
#: later of the requested end and the ground motion's end [s], and at most twice the requested end
#: when that is later: a run that rocks freely for a minute is not drawn to the last second
FIGURE_TAIL_S = 10.0


def figure_t_end(response, t_end: float | None = None) -> float:
    """End of the time axis [s] of a figure or animation of ``response``: ``t_end`` (default the
    response's own sampled end) or, when the run ended later (at rest, or at the rotation limit
    after a collapse), that end plus 5 %, capped at max(2 t_end, motion end + FIGURE_TAIL_S)."""
    t_end = float(response.time[-1]) if t_end is None else float(t_end)
    if not math.isfinite(t_end) or t_end <= 0:
        raise ArchInputError(f"t_end: {t_end!r}; allowed a finite number > 0 s")
    end = response.t_final * 1.05
    if end <= t_end:
        return t_end
    cap = max(2.0 * t_end, response.motion.duration + FIGURE_TAIL_S)
    return min(end, cap)


def _motion_title(motion) -> str:
    """'Oppenheim pulse: $a$ = −1 g, $t_p$ = 0.2 s' for a pulse (from its source), else its name."""
    src = motion.source.split(";")[0]
    if "pulse: " not in src:
        return motion.name
    params = src.split("pulse: ", 1)[1]
    params = (params.replace("t_p =", "$t_p$ =").replace("a =", "$a$ =")
              .replace("period =", "$T$ =").replace("= -", "= \u2212"))
    return f"{motion.name}: {params}"


def plot_ground_motion(motion, ax, t_end: float | None = None, in_g: bool = True):
    """Ground acceleration history (paper Fig. 4a): xg''/g (or m/s^2) against time [s]; the line
    is labelled with the motion (a pulse with its amplitude and duration) for a legend."""
    from ..groundmotion import G

    t_end = max(motion.duration, 1e-9) * 1.1 if t_end is None else t_end
    t = np.concatenate([motion.times, [motion.duration, max(t_end, motion.duration)]])
    a = np.concatenate([motion.accel, [0.0, 0.0]]) / (G if in_g else 1.0)
    ax.plot(t, a, color="#333333", lw=1.4, drawstyle="default", label=_motion_title(motion))
    ax.set_xlim(0.0, t_end)
    ax.set_xlabel("$t$ [s]")
    ax.set_ylabel(r"$\ddot{x}_g/g$" if in_g else r"$\ddot{x}_g$ [m/s$^2$]")
    ax.set_title(_motion_title(motion), fontsize=9)
    ax.grid(True, lw=0.3, alpha=0.4)
    return ax


def plot_response(response, ax, label: str | None = None, color: str | None = None,
                  show_events: bool = True):
    """Signed response phi (+ in M_l, - in M_r, paper Fig. 4b-d) against time [s], each line
    labelled for a legend: the response, the unstable positions +-phi_u of M_l / M_r, the
    impacts and, after a collapse, its instant (on the curve, at phi_u: the last upward passage)
    and the rotation limit where the integration stopped."""
    m = response.model
    line, = ax.plot(response.time, response.response, lw=1.4, color=color,
                    label=r"response $\phi$" if label is None else f"{label}: $\\phi$")
    c = line.get_color()
    t_end = response.time[-1]
    ax.axhline(m.phi_unstable_l, color="#aa3333", lw=0.7, ls="--", alpha=0.7,
               label=r"unstable positions $+\phi_u$ (M$_l$), $-\phi_u$ (M$_r$)")
    ax.axhline(-m.phi_unstable_r, color="#aa3333", lw=0.7, ls="--", alpha=0.7)
    if show_events:
        shown = [t for t in response.impacts if t <= t_end]
        n_all = len(response.impacts)
        for k, t in enumerate(shown):
            ax.axvline(t, color=c, lw=0.6, ls=":", alpha=0.8,
                       label=None if k else f"impacts ({len(shown)}" +
                       (f" shown of {n_all})" if n_all > len(shown) else ")"))
        if response.collapsed and response.t_collapse <= t_end:
            # the collapse is where the curve passes phi_u for the last time: mark it there
            ev = [e for e in response.events if e.kind == "collapse"][-1]
            fl = m.mechanism(ev.row_before)
            y = (1.0 if fl.direction == "l" else -1.0) * fl.phi_unstable
            ax.plot([response.t_collapse], [y], "X", color="#c0392b", ms=8, mec="white", mew=0.8,
                    zorder=5, label=f"collapse $t_c$ = {response.t_collapse:.2f} s "
                                    r"(last passage of $\phi_u$)")
            if response.t_limit <= t_end:
                ylim = (1.0 if fl.direction == "l" else -1.0) * m.chain[1][ev.row_before]
                ax.plot([response.t_limit], [ylim], "|", color="#555555", ms=12, mew=1.5,
                        zorder=5, clip_on=False, label=f"rotation limit at {response.t_limit:.2f} s "
                                        "(integration stops)")
    ax.set_xlim(0.0, t_end)
    ax.set_xlabel("$t$ [s]")
    ax.set_ylabel(r"$\phi$ [rad] (+M$_l$, $-$M$_r$)")
    outcome = (f"collapses at {response.t_collapse:.2f} s" if response.collapsed else
               "at rest" if response.status == "rest" else "still rocking")
    n_imp = len(response.impacts)
    outcome += f" after {n_imp} impact{'s' if n_imp != 1 else ''}" if response.collapsed else \
        f" after {n_imp} impact{'s' if n_imp != 1 else ''}, at {response.t_final:.2f} s" \
        if response.status == "rest" else ""
    ax.set_title(f"{label or m.arch.name}: $k_l$ = {m.k_l:.4f}, $k_r$ = {m.k_r:.4f}; {outcome}",
                 fontsize=9)
    ax.grid(True, lw=0.3, alpha=0.4)
    return ax


def save_response_figure(responses, path, labels=None, dpi: int = 150):
    """Ground motion on top, then one response panel per response (paper Fig. 4 layout), each
    with its legend, on one time axis that runs to the longest response's sampled end."""
    responses = list(responses)
    labels = list(labels) if labels is not None else [None] * len(responses)
    fig, axes = new_figure(len(responses) + 1, 1, figsize=(9.0, 2.4 * (len(responses) + 1)),
                           sharex=True)
    t_end = max(r.time[-1] for r in responses)
    plot_ground_motion(responses[0].motion, axes[0][0], t_end=t_end)
    for k, (res, lab) in enumerate(zip(responses, labels)):
        plot_response(res, axes[k + 1][0], label=lab)
    letters = "abcdefgh"
    for k, row in enumerate(axes):
        ax = row[0]
        ax.set_xlim(0.0, t_end)
        if k < len(axes) - 1:
            ax.set_xlabel("")
        ax.text(0.01, 0.93, f"({letters[k]})", transform=ax.transAxes, fontsize=9,
                va="top", fontweight="bold")
        ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=7, frameon=False,
                  borderaxespad=0.0)
    return save_figure(fig, path, dpi=dpi)


def _open_mechanism(model, mode):
    """The FourLink that ``mode`` names (None at rest): a FourLink, a row of the model's chain
    (int, -1 = rest), 'l' / 'r' (rows 0 / 1: M_l / M_r) or 'rest'."""
    from ..dynamics.fourlink import FourLink

    if mode is None or isinstance(mode, FourLink):
        return mode
    if isinstance(mode, str):
        if mode == "rest":
            return None
        return model.mechanism(mode)
    if isinstance(mode, (int, np.integer)) and not isinstance(mode, bool):
        return None if mode == -1 else model.mechanism(int(mode))
    raise ArchInputError(f"mode: {mode!r}; allowed a FourLink, a chain row (int, -1 = rest), "
                         f"'l', 'r' or 'rest'")


def displaced_outlines(model, mode, phi: float) -> list[np.ndarray]:
    """Outline (m, 2) [m] of every voussoir with mechanism ``mode`` open by rotation phi [rad]
    (phi >= 0 in the mechanism's own coordinate): each voussoir of a link moves rigidly with
    its link (exact four-bar kinematics); voussoirs outside the mechanism stay still.  Any arch
    shape: the outlines are :func:`voussoir_outline`.

    mode: a FourLink, a row of ``model.chain`` (int; -1 = rest; e.g. ``response.rows[k]``),
    or 'l' / 'r' (M_l / M_r, rows 0 / 1) or 'rest'."""
    from ..dynamics.fourlink import configuration

    arch = model.arch
    outlines = [voussoir_outline(arch, i) for i in range(arch.n)]
    fl = _open_mechanism(model, mode)
    if fl is not None and phi > 0:
        bx, by, cx, cy, th1, th2, th3, _ = configuration(phi, fl.geo)
        (ax0, ay0), (b0x, b0y), _, (dx, dy) = fl.points
        refs = (((ax0, ay0), (ax0, ay0), th1), ((b0x, b0y), (bx, by), th2), ((dx, dy), (dx, dy), th3))
        for idx, (p0, p1, th) in zip(fl.link_voussoirs, refs):
            rot = np.array([[math.cos(th), -math.sin(th)], [math.sin(th), math.cos(th)]])
            for i in idx:
                outlines[i] = (outlines[i] - np.array(p0)) @ rot.T + np.array(p1)
    return outlines


def displaced_hinges(model, mode, phi: float) -> np.ndarray:
    """Hinge points A, B, C, D (4, 2) [m] of mechanism ``mode`` (as in
    :func:`displaced_outlines`) open by rotation phi [rad]; empty (0, 2) at rest."""
    from ..dynamics.fourlink import configuration

    fl = _open_mechanism(model, mode)
    if fl is None:
        return np.zeros((0, 2))
    pts = np.array(fl.points, dtype=float)
    if phi > 0:
        bx, by, cx, cy, *_ = configuration(phi, fl.geo)
        pts[1], pts[2] = (bx, by), (cx, cy)
    return pts


def draw_displaced(ax, model, mode, phi: float, **kwargs):
    """Draw the arch displaced as in :func:`displaced_outlines`; returns the voussoir patches
    (update them with ``patch.set_xy`` to animate without redrawing the axes)."""
    from matplotlib.patches import Polygon

    faces = block_faces(model.arch, kwargs.get("facecolor"))
    edge = kwargs.get("edgecolor", STYLE["voussoir_edge"])
    patches = []
    for face, pts in zip(faces, displaced_outlines(model, mode, phi)):
        patch = Polygon(pts, closed=True, facecolor=face, edgecolor=edge, lw=0.8)
        ax.add_patch(patch)
        patches.append(patch)
    return patches


# ---------------------------------------------------------------------------- collapse curves, fragility
_MODE_MARKERS = {"before first impact": ("o", "#c0392b"), "after impacts": ("s", "#1f4e9c")}


def _plural(n: int, one: str, many: str | None = None) -> str:
    return f"{n} {one if n == 1 else (many or one + 's')}"


def _n_arches(n: int, n_requested: int, left_out: int) -> str:
    """'n = 20 random arches (3 of 23 left out)' for a legend or title."""
    extra = f" ({left_out} of {n_requested} left out: not counted)" if left_out else ""
    return f"$n$ = {n} random arch{'es' if n != 1 else ''}{extra}"


def plot_collapse_curve(curve, path: str | os.PathLike | None = None, band=None, *, ax=None,
                        title: str | None = None, dpi: int = 120):
    """Collapse-acceleration curve: first collapse amplitude |a| [g] against t_p [s].

    curve: :class:`archrock.studies.curves.CollapseCurve` (the nominal arch when a band is given);
    markers by collapse mode (before the first impact / after impacts), survival windows above
    the first collapse as vertical bars, the static multiplier k as a dotted line.  band: an
    :class:`archrock.studies.curves.EnsembleCurve` (its outer quantiles shaded, its median dashed, over
    its usable arches, n in the legend; a band that cannot be estimated is said so).  Every
    line has a legend entry.  Writes ``path`` when given; returns the figure.
    """
    fig = None
    if ax is None:
        fig, axes = new_figure(1, 1, figsize=(6.4, 4.4))
        ax = axes[0][0]
    d = np.asarray(curve.durations, dtype=float)
    a = np.asarray(curve.amplitudes, dtype=float)
    if band is not None:
        b = np.asarray(band.bands, dtype=float)
        q = band.quantiles
        n_txt = _n_arches(band.n_samples, band.n_requested, len(band.failed))
        if band.band_note:  # nothing to shade: say so rather than draw a zero-width band
            ax.plot([], [], " ", label=f"quantile band n/a ({band.band_note})")
            if len(band.amplitudes) == 1:
                one = np.where(np.isfinite(band.amplitudes[0]), band.amplitudes[0], np.nan)
                ax.plot(band.durations, one, "--", color="#1f4e9c", lw=1.0,
                        label=f"random arch {band.samples[0]}: first collapse $|a|$, {n_txt}")
        else:
            top = np.where(np.isfinite(b[-1]), b[-1], np.nan)  # inf: no collapse up to a_max
            ax.fill_between(band.durations, b[0], top, color="#9bb7d4", alpha=0.45, lw=0,
                            label=f"$q_{{{q[0]:g}}}$ to $q_{{{q[-1]:g}}}$ of random arches, "
                                  f"{n_txt}")
            if len(q) >= 3:
                mid = len(q) // 2
                ax.plot(band.durations, b[mid], "--", color="#1f4e9c", lw=1.0,
                        label=f"$q_{{{q[mid]:g}}}$ of random arches")
    name = "nominal arch" if band is not None else "arch"
    ax.plot(d, a, "-", color="#444444", lw=1.0, zorder=2, label=f"{name}: first collapse $|a|$")
    for key, (marker, color) in _MODE_MARKERS.items():
        sel = np.array([(m == key) if key == "before first impact" else
                        (m is not None and m.startswith("after")) for m in curve.modes])
        if sel.any():
            ax.plot(d[sel], a[sel], marker, color=color, ms=6, zorder=3,
                    label=f"{name}: collapse {key}")
    first = True
    for tp, wins in zip(d, curve.windows):
        for lo, hi in wins:
            ax.plot([tp, tp], [lo, hi], color="#27ae60", lw=3.0, alpha=0.8, zorder=2,
                    label=f"{name}: survival above first collapse" if first else None)
            first = False
    res = [r for r in (getattr(p, "resolution", None) for p in curve.points)
           if r and r.get("step_relative") is not None]  # the engine searches no windows
    if res:  # a list of windows says the step it was searched at (issue 30)
        rel = max(r["step_relative"] for r in res)
        ax.plot([], [], " ", label=f"windows searched at {100 * rel:.2g}% steps of $|a|$: "
                                   f"narrower ones may be missed")
    sign = curve.points[0].sign if curve.points else -1
    k = curve.k_l if sign < 0 else curve.k_r
    if math.isfinite(k):
        ax.axhline(k, color="#777777", ls=":", lw=1.0,
                   label=f"static multiplier $k_{'l' if sign < 0 else 'r'}$ = {k:.3f} g")
    ax.set_xlabel("pulse duration $t_p$ [s]")
    ax.set_ylabel("first collapse amplitude $|a|$ [g]")
    if title:
        ax.set_title(title, fontsize=10)
    ax.set_xlim(0, max(d) * 1.05)
    ax.set_ylim(0, None)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7.5, frameon=False)
    if fig is not None and path is not None:
        save_figure(fig, path, dpi=dpi)
    return fig if fig is not None else ax.figure


def plot_fragility(fit, stripes=None, path: str | os.PathLike | None = None, *, ida=None, ax=None,
                   im_label: str | None = None, dpi: int = 120):
    """Lognormal fragility P(collapse | IM): the fitted curve, its bootstrap band (the
    curves at the ends of the theta and beta intervals, when the fit carries them; an interval
    that cannot be estimated is said so), observed stripe fractions (an
    :class:`archrock.studies.ida.StripeResult`) and IDA first collapses (an
    :class:`archrock.studies.ida.IDAResult`, as an empirical CDF over its curves).  The title states the
    records and arches; im_label defaults to the IM of the results.  Writes ``path``; returns
    the figure."""
    fig = None
    if ax is None:
        fig, axes = new_figure(1, 1, figsize=(6.4, 4.4))
        ax = axes[0][0]
    from ..groundmotion.intensity import im_label as _label, im_units

    im = getattr(stripes, "im", None) or getattr(ida, "im", None) or "pga"
    unit = "" if im == "scale" else im_units(im)
    if im_label is None:
        im_label = _label(im)
    xs = []
    if stripes is not None:
        xs.append(np.asarray(stripes.levels, dtype=float))
    if ida is not None:
        f = ida.first_ims
        xs.append(f[np.isfinite(f)])
        xs.append(np.array([max(c.max_im for c in ida.curves)]))  # the range tried
    if fit is not None:  # a plateau's top quantile is never reached: up to 99% of p_max
        q = np.asarray(fit.quantile(np.array([0.01, 0.99]) * fit.p_max))
        xs.append(q if fit.p_max >= 1.0 else q[:1])
    if not xs:
        raise ArchInputError("fit: nothing to plot (give a fit, stripes or an IDA result)")
    x_hi = max(float(np.max(v)) for v in xs if np.size(v)) * 1.15
    x = np.linspace(0.0, x_hi, 300)
    if fit is not None:
        if fit.theta_ci is not None and fit.beta_ci is not None:
            from scipy.special import ndtr

            with np.errstate(divide="ignore"):
                lnx = np.log(x)
                curves = [fit.p_max * ndtr((lnx - math.log(t)) / b)
                          for t in fit.theta_ci for b in fit.beta_ci]
            ax.fill_between(x, np.min(curves, axis=0), np.max(curves, axis=0), color="#9bb7d4",
                            alpha=0.5, lw=0, label=f"{fit.confidence:.0%} bootstrap band")
        elif fit.ci_note:  # asked for but not estimated: no zero-width band
            import textwrap

            ax.plot([], [], " ", label=textwrap.fill(f"bootstrap band n/a: {fit.ci_note}", 55))
        plateau = (f", plateau $p_{{max}}$ = {fit.p_max:.3f}" if fit.p_max < 1.0 else "")
        ax.plot(x, fit.probability(x), color="#1f4e9c", lw=1.6,
                label=f"{fit.method} fit: $\\theta$ = {fit.theta:.3g} {unit}, "
                      f"$\\beta$ = {fit.beta:.2f}{plateau} ($n$ = "
                      + (_plural(fit.n_records, 'analysis', 'analyses') if fit.method == "mle"
                         else _plural(fit.n_records, 'curve')) + ")")
        if fit.p_max < 1.0:  # the data level off: say where, rather than run to P = 1
            ax.axhline(fit.p_max, color="#1f4e9c", ls=":", lw=1.0,
                       label=f"upper asymptote: P $\\leq$ {fit.p_max:.3f} over the range tried")
    if stripes is not None:
        ax.plot(stripes.levels, stripes.collapses / stripes.trials, "o", color="#c0392b",
                label=f"stripes: collapsed fraction of {_plural(int(stripes.trials[0]), 'analysis', 'analyses')}")
    if ida is not None:
        _ida_steps(ax, ida, unit)
    ax.set_xlabel(im_label)
    ax.set_ylabel("$P(\\mathrm{collapse} \\mid \\mathrm{IM})$")
    ax.set_xlim(0, x_hi)
    ax.set_ylim(-0.02, 1.02)
    ax.grid(True, alpha=0.3)
    nothing = ida is not None and not np.isfinite(ida.first_ims).any()
    ax.legend(fontsize=7.5, frameon=False, loc="upper left" if nothing else "lower right")
    src = stripes if stripes is not None else None
    if src is not None:
        n_rec, n_arch, failed = len(src.records), len(src.arches), len(src.failed)
    elif ida is not None:
        n_rec = len({c.record for c in ida.curves})
        n_arch, failed = len({c.arch for c in ida.curves}), len(ida.failed)
    else:
        n_rec = n_arch = failed = None
    if n_rec is not None:
        ax.set_title(f"{n_rec} record{'s' if n_rec != 1 else ''} $\\times$ {n_arch} "
                     f"arch{'es' if n_arch != 1 else ''}"
                     + (f" ({failed} more arch{'es' if failed != 1 else ''} left out: not counted)"
                        if failed else ""), fontsize=9)
    if fig is not None and path is not None:
        save_figure(fig, path, dpi=dpi)
    return fig if fig is not None else ax.figure


def _ida_steps(ax, ida, unit: str) -> None:
    """The IDA's first collapses as an empirical CDF over all its curves (those that never
    collapse keep it below 1: the plateau), run on to the top of the range tried; where no
    curve collapses, the observations at P = 0 and the sentence that says so."""
    f = np.sort(ida.first_ims)
    n = f.size
    fin = np.isfinite(f)
    top = max(c.max_im for c in ida.curves)
    never = n - int(fin.sum())
    if not fin.any():
        ax.plot([0.0, top], [0.0, 0.0], color="#444444", lw=1.0,
                label=f"IDA: no collapse up to {top:.3g} {unit} "
                      f"({_plural(n, 'curve')}, none collapsed)")
        up = ida.range_tried()["p_upper_95"]
        ax.plot([0.0, top], [up, up], color="#444444", ls="--", lw=1.0,
                label=f"P(collapse) $\\leq$ {up:.3f} up to {top:.3g} {unit} (one-sided 95%)")
        return
    # from P = 0 at the first collapse, so that one curve still draws its jump; on to the top
    xs = np.r_[f[fin][:1], f[fin], max(top, float(f[fin][-1]))]
    ys = np.r_[0.0, (np.arange(n)[fin] + 1) / n]
    ax.step(xs, np.r_[ys, ys[-1]], where="post", color="#444444", lw=1.0,
            label=f"IDA first collapses, empirical ($n$ = {_plural(n, 'curve')}, "
                  f"{never} never up to {top:.3g} {unit})")


# ---------------------------------------------------------------------------- ensembles
def plot_multiplier_histograms(df, path: str | os.PathLike, dpi: int = 150,
                               reference: dict | None = None) -> Path:
    """Histograms of k_l and k_r over the standing arches of an ensemble (a DataFrame with
    columns k_l, k_r and, if present, error, as from :func:`archrock.studies.ensemble.run_ensemble`);
    the samples not shown are counted by reason under the panels.  Optional ``reference``
    {label: (k_l, k_r)} marks e.g. the nominal arch and the paper's RA-1 / RA-2.  Writes
    ``path`` and returns it."""
    from matplotlib.ticker import MaxNLocator

    from ..dynamics.population import LEFT_OUT, left_out_outcome

    try:
        kl_all = np.asarray(df["k_l"], float)
        kr_all = np.asarray(df["k_r"], float)
    except (KeyError, TypeError, ValueError):
        raise ArchInputError("df: expected a table with numeric columns 'k_l' and 'k_r'") from None
    # the summary's rule: k statistics over standing arches (finite k_l, k_r > 0) only
    with np.errstate(invalid="ignore"):
        shown = np.isfinite(kl_all) & np.isfinite(kr_all) & (kl_all > 0) & (kr_all > 0)
    kl, kr = kl_all[shown], kr_all[shown]
    if kl.size == 0:
        raise ArchInputError("df: no standing arch (finite k_l, k_r > 0) to plot")
    errors = np.asarray(df["error"], dtype=object) if "error" in df else np.full(len(kl_all), "")
    hidden = dict.fromkeys(LEFT_OUT, 0)
    for e, ok, kl_i, kr_i in zip(errors, shown, kl_all, kr_all):
        if not ok:  # a k <= 0 without a recorded reason cannot stand all the same
            hidden["cannot_stand" if not e and np.isfinite(kl_i) and np.isfinite(kr_i)
                   else left_out_outcome(str(e))] += 1
    fig, axes = new_figure(1, 2, figsize=(10.0, 4.3), sharey=True)
    lo = float(min(kl.min(), kr.min()))
    hi = float(max(kl.max(), kr.max()))
    if hi - lo < 1e-9:
        lo, hi = lo - 0.01, hi + 0.01
    bins = np.linspace(lo, hi, 41)
    colors = ("#1f4e9c", "#c0392b", "#2e8b57", "#8e44ad")
    for ax, values, name in ((axes[0, 0], kl, "l"), (axes[0, 1], kr, "r")):
        ax.hist(values, bins=bins, color="#9bb7d4", edgecolor="#4a6d94", lw=0.4,
                label=f"standing arches (n = {values.size})")
        ax.set_xlabel(f"$k_{name}$ [g]")
        std = f"{values.std(ddof=1):.4f}" if values.size > 1 else "n/a (one sample)"
        ax.set_title(f"$k_{name}$: mean {values.mean():.4f}, std {std} (n = {values.size})",
                     fontsize=9)
        for (label, ks), c in zip((reference or {}).items(), colors):
            ax.axvline(ks[0] if name == "l" else ks[1], color=c, lw=1.2, ls="--", label=label)
        ax.grid(True, alpha=0.3)
        ax.yaxis.set_major_locator(MaxNLocator(integer=True))  # counts of samples
    axes[0, 0].set_ylabel("samples")
    # one legend for both panels, below them: inside, it overprinted the reference lines
    handles, labels = axes[0, 0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="outside lower center", ncol=min(len(labels), 5),
               fontsize=8, frameon=False)
    n_hidden = int((~shown).sum())
    why = ", ".join(f"{LEFT_OUT[k].split(' (')[0]} {v}" for k, v in hidden.items() if v)
    fig.suptitle(f"{shown.sum()} of {len(kl_all)} samples shown"
                 + (f"; not shown: {n_hidden} ({why})" if n_hidden else ""), fontsize=9)
    return save_figure(fig, path, dpi=dpi)


# ---------------------------------------------------------------------------- defect maps
#: The defect map's colours: a diverging map centred on 0, losses red, gains blue.
DEFECT_CMAP = "RdBu_r"


def defect_norm(values):
    """The colour scale of a defect map: symmetric about 0 (white) over +-max|value|, so that
    a small gain is pale and a large loss dark, whatever their signs (a 0.3% gain once took the
    darkest blue of a scale whose blue half ran only to -0.3%)."""
    from matplotlib.colors import Normalize

    v = np.asarray(values, float)
    v = v[np.isfinite(v)]
    top = float(np.abs(v).max()) if v.size else 0.0
    top = top if top > 0 else 1.0  # all unchanged: white over an arbitrary +-1
    return Normalize(vmin=-top, vmax=top)


def _short_place(place: str) -> str:
    """A block's or joint's name for a label on the drawing: "voussoir 3" -> "3", "left pier
    course 2" -> "L pier 2", "arch joint 4" -> "4", "right pier foot" -> "R foot"."""
    for word in ("voussoir ", "arch joint ", "joint "):
        if place.startswith(word):
            return place[len(word):]
    out = place.replace("left ", "L ").replace("right ", "R ").replace(" course ", " ")
    return out.replace("springing (pier top)", "springing").replace("bed joint ", "bed ")


def _defect_panel(ax, dmap, values, label, fmt):
    from matplotlib import colormaps
    from matplotlib.cm import ScalarMappable
    from matplotlib.patches import Polygon

    arch = dmap.arch
    values = np.asarray(values, float).copy()
    finite = np.isfinite(values)
    if finite.any():  # round-off (an unchanged multiplier recomputed) is no gain nor loss
        values[finite & (np.abs(values) <= 1e-9 * max(np.abs(values[finite]).max(), 1e-300))] = 0.0
    cmap, norm = colormaps[DEFECT_CMAP], defect_norm(values)
    draw_arch(ax, arch, facecolor="#f4f4f4")
    size = arch.size
    for m, i in enumerate(dmap.indices):
        v = values[m]
        colour = cmap(norm(v)) if np.isfinite(v) else "#bbbbbb"
        text = fmt.format(v) if np.isfinite(v) else "n/a"
        name = _short_place(dmap.places[m])
        if dmap.target == "voussoir":
            pier = dmap.groups[m] == "piers"
            ax.add_patch(Polygon(voussoir_outline(arch, int(i)), closed=True, facecolor=colour,
                                 edgecolor=STYLE["voussoir_edge"], linewidth=0.8, zorder=1.5,
                                 hatch="//" if pier else None))
            x, y = arch.area_centroids[int(i)]
            dark = np.isfinite(v) and abs(norm(v) - 0.5) > 0.3
            ax.text(x, y, f"{name}\n{text}", ha="center", va="center", fontsize=7.5, zorder=3,
                    color="white" if dark else "black")
        else:
            (x0, y0), (x1, y1) = arch.joint_points[int(i)]
            ax.plot([x0, x1], [y0, y1], color=colour, lw=6, solid_capstyle="butt", zorder=2)
            u = np.array([x1 - x0, y1 - y0])
            u /= np.hypot(*u)
            at = (x1 + 0.12 * size * u[0], y1 + 0.12 * size * u[1])
            ax.text(*at, f"{name}\n{text}", ha="center", va="center", fontsize=7.5, zorder=3)
            ax.update_datalim([at, (at[0], at[1] + 0.06 * size)])  # room for the label
    sm = ScalarMappable(norm=norm, cmap=cmap)
    bar = ax.figure.colorbar(sm, ax=ax, shrink=0.7)
    bar.set_label(label, fontsize=8)
    ax.set_axis_off()
    ax.autoscale_view()


def _worst_text(dmap, ties) -> str:
    from ..studies.defectmap import names_text

    m = int(np.flatnonzero(dmap.indices == ties[0])[0])
    return (f"{names_text([dmap.place(t) for t in ties])}, -{dmap.loss[m]:.4f} g "
            f"({dmap.relative_loss[m]:.1%})")


def plot_defect_map(dmap, path: str | os.PathLike | None = None, *, dpi: int = 150,
                    relative: bool = True):
    """The arch with each voussoir (or joint) coloured by the drop of min(k_l, k_r) when it
    alone carries the map's defect (as a % of the undamaged k with ``relative``, else in g) on
    a diverging scale centred on 0 (:func:`defect_norm`: losses red, gains blue, symmetric);
    with a pulse, a second panel with the drop of the first collapse amplitude.  Each one is
    labelled with its name (voussoirs by their number from the arch's left springing, pier
    courses hatched and named "L pier 1") and the value; on piers the title gives the worst
    voussoir and the worst pier defect apart.  Writes ``path`` when given; returns the figure."""
    _require_matplotlib()
    panels = [("k", dmap.relative_loss if relative else dmap.loss)]
    amp = dmap.amplitude_loss
    if amp is not None and dmap.amplitude0 and np.isfinite(dmap.amplitude0):
        panels.append(("amp", amp / dmap.amplitude0 if relative else amp))
    fig, axes = new_figure(len(panels), 1, figsize=(6.4, 3.9 * len(panels)))
    for ax, (what, vals) in zip(axes[:, 0], panels):
        vals = np.asarray(vals, float) * (100.0 if relative else 1.0)
        if what == "k":
            lab = "capacity lost"
            head = f"{dmap.arch.name}:\n{dmap.to_dict()['description']}\n"
            base = f"undamaged min($k_l$, $k_r$) = {dmap.k0:.4f} g"
            if dmap.on_piers and dmap.worst_in("arch") and dmap.worst_pier_all:
                kind = "voussoir" if dmap.target == "voussoir" else "arch joint"
                title = (head + f"{base}; worst {kind}: {_worst_text(dmap, dmap.worst_all)}\n"
                         f"worst pier defect: {_worst_text(dmap, dmap.worst_pier_all)}")
            else:
                title = head + f"{base}; worst: {_worst_text(dmap, dmap.worst_all)}"
        else:
            p = dmap.pulse
            lab = "first collapse amplitude lost"
            sgn = "both signs (the smaller)" if p["sign"] == 0 else f"sign {p['sign']:+d}"
            title = (f"{p['kind']} pulse, $t_p$ = {p['duration']:g} s, {sgn}: "
                     f"undamaged first collapse at {dmap.amplitude0:.3f} g")
        if relative:
            lab += " [% of undamaged k]" if what == "k" else " [% of undamaged]"
        else:
            lab += " [g]"
        lab += "\nred: lost, blue: gained"
        _defect_panel(ax, dmap, vals, lab, "{:.1f}%" if relative else "{:.3f}")
        ax.set_title(title, fontsize=8.5)
    if path is not None:
        save_figure(fig, path, dpi=dpi)
    return fig


#: the figures of the paper's study (:func:`archrock.studies.paper.run_paper_study`)
PAPER_FIGURES = {"fig3": save_limit_figure, "fig4": save_response_figure}

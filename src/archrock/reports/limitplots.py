"""Figures of limit analysis: the paper's Fig. 3 for any arch (:func:`plot_limit`,
:func:`save_limit_figure`, one panel per direction) and k against the piers' height.
"""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np

from ..errors import ArchInputError
from .drawing import (
    STYLE, clip_thrust_polyline, draw_arch, draw_hinges, new_figure, _require_matplotlib,
    save_figure, _thrust_points, voussoir_bounds)


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
    zones = getattr(result, f"zones_{direction}", None)
    draw_hinges(ax, arch if zones is None else _zones(ax, arch, pts, zones), mech)
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
    if getattr(mech, "crushed", ()):
        seq += f"; crushed through at joint {', '.join(map(str, mech.crushed))}"
    if zones is not None:
        seq += f"; $f_c$ = {arch.fc:g} MPa"
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


def _zones(ax, arch, pts, zones):
    """Draw each joint's compressed zone at collapse (finite f_c): a band of the zone's depth
    N / f_c along the joint, centred on the thrust's crossing.  Returns the arch whose contact
    segments end at the stress blocks' centres, where the hinges are drawn."""
    from ..statics.crushing import InsetArch

    jp = np.asarray(arch.joint_points, float)
    e = jp[:, 1] - jp[:, 0]
    length = np.hypot(e[:, 0], e[:, 1])
    u = e / np.where(length > 0, length, 1.0)[:, None]
    first = True
    for j in np.flatnonzero((zones > 0) & np.all(np.isfinite(pts), axis=1)):
        ends = np.array([pts[j] - 0.5 * zones[j] * u[j], pts[j] + 0.5 * zones[j] * u[j]])
        ax.plot(ends[:, 0], ends[:, 1], "-", color="#e07b00", lw=5, alpha=0.8,
                solid_capstyle="butt", zorder=6,
                label="compressed zone (depth N / $f_c$)" if first else None)
        first = False
    return InsetArch(arch, np.minimum(0.5 * zones, 0.4999 * length))


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

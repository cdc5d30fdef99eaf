"""Figure of a defect map (:class:`archrock.defectmap.DefectMap`): the undamaged arch with
each voussoir (or joint) coloured by the capacity lost when it is the damaged one.

matplotlib is imported lazily (:mod:`archrock.plots`)."""

from __future__ import annotations

import os

import numpy as np

from .plots import STYLE, _require_matplotlib, draw_arch, new_figure, save_figure, voussoir_outline

__all__ = ["plot_defect_map"]


def _panel(ax, dmap, values, label, fmt, cmap, vmax):
    from matplotlib import colormaps
    from matplotlib.cm import ScalarMappable
    from matplotlib.colors import Normalize, TwoSlopeNorm
    from matplotlib.patches import Polygon

    arch = dmap.arch
    values = np.asarray(values, float).copy()
    finite = np.isfinite(values)
    if finite.any():  # round-off (an unchanged multiplier recomputed) is no gain nor loss
        values[finite & (np.abs(values) <= 1e-9 * max(np.abs(values[finite]).max(), 1e-300))] = 0.0
    lo = float(np.nanmin(values)) if finite.any() else 0.0
    if lo < 0:  # some defects raise the capacity: gains blue, losses red, 0 white
        cmap = colormaps["RdBu_r"]
        norm = TwoSlopeNorm(vcenter=0.0, vmin=lo, vmax=max(vmax, 1e-12 - lo * 1e-6))
    else:
        norm = Normalize(vmin=0.0, vmax=vmax)
    draw_arch(ax, arch, facecolor="#f4f4f4")
    size = arch.size
    for m, i in enumerate(dmap.indices):
        v = values[m]
        colour = cmap(norm(v)) if np.isfinite(v) else "#bbbbbb"
        text = fmt.format(v) if np.isfinite(v) else "n/a"
        if dmap.target == "voussoir":
            ax.add_patch(Polygon(voussoir_outline(arch, int(i)), closed=True, facecolor=colour,
                                 edgecolor=STYLE["voussoir_edge"], linewidth=0.8, zorder=1.5))
            x, y = arch.area_centroids[int(i)]
            dark = np.isfinite(v) and abs(norm(v) - (0.5 if lo < 0 else 0.0)) > 0.3
            ax.text(x, y, f"{int(i)}\n{text}", ha="center", va="center", fontsize=7.5, zorder=3,
                    color="white" if dark else "black")
        else:
            (x0, y0), (x1, y1) = arch.joint_points[int(i)]
            ax.plot([x0, x1], [y0, y1], color=colour, lw=6, solid_capstyle="butt", zorder=2)
            u = np.array([x1 - x0, y1 - y0])
            u /= np.hypot(*u)
            at = (x1 + 0.12 * size * u[0], y1 + 0.12 * size * u[1])
            ax.text(*at, f"{int(i)}\n{text}", ha="center", va="center", fontsize=7.5, zorder=3)
            ax.update_datalim([at, (at[0], at[1] + 0.06 * size)])  # room for the label
    sm = ScalarMappable(norm=norm, cmap=cmap)
    ax.figure.colorbar(sm, ax=ax, shrink=0.7, label=label)
    ax.set_axis_off()
    ax.autoscale_view()


def plot_defect_map(dmap, path: str | os.PathLike | None = None, *, dpi: int = 150,
                    relative: bool = True):
    """The arch with each voussoir (or joint) coloured by the drop of min(k_l, k_r) when it
    alone carries the map's defect (as a % of the undamaged k with ``relative``, else in g);
    with a pulse, a second panel with the drop of the first collapse amplitude.  Each one is
    labelled with its number and the value.  Writes ``path`` when given; returns the figure."""
    _require_matplotlib()
    from matplotlib import colormaps

    cmap = colormaps["OrRd"]
    panels = [("k", dmap.relative_loss if relative else dmap.loss)]
    amp = dmap.amplitude_loss
    if amp is not None and dmap.amplitude0 and np.isfinite(dmap.amplitude0):
        panels.append(("amp", amp / dmap.amplitude0 if relative else amp))
    fig, axes = new_figure(len(panels), 1, figsize=(6.4, 3.9 * len(panels)))
    for ax, (what, vals) in zip(axes[:, 0], panels):
        vals = np.asarray(vals, float) * (100.0 if relative else 1.0)
        finite = vals[np.isfinite(vals)]
        vmax = max(float(finite.max()) if finite.size else 0.0, 1e-12)
        if what == "k":
            lab = "capacity lost, drop of min($k_l$, $k_r$)"
            title = (f"{dmap.arch.name}:\n{dmap.to_dict()['description']}\n"
                     f"undamaged min($k_l$, $k_r$) = {dmap.k0:.4f} g; worst: {dmap.target}"
                     f"{'s' if len(dmap.worst_all) > 1 else ''} "
                     f"{', '.join(map(str, dmap.worst_all))}, "
                     f"-{dmap.loss.max():.4f} g ({dmap.relative_loss.max():.1%})")
        else:
            p = dmap.pulse
            lab = "drop of the first collapse amplitude"
            sgn = "both signs (the smaller)" if p["sign"] == 0 else f"sign {p['sign']:+d}"
            title = (f"{p['kind']} pulse, $t_p$ = {p['duration']:g} s, {sgn}: "
                     f"undamaged first collapse at {dmap.amplitude0:.3f} g"
                     + ("\n(negative: the damaged arch needs a stronger pulse)"
                        if finite.size and finite.min() < 0 else ""))
        lab += " [%]" if relative else " [g]"
        lab = ("gain < 0 < " if finite.size and finite.min() < 0 else "") + lab
        _panel(ax, dmap, vals, lab, "{:.1f}%" if relative else "{:.3f}", cmap, vmax)
        ax.set_title(title, fontsize=8.5)
    if path is not None:
        save_figure(fig, path, dpi=dpi)
    return fig

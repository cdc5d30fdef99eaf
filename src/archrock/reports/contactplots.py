"""Figures and animation of the contact engine beside the four-link model (matplotlib)."""

from __future__ import annotations

import math
import os
from pathlib import Path

import numpy as np

__all__ = ["save_engine_figure", "save_verify_figure", "animate_engine", "engine_outlines"]

_COLORS = {"engine": "#c0392b", "paper": "#1f4e9c", "momentum": "#2e8b57"}


def engine_outlines(arch, positions: np.ndarray, rotations: np.ndarray) -> list[np.ndarray]:
    """Outline of every voussoir moved rigidly to mass-centre ``positions`` (n, 2) [m] and
    ``rotations`` (n,) [rad] of an engine sample."""
    from .plots import voussoir_outline

    out = []
    for i in range(arch.n):
        th = float(rotations[i])
        rot = np.array([[math.cos(th), -math.sin(th)], [math.sin(th), math.cos(th)]])
        out.append((voussoir_outline(arch, i) - arch.centroids[i]) @ rot.T + positions[i])
    return out


def save_engine_figure(res, four_link, path, dpi: int = 150, four_link_label=None,
                       names=None) -> Path:
    """Three panels: the engine's equivalent rotation over the four-link phi(t); every
    block's rotation; the largest sliding at each joint.  four_link_label: how the
    four-link curve is named (e.g. "four-link (not valid here)"; default "four-link");
    names: each block's name (default "voussoir i"; piers by kind where given)."""
    from .plots import new_figure, save_figure

    fig, axes = new_figure(3, 1, figsize=(7.0, 8.0), height_ratios=(1.3, 1.0, 0.8))
    ax, ax_v, ax_s = axes[0][0], axes[1][0], axes[2][0]
    ax.plot(res.time, res.phi, color=_COLORS["engine"], lw=1.4,
            label="contact engine: equivalent $\\phi$")
    if four_link is not None:
        ax.plot(four_link.time, four_link.response, color=_COLORS["paper"], lw=1.2,
                label=f"{four_link_label or 'four-link'} ({four_link.model.impact.model} "
                      f"impacts): $\\phi$")
        ax.axhline(four_link.model.phi_unstable_l, color="#999999", lw=0.7, ls="--")
        ax.axhline(-four_link.model.phi_unstable_r, color="#999999", lw=0.7, ls="--",
                   label=r"unstable positions $\pm\phi_u$")
    ax.axhline(0.0, color="#cccccc", lw=0.6)
    ax.set_ylabel(r"signed rotation $\phi$ [rad]")
    ax.set_title(f"contact engine: {res.status}" if four_link is None else
                 f"engine: {res.status}; {four_link_label or 'four-link'}: {four_link.status}",
                 fontsize=9)
    # legends outside the axes, on the right: inside they hid curves (voussoir 3's trough)
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0), frameon=False)
    nv = res.rotations.shape[1]
    for i in range(nv):
        ax_v.plot(res.time, res.rotations[:, i], lw=0.9,
                  label=f"voussoir {i}" if names is None else names[i])
    voussoirs_only = names is None or all(n.startswith("voussoir") for n in names)
    ax_v.set_ylabel("voussoir rotation [rad]" if voussoirs_only else "block rotation [rad]")
    ax_v.set_xlabel("$t$ [s]")
    ax_v.legend(fontsize=6.5, loc="upper left", bbox_to_anchor=(1.01, 1.0), frameon=False,
                ncol=1 + (nv - 1) // 14)
    j = np.arange(res.max_sliding.size)
    ax_s.bar(j, res.max_sliding * 1e3, color="#7f8c8d")
    ax_s.set_xlabel("joint (0 = left springing)")
    ax_s.set_ylabel("max sliding [mm]")
    ax_s.set_xticks(j)
    return save_figure(fig, path, dpi=dpi)


def save_verify_figure(res, path, dpi: int = 150, ax=None) -> Path | None:
    """First-collapse |amplitude| against pulse duration for the engine and the four-link
    model (paper and momentum c_v); the grid's collapse decisions as markers."""
    from .plots import new_figure, save_figure

    fig = None
    if ax is None:
        fig, axes = new_figure(1, 1, figsize=(6.4, 4.4))
        ax = axes[0][0]
    first = res.first
    amps = np.abs(res.amplitudes)
    labels = {"engine": f"contact engine (MU = {res.settings.friction:g})",
              "paper": f"four-link, paper $c_v$ = {res.cv['paper']:.3f}",
              "momentum": f"four-link, momentum $c_v$ = {res.cv['momentum']:.3f}"}
    offs = {"engine": 0.0, "paper": -0.012, "momentum": 0.012}
    for m in ("engine", "paper", "momentum"):
        ax.plot(res.durations, first[m], "o-" if m == "engine" else "s--", color=_COLORS[m],
                label=labels[m], lw=1.3)
        for i, d in enumerate(res.durations):
            x = d * (1 + offs[m] * 3)
            c = res.collapsed[m][i]
            ax.scatter(np.full(c.sum(), x), amps[c], marker="x", s=14, color=_COLORS[m], alpha=0.5)
    ax.set_xlabel("pulse duration $t_p$ [s]")
    ax.set_ylabel("first-collapse |amplitude| [g]")
    ax.set_title(f"{res.arch_name}: {res.pulse} pulses (x: collapsing cells)", fontsize=9)
    ax.legend(fontsize=7)
    if fig is not None:
        return save_figure(fig, path, dpi=dpi)
    return None


def animate_engine(res, four_link, arch, path: str | os.PathLike, fps: int = 25,
                   speed: float = 1.0, dpi: int = 80, max_frames: int = 300,
                   progress=None, four_link_label=None) -> Path:
    """Animation: the engine's voussoirs (left) beside the four-link mechanism (right), to
    scale, with both rotations against time below; four_link_label names the four-link
    panel and curve (default "four-link"; "not run" where ``four_link`` is None)."""
    fl_name = (four_link_label or "four-link") + ("" if four_link is not None else ": not run")
    from .animate import animation_path, save_animation
    from .plots import STYLE, displaced_outlines, new_figure, springing_level, voussoir_bounds

    path = animation_path(path)
    from matplotlib.animation import FuncAnimation
    from matplotlib.patches import Polygon

    t = res.time
    ok = np.isfinite(res.rotations[:, 0])
    last = int(np.flatnonzero(ok)[-1]) if ok.any() else 0
    n_frames = min(max_frames, max(2, int(t[last] * fps / speed)))
    frame_t = np.linspace(0.0, t[last], n_frames)
    fig, axes = new_figure(2, 2, figsize=(9.0, 5.6), height_ratios=(2.0, 1.0))
    pts = voussoir_bounds(arch)
    pad = 0.15 * np.ptp(pts[:, 0])
    patches = {}
    ground = springing_level(arch)  # the ground the springings stand on
    for k, name in ((0, "engine"), (1, "four-link")):  # patches' keys; the titles say more
        ax = axes[0][k]
        ax.set_aspect("equal")
        ax.set_xlim(pts[:, 0].min() - pad, pts[:, 0].max() + pad)
        ax.set_ylim(min(pts[:, 1].min(), ground) - pad, pts[:, 1].max() + pad)
        ax.axhline(ground, color=STYLE["ground"], lw=1.0)
        ax.set_xlabel("x [m]")
        ax.set_ylabel("y [m]")
        ax.set_title("contact engine" if k == 0 else fl_name, fontsize=9)
        patches[name] = []
        for i in range(arch.n):
            p = Polygon(np.zeros((3, 2)), closed=True, facecolor=STYLE["voussoir_face"],
                        edgecolor=STYLE["voussoir_edge"], lw=0.8)
            ax.add_patch(p)
            patches[name].append(p)
    gs = axes[1][0].get_gridspec()
    axes[1][0].remove()
    axes[1][1].remove()
    ax_t = fig.add_subplot(gs[1, :])
    ax_t.plot(t, res.phi, color=_COLORS["engine"], lw=1.2, label="engine (equivalent)")
    if four_link is not None:
        ax_t.plot(four_link.time, four_link.response, color=_COLORS["paper"], lw=1.2,
                  label=fl_name)
    ax_t.set_xlim(0, t[last])
    ax_t.set_xlabel("$t$ [s]")
    ax_t.set_ylabel(r"$\phi$ [rad]")
    ax_t.legend(fontsize=7)
    marker = ax_t.axvline(0.0, color="#555555", lw=0.8)
    title = fig.suptitle("", fontsize=9)
    fig.canvas.draw()
    fig.set_layout_engine("none")
    model = four_link.model if four_link is not None else None

    def draw(k):
        tk = frame_t[k]
        i = min(int(round(tk / (t[1] - t[0]))), last)
        for p, o in zip(patches["engine"], engine_outlines(arch, res.positions[i],
                                                           res.rotations[i])):
            p.set_xy(o)
        if model is not None:
            val = float(np.interp(tk, four_link.time, np.nan_to_num(four_link.response)))
            rows = four_link.rows_at(np.array([tk]))
            row = int(rows[0])
            mechs = model.chain[0]
            rot = 0.0 if row < 0 else max(0.0, (1.0 if mechs[row].direction == "l" else -1.0) * val)
            for p, o in zip(patches["four-link"], displaced_outlines(model, row, rot)):
                p.set_xy(o)
        marker.set_xdata([tk, tk])
        title.set_text(f"t = {tk:5.2f} s")
        return [*patches["engine"], *patches["four-link"], marker, title]

    return save_animation(FuncAnimation(fig, draw, frames=n_frames, blit=False), path, fps, dpi,
                          progress=progress)

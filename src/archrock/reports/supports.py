"""Reports of support movements (docs/supports.md): text and JSON of a displaced arch's state
and of a displacement capacity, the figure of the displaced arch with its line of thrust and
the capacity curve (thrust, reactions and crown drop against the imposed movement)."""

from __future__ import annotations

import os
from pathlib import Path

from ..errors import ArchInputError
from .plots import STYLE, clip_thrust_polyline, draw_arch, new_figure, save_figure

__all__ = ["hinge_labels", "format_displaced", "displaced_summary", "format_gap_closing",
           "format_capacity", "plot_displaced", "plot_capacity", "save_supports_figure"]


def hinge_labels(hinges) -> str:
    """'1i, 4e, 6i': joint number and edge initial of each hinge."""
    return ", ".join(f"{h.joint}{h.edge[0]}" for h in hinges)


def format_displaced(arch) -> str:
    """One line naming a displaced arch's imposed movement and open hinges."""
    mv = arch.movement
    what = "support movement" if mv is None else mv.describe()
    pts = arch.point_joints or arch.contacts
    closed = "" if arch.point_joints else "; analysed with these joints re-closed"
    return (f"displaced arch: {what}; open hinges {hinge_labels(arch.hinges)} (contacts at "
            + ", ".join(f"({x:.4f}, {y:.4f})" for _, x, y in pts) + f" m{closed})")


def displaced_summary(arch) -> dict:
    """JSON of a displaced arch: the movement, the open hinges and their points [m], and
    whether the analyses took them re-closed."""
    return {"movement": None if arch.movement is None else arch.movement.to_dict(),
            "hinges": [h.to_dict() for h in arch.hinges],
            "points": [[x, y] for _, x, y in (arch.point_joints or arch.contacts)],
            "reclosed": bool(arch.contacts) and not arch.point_joints}


def format_gap_closing(gc) -> str:
    """One line: the rocking the point contacts allow before the re-closed arch's multipliers
    (:class:`archrock.statics.supports.GapClosing`), bounded by the gaps."""
    shut = sorted(set(gc.closing_l) | set(gc.closing_r))
    return (f"before that, the open joints' point contacts let the arch rock from k_l = "
            f"{gc.k_l:.4g}, k_r = {gc.k_r:.4g}, turning joint(s) {', '.join(map(str, shut))} "
            f"back until their gaps close: a bounded motion, not a collapse (docs/supports.md)")


def format_capacity(cap) -> str:
    """The capacity in words: movement, fraction of span, mechanism, hinge sets followed."""
    word = {"spread": "spreading", "closure": "closing", "settlement": "settlement",
            "heave": "heave"}.get(cap.kind, cap.kind)
    side = "both supports" if cap.side == "both" else f"the {cap.side} support"
    size = (f"{cap.capacity:.6g} rad" if cap.fraction is None else
            f"{cap.capacity:.6g} m = {100 * cap.fraction:.4g}% of the span")
    lines = [f"{word} capacity of {side}: {size} "
             f"({cap.reason}; hinges at onset {hinge_labels(cap.hinges)}, at capacity "
             f"{hinge_labels(cap.mechanism)})"]
    if len(cap.migrations) > 1:
        lines.append("hinge sets followed: " + "; ".join(
            f"from {t:.4g} {'m' if cap.fraction is not None else 'rad'}: {hinge_labels(h)}"
            for t, h in cap.migrations))
    c = cap.curve
    lines.append(f"thrust H: {c[0, 1] / 1e3:.6g} kN/m at onset, {c[-1, 1] / 1e3:.6g} kN/m at "
                 f"capacity; crown drop at capacity {c[-1, 4]:.4g} m")
    return "\n".join(lines)


def plot_displaced(state, ax=None):
    """The base arch (faint), the displaced arch, its line of thrust and its open hinges."""
    if ax is None:
        _, axes = new_figure()
        ax = axes[0, 0]
    disp = state.arch
    base = getattr(disp, "base", disp)
    draw_arch(ax, base, alpha=0.25, joints=False, ground=False, loads=False, zorder=0.5)
    draw_arch(ax, disp, joints=True, ground=False, zorder=1.0)
    if state.line is not None:
        poly = clip_thrust_polyline(state.line.polyline, disp, state.line.points)
        ax.plot(poly[:, 0], poly[:, 1], color=STYLE["thrust"], lw=1.4,
                zorder=3, label=f"line of thrust, H = {state.thrust / 1e3:.4g} kN/m")
    if len(state.points):
        ax.plot(state.points[:, 0], state.points[:, 1], "o", ms=6, mfc="white",
                mec=STYLE["hinge"], mew=1.5, zorder=4,
                label=f"open hinges {hinge_labels(state.hinges)}")
    ax.set_title(state.movement.describe())
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.legend(loc="lower center", fontsize=8, frameon=False)
    return ax


def plot_capacity(cap, axes=None):
    """Two panels against the imposed movement: the thrust H and the vertical reactions
    [kN/m], and the crown drop [m]; the capacity marked."""
    if axes is None:
        _, ax2 = new_figure(1, 2, figsize=(9.0, 3.8))
        axes = ax2[0]
    c = cap.curve
    a, b = axes
    a.plot(c[:, 0], c[:, 1] / 1e3, label="H")
    a.plot(c[:, 0], c[:, 2] / 1e3, "--", label="V left")
    a.plot(c[:, 0], c[:, 3] / 1e3, ":", label="V right")
    a.set_xlabel(f"{cap.kind} [{'m' if cap.fraction is not None else 'rad'}]")
    a.set_ylabel("force [kN/m]")
    a.legend(fontsize=8, frameon=False)
    b.plot(c[:, 0], c[:, 4])
    b.set_xlabel(f"{cap.kind} [{'m' if cap.fraction is not None else 'rad'}]")
    b.set_ylabel("crown drop [m]")
    for ax in axes:
        ax.axvline(cap.capacity, color="0.4", lw=0.8)
    b.set_title(f"capacity {cap.capacity:.4g} m ({100 * cap.fraction:.3g}% of span)",
                fontsize=9)
    return axes


def save_supports_figure(path: str | os.PathLike, state=None, capacity=None,
                         dpi: int = 150) -> Path:
    """Write the displaced arch (``state``), the capacity curve (``capacity``) or both."""
    panels = (state is not None) + 2 * (capacity is not None)
    if panels == 0:
        raise ArchInputError("figure: give a state, a capacity or both")
    fig, axes = new_figure(1, panels, figsize=(4.6 * panels, 4.2))
    k = 0
    if state is not None:
        plot_displaced(state, axes[0, 0])
        k = 1
    if capacity is not None:
        plot_capacity(capacity, (axes[0, k], axes[0, k + 1]))
    return save_figure(fig, path, dpi=dpi)

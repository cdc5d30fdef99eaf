"""Figures of responses: the ground motion, the four-link rotation against time
(:func:`plot_response`, :func:`save_response_figure`: the paper's Fig. 4) and the displaced
arch of a mechanism (:func:`draw_displaced`).
"""

from __future__ import annotations

import math

import numpy as np

from ..errors import ArchInputError
from .drawing import STYLE, block_faces, new_figure, save_figure, voussoir_outline


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

"""Animation of the arch's mechanism moving through a response (GIF or MP4, matplotlib).

Each frame draws every voussoir (its outline, any arch shape) moved rigidly with its link at
the response's rotation (exact four-bar kinematics) in the mechanism of the chain actually open then (from the
response's events, :meth:`archrock.dynamics.response.Response.rows_at`), with its four hinges, and the
ground motion and the signed response below it, over the response's samples (``archrock
respond --animate`` samples to rest or to the rotation limit, past --t-end).  Frames from the
collapse (the last passage of the unstable position) on say COLLAPSED; from the rotation limit
on, where the response ends, the last computed position is held.
Displacements are drawn to scale unless ``exaggerate`` says otherwise.
"""

from __future__ import annotations

import math
import os
from pathlib import Path

import numpy as np

from ..errors import ArchInputError

__all__ = ["animate_response", "animation_path", "save_animation"]

#: Animation formats: Pillow writes GIF, ffmpeg (if installed) MP4.
ANIMATION_SUFFIXES = (".gif", ".mp4")


def animation_path(path: str | os.PathLike) -> Path:
    """``path`` as an animation file, checked before any work is done (extension .gif or
    .mp4, not a folder)."""
    from .plots import output_file

    p = output_file(path, "animation file", "motion.gif")
    if p.suffix.lower() not in ANIMATION_SUFFIXES:
        raise ArchInputError(f"animation file {os.fspath(path)!r}: allowed extensions .gif or .mp4")
    return p


def animate_response(response, path: str | os.PathLike, fps: int = 25, speed: float = 1.0,
                     exaggerate: float = 1.0, dpi: int = 90, max_frames: int = 400,
                     progress=None) -> Path:
    """Write an animation of ``response`` to ``path`` (.gif with Pillow, .mp4 with ffmpeg).

    fps: frames per second; speed: simulated seconds per real second; exaggerate: factor on
    the drawn rotations (1 = to scale); max_frames caps the file size; progress: None or a
    callable given a line per ~10% of the frames drawn (:func:`save_animation`).
    """
    from .plots import (STYLE, displaced_hinges, displaced_outlines, draw_displaced, new_figure,
                        plot_ground_motion, springing_level, voussoir_bounds)

    path = animation_path(path)
    for name, v in (("fps", fps), ("speed", speed), ("exaggerate", exaggerate)):
        if not (isinstance(v, (int, float)) and math.isfinite(v) and v > 0):
            raise ArchInputError(f"{name}: {v!r}; allowed a finite number > 0")
    from matplotlib.animation import FuncAnimation

    model = response.model
    t = response.time
    phi = response.response
    # after a collapse the response is NaN: hold the last computed rotation, with its sign
    held = phi.copy()
    finite = np.isfinite(held)
    if not finite.all():
        last = np.flatnonzero(finite)
        held[~finite] = held[last[-1]] if last.size else 0.0
    n_frames = min(max_frames, max(2, int(t[-1] * fps / speed)))
    frame_t = np.linspace(0.0, t[-1], n_frames)
    frame_rows = response.rows_at(frame_t)
    if response.collapsed:
        # from the rotation limit on (NaN response) hold the collapsing mechanism, as the
        # rotation is held
        last = [e for e in response.events if e.kind == "limit"][-1].row_before
        frame_rows[frame_t >= response.t_limit] = last
    mechs = model.chain[0]
    labels = model.labels
    fig, axes = new_figure(2, 1, figsize=(6.4, 6.0), height_ratios=(2.2, 1.0))
    ax_arch, ax_resp = axes[0][0], axes[1][0]
    pts = voussoir_bounds(model.arch)  # axis limits from the voussoirs' own outlines
    pad = 0.1 * np.ptp(pts[:, 0])

    ax_resp.plot(t, phi, color="#1f77b4", lw=1.2)
    ax_resp.axhline(0.0, color="#999999", lw=0.6)
    ax_resp.set_xlim(0, t[-1])
    ax_resp.set_xlabel("$t$ [s]")
    ax_resp.set_ylabel(r"$\phi$ [rad]")
    marker, = ax_resp.plot([], [], "o", color="#c0392b")
    ax_g = ax_resp.twinx()
    plot_ground_motion(response.motion, ax_g, t_end=t[-1])
    ax_g.set_title("")
    ax_g.set_xlabel("")
    for line in ax_g.get_lines():
        line.set_alpha(0.35)

    ax_arch.set_aspect("equal")
    ax_arch.set_xlim(pts[:, 0].min() - pad, pts[:, 0].max() + pad)
    ground = springing_level(model.arch)  # the ground the springings stand on
    ax_arch.set_ylim(min(pts[:, 1].min(), ground) - pad, pts[:, 1].max() + pad)
    ax_arch.axhline(ground, color=STYLE["ground"], lw=1.0)
    ax_arch.set_xlabel("x [m]")
    ax_arch.set_ylabel("y [m]")
    patches = draw_displaced(ax_arch, model, "rest", 0.0)
    hinge_marks, = ax_arch.plot([], [], "o", ms=6, mfc="white", mec=STYLE["hinge"], mew=1.6,
                                zorder=5)
    title = ax_arch.set_title("", fontsize=9)
    # lay the figure out once; frames then only move the voussoirs (no relayout, no clearing)
    fig.canvas.draw()
    fig.set_layout_engine("none")

    def draw(k):
        tk = frame_t[k]
        val = float(np.interp(tk, t, held))
        collapsed = response.collapsed and response.t_collapse is not None and tk >= response.t_collapse
        row = int(frame_rows[k])
        # the signed response is +phi for an 'l' mechanism, -phi for 'r'; a frame interpolated
        # across an impact may carry the old sign for a moment: the new mechanism is then closed
        rot = 0.0 if row < 0 else max(0.0, (1.0 if mechs[row].direction == "l" else -1.0) * val)
        for patch, outline in zip(patches, displaced_outlines(model, row, rot * exaggerate)):
            patch.set_xy(outline)
        hinge_marks.set_data(*displaced_hinges(model, row, rot * exaggerate).T)
        name = "" if row < 0 else (f"M_{mechs[row].direction} " if row < 2 else "") + labels[row]
        state = ("COLLAPSED " + name) if collapsed else (f"{name} open" if row >= 0 else "at rest")
        title.set_text(f"t = {tk:5.2f} s   phi = {val:+.4f} rad   {state}"
                       + (f"   (rotations x{exaggerate:g})" if exaggerate != 1 else ""))
        marker.set_data([tk], [val])
        return [*patches, hinge_marks, title, marker]

    return save_animation(FuncAnimation(fig, draw, frames=n_frames, blit=False), path, fps, dpi,
                          progress=progress)


def frame_progress(progress, name: str):
    """matplotlib's ``progress_callback(i, n)`` as a line to ``progress`` per ~10% of the
    ``n`` frames, the last at 100% (None: no callback)."""
    if progress is None:
        return None
    shown = [-1]

    def callback(i, n):
        tenth = 10 * (i + 1) // max(n, 1)  # drawing a long animation takes tens of seconds
        if tenth > shown[0]:
            shown[0] = tenth
            progress(f"{name}: frame {i + 1}/{n} ({100 * (i + 1) // max(n, 1)}%)")

    return callback


def save_animation(anim, path: Path, fps: int, dpi: int, progress=None) -> Path:
    """Write a matplotlib animation to ``path`` (.gif with Pillow, .mp4 with ffmpeg); a file
    that cannot be written is an ArchInputError naming it.  progress: None or a callable given
    a line per ~10% of the frames (:func:`frame_progress`)."""
    from matplotlib.animation import FFMpegWriter, PillowWriter

    path.parent.mkdir(parents=True, exist_ok=True)
    writer = PillowWriter(fps=fps) if path.suffix.lower() == ".gif" else FFMpegWriter(fps=fps)
    try:
        anim.save(str(path), writer=writer, dpi=dpi,
                  progress_callback=frame_progress(progress, f"animation {path.name}"))
    except (OSError, RuntimeError, ValueError) as exc:
        # OSError: an unwritable place (PIL/ffmpeg); RuntimeError/FileNotFoundError: no ffmpeg
        hint = "; use .gif if ffmpeg is not installed" if path.suffix.lower() == ".mp4" else ""
        why = getattr(exc, "strerror", None) or " ".join(str(exc).split())
        raise ArchInputError(f"animation file {str(path)!r}: cannot write ({why}){hint}") from None
    return path

"""The app's response where the contact engine governs: which model answers a pulse or a
record (:func:`archrock.studies.enginestudy.choose_dynamics`, the one routing of the package)
and the engine's run as a job of the worker process (app/jobs.py), with progress, cancellable.

Nothing here is physics: the engine is :class:`~archrock.studies.enginestudy.EngineRun`'s,
at the request's friction (:data:`~archrock.statics.friction.DEFAULT_FRICTION` unless given).
Lengths in m, times in s, rotations in rad, accelerations in g.
"""

from __future__ import annotations

import math
import time

import numpy as np

from ..errors import ArchInputError, ArchrockError, GeometryOutcome
from .fields import COMPUTE_LOCK, choice, xy

DYNAMICS = ("auto", "fourlink", "engine")
#: The engine's estimated time of one response [s] (archrock.studies.enginestudy's
#: engine_run_cost_s) the app runs; Oppenheim's arch is about 4 s, the heavy-pier arch 8 s.
MAX_ENGINE_WORK_S = 300.0
#: Frames of the engine's animation (every block's position and angle).
MAX_ENGINE_FRAMES = 300
#: Progress is counted in tenths of a second of simulated time.
TICKS_PER_S = 10


class EngineMissing(ArchrockError):
    """The contact engine governs the arch asked about but pymunk is not installed."""


class FourLinkNotValid(GeometryOutcome):
    """A four-link study of the app (the ensemble under a pulse, the collapse curve) asked for
    an arch where the package's routing says the contact engine answers."""


def four_link_study(arch, mu, what: str, command: str):
    """The :class:`~archrock.studies.enginestudy.DynamicsChoice` of an app study that runs the
    four-link model (``what``: the request's field, ``command``: the CLI command that runs the
    engine instead) on ``arch`` at friction ``mu``; refused (:class:`FourLinkNotValid`) where
    the contact engine answers: the app runs those studies with the four-link model only, and
    never shows its numbers where it does not hold."""
    from ..studies.enginestudy import choose_dynamics

    with COMPUTE_LOCK:
        chosen = choose_dynamics(arch, "auto", friction=mu)
    if chosen.engine:
        raise FourLinkNotValid(f"{what}: the app runs it with the four-link model, which does not "
                               f"hold for this arch ({chosen.reason}); archrock {command} "
                               f"--dynamics engine runs the contact engine")
    return chosen


def choose(arch, params: dict, mu):
    """The :class:`~archrock.studies.enginestudy.DynamicsChoice` of ``arch`` at friction
    ``mu`` for the request's ``dynamics`` (auto, fourlink or engine; default auto); an engine
    choice is refused (:class:`EngineMissing`) where pymunk is missing, never answered by the
    four-link model."""
    from ..studies.enginestudy import choose_dynamics

    dynamics = choice(params, "dynamics", DYNAMICS, "auto")
    with COMPUTE_LOCK:
        chosen = choose_dynamics(arch, dynamics, friction=mu)
    if chosen.engine:
        from ..contact import require_engine

        try:
            require_engine()
        except ImportError:
            raise EngineMissing(f"dynamics: the contact engine answers this arch ({chosen.reason}); "
                                f"it needs pymunk: pip install 'archrock[dem]'") from None
    return chosen


def four_link_valid(chosen) -> bool:
    """False where the four-link model ran only because it was asked for by name on an arch
    where the package's routing calls it not valid."""
    return chosen.used == "fourlink" and "WARNING" not in chosen.reason


def engine_run(mu):
    """The :class:`~archrock.studies.enginestudy.EngineRun` at friction ``mu`` (None: sliding
    excluded, which the engine cannot exclude: the package default then, said in the result)."""
    from ..contact.settings import EngineSettings
    from ..statics.friction import DEFAULT_FRICTION
    from ..studies.enginestudy import EngineRun

    return EngineRun(settings=EngineSettings(friction=DEFAULT_FRICTION if mu is None else mu))


def check_engine_work(arch, motion, mu) -> float:
    """The engine's estimated time [s] of this response, refused above
    :data:`MAX_ENGINE_WORK_S`."""
    from ..studies.enginestudy import engine_run_cost_s
    from ..studies.work import format_duration

    est = engine_run_cost_s(arch, float(motion.times[-1]), engine_run(mu))
    if est > MAX_ENGINE_WORK_S:
        raise ArchInputError(f"t_end: the contact engine's run is estimated at "
                             f"{format_duration(est)} here; the app runs up to "
                             f"{format_duration(MAX_ENGINE_WORK_S)} (archrock dem for more)")
    return est


def run_engine_job(req: dict, progress, cancelled) -> dict | None:
    """The contact engine's response of ``req["arch"]`` to ``req["motion"]`` (the request
    checked by :func:`archrock.app.api.respond_request`), run as
    :meth:`EngineRun.respond <archrock.studies.enginestudy.EngineRun.respond>` runs it, with
    the output window ``t_end``; ``progress`` in tenths of a second of simulated time (the
    run ends at collapse, at rest, or at the end of its free motion).  The result: the engine's
    outcome, its equivalent rotation phi(t) [rad], each block's frames and ``"dynamics"``, the
    choice that sent it here; its CSV (t, phi) kept as the job's download."""
    from ..contact.motion import engine_respond
    from ..contact.settings import engine_scales
    from ..units import G
    from .drawing import arch_drawing
    from .uploads import trace

    arch, motion, t_end = req["arch"], req["motion"], req["t_end"]
    run = engine_run(req["friction"])
    t0 = time.perf_counter()
    t_stop = float(motion.times[-1]) + run.t_free * engine_scales(arch, run.settings).time_scale
    total = int(math.ceil(TICKS_PER_S * max(t_stop, t_end)))

    def said(msg: str) -> None:  # the engine's "engine t = 12.3 s", every 10 T simulated
        try:
            t = float(msg.split("=")[1].split()[0])
        except (IndexError, ValueError):
            return
        progress(min(total, int(TICKS_PER_S * t)), total)

    progress(0, total)
    res = engine_respond(arch, motion, run.settings, t_end=t_end,
                         dt_out=min(max(0.01, t_end / 1500), t_end), t_free=run.t_free,
                         collapse_drop=run.collapse_drop, progress=said)
    if cancelled():
        return None
    progress(total, total)
    t = np.asarray(res.time, float)
    phi = np.asarray(res.phi, float)
    out = res.to_dict(samples=False)
    out.pop("run", None)
    out.update({
        "model": "engine", "valid": True, "dynamics": req["choice"].to_dict(),
        "label": "contact engine (pymunk): " + req["choice"].reason + (
            "" if req["friction"] is not None else
            f"; its joints cannot exclude sliding: mu = {run.settings.friction:g}, the "
            f"package default"),
        "friction": run.settings.friction,
        "time": xy(t), "phi": [None if not math.isfinite(x) else round(float(x), 7) for x in phi],
        "ground": trace(motion.times, np.asarray(motion.accel) / G),
        "drawing": arch_drawing(arch), "block_frames": block_frames(res),
        "pulse": req["spec"].to_dict() if req["spec"] is not None else None,
        "record": req["record"], "t_end": t_end, "wall_s": time.perf_counter() - t0,
    })
    lines = ["t_s,phi_rad"] + [f"{a:.5f},{'' if not math.isfinite(b) else f'{b:.7f}'}"
                               for a, b in zip(t, phi)]
    out["_download"] = ("response-engine.csv", "text/csv", "\n".join(lines) + "\n")
    return out


def block_frames(res) -> dict:
    """Every block's rigid motion at up to :data:`MAX_ENGINE_FRAMES` times: ``time`` [s],
    ``phi`` [rad] (the equivalent rotation) and, per frame, [[dx, dy, theta], ...] per block:
    the page draws block i's outline turned by theta [rad] about ``origin[i]`` (its first
    sampled position [m]) and moved by (dx, dy) [m]."""
    t = np.asarray(res.time, float)
    pos, rot = np.asarray(res.positions, float), np.asarray(res.rotations, float)
    ok = np.isfinite(rot).all(axis=1) & np.isfinite(pos).all(axis=(1, 2))
    idx = np.flatnonzero(ok)
    if not idx.size:
        return {"time": [], "origin": [], "frames": []}
    pick = idx[np.unique(np.linspace(0, idx.size - 1, min(MAX_ENGINE_FRAMES, idx.size))
                         .round().astype(int))]
    p0, r0 = pos[idx[0]], rot[idx[0]]
    frames = [np.round(np.column_stack([pos[k] - p0, rot[k] - r0]), 6).tolist() for k in pick]
    phi = np.asarray(res.phi, float)[pick]
    return {"time": xy(t[pick]), "origin": xy(p0), "frames": frames,
            "phi": [None if not math.isfinite(x) else round(float(x), 7) for x in phi]}

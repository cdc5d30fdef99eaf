"""An arcade (a graph of blocks, :class:`~archrock.geometry.arcade.Arcade`) in the contact
engine: its activation by the engine's ramp and its response to a ground motion.

:class:`ContactArcade` (:mod:`.pymunkarcade`) builds the bodies as :class:`~archrock.contact.engine.ContactArch` does
(exact mass properties, the outline simplified within ``outline_tol`` with every contact's ends
kept, cut into convex pieces with rounded corners, the friction and restitution of
:class:`~archrock.contact.settings.EngineSettings`, ground motion as the ground frame's body
force), with a static ground block under each contact with the ground instead of two
abutments.  A contact's motion: the relative rotation theta_b - theta_a of its two blocks (the
ground does not turn), and the slip of its end that stays closer to closed, along the contact.

:func:`arcade_ramp` is :func:`~archrock.contact.ramp.ramp_direction`'s two stages on the graph
(a slow ramp of the horizontal ground acceleration until a contact turns or slides past its
threshold, then holds from rest bisecting the activation multiplier), and reads the hinges as
(contact, end): the contacts turning by at least 5% of the largest relative rotation, each at
its end that stays closed.  :func:`arcade_respond` runs a pulse or record to rest or collapse
(a block's mass centre dropped by ``collapse_drop`` x size).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from .._records import EngineRecord
from ..errors import ArchInputError
from ..geometry.arcade import Arcade
from ..groundmotion import GroundMotion
from ..units import G
from .pymunkarcade import ContactArcade
from .ramp import RampResult, ramp_range, ramp_stages, read_hinges, start_ramp
from .rigid import engine_arcade
from .settings import EngineSettings

__all__ = ["ContactArcade", "ArcadeRampDirection", "ArcadeRamp", "arcade_ramp",
           "arcade_ramp_direction", "ArcadeResponse", "arcade_respond"]


@dataclass(frozen=True)
class ArcadeRampDirection:
    """The engine's activation of an arcade in one direction: ``multiplier`` |xg''|/g (middle
    of [lower, upper]); ``mode`` 'rocking' or 'sliding'; ``hinges`` ((contact, end), ...) and
    ``places`` in words, read from the lowest hold whose motion grew past four times the
    threshold (the mechanism at activation; the ramp itself overshoots and may open more); ``sliding_contacts``; ``ramp_multiplier``
    where the ramp saw motion, ``ramp_hinges`` what it opened; ``holds`` ((lambda, moved),
    ...)."""

    direction: str
    multiplier: float
    lower: float
    upper: float
    mode: str
    hinges: tuple
    places: tuple
    sliding_contacts: tuple
    ramp_multiplier: float
    ramp_hinges: tuple = ()
    holds: tuple = field(repr=False, default=())

    def to_dict(self) -> dict:
        return {"direction": self.direction, "multiplier": self.multiplier,
                "ramp_hinges": [list(h) for h in self.ramp_hinges],
                "lower": self.lower, "upper": self.upper, "mode": self.mode,
                "hinges": [list(h) for h in self.hinges], "places": list(self.places),
                "sliding_contacts": list(self.sliding_contacts),
                "ramp_multiplier": self.ramp_multiplier,
                "holds": [[lam, moved] for lam, moved in self.holds]}


@dataclass(frozen=True)
class ArcadeRamp(RampResult):
    """Both directions of :func:`arcade_ramp` (:class:`ArcadeRampDirection` each), with the
    settings and ramp options used."""

    def to_dict(self) -> dict:
        return {"k_l": self.l.multiplier, "k_r": self.r.multiplier, "l": self.l.to_dict(),
                "r": self.r.to_dict(), "engine": self.settings.to_dict(),
                "ramp": dict(self.ramp),
                "method": "contact engine (pymunk): ramp of the ground acceleration, then "
                          "holds from rest bisecting the activation"}


def _motion(ca: ContactArcade, thr_rot, thr_slide):
    pos, ang, _, _ = ca.state()
    rot = ca.contact_rotations(ang) - ca.contact_rotations(ca.ref_ang)
    sl = ca.contact_sliding(pos, ang) - ca.ref_slide
    return rot, sl, max(np.abs(rot).max() / thr_rot, np.abs(sl).max() / thr_slide), pos, ang


def _moves(arc, settings, sign, lam, hold, thr_rot, thr_slide, check):
    """(moved, reading) of a hold of ``lam`` from rest: moved as the chain's ramp decides it
    (a contact past its threshold within ``hold`` T); reading (contact rotations, slips, end
    gaps) once the motion has grown past four times the thresholds, else None: a start that
    stops again (the load applied at once rocks the blocks a little and they settle back) shows
    no mechanism to read."""
    ca = engine_arcade(arc, settings)
    ca.settle()
    steps = int(math.ceil(hold * settings.steps_per_T))
    done, moved = 0, False
    while done < steps or (moved and done < 4 * steps):
        k = check if done >= steps else min(check, steps - done)
        ca.step(-sign * lam * G, k)
        done += k
        rot, sl, measure, pos, ang = _motion(ca, thr_rot, thr_slide)
        if measure > 4.0:
            return True, (rot, sl, ca.end_gaps(pos, ang))
        if moved and measure < 0.5:  # it started, and settled back
            return True, None
        moved = moved or measure > 1.0
        if not moved and getattr(ca, "at_rest", None) is not None and ca.at_rest():
            return False, None  # archrock's engine, still under a constant load: for good
    return moved, None


def arcade_ramp_direction(arc: Arcade, direction: str, settings: EngineSettings | None = None,
                          *, rate: float = 0.05, hold: float = 4.0, tol: float = 0.005,
                          threshold: float = 1e-3, slide_threshold: float = 1e-3,
                          lambda_max: float = 2.0, lambda_start: float = 0.0,
                          progress=None) -> ArcadeRampDirection:
    """The engine's activation multiplier and hinges of ``arc`` in ``direction`` ('l': the
    ground accelerates toward -x, the loads push toward +x); the options are those of
    :func:`~archrock.contact.ramp.ramp_direction`."""
    settings, sign = start_ramp(direction, settings, rate, hold, tol, threshold, slide_threshold,
                                lambda_max, lambda_start)
    ca = engine_arcade(arc, settings)
    thr_slide, lam_seen, (rot, sl, _, pos, ang), (lo, hi, holds, first) = ramp_stages(
        ca, ca.contact_lengths, _motion,
        lambda lam, thr, check: _moves(arc, settings, sign, lam, hold, threshold, thr, check),
        direction, threshold, slide_threshold, lambda_start, lambda_max, rate, tol, progress,
        "the arcade did not move in the contact engine up to |xg''|/g = "
        f"{lambda_max:g} in direction {direction!r} (the ramp's range)")
    ramp_reading = read_hinges(rot, sl, ca.end_gaps(pos, ang), threshold, thr_slide)
    hinges, slid, rocking = (read_hinges(*first, threshold, thr_slide) if first is not None
                             else ramp_reading)
    places = tuple(arc.contacts[c].place(e) for c, e in hinges)
    return ArcadeRampDirection(direction, 0.5 * (lo + hi), lo, hi,
                               "rocking" if rocking else "sliding", hinges, places, slid,
                               float(lam_seen), ramp_reading[0], holds)


def arcade_ramp(arc: Arcade, settings: EngineSettings | None = None, progress=None, *,
                k_l: float | None = None, k_r: float | None = None, **kwargs) -> ArcadeRamp:
    """:func:`arcade_ramp_direction` in both directions; the ramp's range follows ``k_l`` and
    ``k_r`` (the graph LP's multipliers, :func:`~archrock.contact.ramp.ramp_range`; computed
    when not given)."""
    settings = settings or EngineSettings()
    ks = {"l": k_l, "r": k_r}
    out, ranges = [], {}
    for d in ("l", "r"):
        if ks[d] is None:
            from ..statics.graph import graph_multiplier

            ks[d] = graph_multiplier(arc, d)
        ranges[d] = ramp_range(ks[d])
        out.append(arcade_ramp_direction(arc, d, settings, progress=progress,
                                         lambda_start=ranges[d][0], lambda_max=ranges[d][1],
                                         **kwargs))
    opts = {"rate": 0.05, "hold": 4.0, "tol": 0.005, "threshold": 1e-3,
            "slide_threshold": 1e-3}
    opts.update(kwargs)
    opts["lambda_start"] = {d: ranges[d][0] for d in ranges}
    opts["lambda_max"] = {d: ranges[d][1] for d in ranges}
    return ArcadeRamp(out[0], out[1], settings, opts)


@dataclass(frozen=True, eq=False)
class ArcadeResponse(EngineRecord):
    """:func:`arcade_respond`'s result: ``time`` (k,) [s], ``rotations`` (k, n) [rad] of every
    block since settling (counter-clockwise +), ``drops`` (k,) [m] the largest drop of a mass
    centre; ``status`` 'rest', 'collapsed' or 'moving'; ``t_collapse`` [s] (None without);
    ``peak_rotation`` [rad] the largest |rotation| of any block; ``moved`` the blocks that
    turned by more than 1e-3 rad; ``t_final`` [s]."""

    time: np.ndarray = field(repr=False)
    rotations: np.ndarray = field(repr=False)
    drops: np.ndarray = field(repr=False)
    status: str
    t_collapse: float | None
    peak_rotation: float
    moved: tuple
    t_final: float
    settings: EngineSettings
    run: dict

    def to_dict(self, samples: bool = False) -> dict:
        d = {"collapsed": self.collapsed, "status": self.status,
             "t_collapse": self.t_collapse, "peak_rotation": self.peak_rotation,
             "moved": list(self.moved), "t_final": self.t_final,
             "engine": self.settings.to_dict(), "run": dict(self.run)}
        if samples:
            d["time"] = self.time.tolist()
            d["rotations"] = self.rotations.tolist()
        return d


def _respond_compiled(ca, motion, every, n_out, t_stop, drop_limit, ke_rest, quiet_needed):
    """archrock's engine: the arcade's response compiled whole
    (:meth:`~archrock.contact.rigid.RigidBlocks.respond_samples`, collapse and rest checked at
    every step), read at its samples: (status, t_collapse, rotations, drops, each block's peak
    |rotation| over the samples and the last state)."""
    t_most = max(t_stop, (n_out - 1) * every * ca.dt)
    status, t_col, samples, k = ca.respond_samples(motion, every, n_out, t_most, drop_limit,
                                                   ke_rest, quiet_needed)
    rots = samples[:, :, 2] - ca.ref_ang
    drops = np.max(ca.ref_pos[:, 1] - samples[:, :, 1], axis=1)
    last = np.abs(ca.q[:, 2] - ca.ref_ang)
    peak = np.maximum(np.nanmax(np.abs(rots[:k]), axis=0), last) if k else last
    return status, t_col, rots, drops, peak


def arcade_respond(arc: Arcade, motion: GroundMotion, settings: EngineSettings | None = None,
                   *, t_end: float = 3.0, dt_out: float = 0.01, t_free: float = 20.0,
                   collapse_drop: float = 0.2) -> ArcadeResponse:
    """The engine's response of ``arc`` to ``motion`` (as
    :func:`~archrock.contact.motion.engine_respond`, without a four-link model beside it): the
    run goes on after the motion until rest, collapse (a mass centre dropped by
    ``collapse_drop`` x size) or ``t_free`` T of free motion."""
    if not isinstance(motion, GroundMotion):
        raise ArchInputError(f"motion: expected a GroundMotion, got {type(motion).__name__}")
    for name, v, lo, hi in (("t_end", t_end, 1e-6, 1e5), ("dt_out", dt_out, 1e-7, 1e5),
                            ("t_free", t_free, 0.0, 1e4),
                            ("collapse_drop", collapse_drop, 1e-4, 10)):
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not lo <= v <= hi:
            raise ArchInputError(f"{name}: {v!r}; allowed {lo:g} <= {name} <= {hi:g}")
    settings = settings or EngineSettings()
    ca = engine_arcade(arc, settings)
    ca.settle()
    dt = ca.dt
    every = max(1, int(round(dt_out / dt)))
    n_out = int(math.floor(t_end / (every * dt) + 1e-9)) + 1
    t_stop = float(motion.times[-1]) + t_free * ca.time_scale
    drop_limit = collapse_drop * ca.size
    ke_rest = 1e-9 * float(ca.masses.sum()) * G * ca.size
    nb = arc.n_blocks
    rots = np.full((n_out, nb), np.nan)
    drops = np.full(n_out, np.nan)
    peak = np.zeros(nb)
    status, t_col, quiet, k = "moving", None, 0, 0
    quiet_needed = int(0.5 * settings.steps_per_T)
    compiled = hasattr(ca, "respond_samples")
    if compiled:  # archrock's engine: compiled, checked at every step
        status, t_col, rots, drops, peak = _respond_compiled(
            ca, motion, every, n_out, t_stop, drop_limit, ke_rest, quiet_needed)
    while not compiled:  # pymunk's: one step at a time from Python
        t = ca.time
        pos, ang, vel, rate = ca.state()
        rel = ang - ca.ref_ang
        np.maximum(peak, np.abs(rel), out=peak)
        drop = float(np.max(ca.ref_pos[:, 1] - pos[:, 1]))
        if k < n_out and ca.steps == k * every:
            rots[k], drops[k] = rel, drop
            k += 1
        if drop > drop_limit:
            status, t_col = "collapsed", t
            break
        if t > motion.times[-1]:
            quiet = quiet + 1 if ca.kinetic_energy(vel, rate) < ke_rest else 0
            if quiet >= quiet_needed:
                status = "rest"
                if k >= n_out:
                    break
        if t >= t_stop and k >= n_out:
            break
        ca.step(float(motion(t + 0.5 * dt)), 1)
    if status == "rest" and quiet < quiet_needed and not compiled:
        status = "moving"
    run = {"t_end": t_end, "dt_out": every * dt, "t_free": t_free,
           "collapse_drop": collapse_drop, "dt": dt, "motion": motion.name}
    moved = tuple(int(i) for i in np.flatnonzero(peak > 1e-3))
    return ArcadeResponse(np.arange(n_out) * every * dt, rots, drops, status, t_col,
                          float(peak.max()), moved, float(ca.time), settings, run)

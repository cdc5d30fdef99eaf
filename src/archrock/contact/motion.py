"""An arch's response to a ground motion in the contact engine, beside the four-link model.

The ground acceleration enters as the body force of the ground's frame (:mod:`.engine`); the run
goes on after the ground motion until the arch is at rest, has collapsed or ``t_free`` T of free
motion have passed.  Collapse in the engine: a voussoir's mass centre has dropped by more than
``collapse_drop`` x size below its settled height (an arch that survives comes back up; one
that falls drops by metres), so the engine's collapse time is later than the four-link model's
(the last passage of the unstable rotation).

The equivalent four-link rotation: phi_l = (rotation of the voussoir of M_l's link 1 that rests
on its ground hinge A) / s_l, with s_l the sign of :class:`~archrock.dynamics.fourlink.FourLink` (theta_1 =
s phi), likewise phi_r for M_r; the signed rotation is +phi_l where phi_l >= phi_r, else -phi_r
(0 when both are <= 0), as ``respond``'s signed response (+phi in M_l, -phi in M_r).  It is the four-link phi exactly
while the engine moves in the limit mechanism; when the engine opens another one (impulsive
pulses often put hinge B elsewhere), it is still the rotation about the springing hinge.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np

from .._records import EngineRecord
from ..errors import ArchInputError
from ..geometry import VoussoirArch
from ..groundmotion import GroundMotion
from ..units import G
from .rigid import engine_arch
from .settings import EngineSettings

__all__ = ["ContactResponse", "engine_respond", "equivalent_rotation"]


@dataclass(frozen=True, eq=False)
class ContactResponse(EngineRecord):
    """Result of :func:`engine_respond`.

    time (k,) [s]: output samples up to t_end; rotations (k, n) [rad]: every voussoir's
    rotation (counter-clockwise +) since settling; joint_rotations (k, n+1) [rad]; sliding
    (k, n+1) [m]: slip along each joint at its closed end (ContactArch.joint_sliding); phi (k,) [rad]:
    the equivalent signed four-link rotation; max_sliding (n+1,) [m] and peak [rad] (|phi|) over
    the whole run; status 'rest', 'collapsed' or 'moving'; t_collapse [s]: when a voussoir had
    dropped by collapse_drop x size (None without collapse); t_final [s]: end of the run."""

    time: np.ndarray = field(repr=False)
    rotations: np.ndarray = field(repr=False)
    joint_rotations: np.ndarray = field(repr=False)
    sliding: np.ndarray = field(repr=False)
    phi: np.ndarray = field(repr=False)
    positions: np.ndarray = field(repr=False)
    max_sliding: np.ndarray
    peak: float
    status: str
    t_collapse: float | None
    t_final: float
    settings: EngineSettings
    run: dict

    def to_dict(self, samples: bool = True) -> dict:
        d = {"collapsed": self.collapsed, "status": self.status, "t_collapse": self.t_collapse,
             "t_final": self.t_final, "peak": self.peak,
             "max_sliding": self.max_sliding.tolist(),
             "engine": self.settings.to_dict(), "run": dict(self.run)}
        if samples:
            d["time"] = self.time.tolist()
            d["phi"] = self.phi.tolist()
            d["rotations"] = self.rotations.tolist()
        return d


def _link1(model, direction):
    """The voussoir of link 1 on the ground hinge A (the springing side), and the sign s."""
    fl = model.mech_l if direction == "l" else model.mech_r
    idx = fl.link_voussoirs[0]
    return np.array([min(idx) if direction == "l" else max(idx)], dtype=int), float(fl.sign)


def largest_rotation(model, rotations: np.ndarray) -> np.ndarray:
    """Where no four-hinge mechanism governs (lift-off: no four-link phi), each sample's
    voussoir rotation of largest magnitude, with its sign [rad] (``model`` unused)."""
    rot = np.atleast_2d(np.asarray(rotations, float))
    return rot[np.arange(rot.shape[0]), np.argmax(np.abs(rot), axis=1)]


def equivalent_rotation(model, rotations: np.ndarray) -> np.ndarray:
    """Signed four-link rotation (module docstring) of voussoir rotations (k, n) [rad], for a
    prepared :class:`~archrock.dynamics.response.DynamicModel` of the same arch."""
    rot = np.atleast_2d(np.asarray(rotations, float))
    il, sl = _link1(model, "l")
    ir, sr = _link1(model, "r")
    pl = rot[:, il].mean(axis=1) / sl
    pr = rot[:, ir].mean(axis=1) / sr
    out = np.where(pl >= pr, pl, -pr)
    out[np.maximum(pl, pr) <= 0] = 0.0
    return out


def _progress_line(progress, ca, t_most):
    progress(f"engine: t = {ca.time:.2f} s of at most {t_most:.2f} s "
             f"({100 * ca.time / t_most:.0f}%)")


def _run_compiled(ca, motion, every, n_out, t_stop, t_most, drop_limit, ke_rest, quiet_needed,
                  progress):
    """archrock's engine: the whole run in compiled chunks of a tenth of its longest span (a
    progress line after each), every step checked for collapse and rest; the samples are read
    afterwards.  Returns (status, t_collapse, rotations, joint rotations, sliding, positions,
    largest sliding over the samples)."""
    status, t_col, samples, taken = ca.respond_samples(
        motion, every, n_out, t_most, drop_limit, ke_rest, quiet_needed,
        None if not progress else lambda eng: _progress_line(progress, eng, t_most))
    n = ca.masses.size
    rots = samples[:, :, 2] - ca.ref_ang
    posn = samples[:, :, :2].copy()
    jrot = np.full((n_out, n + 1), np.nan)
    slide = np.full((n_out, n + 1), np.nan)
    for k in range(taken):
        jrot[k] = ca.joint_rotations(rots[k])
        slide[k] = ca.joint_sliding(posn[k], samples[k, :, 2]) - ca.ref_slide
    max_sl = np.nanmax(np.abs(slide[:taken]), axis=0) if taken else np.zeros(n + 1)
    return status, t_col, rots, jrot, slide, posn, max_sl


def _run_stepwise(ca, motion, every, n_out, t_stop, t_most, drop_limit, ke_rest, quiet_needed,
                  progress):
    """pymunk's engine: one step at a time from Python, read at every step (the same returns
    as :func:`_run_compiled`)."""
    n = ca.arch.n
    dt = ca.dt
    rots = np.full((n_out, n), np.nan)
    jrot = np.full((n_out, n + 1), np.nan)
    slide = np.full((n_out, n + 1), np.nan)
    posn = np.full((n_out, n, 2), np.nan)
    max_sl = np.zeros(n + 1)
    status, t_col = "moving", None
    k = 0
    quiet = 0
    next_line = 0.1
    last_line = time.monotonic()
    while True:
        t = ca.time
        pos, ang, vel, rate = ca.state()
        rel = ang - ca.ref_ang
        sl = ca.joint_sliding(pos, ang) - ca.ref_slide
        np.maximum(max_sl, np.abs(sl), out=max_sl)
        if k < n_out and ca.steps == k * every:
            rots[k] = rel
            jrot[k] = ca.joint_rotations(rel)
            slide[k] = sl
            posn[k] = pos
            k += 1
        if ca.drops(pos).max() > drop_limit:
            status, t_col = "collapsed", t
            break
        if t > motion.times[-1]:
            ke = ca.kinetic_energy(vel, rate)
            quiet = quiet + 1 if ke < ke_rest else 0
            if quiet >= quiet_needed and k >= n_out:
                status = "rest"
                break
            if quiet >= quiet_needed and status != "rest":
                status = "rest"  # keeps sampling the arch at rest to t_end
        if t >= t_stop and k >= n_out:
            break
        ca.step(float(motion(t + 0.5 * dt)), 1)
        if progress and (ca.time >= next_line * t_most
                         or (ca.steps % 64 == 0 and time.monotonic() - last_line > 5.0)):
            # a line per 10% of the longest the run can take, and every 5 s of wall time:
            # collapse or rest often end the run long before its first 10%
            _progress_line(progress, ca, t_most)
            next_line = math.floor(10 * ca.time / t_most + 1e-9) / 10 + 0.1
            last_line = time.monotonic()
    if status == "rest" and quiet < quiet_needed:
        status = "moving"
    return status, t_col, rots, jrot, slide, posn, max_sl


def engine_respond(arch: VoussoirArch, motion: GroundMotion, settings: EngineSettings | None = None,
                   *, model=None, t_end: float = 3.0, dt_out: float = 0.005,
                   t_free: float = 20.0, collapse_drop: float = 0.2,
                   progress=None) -> ContactResponse:
    """The engine's response of ``arch`` to ``motion``.

    model: a prepared :class:`~archrock.dynamics.response.DynamicModel`, for the equivalent rotation (only
    its mechanisms are used: the engine has no impact law; default ``prepare(arch, "momentum")``;
    where lift-off governs and no four-link model exists, phi is :func:`largest_rotation`); t_end, dt_out [s]: output window and sampling; t_free [T]: free
    motion after the ground motion at most; collapse_drop: drop of a mass centre, as a fraction
    of the size, that counts as collapse."""
    if not isinstance(motion, GroundMotion):
        raise ArchInputError(f"motion: expected a GroundMotion, got {type(motion).__name__}")
    for name, v, lo, hi in (("t_end", t_end, 1e-6, 1e5), ("dt_out", dt_out, 1e-7, 1e5),
                            ("t_free", t_free, 0.0, 1e4), ("collapse_drop", collapse_drop, 1e-4, 10)):
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not lo <= v <= hi:
            raise ArchInputError(f"{name}: {v!r}; allowed {lo:g} <= {name} <= {hi:g}")
    if dt_out > t_end:
        raise ArchInputError(f"dt_out: {dt_out} s; allowed <= t_end = {t_end} s")
    if model is None:
        from ..dynamics.response import prepare
        from ..errors import NotFourHingeError

        try:
            model = prepare(arch, "momentum")
        except NotFourHingeError:  # lift-off governs: no four-link phi, the largest rotation
            model = None
    settings = settings or EngineSettings()
    ca = engine_arch(arch, settings)
    ca.settle()
    dt = ca.dt
    every = max(1, int(round(dt_out / dt)))
    dt_s = every * dt  # output sampling actually used: a whole number of steps
    n_out = int(math.floor(t_end / dt_s + 1e-9)) + 1
    t_stop = float(motion.times[-1]) + t_free * ca.time_scale
    drop_limit = collapse_drop * ca.size
    m_tot = float(ca.masses.sum())
    ke_rest = 1e-9 * m_tot * G * ca.size
    quiet_needed = int(0.5 * settings.steps_per_T)
    t_most = max(t_stop, (n_out - 1) * dt_s)  # the run's longest: free motion or the window
    args = (ca, motion, every, n_out, t_stop, t_most, drop_limit, ke_rest, quiet_needed, progress)
    if hasattr(ca, "respond_samples"):  # archrock's engine: compiled, checked at every step
        status, t_col, rots, jrot, slide, posn, max_sl = _run_compiled(*args)
    else:
        status, t_col, rots, jrot, slide, posn, max_sl = _run_stepwise(*args)
    if progress:
        progress(f"engine: 100% ({status} at t = {ca.time:.2f} s)")
    rotation = equivalent_rotation if model is not None else largest_rotation
    phi = rotation(model, np.nan_to_num(rots))
    phi[np.isnan(rots[:, 0])] = np.nan
    # peak |phi| over the whole run from the samples (and the last state)
    full = rotation(model, (ca.state()[1] - ca.ref_ang)[None, :])
    peak = float(np.nanmax(np.abs(np.concatenate([phi, full])))) if n_out else 0.0
    run = {"t_end": t_end, "dt_out": dt_s, "t_free": t_free, "collapse_drop": collapse_drop,
           "dt": dt, "motion": motion.name}
    return ContactResponse(np.arange(n_out) * dt_s, rots, jrot, slide, phi, posn, max_sl, peak,
                           status, t_col, float(ca.time), settings, run)

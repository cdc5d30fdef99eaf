"""Quasi-static activation in the contact engine: a slowly increasing horizontal ground
acceleration, then constant accelerations held from rest to narrow the activation multiplier.

The ground acceleration is xg'' = -lambda g (direction 'l', the one that opens M_l) or
+lambda g ('r').  Stage 1 ramps lambda at ``rate`` per T (T = sqrt(size/g)) until the arch moves:
a joint's relative rotation or sliding passes its threshold.  The ramp overshoots the activation
by the time a slowly starting mechanism needs to reach the threshold, so stage 2 holds constant
values of lambda from rest for ``hold`` T each and bisects between one that leaves the arch at
rest and one that moves it, down to a relative width ``tol``.  The reported multiplier is the
middle of the last bracket; the hinges are the joints whose relative rotation is at least 5%
of the largest one when the ramp's motion has grown to ``4 x threshold``, each at the
end of its joint (intrados or extrados) that stays closed.

The ramp's range follows the arch: :func:`ramp` gives up beyond
``lambda_max = max(2, 1.5 k_d)`` (:func:`ramp_range`, k_d the limit analysis's multiplier of the
direction; at most 100), and on an arch with k_d > 2 it starts from ``0.5 k_d`` held from rest
(as the holds of stage 2 do) instead of from 0, so that its length does not grow with k.  An
arch that does not move within the range is an outcome (:class:`LimitExceededError`), not an
input error.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..errors import ArchInputError, LimitExceededError
from ..geometry import VoussoirArch
from ..units import G
from .rigid import engine_arch
from .settings import EngineSettings

__all__ = ["RampDirection", "RampResult", "ramp", "ramp_direction", "ramp_range",
           "LAMBDA_MAX_FLOOR", "LAMBDA_MAX_FACTOR", "LAMBDA_MAX_CAP"]

EDGE = ("intrados", "extrados")

#: The ramp's range: lambda_max = max(LAMBDA_MAX_FLOOR, LAMBDA_MAX_FACTOR k), at most
#: LAMBDA_MAX_CAP (the engine's activation is within a few % of k on the documented arches, and
#: 8% below it where the joints start to slide: 1.5 k leaves room for both).
LAMBDA_MAX_FLOOR = 2.0
LAMBDA_MAX_FACTOR = 1.5
LAMBDA_MAX_CAP = 100.0


def ramp_range(k: float | None) -> tuple[float, float]:
    """(lambda_start, lambda_max) of the ramp for an arch whose limit-analysis multiplier in the
    direction is ``k`` (None or inf: no mechanism, the whole range up to LAMBDA_MAX_CAP):
    lambda_max = max(2, 1.5 k) capped at 100; the ramp starts at 0, or at 0.5 k where k > 2."""
    if k is None or not math.isfinite(k) or k <= 0:
        return 0.0, LAMBDA_MAX_CAP
    lam_max = min(LAMBDA_MAX_CAP, max(LAMBDA_MAX_FLOOR, LAMBDA_MAX_FACTOR * float(k)))
    start = 0.5 * float(k) if k > LAMBDA_MAX_FLOOR else 0.0
    return min(start, 0.5 * lam_max), lam_max


@dataclass(frozen=True)
class RampDirection:
    """The engine's activation in one direction: ``multiplier`` lambda = |xg''|/g at which the
    arch starts moving (middle of the bracket [lower, upper]); ``mode`` 'rocking' (joints open
    as hinges) or 'sliding' (a joint slides first); ``hinges`` joint numbers (0 = left
    springing) and ``edges`` the closed end of each; ``sliding_joints`` joints whose sliding
    passed its threshold; ``ramp_multiplier`` where the ramp itself saw motion; ``holds``
    (lambda, moved) of stage 2."""

    direction: str
    multiplier: float
    lower: float
    upper: float
    mode: str
    hinges: tuple[int, ...]
    edges: tuple[str, ...]
    sliding_joints: tuple[int, ...]
    ramp_multiplier: float
    joint_rotations: tuple[float, ...]
    joint_sliding: tuple[float, ...]
    holds: tuple[tuple[float, bool], ...] = field(repr=False, default=())

    def to_dict(self) -> dict:
        return {"direction": self.direction, "multiplier": self.multiplier, "lower": self.lower,
                "upper": self.upper, "mode": self.mode, "hinges": list(self.hinges),
                "edges": list(self.edges), "sliding_joints": list(self.sliding_joints),
                "ramp_multiplier": self.ramp_multiplier,
                "joint_rotations": list(self.joint_rotations),
                "joint_sliding": list(self.joint_sliding),
                "holds": [[lam, moved] for lam, moved in self.holds]}


@dataclass(frozen=True)
class RampResult:
    """Both directions of :func:`ramp`, with the settings that made them."""

    l: RampDirection
    r: RampDirection
    settings: EngineSettings
    ramp: dict

    @property
    def k_l(self) -> float:
        return self.l.multiplier

    @property
    def k_r(self) -> float:
        return self.r.multiplier

    def to_dict(self) -> dict:
        return {"k_l": self.k_l, "k_r": self.k_r, "hinges_l": list(self.l.hinges),
                "hinges_r": list(self.r.hinges), "l": self.l.to_dict(), "r": self.r.to_dict(),
                "engine": self.settings.to_dict(), "ramp": dict(self.ramp)}


def _motion(ca, thr_rot: float, thr_slide: float):
    """(relative joint rotations (n+1,), sliding (n+1,), normalised measure) since settling."""
    pos, ang, _, _ = ca.state()
    rot = ca.joint_rotations(ang) - ca.joint_rotations(ca.ref_ang)
    sl = ca.joint_sliding(pos, ang) - ca.ref_slide
    measure = max(np.abs(rot).max() / thr_rot, np.abs(sl).max() / thr_slide)
    return rot, sl, measure, pos, ang


def ramp_until_moving(blocks, motion, sign: float, lam: float, dlam: float, check: int,
                      lambda_max: float, refusal: str):
    """Stage 1 of a ramp: raise |xg''|/g from ``lam`` by ``dlam`` per engine step on ``blocks``
    (a settled engine arch or arcade: RigidArch, ContactArch, ...), reading ``motion(blocks)`` -> (rotations, slips,
    measure, pos, angles) every ``check`` steps, until the measure passes 4 (four times the
    thresholds).  Returns (the first lambda whose measure passed 1, that last reading); raises
    LimitExceededError(``refusal``) past ``lambda_max`` (bounded)."""
    lam_seen = None
    while True:
        if hasattr(blocks, "advance"):  # archrock's engine: the check's steps in one call
            lams = lam + dlam * np.arange(1, check + 1)
            blocks.advance(-sign * lams * G)
            lam = float(lams[-1])
        else:
            for _ in range(check):
                lam += dlam
                blocks.step(-sign * lam * G, 1)
        reading = motion(blocks)
        if lam_seen is None and reading[2] > 1.0:
            lam_seen = lam
        if reading[2] > 4.0:
            return lam_seen, reading
        if lam > lambda_max:
            raise LimitExceededError(refusal)


def start_ramp(direction, settings, rate, hold, tol, threshold, slide_threshold, lambda_max,
               lambda_start) -> tuple[EngineSettings, float]:
    """What a ramp (of an arch or an arcade) starts from: (``settings`` or the default ones, the
    sign of its load: +1 in direction 'l'), once its options are checked: ArchInputError naming
    the first out of its range (:func:`ramp_direction`)."""
    if direction not in ("l", "r"):
        raise ArchInputError(f"direction: {direction!r}; allowed 'l' or 'r'")
    for name, v, lo, hi in (("rate", rate, 1e-5, 10.0), ("hold", hold, 0.1, 1e3),
                            ("tol", tol, 1e-5, 0.5), ("threshold", threshold, 1e-7, 0.5),
                            ("slide_threshold", slide_threshold, 1e-7, 0.5),
                            ("lambda_max", lambda_max, 1e-3, 100.0)):
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not lo <= v <= hi:
            raise ArchInputError(f"{name}: {v!r}; allowed {lo:g} <= {name} <= {hi:g}")
    if (isinstance(lambda_start, bool) or not isinstance(lambda_start, (int, float))
            or not 0.0 <= lambda_start < lambda_max):
        raise ArchInputError(f"lambda_start: {lambda_start!r}; allowed 0 <= lambda_start < "
                             f"lambda_max = {lambda_max:g}")
    return settings or EngineSettings(), 1.0 if direction == "l" else -1.0


def ramp_stage_one(blocks, lengths, motion, direction, threshold, slide_threshold,
                   lambda_start, lambda_max, rate, progress, refusal):
    """Settle ``blocks`` (an engine arch or arcade) and run stage 1 in ``direction`` at ``rate``
    per T from ``lambda_start``; ``lengths`` are its joints' or contacts' lengths [m] (the
    slide threshold is ``slide_threshold`` x their mean) and ``motion(blocks, thr_rot,
    thr_slide)`` its reading.  Returns (slide threshold [m], steps between readings, the lambda
    first seen moving, the last reading), with a progress line."""
    blocks.settle()
    thr_slide = slide_threshold * float(np.mean(lengths))
    steps_per_T = blocks.settings.steps_per_T
    check = max(1, int(steps_per_T // 100))
    sign = 1.0 if direction == "l" else -1.0
    lam_seen, reading = ramp_until_moving(
        blocks, lambda m: motion(m, threshold, thr_slide), sign, float(lambda_start),
        rate / steps_per_T, check, lambda_max, refusal)
    if progress:
        progress(f"ramp {direction}: motion seen at lambda = {lam_seen:.4f}")
    return thr_slide, check, lam_seen, reading


def ramp_stages(blocks, lengths, motion, moves, direction, threshold, slide_threshold,
                lambda_start, lambda_max, rate, tol, progress, refusal):
    """Both stages of a ramp on ``blocks``: :func:`ramp_stage_one`, then :func:`bisect_holds`
    whose hold of ``lam`` is ``moves(lam, slide threshold, steps between readings)``.
    Returns (slide threshold [m], lambda first seen moving, stage 1's last reading,
    bisect_holds' (lo, hi, holds, first))."""
    thr_slide, check, lam_seen, reading = ramp_stage_one(
        blocks, lengths, motion, direction, threshold, slide_threshold, lambda_start,
        lambda_max, rate, progress, refusal)
    bracket = bisect_holds(lambda lam: moves(lam, thr_slide, check), lam_seen, tol, direction,
                           progress)
    return thr_slide, lam_seen, reading, bracket


def bisect_holds(moves, lam_seen: float, tol: float, direction: str, progress=None):
    """Stage 2 of a ramp: holds from rest, ``moves(lam)`` -> (moved, reading or None), halving
    down from ``lam_seen`` until one rests, then bisecting down to a relative width ``tol``.
    Returns (lo, hi, holds ((lambda, moved), ...), the reading of the lowest hold that moved
    with one, else None)."""
    holds = []
    hi, lo = lam_seen, 0.5 * lam_seen
    first = None
    while True:
        moved, got = moves(lo)
        holds.append((lo, moved))
        if not moved:
            break
        first = got or first
        if lo == 0.0:  # moves under gravity alone: the blocks do not stand in the engine
            hi = 0.0
            break
        hi, lo = lo, (0.5 * lo if lo > 0.01 * lam_seen else 0.0)
    while hi - lo > tol * hi:
        mid = 0.5 * (lo + hi)
        moved, got = moves(mid)
        holds.append((mid, moved))
        if progress:
            progress(f"hold {direction}: lambda = {mid:.4f} {'moves' if moved else 'rests'}")
        if moved:
            hi, first = mid, got or first
        else:
            lo = mid
    return lo, hi, tuple(holds), first


def read_hinges(rot, sl, gaps, threshold, thr_slide):
    """(hinges ((joint or contact, end), ...), sliding ones, rocking?) of a motion: relative
    rotations ``rot`` [rad] and slips ``sl`` [m] of each joint or contact, ``gaps`` (.., 2) of
    its two ends [m]; the hinges turn by at least 5% of the largest relative rotation, each at
    its end that stays closed (0 intrados, 1 extrados for an arch's joint)."""
    big = np.abs(rot).max()
    slid = tuple(int(c) for c in np.flatnonzero(np.abs(sl) > thr_slide))
    rocking = big / threshold >= np.abs(sl).max() / thr_slide
    turning = np.flatnonzero(np.abs(rot) >= 0.05 * big) if rocking else np.array([], int)
    return tuple((int(c), int(np.argmin(gaps[c]))) for c in turning), slid, bool(rocking)


def _moves(arch, settings, sign, lam, hold, thr_rot, thr_slide, check_every) -> bool:
    ca = engine_arch(arch, settings)
    ca.settle()
    a = -sign * lam * G
    steps = int(math.ceil(hold * settings.steps_per_T))
    done = 0
    while done < steps:
        k = min(check_every, steps - done)
        ca.step(a, k)
        done += k
        if _motion(ca, thr_rot, thr_slide)[2] > 1.0:
            return True
        if getattr(ca, "at_rest", None) is not None and ca.at_rest():
            return False  # archrock's engine, still under a constant load: still for good
    return False


def ramp_direction(arch: VoussoirArch, direction: str, settings: EngineSettings | None = None, *,
                   rate: float = 0.05, hold: float = 4.0, tol: float = 0.005,
                   threshold: float = 1e-3, slide_threshold: float = 1e-3,
                   lambda_max: float = 2.0, lambda_start: float = 0.0,
                   progress=None) -> RampDirection:
    """The engine's activation multiplier and hinges in ``direction`` ('l' or 'r').

    rate: lambda per T of the ramp; hold: duration of each constant-lambda run [T]; tol:
    relative width of the final bracket; threshold: relative joint rotation [rad] and
    slide_threshold: sliding as a fraction of the joint's length that count as motion;
    lambda_max: the ramp gives up beyond it (:class:`LimitExceededError`: the arch did not move
    within the range; :func:`ramp_range` gives the range that follows an arch's k);
    lambda_start: the ramp starts from this lambda, held from rest (0 <= lambda_start <
    lambda_max)."""
    settings, sign = start_ramp(direction, settings, rate, hold, tol, threshold, slide_threshold,
                                lambda_max, lambda_start)
    ca = engine_arch(arch, settings)
    thr_slide, lam_seen, (rot, sl, _, pos, ang), (lo, hi, holds, _) = ramp_stages(
        ca, ca.joint_lengths, _motion,
        lambda lam, thr, check: (_moves(arch, settings, sign, lam, hold, threshold, thr, check),
                                 None),
        direction, threshold, slide_threshold, lambda_start, lambda_max, rate, tol, progress,
        "the arch did not move in the contact engine up to |xg''|/g = "
        f"{lambda_max:g} in direction {direction!r} (the ramp's range; the limit "
        f"analysis may give a larger multiplier or none: raise lambda_max, "
        f"`archrock dem --ramp --ramp-max`)")
    turning, slid, rocking = read_hinges(rot, sl, ca.end_gaps(pos, ang), threshold, thr_slide)
    hinges = tuple(j for j, _ in turning)
    edges = tuple(EDGE[e] for _, e in turning)
    return RampDirection(direction, 0.5 * (lo + hi), lo, hi, "rocking" if rocking else "sliding",
                         hinges, edges, slid, float(lam_seen),
                         tuple(float(x) for x in rot), tuple(float(x) for x in sl), holds)


def ramp(arch: VoussoirArch, settings: EngineSettings | None = None, progress=None, *,
         limit=None, lambda_max: float | None = None, **kwargs) -> RampResult:
    """:func:`ramp_direction` in both directions ('l' then 'r').

    lambda_max: the ramp's upper end in both directions; None (default): :func:`ramp_range` of
    each direction's multiplier in ``limit`` (the arch's :class:`~archrock.statics.limit.LimitResult`;
    computed when not given), with the start it gives.  The ranges used are in
    ``result.ramp["lambda_max"]`` and ``["lambda_start"]``."""
    settings = settings or EngineSettings()
    ranges = {}
    for d in ("l", "r"):
        if lambda_max is not None:
            ranges[d] = (kwargs.get("lambda_start", 0.0), float(lambda_max))
            continue
        if limit is None:
            from ..statics.limit import limit_analysis

            limit = limit_analysis(arch, verify=False)
        ranges[d] = ramp_range(getattr(limit, f"k_{d}"))
    kw = {k: v for k, v in kwargs.items() if k != "lambda_start"}
    out = [ramp_direction(arch, d, settings, progress=progress, lambda_start=ranges[d][0],
                          lambda_max=ranges[d][1], **kw) for d in ("l", "r")]
    opts = {"rate": 0.05, "hold": 4.0, "tol": 0.005, "threshold": 1e-3, "slide_threshold": 1e-3}
    opts.update(kw)
    opts["lambda_start"] = {d: ranges[d][0] for d in ("l", "r")}
    opts["lambda_max"] = {d: ranges[d][1] for d in ("l", "r")}
    return RampResult(out[0], out[1], settings, opts)

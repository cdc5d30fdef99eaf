"""A support pushed slowly in the contact engine: the thrust, the hinges and the displacement
capacity of an arch whose springing spreads, closes or settles (issue 20, the engine's side of
"Verification by two independent methods").

The moving abutment (:class:`~.engine.ContactArch` with ``moving=``) is a kinematic body: it
translates at a constant speed whatever the arch does, so the contacts give the force the arch
exerts on it.  Movements (``movement``, ``side``; d >= 0 the imposed displacement [m]):

* ``spread``: the span opens by d (side 'right': the right support moves +x by d; 'left': the
  left one -x by d; 'both': each by d/2);
* ``close``: the span closes by d (the same, reversed);
* ``settlement``: the support drops by d (-y; 'both': both drop by d, a rigid translation);
* ``rotate``: the support turns outward about its foot (the outer end of the springing joint
  lowered by ``pivot_depth``; an arch on piers: the pier's outer foot), as
  :class:`~archrock.geometry.displaced.SupportMovement`'s ``rotation`` does, by d / size rad:
  d is the rotation times the arch's size [m], the metres a point one size from the foot
  moves ('both': each turns by half of it; the kinematic body follows the circle about the
  foot exactly, its velocity set every step).

Quasi-static rate.  The support moves at v = rate * sqrt(g size) (``rate`` in sizes per T,
T = sqrt(size/g)).  Once the arch has become a mechanism (three hinges: with one support moving
it has no degree of freedom left) its kinetic energy is about 1/2 M_eff v^2, while the potential
energy it gives up grows as W alpha d (alpha ~ 0.2 for the drop of its mass centre per unit of
spread), so KE / dPE ~ (M_eff / 2 alpha M) rate^2 size / d.  Criterion: KE <= 1% of |dPE| once
d >= 1% of the size; the default rate 0.005 meets it with a margin of ~3 on the semicircles of
docs/supports-engine.md, and the result measures it (``ke_ratio``, ``quasi_static``).

What is recorded every ``sample`` x size of displacement (forces averaged over the steps of that
window from the contact impulses / dt): the force the arch exerts on each support [N per m of
depth; x right, y up], the thrust H on the moving support (> 0: compression pushing it outward),
the crown's drop (the arch's highest point, the extrados at the crown, followed as a material
point of its voussoir), every joint's relative rotation and the kinetic and potential energy.
A joint is open where its relative rotation exceeds ``open_gap`` x size / (the joint's length),
i.e. its open end has moved by ``open_gap`` of the size (1 mm on a 10 m arch by default); its
hinge is the end that stays closed, labelled as archrock labels hinges ('3e': joint 3, between
voussoirs 2 and 3, turning about its extrados end; 'i' intrados; 's' both ends apart).

Collapse.  While pushing, the arch is suspected to run away when its kinetic energy exceeds
``ke_factor`` x 1/2 M v^2 (the whole arch moving ``sqrt(ke_factor)`` times faster than the
support) or a voussoir has turned by more than ``max_rotation``.  A copy of the engine's state
is then held: its support slows down linearly to a stop over ``stop`` T (moving on by
v stop / 2; an abrupt stop shakes an arch near its capacity by several open thresholds) and
stays there for ``hold`` T.  The arch has collapsed if it keeps moving: it runs away as above,
or a joint still turns by its open threshold over the hold's second half.  A suspicion that comes
to rest is a snap between mechanisms and the push goes on.  The capacity is bracketed, in held
displacements, between the last checkpoint (every CHECKPOINT_EVERY samples) whose hold rests and
the first that moves, and bisected (copies pushed on from the resting state, then held) to a
relative width ``tol``; it is the bracket's middle.
Every run is bounded: the push stops at ``max_displacement`` (then the arch stands: no capacity
within it) and may not need more than ``max_time`` T.
"""

from __future__ import annotations

import copy
import math
import time as _time
from dataclasses import dataclass, field

import numpy as np

from .._records import EngineRecord
from ..errors import ArchInputError, CannotStandError
from ..geometry import VoussoirArch
from ..units import G
from .engine import ContactArch
from .settings import EngineSettings

__all__ = ["PushResult", "push_support", "MOVEMENTS", "SIDES", "check_support_movement"]

#: Support movements and sides, as the statics layer's SupportMovement spells them.
MOVEMENTS = ("spread", "settlement", "close", "rotate")
SIDES = ("right", "left", "both")

#: The quasi-static criterion: kinetic energy at most this fraction of the potential energy
#: change, checked once the displacement passes KE_CHECK_FROM x size.
KE_RATIO_MAX = 0.01
KE_CHECK_FROM = 0.01

#: A copy of the engine's state is kept every CHECKPOINT_EVERY samples, for the holds.
CHECKPOINT_EVERY = 5
#: The thrust at the start: a straight line through H(d) over this span of d after the first
#: opening [fraction of the size], extrapolated to d = 0.
FIT_SPAN = 0.01


def check_support_movement(movement: str, side: str) -> tuple[str, str]:
    """(movement, side) checked: movement one of MOVEMENTS, side one of SIDES."""
    if movement not in MOVEMENTS:
        raise ArchInputError(f"movement: {movement!r}; allowed one of {', '.join(MOVEMENTS)}")
    if side not in SIDES:
        raise ArchInputError(f"side: {side!r}; allowed one of {', '.join(SIDES)}")
    return movement, side


def _num(name, value, lo, hi, allowed=None):
    if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)):
        raise ArchInputError(f"{name}: expected a number, got {value!r}")
    v = float(value)
    if not math.isfinite(v) or not lo <= v <= hi:
        raise ArchInputError(f"{name}: {value!r} is out of range; allowed "
                             f"{allowed or f'{lo:g} <= {name} <= {hi:g}'}")
    return v


@dataclass(frozen=True, eq=False)
class PushResult(EngineRecord):
    """Result of :func:`push_support`.

    Samples (k of them; the first at rest before the push): ``displacement`` (k,) [m] the imposed
    movement d; ``time`` (k,) [s]; ``force_left``, ``force_right`` (k, 2) [N/m] the force the arch
    exerts on each support (x right, y up), averaged over the window ending at the sample;
    ``thrust`` (k,) [N/m] the horizontal force on the moving support(s), > 0 pushing it away from
    the span (compression; 'both': the mean of the two); ``crown_drop`` (k,) [m];
    ``joint_rotations`` (k, n+1) [rad] since settling; ``kinetic`` (k,) and ``potential_drop``
    (k,) [J/m] (the potential energy given up since settling).

    ``thrust_rest`` [N/m]: the thrust of the settled arch before the push (statically
    indeterminate: the engine's own); ``thrust_start`` [N/m]: a straight line through the thrust
    over FIT_SPAN x size after the first opening, at d = 0 (None if too few samples);
    ``opening_displacement`` [m]: d where the first joint opened; ``hinges``: the open joints'
    labels at the first opening (the first sample whose largest rotation is 4x its threshold);
    ``hinge_changes``: (d, labels) each time the set of open joints changed.

    ``status``: 'collapsed' or 'standing' (no collapse up to max_displacement); ``capacity`` [m]
    the middle of ``capacity_bracket`` (lower: held, rests; upper: held, moves), None when
    standing; ``collapse_by``: 'hold' (the arch moves on with the support held) or 'rotation' (a
    voussoir turned past max_rotation); ``collapse_hinges``: labels of the joints that had
    turned by their open threshold when the arch started moving in the collapsing hold;
    ``holds``: (d, moved) of every hold.  ``ke_ratio``: the largest
    KE / |dPE| past KE_CHECK_FROM x size before collapse; ``quasi_static``: ke_ratio <= 1%.
    ``simulated_seconds`` (all runs, holds included) and ``wall_seconds``; ``settings`` and
    ``run`` (the options and the scales used)."""

    movement: str
    side: str
    displacement: np.ndarray = field(repr=False)
    time: np.ndarray = field(repr=False)
    force_left: np.ndarray = field(repr=False)
    force_right: np.ndarray = field(repr=False)
    thrust: np.ndarray = field(repr=False)
    crown_drop: np.ndarray = field(repr=False)
    joint_rotations: np.ndarray = field(repr=False)
    kinetic: np.ndarray = field(repr=False)
    potential_drop: np.ndarray = field(repr=False)
    thrust_rest: float
    thrust_start: float | None
    opening_displacement: float | None
    hinges: tuple[str, ...]
    hinge_changes: tuple[tuple[float, tuple[str, ...]], ...]
    status: str
    capacity: float | None
    capacity_bracket: tuple[float, float] | None
    collapse_by: str | None
    collapse_hinges: tuple[str, ...]
    holds: tuple[tuple[float, bool], ...]
    ke_ratio: float | None
    quasi_static: bool | None
    simulated_seconds: float
    wall_seconds: float
    settings: EngineSettings
    run: dict

    def to_dict(self, samples: bool = True) -> dict:
        d = {"movement": self.movement, "side": self.side, "status": self.status,
             "capacity": self.capacity,
             "capacity_bracket": None if self.capacity_bracket is None
             else list(self.capacity_bracket),
             "collapse_by": self.collapse_by, "collapse_hinges": list(self.collapse_hinges),
             "thrust_rest": self.thrust_rest, "thrust_start": self.thrust_start,
             "opening_displacement": self.opening_displacement, "hinges": list(self.hinges),
             "hinge_changes": [[dd, list(h)] for dd, h in self.hinge_changes],
             "holds": [[dd, moved] for dd, moved in self.holds],
             "ke_ratio": self.ke_ratio, "quasi_static": self.quasi_static,
             "simulated_seconds": self.simulated_seconds, "wall_seconds": self.wall_seconds,
             "engine": self.settings.to_dict(), "run": dict(self.run)}
        if samples:
            for name in ("displacement", "time", "thrust", "crown_drop", "kinetic",
                         "potential_drop", "force_left", "force_right"):
                d[name] = getattr(self, name).tolist()
        return d


class _Push:
    """The engine with its moving support(s), the measures of one state and its copies."""

    def __init__(self, arch, settings, movement, side, rate, open_gap, pivot_depth=0.0):
        moving = ("left", "right") if side == "both" else (side,)
        self.ca = ca = ContactArch(arch, settings, moving=moving)
        ca.settle()
        self.n = n = arch.n
        self.dt = ca.dt
        # unit motion of each support per unit of d (x right, y up)
        ul, ur = np.zeros(2), np.zeros(2)
        if movement == "settlement":
            if side in ("left", "both"):
                ul = np.array([0.0, -1.0])
            if side in ("right", "both"):
                ur = np.array([0.0, -1.0])
        else:
            s = 1.0 if movement == "spread" else -1.0
            f = 0.5 if side == "both" else 1.0
            if side in ("left", "both"):
                ul = np.array([-s * f, 0.0])
            if side in ("right", "both"):
                ur = np.array([s * f, 0.0])
        self.unit = (ul, ur)
        self.speed = rate * ca.size / ca.time_scale  # dd/dt [m/s]
        # a turning support: (counter-clockwise rad per m of d, foot) of each, and the fraction
        # of the speed it turns at now (1 pushing, 0 held, between while slowing down)
        self.turn = None
        self.fac = 0.0
        if movement == "rotate":
            from ..geometry.displaced import SupportMovement

            # 'both': each turns by half, as SupportMovement(side='both') does
            (tl, cl, _), (tr, cr, _) = SupportMovement(
                0.0, 0.0, side, 1.0 / ca.size, pivot_depth).rigid_motions(arch.joint_points)
            self.turn = ((tl, cl), (tr, cr))
            self.unit = (np.array([1.0, 0.0]) * (side != "right"),
                         np.array([1.0, 0.0]) * (side != "left"))  # which bodies move
        self.shapes = list(ca.abutment_shapes)
        # a joint is open when its open end has moved by open_gap x size
        self.rot_thr = open_gap * ca.size / ca.joint_lengths
        self.open_gap = open_gap * ca.size
        # the crown: the highest outline vertex, a material point of its voussoir(s)
        tops = [(float(np.max(np.asarray(arch.outline(i))[:, 1])), i) for i in range(n)]
        ytop = max(t for t, _ in tops)
        owners = [i for t, i in tops if t >= ytop - 1e-9 * ca.size]
        pts = np.asarray(arch.outline(owners[0]), float)
        self.crown0 = pts[int(np.argmax(pts[:, 1]))]
        self.crown_owners = owners
        self.m_tot = float(ca.masses.sum())
        self.force = np.zeros((2, 2))  # running sum of forces on (left, right) supports
        self.steps_in_window = 0
        self.sim_steps = 0

    # --------------------------------------------------------------- state
    def copy(self) -> "_Push":
        """A copy whose engine state can run on independently (the arch's geometry shared)."""
        ca = self.ca
        new = copy.copy(self)
        nca = copy.copy(ca)
        space, bodies, abodies, ashapes = copy.deepcopy(
            (ca.space, ca.bodies, ca.abutment_bodies, ca.abutment_shapes))
        nca.space, nca.bodies = space, bodies
        nca.abutment_bodies, nca.abutment_shapes = abodies, ashapes
        new.ca, new.shapes = nca, list(ashapes)
        new.force = np.zeros((2, 2))
        new.steps_in_window = 0
        return new

    def _drive(self) -> None:
        """Velocities of turning supports for the next step: each kinematic body (at the
        origin at rest, its vertices world points) goes to c - R(angle + w dt) c, so that it
        turns about its foot c exactly (no drift off the circle)."""
        for body, (rate, c) in zip(self.ca.abutment_bodies, self.turn):
            if body.body_type == body.STATIC:
                continue
            w = rate * self.speed * self.fac
            a = body.angle + w * self.dt
            target = c - np.array([[math.cos(a), -math.sin(a)], [math.sin(a), math.cos(a)]]) @ c
            body.angular_velocity = float(w)
            body.velocity = tuple(float(v) for v in (target - np.array(tuple(body.position)))
                                  / self.dt)

    def set_moving(self, moving: bool) -> None:
        if self.turn is not None:
            self.fac = 1.0 if moving else 0.0
            if not moving:
                for body in self.ca.abutment_bodies:
                    if body.body_type != body.STATIC:
                        body.velocity, body.angular_velocity = (0.0, 0.0), 0.0
            return
        v = self.speed if moving else 0.0
        for body, u in zip(self.ca.abutment_bodies, self.unit):
            if body.body_type != body.STATIC:
                body.velocity = (float(u[0] * v), float(u[1] * v))

    def displacement(self) -> float:
        """d [m] from the moving supports' positions (kinematic bodies start at the origin):
        the mean over them of position . u / |u|^2; turning supports: their outward turn x
        the size."""
        if self.turn is not None:
            out = [abs(b.angle / rate) for b, (rate, _) in zip(self.ca.abutment_bodies,
                                                                self.turn)
                   if b.body_type != b.STATIC]
            return float(np.mean(out))
        out = [float(np.array(tuple(b.position)) @ u / (u @ u))
               for b, u in zip(self.ca.abutment_bodies, self.unit) if b.body_type != b.STATIC]
        return float(np.mean(out))

    def support_offsets(self) -> tuple[np.ndarray, np.ndarray]:
        """The displacement [m] of each support: of its springing joint's two ends, (2, 2),
        when it turns."""
        bl, br = self.ca.abutment_bodies
        if self.turn is not None:
            pts = np.asarray(self.ca.arch.joint_points, float)
            out = []
            for b, ends in ((bl, pts[0]), (br, pts[-1])):
                a, p = b.angle, np.array(tuple(b.position))
                rot = np.array([[math.cos(a), -math.sin(a)], [math.sin(a), math.cos(a)]])
                out.append(ends @ rot.T + p - ends)
            return tuple(out)
        return tuple(np.zeros(2) if b.body_type == b.STATIC else np.array(tuple(b.position))
                     for b in (bl, br))

    def _support_forces(self) -> np.ndarray:
        """(2, 2): the force [N/m] the arch exerts on the left and right support this step."""
        ca = self.ca
        out = np.zeros((2, 2))
        for k, body in ((0, ca.bodies[0]), (1, ca.bodies[-1])):
            shape = self.shapes[k]

            def add(arb, k=k, shape=shape):
                a, b = arb.shapes
                if shape is a or shape is b:
                    # total_impulse is the impulse on the body iterated; the support gets minus it
                    j = arb.total_impulse
                    out[k, 0] -= j[0]
                    out[k, 1] -= j[1]

            body.each_arbiter(add)
        return out / self.dt

    def step(self, steps: int) -> None:
        space, dt = self.ca.space, self.dt
        for _ in range(steps):
            if self.turn is not None:
                self._drive()
            space.step(dt)
            self.force += self._support_forces()
        self.steps_in_window += steps
        self.sim_steps += steps

    def window_force(self) -> np.ndarray:
        f = self.force / max(1, self.steps_in_window)
        self.force = np.zeros((2, 2))
        self.steps_in_window = 0
        return f

    def measure(self):
        """(relative joint rotations (n+1,), voussoir rotations (n,), kinetic energy, potential
        energy given up, crown drop) of the current state."""
        ca = self.ca
        pos, ang, vel, rate = ca.state()
        rel = ang - ca.ref_ang
        jrot = ca.joint_rotations(ang) - ca.joint_rotations(ca.ref_ang)
        ke = ca.kinetic_energy(vel, rate)
        pe = float(G * np.dot(ca.masses, ca.ref_pos[:, 1] - pos[:, 1]))
        c0 = ca.centroids0
        drops = []
        for v in self.crown_owners:
            r = self.crown0 - c0[v]
            c, s = math.cos(ang[v]), math.sin(ang[v])
            drops.append(self.crown0[1] - (pos[v, 1] + s * r[0] + c * r[1]))
        return jrot, rel, ke, pe, float(np.mean(drops))

    def labels(self, jrot: np.ndarray, base: np.ndarray | None = None) -> tuple[str, ...]:
        """Labels of the joints open in ``jrot`` (relative to ``base`` if given)."""
        ca = self.ca
        r = jrot if base is None else jrot - base
        open_j = np.flatnonzero(np.abs(r) >= self.rot_thr)
        if not len(open_j):
            return ()
        pos, ang, _, _ = ca.state()
        off = ca._end_offsets(pos, ang)
        ul, ur = self.support_offsets()
        off[0] -= ul  # the left side of joint 0 is the left support, moved by ul
        off[-1] += ur  # the right side of joint n is the right support, moved by ur
        gaps = np.hypot(off[:, :, 0], off[:, :, 1])
        out = []
        for j in open_j:
            g = gaps[j]
            if g.min() > self.open_gap:
                out.append(f"{j}s")
            else:
                out.append(f"{j}{'ie'[int(np.argmin(g))]}")
        return tuple(out)

    def hold(self, stop_steps: int, hold_steps: int, check: int, max_rotation: float,
             ke_lim: float):
        """Stop the support(s), slowing down linearly over ``stop_steps`` (an abrupt stop
        would shake the arch by several open thresholds near its capacity), and run on for
        ``hold_steps``: (moved, labels of the joints open when the arch started moving after
        the stop: the collapse mechanism as it starts).  Moved: the arch
        runs away (kinetic energy past ``ke_lim``, a voussoir past ``max_rotation``) or its
        joints still turn by their open threshold over the hold's second half."""
        ca = self.ca
        base, _, _, _, _ = self.measure()
        moving = [(b, u) for b, u in zip(ca.abutment_bodies, self.unit)
                  if b.body_type != b.STATIC]
        for i in range(stop_steps):
            f = self.speed * (1.0 - (i + 0.5) / stop_steps)
            if self.turn is not None:
                self.fac = f / self.speed
            else:
                for b, u in moving:
                    b.velocity = (float(u[0] * f), float(u[1] * f))
            self.step(1)
        self.set_moving(False)
        half = onset = None
        done = 0
        start = jrot = self.measure()[0]
        while done < hold_steps:
            k = min(check, hold_steps - done)
            self.step(k)
            done += k
            jrot, rel, ke, _, _ = self.measure()
            if onset is None and np.any(np.abs(jrot - start) >= 4.0 * self.rot_thr):
                # the mechanism as it starts: the joints past their threshold once the
                # fastest has turned by four (as the first opening of the push)
                onset = self.labels(jrot, start)
            if np.abs(rel).max() > max_rotation or ke > ke_lim:
                return True, onset or self.labels(jrot, base)
            if half is None and done >= hold_steps // 2:
                half = jrot
        if half is not None and np.any(np.abs(jrot - half) >= self.rot_thr):
            return True, onset or self.labels(jrot, base)
        return False, ()


def _push_params(arch, movement, side, settings, *, rate, max_displacement, sample, open_gap,
                 hold, stop, tol, ke_factor, max_rotation, max_time, pivot_depth):
    """Check push_support's input, in its order: (movement, side, settings, checked values)."""
    if not isinstance(arch, VoussoirArch):
        raise ArchInputError(f"arch: expected a VoussoirArch, got {type(arch).__name__}")
    movement, side = check_support_movement(movement, side)
    settings = settings or EngineSettings()
    if not isinstance(settings, EngineSettings):
        raise ArchInputError(f"settings: expected EngineSettings, got {type(settings).__name__}")
    size = float(arch.size)
    p = {"size": size}
    p["rate"] = _num("rate", rate, 1e-5, 0.5, "1e-5 <= rate <= 0.5 (sizes per T)")
    if max_displacement is None:
        max_displacement = 0.5 * size
    p["max_displacement"] = max_displacement = _num(
        "max_displacement", max_displacement, 1e-6 * size, 2.0 * size,
        f"{1e-6 * size:g} m <= max_displacement <= 2 x size = {2 * size:g} m")
    p["sample"] = _num("sample", sample, 1e-5, 0.05,
                       "1e-5 <= sample <= 0.05 (fraction of the size)")
    p["open_gap"] = _num("open_gap", open_gap, 1e-7, 1e-2,
                         "1e-7 <= open_gap <= 1e-2 (fraction of the size)")
    p["hold"] = _num("hold", hold, 0.1, 100.0, "0.1 <= hold <= 100 (T)")
    p["stop"] = _num("stop", stop, 0.0, 100.0, "0 <= stop <= 100 (T)")
    p["tol"] = _num("tol", tol, 1e-4, 0.5)
    p["ke_factor"] = _num("ke_factor", ke_factor, 1.5, 1e6)
    p["max_rotation"] = _num("max_rotation", max_rotation, 1e-3, math.pi,
                             "1e-3 <= max_rotation <= pi (rad)")
    p["max_time"] = max_time = _num("max_time", max_time, 1.0, 1e6, "1 <= max_time <= 1e6 (T)")
    push_T = max_displacement / (p["rate"] * size)
    if push_T > max_time:
        raise ArchInputError(
            f"max_displacement / rate: the push would take {push_T:.4g} T of simulated time; "
            f"allowed at most max_time = {max_time:g} T (raise rate or max_time, or lower "
            f"max_displacement)")
    if p["sample"] * size > max_displacement:
        raise ArchInputError(f"sample: {p['sample']:g} x size = {p['sample'] * size:g} m; "
                             f"allowed at most max_displacement = {max_displacement:g} m")
    p["pivot_depth"] = _num("pivot_depth", pivot_depth, 0.0, 1e4, "0 <= pivot_depth <= 1e4 m")
    return movement, side, settings, p


class _PushRun:
    """One push_support run: the live push, its record, its holds and its collapse."""

    def __init__(self, arch, settings, movement, side, p, progress):
        self.settings, self.movement, self.side, self.p = settings, movement, side, p
        self.live = live = _Push(arch, settings, movement, side, p["rate"], p["open_gap"],
                                 p["pivot_depth"])
        self.v, self.dt = v, dt = live.speed, live.dt
        self.window = max(1, int(round(p["sample"] * p["size"] / (v * dt))))
        self.hold_steps = int(math.ceil(p["hold"] * settings.steps_per_T))
        self.stop_steps = max(1, int(math.ceil(p["stop"] * settings.steps_per_T)))
        self.check = max(1, int(settings.steps_per_T // 100))
        self.ke_lim = p["ke_factor"] * (0.5 * live.m_tot * v * v)
        self.say = progress or (lambda msg: None)
        self.rec = {k: [] for k in ("d", "t", "fl", "fr", "jrot", "ke", "pe", "crown")}
        self.extra_steps = 0  # steps run on copies (holds, bisection)
        self.holds: list[tuple[float, bool]] = []
        self.changes: list[tuple[float, tuple[str, ...]]] = []
        self.last_labels: tuple[str, ...] = ()
        self.opening = self.first_d = None
        self.hinges: tuple[str, ...] = ()
        self.status, self.collapse_by, self.trigger = "standing", None, None
        self.collapse_hinges: tuple[str, ...] = ()

    def record(self, d):
        """Record one sample at displacement d [m]: (joint rotations, relative ones, KE)."""
        f = self.live.window_force()
        jrot, rel, ke, pe, crown = self.live.measure()
        for key, value in (("d", d), ("t", self.live.sim_steps * self.dt), ("fl", f[0]),
                           ("fr", f[1]), ("jrot", jrot), ("ke", ke), ("pe", pe),
                           ("crown", crown)):
            self.rec[key].append(value)
        return jrot, rel, ke

    def held(self, state):
        """Hold a copy of ``state``: (displacement where it is held, moved, labels)."""
        st = state.copy()
        moved, labels = st.hold(self.stop_steps, self.hold_steps, self.check,
                                self.p["max_rotation"], self.ke_lim)
        self.extra_steps += st.sim_steps - state.sim_steps
        d = st.displacement()
        self.holds.append((d, moved))
        self.say(f"hold at d = {d:.5g} m: {'moves' if moved else 'rests'}")
        return d, moved, labels

    def track_hinges(self, d, jrot):
        """Note the open joints' labels at d: a change, the first opening, the first hinges."""
        ratio = np.abs(jrot) / self.live.rot_thr
        labels = self.live.labels(jrot)
        if labels != self.last_labels:
            self.changes.append((d, labels))
            self.last_labels = labels
        if self.opening is None and ratio.max() >= 1.0:
            self.opening = d
        if self.first_d is None and ratio.max() >= 4.0:
            self.first_d, self.hinges = d, labels
            self.say(f"first opening at d = {d:.5g} m: {'-'.join(self.hinges)}")
        return labels

    def collapse(self, by, trigger, labels):
        self.status, self.collapse_by, self.trigger = "collapsed", by, trigger
        self.collapse_hinges = labels

    def push(self):
        """Settle the arch, then push until it collapses or reaches max_displacement."""
        live, p = self.live, self.p
        live.step(self.window)  # the settled arch at rest: one window of forces before the push
        self.record(0.0)
        start = live.copy()
        live.set_moving(True)
        self.checkpoints = [(0.0, start)]
        armed, k = True, 0
        while True:
            live.step(self.window)
            k += 1
            d = live.displacement()
            jrot, rel, ke = self.record(d)
            labels = self.track_hinges(d, jrot)
            if np.abs(rel).max() > p["max_rotation"]:
                self.collapse("rotation", d, labels)
                break
            if ke > self.ke_lim and armed:
                d_held, moved, labels = self.held(live)
                if moved:
                    self.collapse("hold", d_held, labels)
                    break
                armed = False  # a snap between mechanisms: push on, re-arm once it has calmed
            elif ke <= self.ke_lim:
                armed = True
            if k % CHECKPOINT_EVERY == 0:
                self.checkpoints.append((d, live.copy()))
            if d >= p["max_displacement"] - 0.5 * self.v * self.dt:
                break

    def bracket(self):
        """The capacity's bracket (lo, hi) [m], None while the arch stands."""
        if self.status == "collapsed" and self.collapse_by == "rotation":
            prev = self.rec["d"][-2] if len(self.rec["d"]) > 1 else 0.0
            return (float(prev), float(self.trigger))
        if self.status == "collapsed":
            lo, hi, lo_state = self.bisect_checkpoints(float(self.trigger))
            return self.refine(lo, hi, lo_state)
        return None

    def bisect_checkpoints(self, hi):
        """Bisect the checkpoints before hi [m] by holding them: (lo, hi, lo's state).

        In held displacements: lo rests when held, hi moves on (the push itself runs on past
        the capacity, as the unstable motion grows from nothing while the support keeps moving)."""
        cks = [(dc, st) for dc, st in self.checkpoints if dc < hi]
        i_lo, i_hi, lo = 0, len(cks), None
        while i_hi - i_lo > 1:
            i_mid = (i_lo + i_hi) // 2
            d_held, moved, labels = self.held(cks[i_mid][1])
            if moved:
                i_hi, hi, self.collapse_hinges = i_mid, min(hi, d_held), labels
            else:
                i_lo, lo = i_mid, d_held
        lo_state = cks[i_lo][1]
        if lo is None:  # the settled arch itself: does it stand when held?
            d_held, moved, labels = self.held(lo_state)
            if moved:
                raise CannotStandError("arch: it does not stand in the contact engine with its "
                                       "supports held at rest (a held copy of the settled arch "
                                       "moves on)")
            lo = d_held
        return lo, hi, lo_state

    def refine(self, lo, hi, lo_state):
        """Narrow (lo, hi) [m] to the relative width tol with copies pushed on from lo."""
        step_d = self.v * self.dt
        for _ in range(64):
            if hi - lo <= self.p["tol"] * hi:
                break
            mid = 0.5 * (lo + hi)
            steps = int(round((mid - lo) / step_d))
            if steps < 1:  # the step grid cannot split the bracket further
                break
            st = lo_state.copy()
            st.set_moving(True)
            st.step(steps)
            self.extra_steps += steps
            d_held, moved, labels = self.held(st)
            if moved:
                hi, self.collapse_hinges = d_held, labels
            else:
                lo, lo_state = d_held, st
        return (float(lo), float(hi))

    def thrust(self, fl, fr):
        """The thrust H [N/m] on the moving support(s), > 0 pushing it outward."""
        if self.side == "right":
            return fr[:, 0]
        if self.side == "left":
            return -fl[:, 0]
        return 0.5 * (fr[:, 0] - fl[:, 0])

    def thrust_start(self, d_arr, thrust, upto):
        """The thrust at the start: a line through H(d) after the first opening, at d = 0."""
        if self.first_d is None:
            return None
        sel = (d_arr > self.first_d) & (d_arr <= min(self.first_d + FIT_SPAN * self.p["size"],
                                                     upto))
        if sel.sum() < 3:
            return None
        slope, icpt = np.polyfit(d_arr[sel], thrust[sel], 1)
        return float(icpt)

    def run_record(self):
        """The run's parameters, as PushResult.run keeps them."""
        p = self.p
        run = {"rate": p["rate"], "speed": self.v, "max_displacement": p["max_displacement"],
               "sample": p["sample"], "window_steps": self.window, "open_gap": p["open_gap"],
               "hold": p["hold"], "stop": p["stop"], "tol": p["tol"],
               "ke_factor": p["ke_factor"], "max_rotation": p["max_rotation"],
               "max_time": p["max_time"], "dt": self.dt, "size": p["size"],
               "time_scale": self.live.ca.time_scale, "ke_ratio_max": KE_RATIO_MAX,
               "ke_check_from": KE_CHECK_FROM, "fit_span": FIT_SPAN}
        if self.movement == "rotate":
            run.update({"pivot_depth": p["pivot_depth"], "displacement": "rotation x size [m]"})
        return run

    def result(self, bracket, t_wall):
        """The PushResult of this run, bracket [m] from :meth:`bracket`."""
        rec = self.rec
        capacity = None if bracket is None else float(0.5 * (bracket[0] + bracket[1]))
        d_arr = np.array(rec["d"])
        fl, fr = np.array(rec["fl"]).reshape(-1, 2), np.array(rec["fr"]).reshape(-1, 2)
        thrust = self.thrust(fl, fr)
        ke_arr, pe_arr = np.array(rec["ke"]), np.array(rec["pe"])
        upto = bracket[0] if bracket is not None else d_arr[-1]
        thrust_start = self.thrust_start(d_arr, thrust, upto)
        # quasi-static check: KE / |dPE| past KE_CHECK_FROM x size, before the collapse bracket
        sel = (d_arr >= KE_CHECK_FROM * self.p["size"]) & (d_arr <= upto) & (np.abs(pe_arr) > 0)
        ke_ratio = float(np.max(ke_arr[sel] / np.abs(pe_arr[sel]))) if sel.any() else None
        quasi = None if ke_ratio is None else bool(ke_ratio <= KE_RATIO_MAX)
        sim_seconds = (self.live.sim_steps + self.extra_steps) * self.dt
        return PushResult(self.movement, self.side, d_arr, np.array(rec["t"]), fl, fr, thrust,
                          np.array(rec["crown"]), np.array(rec["jrot"]), ke_arr, pe_arr,
                          float(thrust[0]), thrust_start, self.opening, tuple(self.hinges),
                          tuple(self.changes), self.status, capacity, bracket,
                          self.collapse_by, tuple(self.collapse_hinges), tuple(self.holds),
                          ke_ratio, quasi, float(sim_seconds), _time.perf_counter() - t_wall,
                          self.settings, self.run_record())


def push_support(arch: VoussoirArch, movement: str = "spread", side: str = "right",
                 settings: EngineSettings | None = None, *, rate: float = 0.005,
                 max_displacement: float | None = None, sample: float = 1e-3,
                 open_gap: float = 1e-4, hold: float = 4.0, stop: float = 8.0,
                 tol: float = 0.01, ke_factor: float = 10.0, max_rotation: float = 0.5,
                 max_time: float = 2e4, progress=None, pivot_depth: float = 0.0) -> PushResult:
    """Push ``side``'s support(s) of ``arch`` slowly in the contact engine (module docstring).

    movement: 'spread', 'settlement' or 'close'; side: 'right', 'left' or 'both'; rate: the
    support's speed in sizes per T (dd/dt = rate sqrt(g size)); max_displacement [m]: the push
    stops there (default half the size); sample: displacement between samples, a fraction of the
    size; open_gap: a joint is open when its open end has moved by this fraction of the size;
    hold [T]: how long a held support waits for the arch to move, after slowing down to a stop
    over ``stop`` [T] (docs/supports-engine.md: the capacity rises towards its limit as the
    stop's deceleration (rate / stop) g falls); tol: relative width of the capacity's bracket;
    ke_factor: the arch is suspected to run away when its kinetic energy
    exceeds ke_factor x 1/2 M v^2; max_rotation [rad]: a voussoir turned further has collapsed;
    max_time [T]: the longest push allowed (max_displacement / speed must fit in it);
    pivot_depth [m]: with movement 'rotate', how far below the springing's outer end the
    support's foot is (module docstring; d, the capacity and its bracket are then the rotation
    times the size, in m: divide by ``run['size']`` for rad)."""
    t_wall = _time.perf_counter()
    movement, side, settings, p = _push_params(
        arch, movement, side, settings, rate=rate, max_displacement=max_displacement,
        sample=sample, open_gap=open_gap, hold=hold, stop=stop, tol=tol, ke_factor=ke_factor,
        max_rotation=max_rotation, max_time=max_time, pivot_depth=pivot_depth)
    run = _PushRun(arch, settings, movement, side, p, progress)
    run.push()
    return run.result(run.bracket(), t_wall)

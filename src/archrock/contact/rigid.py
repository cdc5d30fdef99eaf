"""archrock's rigid-block engine as an object: a :class:`~.blocksystem.BlockSystem` and its
state, stepped by :func:`~.nscd.advance` (Moreau-Jean, each step's contact problem solved
exactly).

:class:`RigidBlocks` holds the state and steps it (a response compiled whole,
:meth:`RigidBlocks.run_response`); :class:`RigidArch` and :class:`RigidArcade` read it as the
engine's studies read a structure (joint rotations, sliding, the ends' gaps), with the same
methods as the pymunk engine (:class:`~.engine.ContactArch`,
:class:`~.pymunkarcade.ContactArcade`) so that the ramp, the response and the arcade's studies run on
either."""

from __future__ import annotations

import math

import numpy as np

from ..units import G
from .blocksystem import BlockSystem, blocks_of_arcade, blocks_of_arch
from .nscd import SOLVER_FIELDS, advance, end_offsets, run_response
from .settings import EngineSettings, engine_scales

__all__ = ["RigidBlocks", "RigidArch", "RigidArcade", "engine_arch", "engine_arcade",
           "require_engine"]

#: a corner bears on its face up to this fraction of the face's length past its ends
MARGIN = 0.05
#: a corner contact is kept while its gap is below this fraction of the longest face's length
REACH = 0.25
#: the fraction of a penetration removed per step
BETA = 0.2


class RigidBlocks:
    """A block system at rest, stepped by the Moreau-Jean scheme.

    ``time_scale`` T = sqrt(size/g) [s]; ``dt`` = T / steps_per_T [s]; positions are the mass
    centres [m] and the rotations from rest [rad]."""

    def __init__(self, system: BlockSystem, settings: EngineSettings | None = None):
        self.system = s = system
        self.settings = settings = settings or EngineSettings()
        self.scales = sc = engine_scales(s, settings)
        self.size, self.time_scale, self.dt = sc.size, sc.time_scale, sc.dt
        self.masses = s.masses
        self.inertias = s.inertias
        self.centroids0 = s.centroids
        nb = s.n_bodies
        self.q = np.zeros((nb, 3))
        self.q[:, :2] = s.centroids
        self.v = np.zeros((nb, 3))
        self.impulse = np.zeros((s.n_contacts, 2))
        self.stats = np.zeros(4, np.int64)
        self.time = 0.0
        self.steps = 0
        # the reach is a fraction of the longest face (the margin, of each face's own length)
        self._reach = REACH * float(np.max(s.length)) if s.n_contacts else 0.0
        self.ref_pos = self.q[:, :2].copy()
        self.ref_ang = np.zeros(nb)
        self.ref_slide = np.zeros(s.joints)

    # ------------------------------------------------------------------ stepping
    def advance(self, accel) -> None:
        """One step per entry of ``accel`` [m/s^2], the ground's horizontal acceleration."""
        a = np.ascontiguousarray(accel, float).reshape(-1)
        if not a.size:
            return
        s, st = self.system, self.settings
        advance(self.q, self.v, self.impulse, a, self.dt, G, st.friction, st.restitution,
                st.tolerance, st.max_rounds, BETA, MARGIN, self._reach, s.masses, s.inertias,
                s.centroids, s.owner, s.face, s.corner, s.face_start, s.tangent, s.normal,
                s.length, self.stats)
        self.steps += a.size
        self.time = self.steps * self.dt

    def run_response(self, accel, stop, t_motion_end, every, samples, carry, drop_limit,
                     ke_rest, quiet_needed) -> int:
        """:func:`~.nscd.run_response` from the current step to ``stop`` (compiled: the
        checks of collapse and rest at every step, the samples every ``every`` steps).
        Returns its status (0 going on, 1 rest, 2 collapsed, 3 end of ``accel``)."""
        s, st = self.system, self.settings
        status, step = run_response(
            self.q, self.v, self.impulse, accel, self.steps, int(stop), float(t_motion_end),
            int(every), samples, carry, float(drop_limit), float(ke_rest), int(quiet_needed),
            self.dt, G, st.friction, st.restitution, st.tolerance, st.max_rounds, BETA, MARGIN,
            self._reach, s.masses, s.inertias, s.centroids, s.owner, s.face, s.corner,
            s.face_start, s.tangent, s.normal, s.length, self.stats)
        self.steps = int(step)
        self.time = self.steps * self.dt
        return int(status)

    def respond_samples(self, motion, every, n_out, t_most, drop_limit, ke_rest, quiet_needed,
                        progress=None):
        """A whole response to ``motion`` (a GroundMotion) up to ``t_most`` [s], in compiled
        chunks of a tenth of it (``progress(engine)`` after each), every step checked for
        collapse and rest (:meth:`run_response`).  Returns (status 'collapsed', 'rest' or
        'moving', t_collapse [s] or None, samples (n_out, nb, 3) of (x, y, rotation) every
        ``every`` steps, NaN past the last, the number taken)."""
        n_total = int(math.ceil(t_most / self.dt)) + 1
        accel = np.ascontiguousarray(motion((np.arange(n_total) + 0.5) * self.dt), float)
        samples = np.full((n_out, self.system.n_bodies, 3), np.nan)
        carry = np.zeros(3, np.int64)
        chunk = max(1, n_total // 10)
        while True:
            code = self.run_response(accel, self.steps + chunk, float(motion.times[-1]), every,
                                     samples, carry, drop_limit, ke_rest, quiet_needed)
            if code != 0:
                break
            if progress:
                progress(self)
        if code == 2:
            return "collapsed", self.time, samples, int(carry[0])
        status = "rest" if carry[2] and carry[1] >= quiet_needed else "moving"
        return status, None, samples, int(carry[0])

    def step(self, ground_accel: float = 0.0, steps: int = 1) -> None:
        """Advance ``steps`` time steps under the constant ground acceleration [m/s^2]."""
        self.advance(np.full(int(steps), float(ground_accel)))

    def settle(self, duration: float = 0.0) -> None:
        """The exact contacts need no settling: the state now is the reference of every
        rotation, slip and drop, and the clock restarts (kept for the studies written for the
        pymunk engine)."""
        self.ref_pos = self.q[:, :2].copy()
        self.ref_ang = self.q[:, 2].copy()
        self.ref_slide = self._sliding(self.ref_pos, self.ref_ang)
        self.steps, self.time = 0, 0.0

    def at_rest(self) -> bool:
        """Whether every block is still to 1e-9 g dt [m/s] (and its rate times the size): under
        a constant load the exact contacts then keep it still for good -- the next step is the
        same problem with the same answer -- so a hold from rest can stop there.  Above the
        activation the first steps already move it by about (excess) g dt."""
        lim = 1e-9 * G * self.dt
        return bool(np.abs(self.v[:, :2]).max() <= lim
                    and np.abs(self.v[:, 2]).max() * self.size <= lim)

    def solver_stats(self) -> dict:
        """The solver's counters since the engine was built: steps, QP iterations, steps left
        unconverged at max_rounds, the most iterations in one step, and their mean."""
        d = dict(zip(SOLVER_FIELDS, (int(x) for x in self.stats)))
        d["mean_iterations"] = d["qp_iterations"] / d["steps"] if d["steps"] else 0.0
        return d

    # ------------------------------------------------------------------ state
    def state(self):
        """(centroids (nb, 2) [m], rotations (nb,) [rad], velocities (nb, 2) [m/s],
        rates (nb,) [rad/s])."""
        return (self.q[:, :2].copy(), self.q[:, 2].copy(), self.v[:, :2].copy(),
                self.v[:, 2].copy())

    def _q_of(self, pos, angles):
        q = np.empty((self.system.n_bodies, 3))
        q[:, :2] = pos
        q[:, 2] = angles
        return q

    def _end_offsets(self, pos, angles) -> np.ndarray:
        """(joints, 2, 2): the b side's copy minus the a side's copy of each joint's end 0 and
        end 1 [m]."""
        s = self.system
        return end_offsets(self._q_of(pos, angles), s.owner, s.corner, s.joint, s.end,
                           s.joints, s.centroids)

    def _sides(self):
        """(a, b) of every joint: each joint's first row is b's corner on a's face."""
        return self.system.face[::4], self.system.owner[::4]

    def _rel_rotations(self, angles) -> np.ndarray:
        a, b = self._sides()
        th = np.asarray(angles, float)
        ta = np.where(a >= 0, th[np.maximum(a, 0)], 0.0)
        tb = np.where(b >= 0, th[np.maximum(b, 0)], 0.0)
        return tb - ta

    def end_gaps(self, pos, angles) -> np.ndarray:
        """(joints, 2) distance [m] between the two sides' copies of each joint's ends."""
        d = self._end_offsets(pos, angles)
        return np.hypot(d[:, :, 0], d[:, :, 1])

    def _sliding(self, pos, angles) -> np.ndarray:
        """Slip [m] at each joint: the relative displacement (b side minus a side) of the end
        closer to closed, along the joint as turned by the mean rotation of its sides."""
        s = self.system
        d = self._end_offsets(pos, angles)
        a, b = self._sides()
        th = np.asarray(angles, float)
        ta = np.where(a >= 0, th[np.maximum(a, 0)], 0.0)
        tb = np.where(b >= 0, th[np.maximum(b, 0)], 0.0)
        mean = 0.5 * (ta + tb)
        t0 = s.tangent[::4]
        # the tangent of a's face, oriented from end 0 to end 1 of the joint
        tx = np.cos(mean) * t0[:, 0] - np.sin(mean) * t0[:, 1]
        ty = np.sin(mean) * t0[:, 0] + np.cos(mean) * t0[:, 1]
        gap = np.hypot(d[:, :, 0], d[:, :, 1])
        end = np.argmin(gap, axis=1)
        dd = d[np.arange(s.joints), end]
        return dd[:, 0] * tx + dd[:, 1] * ty


class RigidArch(RigidBlocks):
    """An arch (any :class:`~archrock.geometry.VoussoirArch`) in archrock's engine, read as
    :class:`~.engine.ContactArch` reads one: joint j between voussoirs j-1 and j."""

    def __init__(self, arch, settings: EngineSettings | None = None):
        super().__init__(blocks_of_arch(arch), settings)
        self.arch = arch
        pts = np.asarray(arch.joint_points, float)
        self.joint_points = pts
        tan = pts[:, 1] - pts[:, 0]
        ln = np.hypot(tan[:, 0], tan[:, 1])
        self.joint_lengths = ln

    def joint_rotations(self, angles) -> np.ndarray:
        """Relative rotation theta_j - theta_{j-1} at each joint 0..n [rad]."""
        return self._rel_rotations(angles)

    def joint_sliding(self, pos, angles) -> np.ndarray:
        return self._sliding(pos, angles)


class RigidArcade(RigidBlocks):
    """An :class:`~archrock.geometry.arcade.Arcade` in archrock's engine, read as
    :class:`~.pymunkarcade.ContactArcade` reads one."""

    def __init__(self, arc, settings: EngineSettings | None = None):
        super().__init__(blocks_of_arcade(arc), settings)
        self.arcade = arc
        pts = np.array([np.asarray(ct.points, float) for ct in arc.contacts])
        self.contact_points = pts
        self.contact_lengths = np.hypot(*(pts[:, 1] - pts[:, 0]).T)

    def contact_rotations(self, angles) -> np.ndarray:
        return self._rel_rotations(angles)

    def contact_sliding(self, pos, angles) -> np.ndarray:
        return self._sliding(pos, angles)


def engine_arch(arch, settings: EngineSettings | None = None):
    """The arch in the engine that ``settings.engine`` names: archrock's own
    (:class:`RigidArch`, the default) or pymunk's (:class:`~.engine.ContactArch`)."""
    settings = settings or EngineSettings()
    if settings.engine == "pymunk":
        from .engine import ContactArch

        return ContactArch(arch, settings)
    return RigidArch(arch, settings)


def engine_arcade(arc, settings: EngineSettings | None = None):
    """The arcade in the engine that ``settings.engine`` names (:func:`engine_arch`)."""
    settings = settings or EngineSettings()
    if settings.engine == "pymunk":
        from .pymunkarcade import ContactArcade

        return ContactArcade(arc, settings)
    from ..errors import ArchInputError
    from ..geometry.arcade import Arcade

    if not isinstance(arc, Arcade):
        raise ArchInputError(f"arcade: expected an Arcade, got {type(arc).__name__}")
    return RigidArcade(arc, settings)


def require_engine(settings: EngineSettings | None = None) -> None:
    """Raise ImportError (naming the extra) where ``settings`` name the pymunk engine and pymunk
    is not installed; archrock's own engine needs nothing beyond numpy."""
    if (settings or EngineSettings()).engine == "pymunk":
        from .engine import import_pymunk

        import_pymunk()

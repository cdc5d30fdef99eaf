"""An arch as rigid voussoirs in a 2-D rigid-body contact engine (pymunk, i.e. Chipmunk2D).

Each voussoir is one dynamic body whose mass, mass centre and moment of inertia are set to the
arch's exact values (``VoussoirArch.masses``, ``centroids``, ``inertias``: loads included, as
in the four-link model); its outline, cut into convex pieces (:mod:`.convex`), gives the
contact shapes, which carry no mass of their own.  The abutments are static blocks whose faces
are the springing joints.

Ground motion enters as a body force: the engine works in the frame of the ground, which
translates rigidly with acceleration xg''(t), so every body feels gravity plus -m xg''(t),
i.e. the gravity vector (-xg''(t), -g).  For rigid bodies this is exact (the fictitious force
of a translating frame is uniform and acts at the mass centre), and it keeps the abutments
static, so that no contact is solved against a moving body and no drift of the driven ground
enters the relative motion.

Contacts: Chipmunk combines the friction of two shapes by multiplying them (and likewise the
elasticity), so every shape, abutments included, gets sqrt(MU) (and sqrt(e)): every contact,
voussoir-voussoir or voussoir-abutment, then has exactly MU (and e).

Angles: counter-clockwise positive [rad]; joint j (0 = left springing, n = right springing)
opens by the relative rotation theta_j - theta_{j-1} of its two sides (an abutment does not
rotate).
"""

from __future__ import annotations

import math

import numpy as np

from ..errors import ArchInputError
from ..geometry import VoussoirArch
from ..units import G
from .convex import convex_pieces, inset, simplify_outline, strip_pieces
from .settings import EngineSettings, engine_scales

__all__ = ["ContactArch", "PymunkBlocks", "import_pymunk"]


def import_pymunk():
    """pymunk, or an ImportError naming the extra to install."""
    try:
        import pymunk
    except ImportError:
        raise ImportError('the contact engine (archrock dem / verify) needs pymunk: '
                          'pip install "archrock[dem]"') from None
    return pymunk


def settle_blocks(blocks, duration: float, sliding) -> None:
    """Step ``blocks`` (a ContactArch or ContactArcade) under gravity alone for ``duration`` T,
    stop every body and restart the clock; the settled positions, angles and ``sliding(pos,
    angles)`` become the reference of every rotation, slip and drop reported."""
    blocks.step(0.0, max(1, int(round(duration * blocks.settings.steps_per_T))))
    for b in blocks.bodies:
        b.velocity = (0.0, 0.0)
        b.angular_velocity = 0.0
    pos, ang, _, _ = blocks.state()
    blocks.ref_pos, blocks.ref_ang = pos, ang
    blocks.ref_slide = sliding(pos, ang)
    blocks.steps, blocks.time = 0, 0.0


def add_block(pymunk, space, outline, ends, mass, inertia, centroid, sc, mu, e, r):
    """One rigid block in ``space``: a pymunk body of ``mass`` [kg/m] and ``inertia`` about its
    ``centroid``, its shapes the outline cut into convex pieces (simplified within
    ``sc.outline_tol`` keeping the contact ``ends``, else the fine exact cut), each inset by the
    rounding ``r`` where it can be, with friction ``mu`` and elasticity ``e`` (per shape: pymunk
    multiplies the two shapes' values).  Returns (body, the outline cut, its pieces)."""
    body = pymunk.Body(float(mass), float(inertia), pymunk.Body.DYNAMIC)
    body.position = (float(centroid[0]), float(centroid[1]))
    body.center_of_gravity = (0.0, 0.0)
    pieces = None
    if sc.outline_tol > 0:
        simple = simplify_outline(outline, sc.outline_tol, ends)
        try:
            pieces = strip_pieces(simple)
            outline = simple
        except ArchInputError:  # not simple any more: keep the fine cut
            pieces = None
    if pieces is None:
        pieces = convex_pieces(outline)
    shapes = []
    for pc in pieces:
        core = inset(pc, r)
        core, rad = (pc, 0.0) if core is None else (core, r)
        shape = pymunk.Poly(body, [(float(x - centroid[0]), float(y - centroid[1]))
                                   for x, y in core], radius=rad)
        shape.friction, shape.elasticity = mu, e
        shapes.append(shape)
    space.add(body, *shapes)
    # explicit values after the shapes: shapes without mass or density leave them alone
    body.mass = float(mass)
    body.moment = float(inertia)
    return body, outline, pieces


class PymunkBlocks:
    """What the pymunk models of an arch and of an arcade share: stepping under a ground
    acceleration, reading the bodies' state and their kinetic energy.  A subclass sets
    ``space``, ``dt``, ``bodies``, ``masses``, ``inertias``, ``steps`` and ``time``."""

    def step(self, ground_accel: float = 0.0, steps: int = 1) -> None:
        """Advance ``steps`` time steps under the horizontal ground acceleration
        ``ground_accel`` [m/s^2] (the body force -m xg'' of the ground's frame)."""
        self.space.gravity = (-float(ground_accel), -G)
        for _ in range(steps):
            self.space.step(self.dt)
        self.steps += steps
        self.time = self.steps * self.dt

    def state(self) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """(centroids (n, 2) [m], angles (n,) [rad], velocities (n, 2) [m/s], rates (n,) [rad/s])."""
        b = self.bodies
        pos = np.array([tuple(x.position) for x in b])
        ang = np.array([x.angle for x in b])
        vel = np.array([tuple(x.velocity) for x in b])
        rate = np.array([x.angular_velocity for x in b])
        return pos, ang, vel, rate

    def kinetic_energy(self, vel: np.ndarray, rate: np.ndarray) -> float:
        """Kinetic energy relative to the ground [J per m of depth]."""
        return float(0.5 * (self.masses * (vel ** 2).sum(axis=1)).sum()
                     + 0.5 * (self.inertias * rate ** 2).sum())


class ContactArch(PymunkBlocks):
    """One arch in a pymunk space, at rest in its initial configuration.

    ``time_scale`` T = sqrt(size/g) [s]; ``dt`` = T / steps_per_T [s]; :meth:`step` advances the
    engine with a given horizontal ground acceleration [m/s^2, positive toward +x]."""

    def __init__(self, arch: VoussoirArch, settings: EngineSettings | None = None, *,
                 moving: tuple[str, ...] = ()):
        """``moving``: the abutments ('left', 'right') built on a kinematic body of their own
        (at rest until its velocity is set: :mod:`.push`) instead of the static ground; the
        default () builds both on the ground, as always."""
        pymunk = import_pymunk()
        moving = tuple(moving)
        if not set(moving) <= {"left", "right"}:
            raise ArchInputError(f"moving: {moving!r}; allowed a tuple of 'left' and/or 'right'")
        self.arch = arch
        self.settings = settings = settings or EngineSettings()
        self.scales = sc = engine_scales(arch, settings)
        self.size = sc.size
        self.time_scale = sc.time_scale
        self.dt = sc.dt
        space = pymunk.Space()
        space.iterations = settings.iterations
        space.collision_slop = sc.slop
        space.collision_bias = (1.0 - settings.bias) ** (1.0 / self.dt) if settings.bias < 1 else 0.0
        space.gravity = (0.0, -G)
        space.damping = 1.0
        space.sleep_time_threshold = float("inf")
        self.space = space
        mu = math.sqrt(settings.friction)
        # Shapes are their pieces with corners rounded by r: cores inset by r, radius r.  Two
        # voussoirs' cores then never touch exactly, where Chipmunk's GJK contact is degenerate
        # (wrong normals, metre-deep false overlaps were seen on flush joints).
        r = sc.rounding
        e = math.sqrt(settings.restitution)
        self.masses = np.asarray(arch.masses, float)
        self.centroids0 = np.asarray(arch.centroids, float)
        self.inertias = np.asarray(arch.inertias, float)
        self.bodies = []
        self.pieces = []
        self.outlines = []
        jp = np.asarray(arch.joint_points, float)
        for i in range(arch.n):
            body, outline, pieces = add_block(
                pymunk, space, arch.outline(i), jp[[i, i + 1]].reshape(-1, 2),
                self.masses[i], self.inertias[i], self.centroids0[i], sc, mu, e, r)
            self.outlines.append(np.asarray(outline, float))
            self.pieces.append(pieces)
            self.bodies.append(body)
        pts = np.asarray(arch.joint_points, float)
        self.joint_points = pts
        self.abutment_outlines = []
        self.abutment_bodies = []
        self.abutment_shapes = []
        ground = space.static_body
        # a displaced arch's supports (archrock.geometry.DisplacedArch): their own faces, which
        # an open springing joint touches at one point
        faces = getattr(arch, "abutment_faces", None)
        for k, (j, side, name) in enumerate(((0, 0, "left"), (arch.n, arch.n - 1, "right"))):
            pi, pe = (pts[j, 0], pts[j, 1]) if faces is None else (faces[k, 0], faces[k, 1])
            t = pe - pi
            length = float(np.hypot(*t))
            nrm = np.array([-t[1], t[0]]) / length
            if np.dot(self.centroids0[side] - 0.5 * (pi + pe), nrm) > 0:
                nrm = -nrm  # away from the springing voussoir
            quad = np.array([pi, pe, pe + length * nrm, pi + length * nrm])
            self.abutment_outlines.append(quad)
            body = ground
            if name in moving:  # its own kinematic body at the origin: vertices stay world ones
                body = pymunk.Body(body_type=pymunk.Body.KINEMATIC)
                space.add(body)
            s = pymunk.Poly(body, [tuple(map(float, q)) for q in quad])
            s.friction, s.elasticity = mu, e
            space.add(s)
            self.abutment_bodies.append(body)
            self.abutment_shapes.append(s)
        # joint midpoints, lengths and tangents at rest (for sliding)
        mid = 0.5 * (pts[:, 0] + pts[:, 1])
        tan = pts[:, 1] - pts[:, 0]
        if np.any(np.hypot(tan[:, 0], tan[:, 1]) == 0.0):  # point contacts: their direction
            point = np.hypot(tan[:, 0], tan[:, 1]) == 0.0
            tan = np.where(point[:, None], np.asarray(arch.joint_directions, float), tan)
        self.joint_tangents = tan / np.hypot(tan[:, 0], tan[:, 1])[:, None]
        self.joint_lengths = np.hypot(*(pts[:, 1] - pts[:, 0]).T)
        self.joint_mid = mid
        self.time = 0.0
        self.steps = 0

    # ------------------------------------------------------------------ stepping
    def settle(self, duration: float = 0.5) -> None:
        """Let the arch settle under gravity for ``duration`` T (its rounded joints close by
        about 2 x rounding x size), then stop every body and restart the clock: the settled state
        is the reference of every rotation, sliding and drop reported."""
        settle_blocks(self, duration, self.joint_sliding)

    # ------------------------------------------------------------------ state
    def joint_rotations(self, angles: np.ndarray) -> np.ndarray:
        """Relative rotation theta_j - theta_{j-1} at each joint 0..n [rad]."""
        th = np.concatenate([[0.0], angles, [0.0]])
        return np.diff(th)

    def _end_offsets(self, pos: np.ndarray, angles: np.ndarray) -> np.ndarray:
        """(n+1, 2, 2): right side's copy minus left side's copy of each joint's intrados (0)
        and extrados (1) end [m] (an abutment's copy stays where it was)."""
        n = self.arch.n
        c0 = self.centroids0
        ca, sa = np.cos(angles), np.sin(angles)
        out = np.empty((n + 1, 2, 2))
        for j in range(n + 1):
            for e in (0, 1):
                m = self.joint_points[j, e]
                sides = []
                for v in (j - 1, j):
                    if v < 0 or v >= n:
                        sides.append(m)
                        continue
                    r = m - c0[v]
                    sides.append(pos[v] + np.array([ca[v] * r[0] - sa[v] * r[1],
                                                    sa[v] * r[0] + ca[v] * r[1]]))
                out[j, e] = sides[1] - sides[0]
        return out

    def joint_sliding(self, pos: np.ndarray, angles: np.ndarray) -> np.ndarray:
        """Sliding [m] at each joint: the relative displacement (right side minus left side)
        of the joint's end that is closer to closed, along the joint (intrados to extrados) as
        turned by the mean rotation of its two sides.  At a hinge that end is the contact point,
        so an opening joint reads only its slip; a closed joint reads the slip of both ends."""
        n = self.arch.n
        d = self._end_offsets(pos, angles)
        th = np.concatenate([[0.0], angles, [0.0]])
        mean = 0.5 * (th[:-1] + th[1:])
        t0 = self.joint_tangents
        tx = np.cos(mean) * t0[:, 0] - np.sin(mean) * t0[:, 1]
        ty = np.sin(mean) * t0[:, 0] + np.cos(mean) * t0[:, 1]
        gap = np.hypot(d[:, :, 0], d[:, :, 1])
        end = np.argmin(gap, axis=1)
        dd = d[np.arange(n + 1), end]
        return dd[:, 0] * tx + dd[:, 1] * ty

    def end_gaps(self, pos: np.ndarray, angles: np.ndarray) -> np.ndarray:
        """(n+1, 2) distance [m] between the two sides' copies of each joint's intrados (0) and
        extrados (1) end: the end that stays closed while a joint opens is its hinge."""
        d = self._end_offsets(pos, angles)
        return np.hypot(d[:, :, 0], d[:, :, 1])

    def drops(self, pos: np.ndarray) -> np.ndarray:
        """How far each voussoir's mass centre has dropped below its initial height [m]."""
        return self.centroids0[:, 1] - pos[:, 1]

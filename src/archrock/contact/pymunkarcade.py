"""An arcade (:class:`~archrock.geometry.arcade.Arcade`) as rigid blocks in pymunk, the
cross-check engine: built as :class:`~archrock.contact.engine.ContactArch` builds an arch (exact
mass properties, the outline simplified within ``outline_tol`` with every contact's ends kept,
cut into convex pieces with rounded corners, the friction and restitution of
:class:`~archrock.contact.settings.EngineSettings`, ground motion as the ground frame's body
force), with a static ground block under each contact with the ground instead of two
abutments.  Its ramp and response are :mod:`archrock.contact.arcade`'s."""

from __future__ import annotations

import math

import numpy as np

from ..errors import ArchInputError
from ..geometry.arcade import GROUND, Arcade
from ..units import G
from .engine import PymunkBlocks, add_block, import_pymunk, settle_blocks
from .settings import EngineSettings, engine_scales

__all__ = ["ContactArcade"]


class ContactArcade(PymunkBlocks):
    """One arcade in a pymunk space, at rest in its initial configuration (module docstring).
    ``time_scale`` T = sqrt(size/g) [s] with size = ``arcade.size``; ``dt`` = T / steps_per_T."""

    def __init__(self, arc: Arcade, settings: EngineSettings | None = None):
        pymunk = import_pymunk()
        if not isinstance(arc, Arcade):
            raise ArchInputError(f"arcade: expected an Arcade, got {type(arc).__name__}")
        self.arcade = arc
        self.settings = settings = settings or EngineSettings()
        self.scales = sc = engine_scales(arc, settings)
        self.size, self.time_scale, self.dt = sc.size, sc.time_scale, sc.dt
        space = pymunk.Space()
        space.iterations = settings.iterations
        space.collision_slop = sc.slop
        space.collision_bias = (1.0 - settings.bias) ** (1.0 / self.dt) if settings.bias < 1 \
            else 0.0
        space.gravity = (0.0, -G)
        space.damping = 1.0
        space.sleep_time_threshold = float("inf")
        self.space = space
        mu, e, r = math.sqrt(settings.friction), math.sqrt(settings.restitution), sc.rounding
        self.masses = np.asarray(arc.masses, float)
        self.centroids0 = np.asarray(arc.centroids, float)
        self.inertias = np.asarray(arc.inertias, float)
        self.bodies, self.pieces = [], []
        ends = {i: [] for i in range(arc.n_blocks)}
        for ct in arc.contacts:
            for blk in (ct.a, ct.b):
                if blk != GROUND:
                    ends[blk] += [ct.points[0], ct.points[1]]
        for i, blk in enumerate(arc.blocks):
            # the arcade keeps its blocks' own outlines (the pieces carry the cut)
            body, _, pieces = add_block(pymunk, space, np.asarray(blk.outline, float),
                                        np.array(ends[i]), self.masses[i], self.inertias[i],
                                        self.centroids0[i], sc, mu, e, r)
            self.pieces.append(pieces)
            self.bodies.append(body)
        normals = np.asarray(arc.contact_normals, float)
        self.ground_outlines = []
        for c, ct in enumerate(arc.contacts):
            if ct.a != GROUND:
                continue
            p0, p1 = ct.points
            length = float(np.hypot(*(p1 - p0)))
            n = normals[c]  # into the block: the ground lies on the other side
            quad = np.array([p0, p1, p1 - length * n, p0 - length * n])
            s = pymunk.Poly(space.static_body, [tuple(map(float, q)) for q in quad])
            s.friction, s.elasticity = mu, e
            space.add(s)
            self.ground_outlines.append(quad)
        pts = np.array([ct.points for ct in arc.contacts], float)
        self.contact_points = pts
        tan = pts[:, 1] - pts[:, 0]
        self.contact_lengths = np.hypot(tan[:, 0], tan[:, 1])
        self.contact_tangents = tan / self.contact_lengths[:, None]
        self.a = np.array([ct.a for ct in arc.contacts])
        self.b = np.array([ct.b for ct in arc.contacts])
        self.time, self.steps = 0.0, 0

    def settle(self, duration: float = 0.5) -> None:
        """Settle under gravity for ``duration`` T, stop every body, restart the clock: the
        reference of every rotation and slip reported."""
        settle_blocks(self, duration, self.contact_sliding)

    def contact_rotations(self, angles: np.ndarray) -> np.ndarray:
        """theta_b - theta_a at each contact [rad] (the ground: 0)."""
        th = np.concatenate([angles, [0.0]])  # index -1: the ground
        return th[self.b] - th[self.a]

    def _copies(self, pos, angles, blk, p):
        if blk == GROUND:
            return p
        r = p - self.centroids0[blk]
        ca, sa = math.cos(angles[blk]), math.sin(angles[blk])
        return pos[blk] + np.array([ca * r[0] - sa * r[1], sa * r[0] + ca * r[1]])

    def _end_offsets(self, pos, angles) -> np.ndarray:
        """(m, 2, 2): block b's copy minus block a's copy of each contact's two ends [m]."""
        out = np.empty((len(self.a), 2, 2))
        for c in range(len(self.a)):
            for e in (0, 1):
                p = self.contact_points[c, e]
                out[c, e] = (self._copies(pos, angles, self.b[c], p)
                             - self._copies(pos, angles, self.a[c], p))
        return out

    def end_gaps(self, pos, angles) -> np.ndarray:
        """(m, 2) distance between the two blocks' copies of each contact end [m]."""
        d = self._end_offsets(pos, angles)
        return np.hypot(d[:, :, 0], d[:, :, 1])

    def contact_sliding(self, pos, angles) -> np.ndarray:
        """Slip [m] at each contact: the relative displacement of its end closer to closed,
        along the contact turned by the mean rotation of its two blocks."""
        d = self._end_offsets(pos, angles)
        th = np.concatenate([angles, [0.0]])
        mean = 0.5 * (th[self.a] + th[self.b])
        t0 = self.contact_tangents
        tx = np.cos(mean) * t0[:, 0] - np.sin(mean) * t0[:, 1]
        ty = np.sin(mean) * t0[:, 0] + np.cos(mean) * t0[:, 1]
        end = np.argmin(np.hypot(d[:, :, 0], d[:, :, 1]), axis=1)
        dd = d[np.arange(len(end)), end]
        return dd[:, 0] * tx + dd[:, 1] * ty

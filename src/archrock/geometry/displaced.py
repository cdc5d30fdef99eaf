"""Arches whose supports have moved: a prescribed support movement, and the displaced arch.

:class:`SupportMovement` is the movement imposed on the springings: a horizontal ``spread``
[m] (> 0 opens the span, < 0 closes it) and a vertical ``settlement`` [m] (> 0 the support goes
down), applied to the right support, the left one, or half to each (``side="both"``, symmetric).

:class:`DisplacedArch` is a base arch whose voussoirs have been moved rigidly, each by its own
rotation and translation (``x' = R(angle) (x - origin) + image``), and whose open joints are
point contacts: the joint's contact segment shrinks to the hinge point (intrados end ==
extrados end).  It is a :class:`VoussoirArch`, so limit analysis, the four-link model and the
contact engine take it unchanged.  Rigid motions keep every voussoir's area, polar moment and
mass; centroids, loads, outlines and closed joints move with their voussoir.  A point joint
also carries a direction (:attr:`DisplacedArch.joint_directions`, the bisector of its two
faces' turned directions) that the static program uses for the sign of its normal force.
:mod:`archrock.statics.supports` computes the hinges and the exact finite-displacement
kinematics that build it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from functools import cached_property

import numpy as np

from ..errors import ArchInputError
from .base import MAX_LENGTH_M, Load, VoussoirArch, _check_scalar

__all__ = ["SupportMovement", "DisplacedArch", "SIDES", "MAX_ROTATION"]

#: Which support moves: the right one, the left one, or both by half (symmetric).
SIDES = ("right", "left", "both")
#: Largest support rotation [rad] (about 28.6 deg): beyond it a pier or abutment has fallen.
MAX_ROTATION = 0.5


@dataclass(frozen=True)
class SupportMovement:
    """A prescribed movement of the springings [m].

    spread: horizontal movement that opens the span (> 0) or closes it (< 0);
    settlement: vertical movement downward (> 0) or upward (< 0);
    side: "right" (the right support moves, the left one stays), "left" (the mirror: the left
    support moves by -spread horizontally) or "both" (each moves half, symmetrically: the right
    one by (spread/2, -settlement/2), the left one by (-spread/2, -settlement/2));
    rotation [rad], |rotation| <= MAX_ROTATION: the support (abutment or pier) turns rigidly
    about its foot, > 0 outward (its top away from the span: clockwise on the right, counter-
    clockwise on the left; "both": each by half); pivot_depth [m] >= 0: the foot is the outer
    end of the springing joint (joint 0 or n; on an arch on piers the pier's outer foot)
    lowered by pivot_depth (the height of an abutment below the springing).  The rotation is
    applied first, about the foot, then the translation.
    """

    spread: float = 0.0
    settlement: float = 0.0
    side: str = "right"
    rotation: float = 0.0
    pivot_depth: float = 0.0

    def __post_init__(self):
        for name in ("spread", "settlement"):
            v = _check_scalar(name, getattr(self, name),
                              allowed=f"a finite length in m, |value| <= {MAX_LENGTH_M:g} m")
            if abs(v) > MAX_LENGTH_M:
                raise ArchInputError(f"{name}: {v:g} m is out of range; allowed |{name}| <= "
                                     f"{MAX_LENGTH_M:g} m (units? lengths are in metres)")
            object.__setattr__(self, name, v)
        if self.side not in SIDES:
            raise ArchInputError(f"side: {self.side!r}; allowed 'right', 'left' or 'both'")
        r = _check_scalar("rotation", self.rotation,
                          allowed=f"a finite angle in rad, |rotation| <= {MAX_ROTATION:g} rad")
        if abs(r) > MAX_ROTATION:
            raise ArchInputError(f"rotation: {r:g} rad is out of range; allowed |rotation| <= "
                                 f"{MAX_ROTATION:g} rad (about 28.6 deg; units? angles are in "
                                 f"radians)")
        object.__setattr__(self, "rotation", r)
        dp = _check_scalar("pivot_depth", self.pivot_depth,
                           allowed=f"a finite depth in m, 0 <= pivot_depth <= {MAX_LENGTH_M:g}")
        if not 0.0 <= dp <= MAX_LENGTH_M:
            raise ArchInputError(f"pivot_depth: {dp:g} m is out of range; allowed 0 <= "
                                 f"pivot_depth <= {MAX_LENGTH_M:g} m")
        object.__setattr__(self, "pivot_depth", dp)

    @property
    def is_zero(self) -> bool:
        return self.spread == 0.0 and self.settlement == 0.0 and self.rotation == 0.0

    def rigid_motions(self, joint_points) -> tuple:
        """((theta_l, c_l, u_l), (theta_r, c_r, u_r)): each support's rigid motion, a point p
        of it going to R(theta) (p - c) + c + u [rad counter-clockwise, m]; c the foot about
        which it turns (class docstring) in the arch's ``joint_points``."""
        jp = np.asarray(joint_points, float)
        ul, ur = self.supports
        r = self.rotation
        rl, rr = {"right": (0.0, r), "left": (r, 0.0), "both": (0.5 * r, 0.5 * r)}[self.side]
        drop = np.array([0.0, self.pivot_depth])
        cl = jp[0][int(np.argmin(jp[0][:, 0]))] - drop    # the outer (leftmost) end
        cr = jp[-1][int(np.argmax(jp[-1][:, 0]))] - drop  # the outer (rightmost) end
        return (rl, cl, ul), (-rr, cr, ur)

    @property
    def supports(self) -> tuple[np.ndarray, np.ndarray]:
        """(u_left, u_right): the displacement vectors [m] of the left and right supports."""
        s, v = self.spread, self.settlement
        if self.side == "right":
            return np.zeros(2), np.array([s, -v])
        if self.side == "left":
            return np.array([-s, -v]), np.zeros(2)
        return np.array([-0.5 * s, -0.5 * v]), np.array([0.5 * s, -0.5 * v])

    @property
    def relative(self) -> np.ndarray:
        """u_right - u_left [m]: the right support's movement seen from the left one (what
        deforms the arch; the rest is a rigid translation by u_left)."""
        ul, ur = self.supports
        return ur - ul

    def scaled(self, t: float) -> "SupportMovement":
        """The same movement multiplied by ``t`` (the foot stays where it is)."""
        if self.rotation == 0.0 and self.pivot_depth == 0.0:
            return SupportMovement(self.spread * t, self.settlement * t, self.side)
        return SupportMovement(self.spread * t, self.settlement * t, self.side,
                               self.rotation * t, self.pivot_depth)

    def mirrored(self) -> "SupportMovement":
        """The movement that the mirrored arch receives: the same spread, settlement and
        (outward) rotation on the other side."""
        other = {"right": "left", "left": "right", "both": "both"}[self.side]
        return SupportMovement(self.spread, self.settlement, other, self.rotation,
                               self.pivot_depth)

    def to_dict(self) -> dict:
        d = {"spread": self.spread, "settlement": self.settlement, "side": self.side}
        if self.rotation or self.pivot_depth:  # written only when set: older dicts unchanged
            d.update(rotation=self.rotation, pivot_depth=self.pivot_depth)
        return d

    @classmethod
    def from_dict(cls, data) -> "SupportMovement":
        keys = {"spread", "settlement", "side", "rotation", "pivot_depth"}
        if not isinstance(data, dict) or set(data) - keys:
            raise ArchInputError("support movement: expected an object with spread, settlement, "
                                 "side (and rotation, pivot_depth)")
        return cls(data.get("spread", 0.0), data.get("settlement", 0.0),
                   data.get("side", "right"), data.get("rotation", 0.0),
                   data.get("pivot_depth", 0.0))

    def describe(self) -> str:
        parts = []
        if self.spread:
            parts.append(f"spread {self.spread:+.4g} m")
        if self.settlement:
            parts.append(f"settlement {self.settlement:+.4g} m")
        if self.rotation:
            parts.append(f"rotation {self.rotation:+.4g} rad outward about the foot"
                         + (f" {self.pivot_depth:g} m below the springing"
                            if self.pivot_depth else ""))
        return (", ".join(parts) or "no movement") + f" ({self.side} support" + (
            "s" if self.side == "both" else "") + ")"


def _rot(a: float) -> np.ndarray:
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, -s], [s, c]])


@dataclass(frozen=True, eq=False)
class DisplacedArch(VoussoirArch):
    """``base`` with voussoir i moved rigidly by ``x' = R(angles[i]) (x - origins[i]) +
    images[i]`` [rad, m], and the joints ``point_joints`` (joint, x, y) reduced to point contacts
    at (x, y) [m] (the open hinges).  ``movement`` and ``hinges`` (Hinge objects) record what
    made it (for reports)."""

    base: VoussoirArch
    angles: tuple
    origins: tuple
    images: tuple
    point_joints: tuple = ()
    movement: SupportMovement | None = None
    hinges: tuple = ()
    name: str = field(default="", compare=False)
    #: a re-closed arch's open joints (joint, x, y): where they touched at one point before
    #: re-closing (archrock.statics.supports.reclosed; reports and the gap-closing check)
    contacts: tuple = field(default=(), compare=False)

    def __post_init__(self):
        if not isinstance(self.base, VoussoirArch):
            raise ArchInputError(f"base: expected a VoussoirArch, got {type(self.base).__name__}")
        n = self.base.n
        a = np.asarray(self.angles, float).reshape(-1)
        o = np.asarray(self.origins, float).reshape(-1, 2)
        m = np.asarray(self.images, float).reshape(-1, 2)
        if a.size != n or o.shape[0] != n or m.shape[0] != n:
            raise ArchInputError(f"angles, origins, images: one per voussoir ({n}); got "
                                 f"{a.size}, {o.shape[0]}, {m.shape[0]}")
        if not (np.all(np.isfinite(a)) and np.all(np.isfinite(o)) and np.all(np.isfinite(m))):
            raise ArchInputError("angles, origins, images: every value must be finite")
        for arr in (a, o, m):
            arr.setflags(write=False)
        object.__setattr__(self, "angles", a)
        object.__setattr__(self, "origins", o)
        object.__setattr__(self, "images", m)
        pj = []
        for k, item in enumerate(self.point_joints):
            j, x, y = item
            if isinstance(j, bool) or int(j) != j or not 0 <= int(j) <= n:
                raise ArchInputError(f"point_joints[{k}]: joint {j!r}; allowed 0..{n}")
            if not (math.isfinite(x) and math.isfinite(y)):
                raise ArchInputError(f"point_joints[{k}]: the point must be finite")
            pj.append((int(j), float(x), float(y)))
        object.__setattr__(self, "point_joints", tuple(sorted(pj)))
        if not self.name:
            object.__setattr__(self, "name", f"{self.base.name} (displaced)")

    # ------------------------------------------------------------------ the moves
    def move(self, i: int, pts) -> np.ndarray:
        """Points [m] of voussoir i's base geometry, moved with it."""
        p = np.asarray(pts, float)
        return (p - self.origins[i]) @ _rot(float(self.angles[i])).T + self.images[i]

    @property
    def density(self) -> float:
        return self.base.density

    @property
    def fc(self) -> float | None:
        """The base arch's compressive strength [MPa] (None: infinite)."""
        return self.base.fc

    def with_fc(self, fc) -> "DisplacedArch":
        """The same moves of the base arch with compressive strength ``fc`` [MPa]."""
        if fc == self.fc:
            return self
        return replace(self, base=self.base.with_fc(fc))

    @cached_property
    def loads(self) -> tuple:
        return tuple(Load(ld.voussoir, ld.mass, tuple(self.move(ld.voussoir, ld.at)))
                     for ld in self.base.loads)

    @property
    def n(self) -> int:
        return self.base.n

    @property
    def size(self) -> float:
        """The base arch's size: the displaced arch keeps its reference length."""
        return self.base.size

    @cached_property
    def _centroids_moved(self) -> tuple[np.ndarray, np.ndarray]:
        ac = np.array([self.move(i, c) for i, c in enumerate(self.base.area_centroids)])
        mc = np.array([self.move(i, c) for i, c in enumerate(self.base.centroids)])
        for arr in (ac, mc):
            arr.setflags(write=False)
        return ac, mc

    @property
    def areas(self) -> np.ndarray:
        return self.base.areas

    @property
    def area_centroids(self) -> np.ndarray:
        return self._centroids_moved[0]

    @property
    def area_polar(self) -> np.ndarray:
        return self.base.area_polar

    @cached_property
    def _mass_properties(self):
        # a rigid motion keeps masses and polar moments; only the mass centres move
        return self.base.masses, self._centroids_moved[1], self.base.inertias

    def outline(self, i: int) -> np.ndarray:
        return self.move(i, self.base.outline(i))

    @cached_property
    def _joints(self) -> tuple[np.ndarray, np.ndarray]:
        """(joint_points, joint_directions): closed joints move with a neighbour voussoir (the
        right one; the last joint with the last voussoir); point joints sit at their point."""
        n = self.n
        base = np.asarray(self.base.joint_points, float)
        pts = np.empty_like(base)
        dirs = np.empty((n + 1, 2))
        for j in range(n + 1):
            i = min(j, n - 1)
            pts[j] = self.move(i, base[j])
            e = base[j, 1] - base[j, 0]
            e = e / np.hypot(*e)
            # the bisector of the two faces' directions (an abutment does not turn)
            left = float(self.angles[j - 1]) if j > 0 else 0.0
            right = float(self.angles[j]) if j < n else 0.0
            dirs[j] = _rot(0.5 * (left + right)) @ e
        for j, x, y in self.point_joints:
            pts[j] = (x, y), (x, y)
        pts.setflags(write=False)
        dirs.setflags(write=False)
        return pts, dirs

    @property
    def joint_points(self) -> np.ndarray:
        return self._joints[0]

    @property
    def joint_directions(self) -> np.ndarray:
        """(n+1, 2) unit vectors from each joint's intrados end toward its extrados end as the
        faces lie now (for a point joint, the bisector of its two faces; the static program uses
        it for the normal force's sign, where the zero-length segment gives no direction)."""
        return self._joints[1]

    @property
    def abutment_faces(self) -> np.ndarray:
        """(2, 2, 2): the left and right supports' faces [m] (intrados end, extrados end) as the
        supports now lie: the base springing faces moved by the supports' translations.  At an
        open springing joint the voussoir touches its support's face at the hinge point only."""
        base = np.asarray(self.base.joint_points, float)
        ul, ur = (np.zeros(2), np.zeros(2)) if self.movement is None else self.movement.supports
        if self.movement is None or self.movement.rotation == 0.0:
            return np.array([base[0] + ul, base[-1] + ur])
        (tl, cl, ul), (tr, cr, ur) = self.movement.rigid_motions(base)
        return np.array([(base[0] - cl) @ _rot(tl).T + cl + ul,
                         (base[-1] - cr) @ _rot(tr).T + cr + ur])

    @property
    def open_joints(self) -> tuple[int, ...]:
        return tuple(j for j, _, _ in self.point_joints)

    # ------------------------------------------------------------------ transformations
    def mirrored(self) -> "DisplacedArch":
        n = self.n
        f = np.array([-1.0, 1.0])
        idx = list(range(n - 1, -1, -1))
        return DisplacedArch(self.base.mirrored(), tuple(-self.angles[idx]),
                             tuple(self.origins[idx] * f), tuple(self.images[idx] * f),
                             tuple((n - j, -x, y) for j, x, y in self.point_joints),
                             None if self.movement is None else self.movement.mirrored(),
                             tuple(type(h)(n - h.joint, h.edge) for h in self.hinges[::-1]),
                             f"{self.name} (mirrored)")

    def scaled(self, factor: float) -> "DisplacedArch":
        f = _check_scalar("factor", factor, 0.0, None, allowed="> 0")
        mv = self.movement
        return DisplacedArch(self.base.scaled(f), tuple(self.angles), tuple(self.origins * f),
                             tuple(self.images * f),
                             tuple((j, x * f, y * f) for j, x, y in self.point_joints),
                             None if mv is None else SupportMovement(
                                 mv.spread * f, mv.settlement * f, mv.side, mv.rotation,
                                 mv.pivot_depth * f),
                             self.hinges, self.name)

    def to_dict(self) -> dict:
        """The base geometry and the moves (not a geometry file: the displaced arch is rebuilt
        from its base and movement by :func:`archrock.statics.supports.displace`)."""
        return {
            "displaced": {
                "base": self.base.to_dict(),
                "movement": None if self.movement is None else self.movement.to_dict(),
                "hinges": [{"joint": int(h.joint), "edge": h.edge} for h in self.hinges],
                "angles": [float(a) for a in self.angles],
                "origins": self.origins.tolist(),
                "images": self.images.tolist(),
                "point_joints": [list(p) for p in self.point_joints],
            }
        }

    def __repr__(self) -> str:
        return (f"DisplacedArch(name={self.name!r}, n={self.n}, open joints="
                f"{list(self.open_joints)})")


def refuse_moved_supports(nominal) -> None:
    """Raise ArchInputError when a study is given an arch on moved supports as the nominal arch
    of its random arches (only the ensemble moves supports: EnsembleConfig(support=...))."""
    if isinstance(nominal, DisplacedArch):
        raise ArchInputError(
            f"nominal: {nominal.name!r} stands on moved supports (--spread/--settlement/"
            f"--rotation); allowed here an arch on fixed supports: the studies move their random "
            f"arches' supports themselves (EnsembleConfig(support=...), "
            f"statics.supports.study_sampler for curves, fragility and sensitivity), "
            f"random-arch does not")

"""Oppenheim's four-link mechanism of an arch: :class:`FourLink` and :func:`four_link`, which build
the flat geometry vector of its compiled kinematics (:mod:`archrock.dynamics.fourbar`: the loop
closure and the coefficients of the equation of motion, docs/method.md, Four-link equation) and
its coefficient tables for the fast integrator (:mod:`archrock.dynamics.tables`).  The compiled
functions of both modules are importable from here too, as before they were split off.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property

import numpy as np

from .._records import readonly_arrays
from ..errors import ArchInputError, NotFourHingeError
from ..geometry import VoussoirArch
from ..statics.hinges import EDGES, Mechanism
from ..units import G
from .fourbar import (_GC, _I, _M, _S, GEO_SIZE, configuration, rates, coefficients, potential,
                      GEO_OK, GEO_SINGULAR, GEO_NOT_ADMISSIBLE, GEO_WRONG_DIRECTION, GEO_ERRORS,
                      mechanism_geo, dead_point, unstable_rotation, rotation_limit, rest_rate,
                      table_range)
from .tables import (TABLE_HEADER, MIN_TABLE_INTERVALS, check_table_intervals, table_size,
                     init_table, empty_table, build_interval, build_table, coefficient_table,
                     fast_coefficients, exact_acceleration, table_acceleration,
                     filling_acceleration)

__all__ = ["FourLink", "four_link", "candidate_four_links",
           "GEO_SIZE", "configuration", "rates", "coefficients", "potential", "GEO_OK",
           "GEO_SINGULAR", "GEO_NOT_ADMISSIBLE", "GEO_WRONG_DIRECTION", "GEO_ERRORS",
           "mechanism_geo", "dead_point", "unstable_rotation", "rotation_limit", "rest_rate",
           "table_range", "TABLE_HEADER", "MIN_TABLE_INTERVALS", "check_table_intervals",
           "table_size", "init_table", "empty_table", "build_interval", "build_table",
           "coefficient_table", "fast_coefficients", "exact_acceleration", "table_acceleration",
           "filling_acceleration"]


# ---------------------------------------------------------------------------- model object
@dataclass(frozen=True, eq=False)
class FourLink:
    """One mechanism of an arch as a four-link system (or any three rigid links on four hinges).

    points: hinge points A, B, C, D at phi = 0, ordered from the leading side [m];
    link_voussoirs: voussoir indices of links 1, 2, 3 (empty for synthetic links);
    geo: the flat parameter vector of the scalar kernels; direction: 'l' or 'r'.
    """

    direction: str
    points: np.ndarray
    sign: float
    link_masses: np.ndarray
    link_centroids: np.ndarray
    link_inertias: np.ndarray
    link_voussoirs: tuple = ()
    mechanism: Mechanism | None = None
    arch: VoussoirArch | None = field(default=None, repr=False)

    def __post_init__(self):
        readonly_arrays(self)

    @cached_property
    def geo(self) -> np.ndarray:
        g = np.empty(GEO_SIZE)
        g[0:8] = np.asarray(self.points, float).ravel()
        g[_S] = self.sign
        g[_M:_M + 3] = self.link_masses
        g[_GC:_GC + 6] = np.asarray(self.link_centroids, float).ravel()
        g[_I:_I + 3] = self.link_inertias
        g.setflags(write=False)
        return g

    # -- equation of motion
    def coefficients(self, phi: float):
        """(M, L, F, P) at rotation phi [rad], Python floats (numpy scalars without numba would
        leak into JSON output)."""
        M, L, F, P = coefficients(phi, self.geo)
        return float(M), float(L), float(F), float(P)

    def static_multiplier(self) -> float:
        """xg''/g at which phi = 0 is in equilibrium: F(0)/P(0) (= -k_l for M_l, +k_r for M_r)."""
        _, _, F, P = coefficients(0.0, self.geo)
        return F / P

    def energy(self, phi: float, rate: float, g: float = G) -> float:
        """Kinetic + gravity potential energy [J per m of depth] relative to rest at phi = 0."""
        M, _, _, _ = coefficients(phi, self.geo)
        return 0.5 * M * rate * rate + g * potential(phi, self.geo)

    @cached_property
    def phi_dead(self) -> float:
        """First rotation [rad] at which the four-bar locks (dead point), capped at pi/2."""
        return float(dead_point(self.geo))

    @cached_property
    def phi_unstable(self) -> float:
        """Rotation [rad] of the unstable static position under gravity alone (F = 0)."""
        return float(unstable_rotation(self.geo, self.phi_dead))

    def default_limit(self) -> float:
        """Rotation limit [rad] for collapse: well beyond the unstable position, before the dead
        point (halfway to the dead point, at most 2.5 times the unstable rotation)."""
        return float(rotation_limit(self.phi_unstable, self.phi_dead))

    # -- velocity field at phi = 0, voussoir by voussoir (for impacts)
    def voussoir_field(self):
        """Velocity of every voussoir centroid (n, 2) and its angular rate (n,) per unit
        phi-rate at phi = 0; voussoirs outside the mechanism have zero velocity."""
        if self.arch is None:
            raise ArchInputError("voussoir_field: this four-link system was not built from an arch")
        arch = self.arch
        t1, t2, t3, *_ = rates(0.0, self.geo)
        (ax, ay), (bx, by), _, (dx, dy) = self.points
        v = np.zeros((arch.n, 2))
        w = np.zeros(arch.n)
        for k, (idx, th, ref) in enumerate(zip(self.link_voussoirs, (t1, t2, t3),
                                                ((ax, ay), (bx, by), (dx, dy)))):
            idx = np.asarray(idx, dtype=int)
            r = arch.centroids[idx] - np.array(ref)
            vel = th * np.column_stack([-r[:, 1], r[:, 0]])
            if k == 1:  # link 2 moves with B's velocity plus its own rotation about B
                vel = vel + t1 * np.array([-(by - ay), bx - ax])
            v[idx] = vel
            w[idx] = th
        return v, w

    def tabulated(self, phi_max: float, n_intervals: int = 600) -> np.ndarray:
        """``geo`` with the tables of the coefficients for 0 <= phi <= ``phi_max`` [rad] (for
        the fast integrator; the tables reach past both ends so that their free ends are far)."""
        start, top = table_range(self.geo, phi_max, self.phi_dead)
        tab = coefficient_table(np.asarray(self.geo), start, top,
                                check_table_intervals(n_intervals, "n_intervals"))
        tab.setflags(write=False)
        return tab


def four_link(arch: VoussoirArch, mechanism: Mechanism, zones=None) -> FourLink:
    """The four-link model of ``mechanism`` on ``arch``, an arch of any shape: links are rigid
    unions of voussoirs, hinges the ends of the joints' contact segments
    (``arch.joint_points``), link masses, centroids and inertias those of the voussoirs with
    their loads (``arch.masses``, ``centroids``, ``inertias``).  zones: the compressed zones'
    depths [m] (n+1,) at collapse of an arch of finite strength: each hinge then sits half a
    zone in from its edge (:func:`archrock.dynamics.finite.inset_joint_points`); None: at the
    edges."""
    if not isinstance(arch, VoussoirArch):
        raise ArchInputError(f"arch: expected a VoussoirArch (Arch, PolygonArch), got "
                             f"{type(arch).__name__}")
    if mechanism.direction not in ("l", "r"):
        raise ArchInputError(f"mechanism.direction: {mechanism.direction!r}; allowed 'l' or 'r'")
    if getattr(mechanism, "lift_off", ()) or len(mechanism.hinges) != 4:
        raise NotFourHingeError(f"mechanism: a {mechanism.describe()} is not a four-hinge chain; "
                                f"the four-link model does not describe it (archrock dem does)")
    hinges = sorted(mechanism.hinges, key=lambda h: h.joint)
    joints = [h.joint for h in hinges]
    if len(set(joints)) != 4 or joints[0] < 0 or joints[-1] > arch.n:
        raise ArchInputError(f"mechanism.hinges: need 4 distinct joints in 0..{arch.n}, got {joints}")
    # (n+1, 2) per coordinate: [joint, edge]; for a circular arch the very numbers r cos(psi),
    # r sin(psi) it always used, so its models are unchanged to the bit
    if zones is None:
        pts = arch.joint_points
    else:
        from .finite import inset_joint_points

        pts = inset_joint_points(arch, mechanism, zones)
    px = np.ascontiguousarray(pts[:, :, 0])
    py = np.ascontiguousarray(pts[:, :, 1])
    edges = np.array([EDGES.index(h.edge) for h in hinges], dtype=np.int64)
    geo = np.empty(GEO_SIZE)
    code = mechanism_geo(px, py, arch.masses, np.ascontiguousarray(arch.centroids), arch.inertias,
                         np.array(joints, dtype=np.int64), edges, mechanism.direction == "r", geo)
    if code != GEO_OK:
        label = f"M_{mechanism.direction} {[h.to_dict() for h in hinges]}"
        raise ArchInputError(GEO_ERRORS[int(code)].format(m=label))
    groups = [tuple(range(joints[0], joints[1])), tuple(range(joints[1], joints[2])),
              tuple(range(joints[2], joints[3]))]
    if mechanism.direction == "r":  # links and hinges from the leading (right) side
        groups = groups[::-1]
    return FourLink(mechanism.direction, geo[0:8].reshape(4, 2).copy(), float(geo[8]),
                    geo[9:12].copy(), geo[12:18].reshape(3, 2).copy(), geo[18:21].copy(),
                    tuple(groups), mechanism, arch)


def candidate_four_links(arch: VoussoirArch, direction: str):
    """(mechanism, FourLink) of every four-hinge candidate of ``arch`` in ``direction``, in the
    one order of :func:`archrock.statics.hinges.four_hinge_candidates`, skipping the sets whose
    four-link model cannot be built (degenerate links): the candidates a post-impact
    mechanism is chosen from (least loss, a pier's step)."""
    from ..statics.hinges import four_hinge_candidates

    for mech in four_hinge_candidates(arch.n, direction):
        try:
            fl = four_link(arch, mech)
        except (ArchInputError, ZeroDivisionError):
            continue
        yield mech, fl

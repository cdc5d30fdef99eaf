"""Whether one degree of freedom can follow an arch on piers (issue 19, docs/piers-dynamics.md).

The four-link model moves the whole chain in one four-hinge mechanism at a time and, at each
closing, stops every block that the next mechanism does not move.  A pier that rocks on its
foundation in a mechanism is a slender rocking block of its own: in the contact engine it keeps
its momentum through its own impacts (Housner's c = 1 - 1.5 sin^2(alpha), 0.96 for the 30 x 5 m
piers of ``tests/data/heavy_piers.json``) while the arch above it moves in another mechanism,
so the motion has two or more degrees of freedom.  Measured (docs/piers-dynamics.md): where a
limit mechanism moves a pier, the four-link model's first collapse under Oppenheim's pulse is
2-4x the engine's (heavy piers: 3.02 g against 0.71 g).

:func:`single_dof_check` says so for a prepared model.  It changes no number of the four-link
model: the response is computed as before, and its record carries the verdict
(``Response.single_dof``).  The studies read it (:func:`archrock.studies.enginestudy.
choose_dynamics`) and run the contact engine where it is not valid.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["SingleDofCheck", "pier_blocks", "single_dof_check", "PIER_MASS_RATIO", "StepMechanism",
           "step_mechanism"]

#: An end block on a horizontal foundation joint counts as a pier, in an arch that does not name
#: its blocks (a geometry file read back), when its mass is at least this multiple of the median
#: block's (a voussoir of a semicircle on rigid ground also stands on a horizontal joint, but it
#: weighs what its neighbours weigh).
PIER_MASS_RATIO = 2.0


@dataclass(frozen=True)
class SingleDofCheck:
    """Whether the four-link model (one degree of freedom) can follow this arch.

    valid: False where a limit mechanism moves a pier (the piers rock with the arch);
    reason: why not (None when valid); piers: the pier blocks' indices in chain order;
    found_by: 'block_kinds' (an ArchOnPiers), 'geometry' (heavy end blocks on horizontal
    foundation joints) or 'none' (no piers); pier_share: per direction ('l', 'r') the share of
    the limit mechanism's M(0) (its kinetic energy at phi = 0) carried by pier blocks.
    """

    valid: bool
    reason: str | None
    piers: tuple
    found_by: str
    pier_share: dict

    def to_dict(self) -> dict:
        return {"valid": self.valid, "reason": self.reason, "piers": list(self.piers),
                "found_by": self.found_by, "pier_share": dict(self.pier_share)}


def pier_blocks(arch) -> tuple[tuple, str]:
    """(indices of the pier blocks, how they were found): from ``block_kinds`` where the arch
    has them (:class:`~archrock.geometry.ArchOnPiers`); otherwise the end blocks (0, n-1) of a
    polygon arch that stand on a horizontal foundation joint (joint 0 / n, its ends level to
    1e-9 of the size), weigh at least :data:`PIER_MASS_RATIO` times the median block and rise
    from it as a column, both faces straight and vertical over at least the foundation's width
    (monolithic piers of a geometry file such as ``tests/data/heavy_piers.json``)."""
    kinds = getattr(arch, "block_kinds", None)
    if kinds:
        idx = tuple(i for i, k in enumerate(kinds) if k in ("pier", "buttress"))
        return (idx, "block_kinds") if idx else ((), "none")
    n = arch.n
    if n < 3 or getattr(arch, "intrados", None) is None:
        return (), "none"
    pts = np.asarray(arch.joint_points, float)
    masses = np.asarray(arch.masses, float)
    tol = 1e-9 * float(arch.size)
    heavy = PIER_MASS_RATIO * float(np.median(masses))

    def column(i, j):
        # both faces rise from the foundation as straight vertical segments at least as long
        # as the foundation is wide: a pier, not the springer of a ring on vertical joints
        # (heavy too, on a level springing, but its faces curve away at once)
        width = abs(pts[j, 1, 0] - pts[j, 0, 0])
        for line in (arch.intrados[i], arch.extrados[i]):
            a, b = (line[0], line[1]) if i == 0 else (line[-1], line[-2])
            if abs(b[0] - a[0]) > tol or abs(b[1] - a[1]) < width:
                return False
        return True

    found = tuple(i for i, j in ((0, 0), (n - 1, n))
                  if abs(pts[j, 0, 1] - pts[j, 1, 1]) <= tol and masses[i] >= heavy
                  and column(i, j))
    return (found, "geometry") if found else ((), "none")


def _pier_share(fl, piers) -> float:
    """Share of M(0) [-] carried by the blocks ``piers`` in the mechanism ``fl``."""
    arch = fl.arch
    v, w = fl.voussoir_field()
    e = arch.masses * np.sum(v * v, axis=1) + arch.inertias * w * w
    total = float(np.sum(e))
    return float(np.sum(e[list(piers)]) / total) if total > 0 else 0.0


def single_dof_check(model) -> SingleDofCheck:
    """The verdict for a prepared :class:`~archrock.dynamics.response.DynamicModel`: not valid
    where the arch has piers and a limit mechanism (M_l or M_r) moves one of them (module
    docstring); valid on rigid ground (no pier blocks) and where the piers stay still."""
    piers, how = pier_blocks(model.arch)
    if not piers:
        return SingleDofCheck(True, None, (), how, {})
    share = {d: _pier_share(fl, piers) for d, fl in (("l", model.mech_l), ("r", model.mech_r))}
    moving = [d for d in ("l", "r") if share[d] > 1e-12]
    if not moving:
        return SingleDofCheck(True, None, piers, how, share)
    which = ", ".join(f"M_{d} {getattr(model.mechanism(d).mechanism, 'label', '')} moves a pier "
                      f"({100 * share[d]:.0f}% of its kinetic energy)" for d in moving)
    reason = (f"the piers rock with the arch ({which}): a pier keeps rocking on its own "
              f"foundation after an impact while the arch moves in another mechanism, two "
              f"degrees of freedom or more; the four-link model (one) is unconservative here "
              f"(heavy piers: first collapse 3.02 g against the contact engine's 0.71 g); use "
              f"the contact engine (archrock dem; studies and the report do so by default)")
    return SingleDofCheck(False, reason, piers, how, share)


@dataclass(frozen=True)
class StepMechanism:
    """The four-hinge mechanism that a step of ground acceleration opens from rest, by Gauss's
    principle of least constraint: among the admissible mechanisms of ``direction`` with a
    positive generalised force Q = P(0) xg'' - F(0) g, the one with the largest Q^2 / M(0)
    (the acceleration energy it releases).  mechanism: its hinges (its own multiplier);
    score: Q^2/M [kg m^2 / s^4 per m]; limit_score: the same for the limit mechanism (None when
    the step does not exceed its threshold); candidates: how many were compared."""

    direction: str
    accel_g: float
    mechanism: object
    score: float
    limit_score: float | None
    candidates: int

    @property
    def is_limit_mechanism(self) -> bool:
        return self.limit_score is not None and self.score <= self.limit_score * (1 + 1e-12)


def step_mechanism(model, accel_g: float) -> StepMechanism:
    """Which four-hinge mechanism a step xg'' = ``accel_g`` g [signed, +x] opens from rest on
    the arch of the prepared ``model`` (:class:`StepMechanism`).  A diagnostic of
    docs/piers-dynamics.md: the dynamics open the limit mechanism, as the paper does; under a
    step of several k the contact engine opens this one (heavy piers at 0.7 g: both piers
    rocking, ``0i-4e-12i-14e``).  Enumerates every joint 0..n and edge (as the least-loss law
    does): seconds on a 14-block chain."""
    from ..errors import ArchInputError
    from ..statics.hinges import Mechanism
    from ..units import G
    from .fourlink import candidate_four_links

    if isinstance(accel_g, bool) or not isinstance(accel_g, (int, float)) or not (
            np.isfinite(accel_g) and accel_g != 0):
        raise ArchInputError(f"accel_g: {accel_g!r}; allowed a finite number != 0 (in g, +x)")
    direction = "l" if accel_g < 0 else "r"
    arch = model.arch

    def score(fl):
        M, _, F, P = fl.coefficients(0.0)
        q = P * accel_g * G - F * G
        return q * q / M if q > 0 else None

    lim = model.mechanism(direction)
    best_s, best = score(lim), lim.mechanism
    limit_s = best_s
    best_s = -1.0 if best_s is None else best_s
    count = 0
    for mech, fl in candidate_four_links(arch, direction):
        count += 1
        s = score(fl)
        if s is not None and s > best_s * (1 + 1e-12):
            best_s = s
            best = Mechanism(direction, mech.hinges, abs(fl.static_multiplier()))
    return StepMechanism(direction, float(accel_g), best, float(best_s), limit_s, count)

"""Support movements: the hinges they open, the exact displaced arch, and the displacement
capacity (docs/supports.md).

Setting: Ochsendorf, "The masonry arch on spreading supports", The Structural Engineer 84
(2006); Coccia, Di Carlo & Rinaldi, "On the safety assessment of masonry arches on moving
supports" (Meccanica, 2015).  The numbers are archrock's.

1. **Which hinges open.**  Of the statically admissible states under self-weight (the static
   program of :mod:`archrock.statics.lp`, lambda = 0), the movement selects the one that
   minimises the work of the arch's forces on the supports, which for u_left, u_right is
   F_0 . (u_right - u_left) plus a constant (F_0: the force the left support exerts on the
   arch, per total weight W).  Pure spread gives the minimum thrust, closing the maximum,
   settling the right support the least vertical reaction there.  The joints where that line
   of thrust touches an edge are the candidate hinges; the three-hinge set is the kinematically
   admissible one (each hinge turns so that its joint opens on the side opposite its edge) under
   which the displaced arch stands after a first small step; ties (a symmetric arch with a
   keystone touches four points) go to the set whose hinges lie nearer the moving support.
2. **Finite displacement.**  Hinges h1 < h2 < h3 (joints, left to right): the voussoirs between
   the left support and h1 move with the left support, those between h3 and the right support
   with the right one, and the two middle bodies form a two-bar linkage: h2's new place is the
   intersection of the circles about h1 and h3 (moved), on the branch continuous with the
   start.  Exact: no small-angle approximation.  Open joints become point contacts
   (:class:`~archrock.geometry.displaced.DisplacedArch`).
3. **Statics of the displaced arch.**  With its three hinges as points, the line of thrust
   passes through them: three equations for the three redundants, so the displaced arch is
   statically determinate; it stands while that line lies inside every other joint in
   compression.  :func:`displace` re-solves the LP on the displaced geometry (HiGHS) and reports
   the thrust and reactions; the margin that decides standing is the smallest fraction of a
   contact segment between that line and the segment's ends.
4. **Capacity.**  The movement is followed in steps (1/200 of the arch's size) until the arch
   can no longer stand (a fourth hinge forms, or the linkage cannot close: h1, h2, h3 in line);
   the capacity is then found by bisection to 1e-10 of the size.
5. **A support that turns** (``SupportMovement(rotation=..., pivot_depth=...)``) moves rigidly
   about its foot: the objective of 1. adds the rotation times the moment about the foot of
   the force on that support (:func:`_work`), the bodies on its side of the nearer hinge turn
   with it and the linkage closes between the moved h1 and h3 (:func:`_build_rotated`);
   ``displacement_capacity(arch, "rotation")`` reports radians.
6. **Studies.**  :func:`study_sampler` gives a study's random arches on the nominal's moved
   supports (:class:`MovedSampler`, sample i = the ensemble's), or the plain ArchSampler on
   fixed supports; :func:`movement_capacity` is the capacity along any movement's direction.
"""

from __future__ import annotations

from dataclasses import dataclass

from ..errors import ArchInputError
from ..geometry import VoussoirArch
from ..geometry.displaced import DisplacedArch, SupportMovement
from ..geometry.sampling import ArchSampler, Spreads
from .determinate import DisplacedState
from .displacement import (BISECT_TOL, MAX_MOVEMENT, STEPS, DisplacementCapacity, displace,
                           displacement_capacity, movement_capacity, movement_size)
from .onset import CAPACITY_KINDS, onset_hinges
from .reclosing import (GapClosing, closing_hinges, gap_closing, on_moved_supports, point_contacts,
                        reclosed)

__all__ = ["DisplacedState", "DisplacementCapacity", "onset_hinges", "displace",
           "displacement_capacity", "movement_capacity", "movement_size", "closing_hinges",
           "reclosed", "on_moved_supports",
           "point_contacts", "gap_closing",
           "GapClosing", "CAPACITY_KINDS", "STEPS",
           "BISECT_TOL", "MAX_MOVEMENT", "moved_parts", "MovedSampler", "study_sampler",
           "SUPPORT_DRAWS"]


# ---------------------------------------------------------------------------- studies
def moved_parts(arch: VoussoirArch) -> tuple[VoussoirArch, SupportMovement | None]:
    """(base arch, movement) of an arch on moved supports as the studies take it (the
    re-closed arch of :func:`on_moved_supports`, e.g. from ``--spread``/``--settlement``), or
    (arch, None) for an arch on fixed supports.  A displaced arch with open point contacts
    (``displace(...).arch``) is refused: the analyses take it re-closed (docs/supports.md)."""
    if not isinstance(arch, DisplacedArch):
        return arch, None
    if arch.point_joints:
        raise ArchInputError(f"nominal: {arch.name!r} has open joints as point contacts; allowed "
                             f"the arch re-closed on its moved supports "
                             f"(statics.supports.on_moved_supports(base, movement) or "
                             f"reclosed(displace(...).arch)), as every analysis takes it")
    if arch.movement is None:
        raise ArchInputError(f"nominal: {arch.name!r} is displaced without a recorded support "
                             f"movement; allowed an arch of on_moved_supports(base, movement)")
    return arch.base, arch.movement


#: How a study's random arches take the support movement: all of it, or U_i x it.
SUPPORT_DRAWS = ("fixed", "uniform")


@dataclass(frozen=True, eq=False)
class MovedSampler(ArchSampler):
    """The random arches of a study around a nominal arch on moved supports: sample i is
    ``ArchSampler(nominal, spreads, seed).arch(i)`` (``nominal`` is the base arch, on fixed
    supports) moved by ``movement`` (``support_draw='fixed'``) or by U_i x ``movement``
    (``'uniform'``, U_i of :meth:`ArchSampler.movement_fractions`), and re-closed
    (:func:`on_moved_supports`): the same arch as sample i of an ensemble with
    ``EnsembleConfig(support=movement, support_draw=...)``.  A draw that cannot stand on its
    moved supports is an InvalidSampleError ("cannot stand on its moved supports"), which the
    studies leave out as "cannot stand"."""

    movement: SupportMovement | None = None
    support_draw: str = "fixed"

    def __post_init__(self):
        super().__post_init__()
        if not isinstance(self.movement, SupportMovement):
            raise ArchInputError(f"movement: expected a SupportMovement, got "
                                 f"{type(self.movement).__name__}")
        if self.support_draw not in SUPPORT_DRAWS:
            raise ArchInputError(f"support_draw: {self.support_draw!r}; allowed "
                                 f"{', '.join(SUPPORT_DRAWS)}")

    @property
    def moved_nominal(self) -> VoussoirArch:
        """The nominal arch on the whole movement, as the study analyses it."""
        return on_moved_supports(self.nominal, self.movement)

    def movements(self, start: int, count: int) -> list:
        """The support movement of samples start .. start + count - 1."""
        if self.support_draw == "fixed":
            return [self.movement] * int(count)
        return [self.movement.scaled(float(u)) for u in self.movement_fractions(start, count)]

    def arch(self, index: int) -> VoussoirArch:
        return _moved_sample(super().arch(index), self.movements(index, 1)[0])

    def arches(self, start: int, count: int) -> list:
        return [a if isinstance(a, Exception) else _moved_sample(a, mv, raise_=False)
                for a, mv in zip(super().arches(start, count), self.movements(start, count))]

    def to_dict(self) -> dict:
        d = super().to_dict()
        d["support"] = self.movement.to_dict()
        if self.support_draw != "fixed":
            d["support_draw"] = self.support_draw
        return d


def _moved_sample(arch, movement, raise_=True):
    """``arch`` on ``movement`` re-closed, or the InvalidSampleError saying it cannot stand
    there (raised, or returned with ``raise_=False``, as ArchSampler.arches does)."""
    from ..errors import ArchrockError, InvalidSampleError

    try:
        return on_moved_supports(arch, movement)
    except ArchrockError as exc:
        err = InvalidSampleError(f"cannot stand on its moved supports ({movement.describe()}): "
                                 f"{' '.join(str(exc).split())}")
    if raise_:
        raise err
    return err


def study_sampler(nominal: VoussoirArch, spreads=None, seed: int = 0,
                  support_draw: str = "fixed") -> ArchSampler:
    """The sampler of a study's random arches around ``nominal``: an
    :class:`~archrock.geometry.sampling.ArchSampler` on fixed supports (the same object as
    before, so every fixed-support study is unchanged bit for bit), or a :class:`MovedSampler`
    around the base of a nominal on moved supports (:func:`moved_parts`)."""
    base, mv = moved_parts(nominal)
    spreads = Spreads.from_dict(spreads)
    if mv is None:
        if support_draw != "fixed":
            raise ArchInputError(f"support_draw: {support_draw!r} needs an arch on moved "
                                 f"supports (--spread/--settlement)")
        return ArchSampler(nominal, spreads, seed)
    return MovedSampler(base, spreads, seed, movement=mv, support_draw=support_draw)

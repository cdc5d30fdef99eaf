"""Why a loaded arch cannot stand: its self-weight, or a load it cannot carry.

When the arch with its loads has no line of thrust inside it but the arch without them has,
the load is to blame, not the thickness: :func:`cannot_stand_message` names the load (index,
mass, voussoir, point) and the largest mass of it the arch carries on its own, found by
bisection on the static program's feasibility (:func:`archrock.statics.lp._stands`, the test
of the minimum thickness).  A 1e12 kg load used to be told "increase the thickness".
"""

from __future__ import annotations

import dataclasses
import math

from ..errors import ArchrockError
from .lp import _stands
from .pierwidth import piers_cannot_stand
from .search import least_standing

__all__ = ["cannot_stand_message", "largest_load_mass"]

#: The largest carried mass is searched down to this fraction of the load's own mass (15
#: decades: a 1e12 kg/m load on an arch that carries 1e-3 kg/m).
_DECADES = 15.0
#: Relative tolerance on the decade of the largest mass (1e-4 of up to 15 decades: the mass
#: to about 0.3 %), and the bisection's bound on steps.
_TOL, _MAX_STEPS = 1e-4, 60
#: Arches with more voussoirs skip the search (each step is one linear program).
_MAX_VOUSSOIRS = 400


def _with_loads(arch, loads):
    """``arch`` with ``loads`` instead of its own, or None where the arch cannot be rebuilt so
    (a displaced arch, a type without a ``loads`` field)."""
    try:
        return dataclasses.replace(arch, loads=tuple(loads))
    except (TypeError, ValueError, ArchrockError):
        return None


def largest_load_mass(arch, k: int) -> float | None:
    """The largest mass [kg/m] of load ``k`` (at its point, the other loads removed) with which
    ``arch`` stands under its own weight, to about 0.3 %; None where the search does not apply
    (the arch stands with the load as given, cannot stand without it, or is too large)."""
    ld = arch.loads[k]
    if arch.n > _MAX_VOUSSOIRS or not ld.mass > 0:
        return None

    def stands(u: float) -> bool:  # the load's mass divided by 10**(u - 1), u in [1, 16]
        a = _with_loads(arch, [dataclasses.replace(ld, mass=ld.mass * 10.0 ** (1.0 - u))])
        return a is not None and _stands(a)

    if stands(1.0) or not stands(1.0 + _DECADES):
        return None
    # u >= 1 keeps the relative tolerance an absolute one of at most 1.6e-3 decades
    hi, _ = least_standing(stands, 1.0, 1.0 + _DECADES, _TOL, _MAX_STEPS, "largest load mass")
    return ld.mass * 10.0 ** (1.0 - hi)


def _describe(k: int, ld) -> str:
    return (f"load {k} ({ld.mass:.4g} kg/m on voussoir {ld.voussoir} at ({ld.at[0]:.4g}, "
            f"{ld.at[1]:.4g}) m)")


def cannot_stand_message(arch, detail: str) -> str:
    """The one-line reason an arch cannot stand, ``detail`` (e.g. the multipliers) included:
    the load it cannot carry and what would carry it, where the arch without its loads stands;
    otherwise its self-weight, with the advice to thicken it."""
    # on piers that cannot carry the arch's thrust the piers are to blame, not the thickness
    piers = piers_cannot_stand(arch, detail)
    if piers is not None:
        return piers
    own = (f"arch: it cannot stand under its own weight {detail}; increase the thickness")
    loads = tuple(getattr(arch, "loads", ()) or ())
    if not loads or arch.n > _MAX_VOUSSOIRS:
        return own
    bare = _with_loads(arch, ())
    if bare is None or not _stands(bare):
        return own
    alone = [k for k, ld in enumerate(loads)
             if ld.mass > 0 and (a := _with_loads(arch, [ld])) is not None and not _stands(a)]
    if not alone:
        listed = ", ".join(_describe(k, ld) for k, ld in enumerate(loads))
        return (f"arch: its loads together are more than it can carry {detail}; it stands "
                f"without them and under each alone: {listed}; reduce the loads' masses or "
                f"thicken the arch")
    k = max(alone, key=lambda i: loads[i].mass)
    most = largest_load_mass(arch, k)
    carry = "" if most is None or not math.isfinite(most) else (
        f"; it carries at most {most:.3g} kg/m there (load {k} alone)")
    return (f"arch: {_describe(k, loads[k])} is more than it can carry {detail}; it stands "
            f"without its loads{carry}: reduce load {k}'s mass or thicken the arch")

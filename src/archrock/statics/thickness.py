"""Minimum thickness: the smallest common thickness factor at which an arch stands under
its own weight (multiplier 0), by bisection on the static program's feasibility
(:func:`archrock.statics.lp._stands`).  Factors multiply every voussoir's thickness; ratios are
mean t/R (circular arches) or mean thickness / size (families).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .._records import readonly_arrays
from ..errors import ArchInputError, CannotStandError
from .search import check_tol, least_standing
from ..geometry import Arch, VoussoirArch
from .lp import _stands

__all__ = ["MinimumThickness", "minimum_thickness", "thickness_bisection"]


# Largest thickness factor tried on an arch family (circular arches stop at t = 2 R).
_MAX_THICKNESS_FACTOR = 64.0
# Bound on the minimum-thickness bisection's steps (tol >= 1e-15 needs fewer than 70).
_MAX_BISECTIONS = 100


@dataclass(frozen=True)
class MinimumThickness:
    """Smallest thickness scale at which the arch stands under its own weight.

    factor: multiplier of every voussoir thickness; ratio: the resulting mean t/R (circular
    arches; for other families the mean thickness / size where the family has ``thicknesses``,
    else None); thicknesses [m] (None where the family has none).
    """

    factor: float
    ratio: float | None
    thicknesses: np.ndarray | None
    iterations: int

    def __post_init__(self):
        readonly_arrays(self)


def minimum_thickness(arch: VoussoirArch, tol: float = 1e-7) -> MinimumThickness:
    """Minimum thickness under self-weight alone (multiplier = 0), by bisection on a common
    thickness factor with the static feasibility LP (lambda = 0).  Needs an arch that can vary
    its thickness (``with_thickness_factor``: circular arches, families); a surveyed
    :class:`~archrock.geometry.PolygonArch` cannot (ArchInputError).  With a finite ``fc``
    the arch must also stand without crushing (:func:`archrock.statics.crushing.
    crushing_stands`): the answer then depends on the arch's size and density."""
    if getattr(arch, "fc", None) is not None:
        from .crushing import crushing_stands

        return thickness_bisection(arch, crushing_stands, tol)
    return thickness_bisection(arch, _stands, tol)


def thickness_bisection(arch: VoussoirArch, stands, tol: float = 1e-7,
                        cannot: str = "arch: it does not stand under its own weight at any "
                                      "thickness") -> MinimumThickness:
    """Smallest common thickness factor f at which ``stands(arch.with_thickness_factor(f))``
    holds, by doubling from 1 then bisection to ``tol`` (relative); ``stands`` must be monotone
    in the thickness.  Raises CannotStandError with the message ``cannot`` when no thickness
    the arch allows stands.  :func:`minimum_thickness` and the friction-limited minimum
    thickness (:mod:`archrock.statics.friction`) share it."""
    if not isinstance(arch, VoussoirArch):
        raise ArchInputError(f"arch: expected a VoussoirArch, got {type(arch).__name__}")
    if isinstance(arch, Arch):
        max_factor = float(np.min(2 * arch.radii / arch.thicknesses)) * (1 - 1e-9)
    elif callable(getattr(arch, "with_thickness_factor", None)):
        max_factor = _MAX_THICKNESS_FACTOR
    else:
        raise ArchInputError(
            f"arch: the thickness cannot be varied for a surveyed polygon arch "
            f"({type(arch).__name__} has no with_thickness_factor); minimum thickness needs a "
            f"circular arch or an arch family")

    def at(f):
        try:
            a = arch.with_thickness_factor(f)
        except ArchInputError:  # thicker than the family allows
            return None
        return stands(a)

    tol = check_tol(tol, "thickness")
    lo, hi = 1e-6, min(1.0, max_factor)
    while True:  # at most log2(max_factor) + 1 doublings (max_factor <= 64 or 2R/t)
        ok = at(hi)
        if ok:
            break
        if ok is None or hi >= max_factor:
            raise CannotStandError(cannot)
        hi = min(2 * hi, max_factor)
    # a halving narrows by 2: 1e-15 from 1e-6 takes < 70 of the _MAX_BISECTIONS
    hi, it = least_standing(at, lo, hi, tol, _MAX_BISECTIONS, "minimum thickness")
    if isinstance(arch, Arch):
        t = arch.thicknesses * hi
        return MinimumThickness(hi, float(np.mean(t / arch.radii)), t, it)
    thin = arch.with_thickness_factor(hi)
    t = getattr(thin, "thicknesses", None)
    if t is None:
        return MinimumThickness(hi, None, None, it)
    t = np.array(t, float)
    return MinimumThickness(hi, float(np.mean(t)) / thin.size, t, it)

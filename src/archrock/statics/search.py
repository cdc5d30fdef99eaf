"""The bounded bisection of the statics' least-value searches (minimum thickness, minimum pier
width): the least x in [lo, hi] at which a structure stands, to a tolerance relative to x."""

from __future__ import annotations

import math

from ..errors import ArchInputError, LimitExceededError

__all__ = ["least_standing", "check_tol"]


def check_tol(tol, what: str) -> float:
    """``tol`` as a float in [1e-15, 0.5), or ArchInputError naming it as the relative width of
    ``what``'s bracket."""
    try:
        tol = float(tol)
    except (TypeError, ValueError):
        tol = math.nan
    if not 1e-15 <= tol < 0.5:
        raise ArchInputError(f"tol: {tol!r}; allowed 1e-15 <= tol < 0.5 (relative width of the "
                             f"{what} bracket)")
    return tol


def least_standing(stands, lo: float, hi: float, tol: float, max_steps: int, what: str,
                   steps: int = 0) -> tuple[float, int]:
    """(hi, steps): bisect [lo, hi] (``stands(lo)`` false, ``stands(hi)`` true) until
    hi - lo <= tol * hi; ``steps`` counts on from the caller's (its bracketing), and more than
    ``max_steps`` raises LimitExceededError naming ``what`` and the bracket reached."""
    while hi - lo > tol * hi:
        if steps >= max_steps:
            raise LimitExceededError(f"{what}: the bisection did not reach tol = {tol:g} in "
                                     f"{max_steps} steps ([{lo:.17g}, {hi:.17g}])")
        mid = 0.5 * (lo + hi)
        if stands(mid):
            hi = mid
        else:
            lo = mid
        steps += 1
    return hi, steps

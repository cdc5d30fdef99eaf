"""The bounded bisection of the statics' least-value searches (minimum thickness, minimum pier
width): the least x in [lo, hi] at which a structure stands, to a tolerance relative to x."""

from __future__ import annotations

from ..errors import LimitExceededError

__all__ = ["least_standing"]


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

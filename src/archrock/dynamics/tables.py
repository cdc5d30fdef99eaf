"""Tabulated coefficients of the four-link equation of motion, read by the fast integrator
(:mod:`archrock.dynamics.kernel`), and the accelerations from them or from the exact closure.
``FourLink.tabulated`` (:mod:`archrock.dynamics.fourlink`) builds a mechanism's tables; the batch
kernel builds them interval by interval as the motion reaches them."""

from __future__ import annotations

import math

import numpy as np

from .._device import device_override
from .._jit import maybe_njit
from ..errors import ArchInputError
from .fourbar import GEO_SIZE, coefficients

# ---------------------------------------------------------------------------- tabulated coefficients
# The fast integrator evaluates the equation of motion a few million times per ensemble.  It
# reads it from piecewise cubics through exact values on a uniform grid of phi instead of
# redoing the loop closure.  The cubics are of M and of the ratios L/M, F/M, P/M, so that
# phi'' = (P/M) a - (F/M) g - (L/M) phi'^2 needs no division: the four stages of an RK4 step
# are one dependent chain, and a division was a third of each link.  (The ratios are also the
# better-conditioned functions near the dead point, where M grows without bound.)
#
# Each interval's cubic is local: the cubic Hermite interpolant of the grid values at its two
# ends and of their slopes, the slopes by fourth-order differences of the five nearest grid
# values.  An interval can therefore be built alone, when the motion first reaches it: a
# recovering arch of an ensemble visits a quarter of its range, and building whole tables (600
# intervals x 2 mechanisms, 134 ns per exact evaluation) was two thirds of the time of an
# ensemble under a pulse.  The error is h^4 max|d4f/dphi4| / 384 plus O(h^5) from the slopes,
# against 5/384 for the interior of a natural spline, with none of the spline's O(h^2) ends
# (measured: the same 1.7e-9 of phi'' as natural splines of the same ratios).
#
# Layout appended to the 21 geometry numbers: [phi_start, h, n_intervals, 1/h], then per
# interval 4 functions (M, L/M, F/M, P/M) x 4 polynomial coefficients in s = phi - phi_i (NaN
# until built), then per knot the 4 function values and their 4 slopes (NaN until computed).
TABLE_HEADER = 4


#: fewest table intervals: the one-sided slopes at the ends use five knots
MIN_TABLE_INTERVALS = 4


def check_table_intervals(n, name: str = "table_intervals") -> int:
    """``n`` as an int, or ArchInputError naming ``name`` unless it is an integer >= 4."""
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < MIN_TABLE_INTERVALS:
        raise ArchInputError(f"{name}: {n!r}; allowed an integer >= {MIN_TABLE_INTERVALS}")
    return int(n)


@maybe_njit
def table_size(n_intervals):
    """Length of a geometry vector with tables of ``n_intervals`` intervals."""
    return GEO_SIZE + TABLE_HEADER + 24 * n_intervals + 8


@maybe_njit
def init_table(out, geo, start, phi_max, n_intervals):
    """Write into ``out`` (length :func:`table_size`) geo and empty tables of (M, L/M, F/M,
    P/M) on [start, phi_max] (start < 0, ``n_intervals`` >= 4), none of them built yet (see
    :func:`build_interval`).  In place, so that a batch loop fills its own rows."""
    n = n_intervals
    h = (phi_max - start) / n
    # element by element: a slice assignment needs numba's runtime, which a GPU thread lacks
    for q in range(out.size):
        out[q] = geo[q] if q < GEO_SIZE else np.nan
    out[GEO_SIZE] = start
    out[GEO_SIZE + 1] = h
    out[GEO_SIZE + 2] = n
    out[GEO_SIZE + 3] = 1.0 / h


@device_override(init_table, simulator_only=True)
def _init_table_simulated(out, geo, start, phi_max, n_intervals):
    """:func:`init_table` by whole-array assignments (the same numbers), for numba's CUDA
    simulator only: a GPU thread cannot run them, the simulator runs them 100 times faster than
    the element loop."""
    h = (phi_max - start) / n_intervals
    out[:] = np.nan
    out[:GEO_SIZE] = geo[:GEO_SIZE]
    out[GEO_SIZE] = start
    out[GEO_SIZE + 1] = h
    out[GEO_SIZE + 2] = n_intervals
    out[GEO_SIZE + 3] = 1.0 / h


@maybe_njit
def empty_table(geo, start, phi_max, n_intervals):
    """:func:`init_table` in a new array."""
    out = np.empty(table_size(n_intervals))
    init_table(out, geo, start, phi_max, n_intervals)
    return out


@maybe_njit
def _knot(tab, knots, start, h, j):
    """Offset of knot j's values (M, L/M, F/M, P/M, then their slopes), evaluated exactly the
    first time."""
    kb = knots + 8 * j
    if tab[kb] != tab[kb]:
        M, L, F, P = coefficients(start + j * h, tab)
        tab[kb], tab[kb + 1], tab[kb + 2], tab[kb + 3] = M, L / M, F / M, P / M
    return kb


@maybe_njit
def _slopes(tab, knots, start, h, n, j):
    """Offset of knot j's values, with their phi-derivatives (slots 4-7) by fourth-order
    differences of the knot values (one-sided at the ends) computed the first time."""
    kb = _knot(tab, knots, start, h, j)
    if tab[kb + 4] == tab[kb + 4]:
        return kb
    if j < 2 or j > n - 2:
        # the five knots nearest the end, counted inward from it
        e, sign = (0, 1) if j < 2 else (n, -1)
        c = (-25.0, 48.0, -36.0, 16.0, -3.0) if j == e else (-3.0, -10.0, 18.0, -6.0, 1.0)
        ks = (e, e + sign, e + 2 * sign, e + 3 * sign, e + 4 * sign)
        w = sign / (12.0 * h)
    else:
        c = (1.0, -8.0, 0.0, 8.0, -1.0)
        ks = (j - 2, j - 1, j, j + 1, j + 2)
        w = 1.0 / (12.0 * h)
    o0 = _knot(tab, knots, start, h, ks[0])
    o1 = _knot(tab, knots, start, h, ks[1])
    o2 = _knot(tab, knots, start, h, ks[2])
    o3 = _knot(tab, knots, start, h, ks[3])
    o4 = _knot(tab, knots, start, h, ks[4])
    for f in range(4):
        tab[kb + 4 + f] = w * (c[0] * tab[o0 + f] + c[1] * tab[o1 + f] + c[2] * tab[o2 + f]
                               + c[3] * tab[o3 + f] + c[4] * tab[o4 + f])
    return kb


@maybe_njit
def build_interval(tab, i):
    """Write interval i's cubics into ``tab`` (from :func:`empty_table`): the cubic Hermite
    interpolant of the knot values and slopes at its ends, the knots it needs evaluated where
    not done yet.  The result depends on i and the geometry alone, not on which intervals were
    built before."""
    n = int(tab[GEO_SIZE + 2])
    start = tab[GEO_SIZE]
    h = tab[GEO_SIZE + 1]
    knots = GEO_SIZE + TABLE_HEADER + 16 * n
    k0 = _slopes(tab, knots, start, h, n, i)
    k1 = _slopes(tab, knots, start, h, n, i + 1)
    base = GEO_SIZE + TABLE_HEADER + 16 * i
    for f in range(4):
        y0 = tab[k0 + f]
        d0 = tab[k0 + 4 + f]
        d1 = tab[k1 + 4 + f]
        secant = (tab[k1 + f] - y0) / h
        tab[base + 4 * f] = y0
        tab[base + 4 * f + 1] = d0
        tab[base + 4 * f + 2] = (3.0 * secant - 2.0 * d0 - d1) / h
        tab[base + 4 * f + 3] = (d0 + d1 - 2.0 * secant) / (h * h)


@maybe_njit
def build_table(tab):
    """Build every interval of ``tab`` (from :func:`init_table`)."""
    for i in range(int(tab[GEO_SIZE + 2])):
        build_interval(tab, i)


@maybe_njit
def coefficient_table(geo, start, phi_max, n_intervals):
    """geo extended with the tables of (M, L/M, F/M, P/M) on [start, phi_max] (start < 0,
    ``n_intervals`` >= 4), every interval built."""
    out = empty_table(geo, start, phi_max, n_intervals)
    build_table(out)
    return out


@maybe_njit
def _table_interval(phi, geo):
    """(base, s): the offset of phi's interval in ``geo``'s tables and phi - phi_i [rad], or
    (-1, 0) when ``geo`` carries no tables or phi is outside them (built or not)."""
    if geo.size <= GEO_SIZE:
        return -1, 0.0
    start = geo[GEO_SIZE]
    x = (phi - start) * geo[GEO_SIZE + 3]
    if not (x >= 0.0 and x < geo[GEO_SIZE + 2]):
        return -1, 0.0
    i = int(x)
    return GEO_SIZE + TABLE_HEADER + 16 * i, phi - (start + i * geo[GEO_SIZE + 1])


@maybe_njit
def fast_coefficients(phi, geo):
    """(M, L, F, P) from the tables when ``geo`` carries them and phi is in a built interval,
    else exactly."""
    base, s = _table_interval(phi, geo)
    if base < 0 or geo[base] != geo[base]:
        return coefficients(phi, geo)
    M = ((geo[base + 3] * s + geo[base + 2]) * s + geo[base + 1]) * s + geo[base]
    L = ((geo[base + 7] * s + geo[base + 6]) * s + geo[base + 5]) * s + geo[base + 4]
    F = ((geo[base + 11] * s + geo[base + 10]) * s + geo[base + 9]) * s + geo[base + 8]
    P = ((geo[base + 15] * s + geo[base + 14]) * s + geo[base + 13]) * s + geo[base + 12]
    return M, L * M, F * M, P * M


@maybe_njit
def exact_acceleration(phi, rate, a, g, geo):
    """phi'' [rad/s^2] at rotation phi [rad], rate phi' [rad/s], ground acceleration a [m/s^2]
    (positive toward +x) and gravity g [m/s^2], from the exact coefficients."""
    M, L, F, P = coefficients(phi, geo)
    return (P * a - F * g - L * rate * rate) / M


@maybe_njit
def table_acceleration(phi, rate, a, g, geo):
    """:func:`exact_acceleration` from the tables; NaN when ``geo`` carries none, or phi is
    outside them or in an interval not built yet.  It never calls anything itself: a call in
    this innermost chain made the compiled RK4 step almost twice as slow even when not taken,
    so the caller redoes the step with :func:`filling_acceleration` when it sees a NaN."""
    base, s = _table_interval(phi, geo)
    if base < 0:
        return math.nan
    lm = ((geo[base + 7] * s + geo[base + 6]) * s + geo[base + 5]) * s + geo[base + 4]
    fm = ((geo[base + 11] * s + geo[base + 10]) * s + geo[base + 9]) * s + geo[base + 8]
    pm = ((geo[base + 15] * s + geo[base + 14]) * s + geo[base + 13]) * s + geo[base + 12]
    return pm * a - fm * g - lm * rate * rate


@maybe_njit
def filling_acceleration(phi, rate, a, g, geo):
    """:func:`table_acceleration`, building phi's interval first when it is not yet (writes
    into ``geo``), and :func:`exact_acceleration` outside the tables."""
    base, _ = _table_interval(phi, geo)
    if base >= 0:
        if geo[base + 4] != geo[base + 4]:
            build_interval(geo, (base - GEO_SIZE - TABLE_HEADER) // 16)
        v = table_acceleration(phi, rate, a, g, geo)
        if v == v:
            return v
    return exact_acceleration(phi, rate, a, g, geo)
